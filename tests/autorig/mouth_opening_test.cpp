#include "autorig/mouth_opening.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <queue>
#include <random>
#include <string>
#include <unordered_map>
#include <utility>

#include <gtest/gtest.h>

#include "autorig/face_frame.h"
#include "engine/scene/position_hash.h"
#include "engine/scene/weights.h"
#include "tests/autorig/transfer_fixture.h"

namespace {

using transfer_fixture::headSource;
using transfer_fixture::loadHead;
using transfer_fixture::stripped;

// The built-in head as a scan often comes: no targets and nothing inside the
// mouth (its mouth's inside, teeth and tongue dropped), only the skin.
eng::Model withoutTheInsideOfTheMouth(const eng::Model& head) {
  eng::Model face = stripped(head);
  for (eng::Mesh& mesh : face.meshes)
    if (mesh.name == "Head") mesh.primitives.resize(1);
  return face;
}

// The same with its lips welded, as a scan's are: the skin's open rim
// inside the lips (where the dropped inside of the mouth joined it) closed by
// moving each lower-lip rim vertex onto the upper-lip rim vertex across from
// it and making them one. `weld` (optional) receives where they were made one.
eng::Model welded(eng::Model face, const autorig::FaceLandmarks& landmarks, std::vector<glm::vec3>* weld = nullptr) {
  const autorig::LandmarkFrame frame(landmarks);
  const float mouthWidth = glm::distance(landmarks.points[48], landmarks.points[54]);
  glm::vec3 lipCentre(0.0f);
  for (size_t i = 60; i < 68; ++i) lipCentre += landmarks.points[i] / 8.0f;
  for (eng::Mesh& mesh : face.meshes) {
    if (mesh.name != "Head") continue;
    eng::Primitive& skin = mesh.primitives[0];  // unskinned, its node at the origin: world space
    std::map<std::pair<uint32_t, uint32_t>, int> edgeUses;
    for (size_t t = 0; t + 2 < skin.indices.size(); t += 3)
      for (int k = 0; k < 3; ++k) ++edgeUses[std::minmax(skin.indices[t + size_t(k)], skin.indices[t + size_t((k + 1) % 3)])];
    // A rim vertex's lip is where its triangles lie (the rims touch: both at the line).
    std::vector<glm::vec3> around(skin.vertexCount(), glm::vec3(0.0f));
    for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
      const uint32_t* i = &skin.indices[t];
      const glm::vec3 centre = (skin.positions[i[0]] + skin.positions[i[1]] + skin.positions[i[2]]) / 3.0f;
      for (int k = 0; k < 3; ++k) around[i[k]] += centre - skin.positions[i[k]];
    }
    std::vector<uint32_t> upper, lower;
    for (const auto& [edge, uses] : edgeUses) {
      if (uses != 1) continue;
      for (uint32_t v : {edge.first, edge.second}) {
        const glm::vec3& q = skin.positions[v];
        if (glm::distance(q, lipCentre) > 0.7f * mouthWidth) continue;
        std::vector<uint32_t>& rim = glm::dot(around[v], frame.up()) >= 0.0f ? upper : lower;
        if (std::find(rim.begin(), rim.end(), v) == rim.end()) rim.push_back(v);
      }
    }
    if (upper.empty()) continue;
    std::map<uint32_t, uint32_t> into;
    for (uint32_t v : lower) {
      const uint32_t u = *std::min_element(upper.begin(), upper.end(), [&](uint32_t a, uint32_t b) {
        return std::abs(frame.sideOf(skin.positions[a]) - frame.sideOf(skin.positions[v])) <
               std::abs(frame.sideOf(skin.positions[b]) - frame.sideOf(skin.positions[v]));
      });
      into[v] = u;
      skin.positions[u] = (skin.positions[u] + skin.positions[v]) * 0.5f;
    }
    std::vector<uint32_t> indices;
    for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
      uint32_t tri[3];
      for (int k = 0; k < 3; ++k) {
        const auto it = into.find(skin.indices[t + size_t(k)]);
        tri[k] = it == into.end() ? skin.indices[t + size_t(k)] : it->second;
      }
      if (tri[0] != tri[1] && tri[1] != tri[2] && tri[0] != tri[2]) indices.insert(indices.end(), tri, tri + 3);
    }
    skin.indices = std::move(indices);
    if (weld)
      for (uint32_t u : upper) weld->push_back(skin.positions[u]);
  }
  return face;
}

// The head as an STL holds it (its one surface welded wherever two corners
// meet): the skin and the mouth's inside made one primitive without UVs,
// every pair of vertices at one place made one. The head's closed lips then
// join twice: at their outer contact and at their inner rims, where the
// mouth's inside meets them.
eng::Model weldedLikeAnStl(eng::Model face) {
  for (eng::Mesh& mesh : face.meshes) {
    if (mesh.name != "Head") continue;
    eng::Primitive merged;
    merged.material = mesh.primitives[0].material;
    std::unordered_map<eng::ExactPosition, uint32_t, eng::ExactPosition::Hash> at;
    for (size_t p = 0; p < 2; ++p) {
      const eng::Primitive& prim = mesh.primitives[p];
      for (uint32_t i : prim.indices) {
        const auto [it, added] = at.try_emplace(eng::ExactPosition(prim.positions[i]), uint32_t(merged.positions.size()));
        if (added) {
          merged.positions.push_back(prim.positions[i]);
          merged.normals.push_back(prim.normals[i]);
        }
        merged.indices.push_back(it->second);
      }
    }
    mesh.primitives.erase(mesh.primitives.begin(), mesh.primitives.begin() + 2);
    mesh.primitives.insert(mesh.primitives.begin(), std::move(merged));
  }
  return face;
}

size_t vertexCount(const eng::Model& model) {
  size_t n = 0;
  for (const eng::Mesh& mesh : model.meshes)
    for (const eng::Primitive& prim : mesh.primitives) n += prim.vertexCount();
  return n;
}

struct Opened {
  eng::Model face;
  autorig::MouthOpening opening;
};

Opened open(eng::Model face, const autorig::SourceFace& source) {
  const autorig::FaceLandmarks& landmarks = source.landmarks;
  const autorig::PosedFace posed = autorig::poseAtRest(face);
  const autorig::FaceParts parts = autorig::findFaceParts(face, posed, landmarks);
  Opened opened{std::move(face), {}};
  opened.opening = autorig::openTheMouth(opened.face, posed, landmarks, parts, source);
  return opened;
}

// The opened face rigged (its shapes only), as FaceAutorig::rig rigs it: its
// mesh named "Head" and the index of its AU26 (jaw drop) target.
struct RiggedJaw {
  eng::Model model;
  const eng::Mesh* mesh = nullptr;
  size_t jaw = 0;
};
void rigTheJaw(const Opened& opened, const autorig::SourceFace& source, RiggedJaw& out) {
  const autorig::PosedFace posed = autorig::poseAtRest(opened.face);
  const autorig::FaceParts parts = autorig::findFaceParts(opened.face, posed, source.landmarks);
  eng::Result<autorig::TransferResult> rigged =
      autorig::transferTargets(source, opened.face, posed, source.landmarks, parts, transfer_fixture::kShapesOnly);
  ASSERT_TRUE(rigged) << rigged.error().message;
  out.model = std::move(rigged->model);
  for (const eng::Mesh& m : out.model.meshes)
    if (m.name == "Head") out.mesh = &m;
  ASSERT_TRUE(out.mesh);
  const auto jaw = std::find(out.mesh->targetNames.begin(), out.mesh->targetNames.end(), "AU26_JawDrop");
  ASSERT_NE(jaw, out.mesh->targetNames.end());
  out.jaw = size_t(jaw - out.mesh->targetNames.begin());
  ASSERT_EQ(out.mesh->primitives[0].targets[out.jaw].positions.size(), out.mesh->primitives[0].vertexCount());
}

// Whether the skin of the mesh named "Head" joins the vertex nearest landmark
// `from` to the one nearest `to` through the mouth's front between its corners
// (`inset` of the mouth's width within them; below 0, past them), in front of its inside.
bool lipsJoined(const eng::Model& face, const autorig::FaceLandmarks& landmarks, size_t from, size_t to,
                float inset = 0.1f) {
  const autorig::PosedFace posed = autorig::poseAtRest(face);
  const autorig::LandmarkFrame frame(landmarks);
  const auto& p = landmarks.points;
  const float left = frame.sideOf(p[48]), right = frame.sideOf(p[54]);
  inset *= right - left;
  glm::vec3 lipCentre(0.0f);
  for (size_t i = 60; i < 68; ++i) lipCentre += p[i] / 8.0f;
  for (const autorig::PosedPrimitive& pp : posed.primitives) {
    if (face.meshes[pp.mesh].name != "Head" || pp.primitive != 0) continue;
    const eng::Primitive& prim = face.meshes[pp.mesh].primitives[pp.primitive];
    auto inMouth = [&](uint32_t v) {
      const glm::vec3& q = pp.positions[v];
      return frame.sideOf(q) > left + inset && frame.sideOf(q) < right - inset && std::abs(frame.aboveLipLine(q)) < 0.2f &&
             glm::dot(q - lipCentre, frame.forward()) > -0.3f * frame.eyeSpan();
    };
    auto nearest = [&](const glm::vec3& q) {
      uint32_t best = 0;
      for (uint32_t v = 0; v < pp.positions.size(); ++v)
        if (glm::distance(pp.positions[v], q) < glm::distance(pp.positions[best], q)) best = v;
      return best;
    };
    std::vector<std::vector<uint32_t>> neighbours(prim.vertexCount());
    for (size_t t = 0; t + 2 < prim.indices.size(); t += 3)
      for (int k = 0; k < 3; ++k) {
        const uint32_t a = prim.indices[t + size_t(k)], b = prim.indices[t + size_t((k + 1) % 3)];
        if (inMouth(a) && inMouth(b)) neighbours[a].push_back(b), neighbours[b].push_back(a);
      }
    const uint32_t start = nearest(p[from]), goal = nearest(p[to]);
    std::vector<char> seen(prim.vertexCount(), 0);
    std::queue<uint32_t> queue;
    queue.push(start);
    seen[start] = 1;
    while (!queue.empty()) {
      const uint32_t v = queue.front();
      queue.pop();
      if (v == goal) return true;
      for (uint32_t w : neighbours[v])
        if (!seen[w]) seen[w] = 1, queue.push(w);
    }
  }
  return false;
}

TEST(MouthOpening, LeavesAFaceWithSeparateLipsAndAMouthAlone) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  const Opened opened = open(stripped(*head), source);
  EXPECT_FALSE(opened.opening.changed());
  EXPECT_TRUE(opened.opening.notes.empty());
  EXPECT_EQ(vertexCount(opened.face), vertexCount(*head));
}

// Whether lips are welded must not hang on where dlib puts the lip points.
// Closed lips under a moustache were seen parted (the upper lip's inner
// points 0.05 eye span high, the corners 0.04): the line where they meet ran
// between the rims, one lip's rim, curling in, reached as far across it as
// the other lip, and separate lips were cut (torn corners at a dropped jaw
// on that avatar). Told by the height off that line, 9 of these 11 separate
// mouths were cut and one welded mouth was not (its corner's nearest vertex
// was a welded copy no triangle used); with noise of 0.02 to 0.04 eye span on
// dlib's points, 18 of 42 rigs of three faces cut separate lips
// (tools/landmark_noise.py).
TEST(MouthOpening, TellsWeldedFromSeparateLipsWhereverTheLipPointsLie) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  autorig::SourceFace source = headSource(*head);
  const autorig::FaceLandmarks atRest = source.landmarks;
  const autorig::LandmarkFrame frame(atRest);
  const eng::Model separate = stripped(*head), weldedLips = welded(withoutTheInsideOfTheMouth(*head), atRest);
  struct Seen {
    std::string how;
    autorig::FaceLandmarks landmarks;
  };
  std::vector<Seen> seen;
  auto moved = [&](std::initializer_list<size_t> points, float rise) {
    autorig::FaceLandmarks l = atRest;
    for (size_t i : points) l.points[i] += rise * frame.eyeSpan() * frame.up();
    return l;
  };
  seen.push_back({"the lower lip's inner points 0.04 eye span low", moved({65, 66, 67}, -0.04f)});
  seen.push_back({"the lower lip's inner points 0.1 eye span low", moved({65, 66, 67}, -0.1f)});
  seen.push_back({"the lip line 0.1 eye span high", moved({48, 54, 60, 61, 62, 63, 64, 65, 66, 67}, 0.1f)});
  std::mt19937 random(7);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  for (int draw = 0; draw < 8; ++draw) {
    autorig::FaceLandmarks l = atRest;
    for (size_t i = 48; i < 68; ++i) l.points[i] += frame.eyeSpan() * (noise(random) * frame.side() + noise(random) * frame.up());
    seen.push_back({"noise of 0.02 eye span on the lip points, draw " + std::to_string(draw), l});
  }
  for (const Seen& s : seen) {
    source.landmarks = s.landmarks;
    EXPECT_EQ(open(separate, source).opening.cutVertices, 0u) << "separate lips, " << s.how;
    EXPECT_GE(open(weldedLips, source).opening.cutVertices, 10u) << "welded lips, " << s.how;
  }
}

TEST(MouthOpening, GivesAMouthWithNothingInsideTheHeadsTeethAndTongue) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  const eng::Model face = withoutTheInsideOfTheMouth(*head);
  const Opened opened = open(face, source);
  EXPECT_EQ(opened.opening.cutVertices, 0u) << "the head's lips are separate";
  ASSERT_GT(opened.opening.insideVertices, 0u);
  ASSERT_EQ(opened.opening.notes.size(), 1u);
  EXPECT_NE(opened.opening.notes[0].find("teeth and tongue"), std::string::npos) << opened.opening.notes[0];

  const eng::Mesh* mesh = nullptr;
  for (const eng::Mesh& m : opened.face.meshes)
    if (m.name == "Head") mesh = &m;
  ASSERT_TRUE(mesh);
  ASSERT_EQ(mesh->primitives.size(), head->meshes[0].primitives.size()) << "the mouth's inside, two rows of teeth, a tongue";
  size_t added = 0;
  for (size_t i = 1; i < mesh->primitives.size(); ++i) {
    const eng::Primitive& piece = mesh->primitives[i];
    added += piece.vertexCount();
    EXPECT_EQ(piece.targets.size(), mesh->targetNames.size());
    ASSERT_GE(piece.material, 0);
    EXPECT_EQ(opened.face.materials[size_t(piece.material)].name,
              head->materials[size_t(head->meshes[0].primitives[i].material)].name);
    // Seen from inside only: its back, where the face's lips pass it, is not drawn.
    EXPECT_FALSE(opened.face.materials[size_t(piece.material)].doubleSided) << opened.face.materials[size_t(piece.material)].name;
  }
  EXPECT_EQ(added, opened.opening.insideVertices);

  // The parts finder takes them for what they are.
  const autorig::PosedFace posed = autorig::poseAtRest(opened.face);
  const autorig::FaceParts parts = autorig::findFaceParts(opened.face, posed, source.landmarks);
  size_t upperTeeth = 0, lowerTeeth = 0, tongue = 0;
  for (const std::vector<autorig::FacePart>& vertexParts : parts.vertexParts)
    for (autorig::FacePart part : vertexParts) {
      upperTeeth += part == autorig::FacePart::UpperTeeth;
      lowerTeeth += part == autorig::FacePart::LowerTeeth;
      tongue += part == autorig::FacePart::Tongue;
    }
  EXPECT_GT(upperTeeth, 0u);
  EXPECT_GT(lowerTeeth, 0u);
  EXPECT_GT(tongue, 0u);

  // Behind the skin: every carried vertex lies deeper (along the face's
  // forward) than the skin in front of it, the closed lips' line aside.
  const autorig::LandmarkFrame frame(source.landmarks);
  const eng::Primitive& skin = mesh->primitives[0];  // the head is not skinned and its node is at the origin
  const float cell = 0.03f * frame.eyeSpan();
  size_t checked = 0, inFront = 0;
  for (size_t i = 1; i < mesh->primitives.size(); ++i)
    for (size_t v = 0; v < mesh->primitives[i].vertexCount(); v += 7) {
      const glm::vec3& q = mesh->primitives[i].positions[v];
      float skinDepth = -INFINITY;
      for (const glm::vec3& s : skin.positions) {
        const glm::vec3 d = s - q;
        if (std::abs(glm::dot(d, frame.side())) < cell && std::abs(glm::dot(d, frame.up())) < cell &&
            std::abs(frame.aboveLipLine(s)) > 0.02f)
          skinDepth = std::max(skinDepth, glm::dot(s, frame.forward()));
      }
      if (!std::isfinite(skinDepth)) continue;
      ++checked;
      inFront += glm::dot(q, frame.forward()) >= skinDepth;
    }
  EXPECT_GT(checked, 200u);
  EXPECT_EQ(inFront, 0u) << "of " << checked << " carried vertices";
}

TEST(MouthOpening, CutsWeldedLipsBetweenTheCorners) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  std::vector<glm::vec3> weld;
  const eng::Model face = welded(withoutTheInsideOfTheMouth(*head), source.landmarks, &weld);
  ASSERT_TRUE(lipsJoined(face, source.landmarks, 62, 66)) << "the welded lips are one surface";
  size_t before = 0;  // skin vertices before the cut: the copies come after them
  for (const eng::Mesh& m : face.meshes)
    if (m.name == "Head") before = m.primitives[0].vertexCount();
  const Opened opened = open(face, source);
  EXPECT_GT(opened.opening.cutVertices, 10u);
  // The cut runs along the weld (the crease), not a row or two off it: a
  // strip of the lower lip left on the upper made the opening's edge steps.
  const autorig::LandmarkFrame frame(source.landmarks);
  const float left = frame.sideOf(source.landmarks.points[48]), right = frame.sideOf(source.landmarks.points[54]);
  size_t offTheWeld = 0, weldBetweenTheCorners = 0;
  for (const glm::vec3& w : weld) weldBetweenTheCorners += frame.sideOf(w) > left && frame.sideOf(w) < right;
  for (const eng::Mesh& m : opened.face.meshes) {
    if (m.name != "Head") continue;
    const eng::Primitive& skin = m.primitives[0];
    for (size_t v = before; v < skin.vertexCount(); ++v)
      offTheWeld += std::none_of(weld.begin(), weld.end(), [&](const glm::vec3& w) { return glm::distance(w, skin.positions[v]) < 1e-6f; });
  }
  EXPECT_EQ(offTheWeld, 0u) << "of " << opened.opening.cutVertices << " cut vertices";
  EXPECT_GE(opened.opening.cutVertices + 2, weldBetweenTheCorners) << "the weld between the corners is cut";
  EXPECT_FALSE(lipsJoined(opened.face, source.landmarks, 62, 66)) << "cut, the lips meet only past the corners";
  // The corners stay joined: the cut ends inside them.
  EXPECT_TRUE(lipsJoined(opened.face, source.landmarks, 49, 59, -0.1f));
}

// Rigged, the welded head opens its mouth: at AU26 the lips' middle parts.
TEST(MouthOpening, AWeldedMouthOpensWhenRigged) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  const eng::Model face = welded(withoutTheInsideOfTheMouth(*head), source.landmarks);
  size_t before = 0;  // skin vertices before the cut: the copies come after them
  for (const eng::Mesh& m : face.meshes)
    if (m.name == "Head") before = m.primitives[0].vertexCount();
  const Opened opened = open(face, source);
  RiggedJaw rigged;  // teeth from the source, as FaceAutorig::rig says of a face given the head's mouth
  ASSERT_NO_FATAL_FAILURE(rigTheJaw(opened, source, rigged));
  const eng::Mesh* mesh = rigged.mesh;
  const eng::Primitive& skin = mesh->primitives[0];
  const eng::MorphTarget& drop = skin.targets[rigged.jaw];
  // The seam's twins (a vertex and its copy, at one place at rest) about the
  // middle of the mouth move apart at AU26 1 by a good share of the mouth's width.
  const float mouthWidth = glm::distance(source.landmarks.points[48], source.landmarks.points[54]);
  const glm::vec3 middle = (source.landmarks.points[62] + source.landmarks.points[66]) * 0.5f;
  size_t twins = 0;
  float narrowest = INFINITY;
  for (size_t a = 0; a < before; ++a) {
    if (glm::distance(skin.positions[a], middle) > 0.15f * mouthWidth) continue;
    for (size_t b = before; b < skin.vertexCount(); ++b) {
      if (glm::distance(skin.positions[a], skin.positions[b]) > 1e-7f) continue;
      ++twins;
      narrowest = std::min(narrowest, glm::length(drop.positions[a] - drop.positions[b]) / mouthWidth);
    }
  }
  std::printf("welded head at AU26 1: %zu seam twins about the middle, at least %.2f of the mouth's width apart\n", twins,
              narrowest);
  EXPECT_GE(twins, 3u);
  EXPECT_GT(narrowest, 0.2f);

  // The teeth carried in: the lower row drops with the jaw, the upper stays.
  std::vector<float> teethTravel;
  for (const eng::Primitive& piece : mesh->primitives) {
    if (piece.material < 0 || rigged.model.materials[size_t(piece.material)].name != "Teeth") continue;
    const eng::MorphTarget& target = piece.targets[rigged.jaw];
    float travel = 0.0f;
    for (const glm::vec3& d : target.positions) travel = std::max(travel, glm::length(d));
    teethTravel.push_back(travel / mouthWidth);
  }
  ASSERT_EQ(teethTravel.size(), 2u);
  std::sort(teethTravel.begin(), teethTravel.end());
  std::printf("teeth at AU26 1: upper row %.3f, lower row %.3f of the mouth's width\n", teethTravel[0], teethTravel[1]);
  EXPECT_LT(teethTravel[0], 0.01f);
  // The lower row drops about as far as the head's own (it floated at 0.67
  // of that when it turned only as far as the lips' opening asked).
  float own = 0.0f;
  for (const eng::Mesh& m : head->meshes) {
    const auto unit = std::find(m.targetNames.begin(), m.targetNames.end(), "AU26_JawDrop");
    if (unit == m.targetNames.end()) continue;
    for (const eng::Primitive& piece : m.primitives) {
      if (piece.material < 0 || head->materials[size_t(piece.material)].name != "Teeth") continue;
      for (const glm::vec3& d : piece.targets[size_t(unit - m.targetNames.begin())].positions)
        own = std::max(own, glm::length(d) / mouthWidth);
    }
  }
  std::printf("the head's own lower row at AU26 1: %.3f of the mouth's width\n", own);
  EXPECT_GT(teethTravel[1], 0.85f * own);
  EXPECT_LT(teethTravel[1], 1.6f * own);
}

// Welded twice (an STL of a head whose closed lips are separate surfaces),
// the lips are cut at both lines: rigged, no sheet of skin spans the opening
// at AU26. One cut (along the inner line) left the outer contact joined, and
// the lower lip stretched up to the upper across the mouth.
TEST(MouthOpening, LipsWeldedTwiceOpenWithoutASheetAcrossTheMouth) {
  std::optional<eng::Model> head = loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = headSource(*head);
  const Opened opened = open(weldedLikeAnStl(stripped(*head)), source);
  RiggedJaw rigged;
  ASSERT_NO_FATAL_FAILURE(rigTheJaw(opened, source, rigged));
  const eng::Primitive& skin = rigged.mesh->primitives[0];
  const std::vector<glm::vec3>& drop = skin.targets[rigged.jaw].positions;
  // Triangles about the mouth's middle that AU26 stretches to more than four
  // times their rest length and past a tenth of the mouth's width.
  const auto& p = source.landmarks.points;
  const float mouthWidth = glm::distance(p[48], p[54]);
  const glm::vec3 middle = (p[62] + p[66]) * 0.5f;
  size_t stretched = 0;
  for (size_t t = 0; t + 2 < skin.indices.size(); t += 3) {
    const uint32_t* i = &skin.indices[t];
    if (glm::distance(skin.positions[i[0]], middle) > 0.3f * mouthWidth) continue;
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = i[k], b = i[(k + 1) % 3];
      const float rest = glm::distance(skin.positions[a], skin.positions[b]);
      const float opened = glm::distance(skin.positions[a] + drop[a], skin.positions[b] + drop[b]);
      if (opened > 4.0f * rest && opened > 0.1f * mouthWidth) {
        ++stretched;
        break;
      }
    }
  }
  std::printf("the head welded as an STL: %zu seam vertices cut, %zu triangles about the mouth stretched across it at AU26\n",
              opened.opening.cutVertices, stretched);
  EXPECT_EQ(stretched, 0u);
}

}  // namespace
