#include "autorig/eye_opening.h"

#include <algorithm>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <span>

#include "autorig/carried_pieces.h"
#include "autorig/face_frame.h"
#include "autorig/skin_in_front.h"
#include "engine/core/uv_raster.h"

namespace autorig {
namespace {

// The cut-free eye's distance from the ball's centre, of what it was: a lid
// closing along the ball at its rim's distance passes in front of it.
constexpr float kEyeSetBack = 0.99f;
// The carried eyeball's radius, of the ball's: behind the cut-free eye.
constexpr float kBallInside = 0.97f;
// Fewer of an eye's triangles than this are no eye to cut free.
constexpr size_t kMinEyeTriangles = 8;

FacePart eyeballOf(size_t eye) { return eye == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft; }

glm::mat3 axesOf(const FaceLandmarks& landmarks) {
  const LandmarkFrame frame(landmarks);
  return glm::mat3(frame.side(), frame.up(), frame.forward());
}

// The source's primitives that are its eyeball of that side.
std::vector<size_t> sourceEyeballs(const SourceFace& source, FacePart side) {
  std::vector<size_t> balls;
  for (size_t i = 0; i < source.parts.vertexParts.size(); ++i) {
    const std::vector<FacePart>& parts = source.parts.vertexParts[i];
    if (!parts.empty() && std::all_of(parts.begin(), parts.end(), [&](FacePart p) { return p == side; })) balls.push_back(i);
  }
  return balls;
}

// The skin vertex of a posed primitive nearest `point` (the carried eyeball
// moves as it does: with the head, between the eyes), or nullopt without skin.
std::optional<uint32_t> nearestSkinVertex(const PosedPrimitive& pp, const std::vector<FacePart>& parts, const glm::vec3& point) {
  std::optional<uint32_t> nearest;
  float best = std::numeric_limits<float>::max();
  for (size_t v = 0; v < pp.positions.size(); ++v)
    if (parts[v] == FacePart::Skin && glm::distance(pp.positions[v], point) < best)
      best = glm::distance(pp.positions[v], point), nearest = uint32_t(v);
  return nearest;
}

// The white of an eye as the face shows it: the brightest quarter of its
// colour (linear: texture at the vertices' UVs, nearest texel, times the
// factor, times a scan's vertex colours). Nullopt for a texture without UVs.
std::optional<glm::vec3> whiteOf(const eng::Model& model, const eng::Primitive& prim, std::span<const uint32_t> vertices) {
  if (prim.material < 0 || size_t(prim.material) >= model.materials.size()) return std::nullopt;
  const eng::Material& material = model.materials[size_t(prim.material)];
  const glm::vec3 factor(material.baseColorFactor);
  const eng::Image* image = material.baseColorImage >= 0 && size_t(material.baseColorImage) < model.images.size()
                                ? &model.images[size_t(material.baseColorImage)]
                                : nullptr;
  if (image && (prim.texcoords.size() != prim.vertexCount() || image->width <= 0 || image->height <= 0 ||
                image->rgba8.size() != size_t(image->width) * size_t(image->height) * 4))
    return std::nullopt;
  const bool painted = prim.colors.size() == prim.vertexCount();
  std::vector<glm::vec3> colours;
  for (uint32_t v : vertices) {
    glm::vec3 colour = factor;
    if (image) {
      const glm::vec2 uv = prim.texcoords[v] - glm::floor(prim.texcoords[v]);  // repeat
      const int x = std::clamp(int(uv.x * float(image->width)), 0, image->width - 1);
      const int y = std::clamp(int(uv.y * float(image->height)), 0, image->height - 1);
      const uint8_t* t = &image->rgba8[(size_t(y) * size_t(image->width) + size_t(x)) * 4];
      colour *= eng::srgb(t[0], t[1], t[2]);
    }
    if (painted) colour *= glm::vec3(prim.colors[v]);
    colours.push_back(colour);
  }
  if (colours.empty()) return std::nullopt;
  auto brightness = [](const glm::vec3& c) { return c.r + c.g + c.b; };
  std::sort(colours.begin(), colours.end(), [&](const glm::vec3& a, const glm::vec3& b) { return brightness(a) > brightness(b); });
  glm::vec3 sum(0.0f);
  const size_t quarter = std::max<size_t>(1, colours.size() / 4);
  for (size_t i = 0; i < quarter; ++i) sum += colours[i];
  return sum / float(quarter);
}

struct EyeCut {
  size_t posed;  // into PosedFace::primitives
  size_t eye;    // 0: right, 1: left
  std::vector<uint32_t> triangles;
};

// Of an eye's triangles, those seen at rest: the rest lie under its lids,
// where a scan's texture holds whatever the camera never saw (the lid's
// underside, the socket); cut free, a turned eye would bring them into view.
// They stay with the lids, and the eyeball behind fills what a turned eye
// uncovers. A triangle is under a lid when a ray out of the face from just
// in front of it meets the skin.
void keepTheSeen(EyeCut& cut, const PosedPrimitive& pp, const std::vector<uint32_t>& indices, const FaceParts& parts,
                 const LandmarkFrame& frame) {
  if (cut.triangles.empty()) return;
  const glm::vec3& centre = parts.eyeCentres[cut.eye];
  const float radius = parts.eyeRadii[cut.eye];
  SkinInFront skin(frame, 0.1f * radius);
  std::vector<char> onTheEye(indices.size() / 3, 0);
  for (uint32_t t : cut.triangles) onTheEye[t] = 1;
  for (size_t t = 0; t < onTheEye.size(); ++t) {
    if (onTheEye[t]) continue;
    const glm::vec3 &a = pp.positions[indices[t * 3]], &b = pp.positions[indices[t * 3 + 1]], &c = pp.positions[indices[t * 3 + 2]];
    if (glm::distance((a + b + c) / 3.0f, centre) < 3.0f * radius) skin.add(a, b, c);
  }
  std::erase_if(cut.triangles, [&](uint32_t t) {
    const glm::vec3 middle =
        (pp.positions[indices[t * 3]] + pp.positions[indices[t * 3 + 1]] + pp.positions[indices[t * 3 + 2]]) / 3.0f;
    return skin.covers(middle + frame.forward() * (0.01f * radius));
  });
}

}  // namespace

EyeOpening openTheEyes(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks, const FaceParts& parts,
                       const SourceFace& source) {
  EyeOpening opening;
  if (parts.vertexParts.size() != posed.primitives.size() || !(parts.eyesInTheSkin[0] || parts.eyesInTheSkin[1]))
    return opening;
  // Each eye's triangles: all three corners on the ball.
  const LandmarkFrame frame(landmarks);
  std::vector<EyeCut> cuts;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    const std::vector<uint32_t>& indices = face.meshes[pp.mesh].primitives[pp.primitive].indices;
    for (size_t e = 0; e < 2; ++e) {
      if (!parts.eyesInTheSkin[e]) continue;
      EyeCut cut{i, e, {}};
      for (size_t t = 0; t + 2 < indices.size(); t += 3)
        if (std::all_of(&indices[t], &indices[t] + 3, [&](uint32_t v) {
              return v < parts.vertexParts[i].size() && parts.vertexParts[i][v] == eyeballOf(e);
            }))
          cut.triangles.push_back(uint32_t(t / 3));
      keepTheSeen(cut, pp, indices, parts, frame);
      if (cut.triangles.size() >= kMinEyeTriangles) cuts.push_back(std::move(cut));
    }
  }
  if (cuts.empty()) return opening;

  // The head's eyeballs behind them first: carried into the mesh as its
  // primitives stand (the cut below rebuilds the skin's), one carrier per
  // skin primitive (the eyes share the head's eye material and its image).
  const glm::mat3 turn = axesOf(landmarks) * glm::transpose(axesOf(source.landmarks));
  std::map<size_t, CarriedPieces> carriers;  // by posed skin primitive
  std::map<size_t, std::vector<glm::vec3>> whiteRatios;  // the scan's white over the head's, per carrier
  for (const EyeCut& cut : cuts) {
    const PosedPrimitive& host = posed.primitives[cut.posed];
    const std::optional<uint32_t> anchor = nearestSkinVertex(host, parts.vertexParts[cut.posed], landmarks.points[27]);
    const float sourceRadius = source.parts.eyeRadii[cut.eye];
    const std::vector<size_t> balls = sourceEyeballs(source, eyeballOf(cut.eye));
    if (!anchor || !(sourceRadius > 0.0f) || balls.empty() || source.model == nullptr) continue;
    const float scale = kBallInside * parts.eyeRadii[cut.eye] / sourceRadius;
    CarriedPieces& carrier = carriers.try_emplace(cut.posed, face, host, *anchor).first->second;
    for (size_t ball : balls) {
      std::vector<glm::vec3> world;
      for (const glm::vec3& q : source.posed.primitives[ball].positions)
        world.push_back(parts.eyeCentres[cut.eye] + turn * (q - source.parts.eyeCentres[cut.eye]) * scale);
      opening.ballVertices += carrier.add(source, ball, world, turn);
    }
    // The white a raised lid uncovers matched to the scan's painted one.
    std::vector<uint32_t> onTheEye;
    const std::vector<uint32_t>& indices = face.meshes[host.mesh].primitives[host.primitive].indices;
    for (uint32_t t : cut.triangles) onTheEye.insert(onTheEye.end(), &indices[size_t(t) * 3], &indices[size_t(t) * 3] + 3);
    const PosedPrimitive& ball = source.posed.primitives[balls.front()];
    const eng::Primitive& ballPrim = source.model->meshes[ball.mesh].primitives[ball.primitive];
    std::vector<uint32_t> allOfIt(ballPrim.vertexCount());
    std::iota(allOfIt.begin(), allOfIt.end(), 0u);
    const std::optional<glm::vec3> scanWhite = whiteOf(face, face.meshes[host.mesh].primitives[host.primitive], onTheEye);
    const std::optional<glm::vec3> headWhite = whiteOf(*source.model, ballPrim, allOfIt);
    if (scanWhite && headWhite) whiteRatios[cut.posed].push_back(*scanWhite / glm::max(*headWhite, glm::vec3(1e-3f)));
  }
  for (const auto& [host, ratios] : whiteRatios) {
    glm::vec3 ratio(0.0f);
    for (const glm::vec3& r : ratios) ratio += r / float(ratios.size());
    for (const auto& [sourceMaterial, material] : carriers.at(host).materialsMade()) {
      glm::vec4& colour = face.materials[size_t(material)].baseColorFactor;
      colour = glm::vec4(glm::clamp(glm::vec3(colour) * ratio, glm::vec3(0.0f), glm::vec3(1.0f)), colour.a);
    }
  }

  // Then each eye cut free: its triangles a primitive of their own, the
  // rest of the skin's primitive rebuilt without them.
  std::map<int, int> eyeMaterialOf;  // the skin's material -> its copy for the eyes
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& pp = posed.primitives[i];
    eng::Mesh& mesh = face.meshes[pp.mesh];
    const eng::Primitive& skin = mesh.primitives[pp.primitive];
    std::vector<char> cutAway(skin.indices.size() / 3, 0);
    std::vector<eng::Primitive> eyes;
    for (const EyeCut& cut : cuts) {
      if (cut.posed != i) continue;
      std::vector<uint32_t> vertexOf;
      eng::Primitive eye = withTriangles(skin, cut.triangles, &vertexOf);
      const glm::vec3& centre = parts.eyeCentres[cut.eye];
      for (size_t k = 0; k < vertexOf.size(); ++k) {
        const glm::vec3& world = pp.positions[vertexOf[k]];
        eye.positions[k] += pp.toLocal(vertexOf[k], (centre + (world - centre) * kEyeSetBack) - world);
      }
      auto [material, fresh] = eyeMaterialOf.try_emplace(skin.material, int(face.materials.size()));
      if (fresh) {
        eng::Material copy = skin.material >= 0 ? face.materials[size_t(skin.material)] : eng::Material{};
        copy.name = "Eye (a scan's, cut free)";  // an eyeball by name (autorig::facePartFromNames)
        copy.detailLayers.clear();
        face.materials.push_back(std::move(copy));
      }
      eye.material = material->second;
      for (uint32_t t : cut.triangles) cutAway[t] = 1;
      opening.notes.push_back(meshLabel(face, pp.mesh) + ": the " + (cut.eye == 0 ? "right" : "left") + " eye (" +
                              std::to_string(eye.vertexCount()) +
                              " vertices of the skin) cut free from its lids, the built-in head's eyeball behind it");
      eyes.push_back(std::move(eye));
      ++opening.eyesCut;
    }
    if (eyes.empty()) continue;
    std::vector<uint32_t> kept;
    for (size_t t = 0; t < cutAway.size(); ++t)
      if (!cutAway[t]) kept.push_back(uint32_t(t));
    eng::Primitive rest = withTriangles(skin, kept);
    mesh.primitives[pp.primitive] = std::move(rest);
    for (eng::Primitive& eye : eyes) mesh.primitives.push_back(std::move(eye));
  }
  return opening;
}

}  // namespace autorig
