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

// Eyes whose openings have nothing in them (a head exported without its
// eyeballs, the socket's lining or the inside of the skin behind the lids):
// a ray out of the face from the middle of the lid margins (landmarks 36-41,
// 42-47) meets no skin. A flat painted eye or an eye in the skin lies on or
// in front of that point and is met. Only on faces without eyeballs of their own.
std::vector<size_t> emptyOpenings(const eng::Model& face, const PosedFace& posed, const FaceParts& parts,
                                  const FaceLandmarks& landmarks, const LandmarkFrame& frame) {
  std::vector<size_t> empty;
  if (parts.eyeballsFound) return empty;
  for (size_t e = 0; e < 2; ++e) {
    const glm::vec3& centre = parts.eyeCentres[e];
    const float radius = parts.eyeRadii[e];
    if (parts.eyesInTheSkin[e] || !(radius > 0.0f)) continue;
    SkinInFront skin(frame, 0.25f * radius);
    size_t around = 0;
    for (size_t i = 0; i < posed.primitives.size(); ++i) {
      const PosedPrimitive& pp = posed.primitives[i];
      const std::vector<uint32_t>& indices = face.meshes[pp.mesh].primitives[pp.primitive].indices;
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        if (!std::all_of(&indices[t], &indices[t] + 3, [&](uint32_t v) {
              return v < pp.positions.size() && v < parts.vertexParts[i].size() && parts.vertexParts[i][v] == FacePart::Skin;
            }))
          continue;
        const glm::vec3 &a = pp.positions[indices[t]], &b = pp.positions[indices[t + 1]], &c = pp.positions[indices[t + 2]];
        if (glm::distance((a + b + c) / 3.0f, centre) > 3.0f * radius) continue;
        skin.add(a, b, c);
        ++around;
      }
    }
    if (around >= kMinEyeTriangles && !skin.covers(eyeballBehindTheLids(landmarks, e).margins)) empty.push_back(e);
  }
  return empty;
}

// The head's eyeball of side `eye` carried into the face at `at` (a little
// smaller), by the carrier of posed primitive `host`, moving with the skin
// between the eyes. Returns the vertices carried, 0 where there is nothing to
// carry or no skin to hold it.
size_t carryEyeball(eng::Model& face, const PosedFace& posed, size_t host, size_t eye, const Eyeball& at,
                    const FaceLandmarks& landmarks, const FaceParts& parts, const SourceFace& source,
                    std::map<size_t, CarriedPieces>& carriers) {
  const PosedPrimitive& pp = posed.primitives[host];
  const std::optional<uint32_t> anchor = nearestSkinVertex(pp, parts.vertexParts[host], landmarks.points[27]);
  const float sourceRadius = source.parts.eyeRadii[eye];
  const std::vector<size_t> balls = sourceEyeballs(source, eyeballOf(eye));
  if (!anchor || !(sourceRadius > 0.0f) || balls.empty() || source.model == nullptr) return 0;
  const glm::mat3 turn = axesOf(landmarks) * glm::transpose(axesOf(source.landmarks));
  const float scale = kBallInside * at.radius / sourceRadius;
  CarriedPieces& carrier = carriers.try_emplace(host, face, pp, *anchor).first->second;
  size_t carried = 0;
  for (size_t ball : balls) {
    std::vector<glm::vec3> world;
    for (const glm::vec3& q : source.posed.primitives[ball].positions)
      world.push_back(at.centre + turn * (q - source.parts.eyeCentres[eye]) * scale);
    carried += carrier.add(source, ball, world, turn);
  }
  return carried;
}

// The posed primitive holding the skin vertex nearest the bridge of the nose
// (landmark 27): the skin an eyeball set in an empty opening moves with.
std::optional<size_t> skinBetweenTheEyes(const PosedFace& posed, const FaceParts& parts, const FaceLandmarks& landmarks) {
  std::optional<size_t> best;
  float nearest = std::numeric_limits<float>::max();
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const std::optional<uint32_t> v = nearestSkinVertex(posed.primitives[i], parts.vertexParts[i], landmarks.points[27]);
    if (!v) continue;
    const float d = glm::distance(posed.primitives[i].positions[*v], landmarks.points[27]);
    if (d < nearest) nearest = d, best = i;
  }
  return best;
}

}  // namespace

namespace {

// Each painted eye's triangles (all three corners on the ball) that show
// enough at rest to be cut free.
std::vector<EyeCut> eyesToCut(const eng::Model& face, const PosedFace& posed, const FaceParts& parts, const LandmarkFrame& frame) {
  std::vector<EyeCut> cuts;
  for (size_t i = 0; i < posed.primitives.size() && (parts.eyesInTheSkin[0] || parts.eyesInTheSkin[1]); ++i) {
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
  return cuts;
}

// Each eye cut free: its triangles a primitive of their own (set back into
// the head, with a copy of the skin's material named as an eye), the rest of
// the skin's primitive rebuilt without them.
void cutTheEyesFree(eng::Model& face, const PosedFace& posed, const FaceParts& parts, std::span<const EyeCut> cuts,
                    EyeOpening& opening) {
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
}

}  // namespace

EyeOpening openTheEyes(eng::Model& face, const PosedFace& posed, const FaceLandmarks& landmarks, const FaceParts& parts,
                       const SourceFace& source) {
  EyeOpening opening;
  if (parts.vertexParts.size() != posed.primitives.size()) return opening;
  const LandmarkFrame frame(landmarks);
  const std::vector<EyeCut> cuts = eyesToCut(face, posed, parts, frame);
  std::vector<size_t> empty = emptyOpenings(face, posed, parts, landmarks, frame);
  // A ball of skin inside the lids of which too little shows at rest to cut
  // free is no painted eye but the socket's lining of a head exported
  // without its eyeballs (what shows through its opening is the inside of
  // the head): it gets an eyeball set in it, as an empty opening does.
  for (size_t e = 0; e < 2; ++e)
    if (parts.eyesInTheSkin[e] && std::none_of(cuts.begin(), cuts.end(), [&](const EyeCut& cut) { return cut.eye == e; }))
      empty.push_back(e);
  if (cuts.empty() && empty.empty()) return opening;

  // The head's eyeballs behind them first: carried into the mesh as its
  // primitives stand (the cut below rebuilds the skin's), one carrier per
  // skin primitive (the eyes share the head's eye material and its image).
  std::map<size_t, CarriedPieces> carriers;  // by posed skin primitive
  std::map<size_t, std::vector<glm::vec3>> whiteRatios;  // the scan's white over the head's, per carrier
  const std::optional<size_t> bridge = empty.empty() ? std::nullopt : skinBetweenTheEyes(posed, parts, landmarks);
  for (size_t e : empty) {
    const size_t carried =
        bridge ? carryEyeball(face, posed, *bridge, e, eyeballBehindTheLids(landmarks, e), landmarks, parts, source, carriers) : 0;
    if (carried == 0) continue;
    opening.ballVertices += carried;
    ++opening.eyesFilled;
    opening.notes.push_back(meshLabel(face, posed.primitives[*bridge].mesh) + ": nothing behind the " +
                            (e == 0 ? "right" : "left") + " eye's opening; the built-in head's eyeball set in it");
  }
  for (const EyeCut& cut : cuts) {
    const PosedPrimitive& host = posed.primitives[cut.posed];
    const std::vector<size_t> balls = sourceEyeballs(source, eyeballOf(cut.eye));
    const size_t carried = carryEyeball(face, posed, cut.posed, cut.eye, {parts.eyeCentres[cut.eye], parts.eyeRadii[cut.eye]},
                                        landmarks, parts, source, carriers);
    if (carried == 0) continue;
    opening.ballVertices += carried;
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

  cutTheEyesFree(face, posed, parts, cuts, opening);
  return opening;
}

}  // namespace autorig
