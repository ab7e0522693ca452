// How far the made units move a face's features, in the face's own size,
// against how far the built-in head's own units move the head's: the jaw's
// opening as the inner lips' gap over the mouth's width, the brows and lids
// in eye spans. A made face whose jaw opens half as wide as the head's (for
// its proportions) reads as a snarl, not surprise (issue 33).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "autorig/dense_correspondence.h"
#include "autorig/face_frame.h"
#include "engine/scene/gltf_loader.h"
#include "tests/autorig/transfer_fixture.h"
#include "tests/common/test_support.h"

namespace {

// A face with its unit targets, its rest pose, landmarks and skin.
struct Measured {
  const eng::Model* model = nullptr;
  autorig::PosedFace posed;
  autorig::FaceLandmarks landmarks;
  autorig::FaceSurface skin;
  std::vector<autorig::FaceRegion> regions;
};

Measured measured(const eng::Model& model, autorig::PosedFace posed, const autorig::FaceLandmarks& landmarks) {
  Measured m{.model = &model, .posed = std::move(posed), .landmarks = landmarks, .skin = {}, .regions = {}};
  const autorig::FaceParts parts = autorig::findFaceParts(model, m.posed, landmarks);
  m.skin = autorig::gatherSurface(model, m.posed, parts, {autorig::FacePart::Skin});
  m.regions = autorig::labelRegions(m.skin, autorig::LandmarkFrame(landmarks));
  return m;
}

// The world displacement of skin vertex `v` under `target` at 1.
glm::vec3 skinMotion(const Measured& m, size_t v, const char* target) {
  const autorig::FaceSurface::VertexRef ref = m.skin.vertices[v];
  const autorig::PosedPrimitive& posed = m.posed.primitives[ref.primitive];
  const eng::Mesh& mesh = m.model->meshes[posed.mesh];
  const auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), target);
  if (it == mesh.targetNames.end()) return glm::vec3(0.0f);
  const eng::MorphTarget& t = mesh.primitives[posed.primitive].targets[size_t(it - mesh.targetNames.begin())];
  return glm::inverse(posed.worldToLocal[ref.vertex]) * t.positions[ref.vertex];
}

// The world displacement, under `target` at 1, of the skin vertex nearest
// landmark `index` (on the landmark's own lip for the inner lips).
glm::vec3 motion(const Measured& m, size_t index, const char* target) {
  const autorig::FaceRegion wanted = index >= 61 && index <= 63   ? autorig::FaceRegion::UpperLip
                                     : index >= 65 && index <= 67 ? autorig::FaceRegion::LowerLip
                                                                  : autorig::FaceRegion::None;
  size_t best = m.skin.positions.size();
  float bestDistance = std::numeric_limits<float>::max();
  for (size_t v = 0; v < m.skin.positions.size(); ++v) {
    if (wanted != autorig::FaceRegion::None && m.regions[v] != wanted) continue;
    const float d = glm::length(m.skin.positions[v] - m.landmarks.points[index]);
    if (d < bestDistance) bestDistance = d, best = v;
  }
  if (best == m.skin.positions.size()) return glm::vec3(0.0f);
  return skinMotion(m, best, target);
}

// A mouth's units and their weights.
using Weighted = std::vector<std::pair<const char*, float>>;
const Weighted kJawOpening{{"AU26_JawDrop", 1.0f}, {"AU25_LipsPart", 1.0f}};
// Anger's and disgust's lip units (data/expressions.json), no jaw.
const Weighted kAngerMouth{{"AU9_NoseWrinkler", 0.35f}, {"AU10_UpperLipRaiser", 0.9f}, {"AU16_LowerLipDepressor", 0.4f},
                           {"AU17_ChinRaiser", 0.3f}, {"AU23_LipTightener", 0.5f}, {"AU25_LipsPart", 0.95f}};
const Weighted kDisgustMouth{{"AU9_NoseWrinkler", 1.0f}, {"AU10_UpperLipRaiser", 0.9f}, {"AU15_LipCornerDepressor", 0.7f},
                             {"AU16_LowerLipDepressor", 0.5f}, {"AU17_ChinRaiser", 0.4f}, {"AU25_LipsPart", 0.3f}};

// Every edge between two lip-region vertices, at rest and with `units`
// applied, both over the skin's size (its box's diagonal).
struct LipEdge {
  float rest = 0.0f, moved = 0.0f;
};
std::vector<LipEdge> lipEdges(const Measured& m, const Weighted& units) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::vec3& p : m.skin.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const float size = glm::length(hi - lo);
  auto lip = [&](uint32_t v) { return m.regions[v] == autorig::FaceRegion::UpperLip || m.regions[v] == autorig::FaceRegion::LowerLip; };
  auto moved = [&](uint32_t v) {
    glm::vec3 p = m.skin.positions[v];
    for (const auto& [unit, weight] : units) p += weight * skinMotion(m, v, unit);
    return p;
  };
  std::vector<LipEdge> edges;
  for (const auto& t : m.skin.triangles)
    for (size_t k = 0; k < 3; ++k) {
      const uint32_t a = t[k], b = t[(k + 1) % 3];
      if (lip(a) && lip(b))
        edges.push_back({glm::length(m.skin.positions[a] - m.skin.positions[b]) / size, glm::length(moved(a) - moved(b)) / size});
    }
  return edges;
}

// How far `units` stretch the skin about the mouth: the largest growth of a
// lip edge, over the skin's size.
float largestLipStretch(const Measured& m, const Weighted& units) {
  float largest = 0.0f;
  for (const LipEdge& e : lipEdges(m, units)) largest = std::max(largest, e.moved - e.rest);
  return largest;
}

// How many lip edges `units` stretch past `times` their length and by more
// than a hundredth of the skin's size.
size_t tornLipEdges(const Measured& m, const Weighted& units, float times) {
  const std::vector<LipEdge> edges = lipEdges(m, units);
  return size_t(std::count_if(edges.begin(), edges.end(),
                              [&](const LipEdge& e) { return e.moved > times * e.rest && e.moved - e.rest > 0.01f; }));
}

// The features a unit moves, each as one number in the face's size.
struct Amounts {
  float lipGap = 0.0f;       // inner lips apart (61-63 against 65-67), over the mouth's width
  float upperLipUp = 0.0f;   // of which the upper lip's rise
  float chinDown = 0.0f;     // chin 8 down, over the mouth's width
  float cornersDown = 0.0f;  // lip corners 48/54 down, over the mouth's width
  float innerBrowUp = 0.0f;  // 21/22 up, eye spans
  float outerBrowUp = 0.0f;  // 17/26 up, eye spans
  float upperLidUp = 0.0f;   // 37/38/43/44 up, over the lids' opening
  float mouthWider = 0.0f;   // lip corners 48-54 apart, over the mouth's width (< 0: narrower)
};

Amounts amounts(const Measured& m, const char* target) {
  const autorig::LandmarkFrame frame(m.landmarks);
  const glm::vec3 up = frame.up();
  const auto& p = m.landmarks.points;
  const float mouth = glm::length(p[54] - p[48]);
  const float eye = frame.eyeSpan();
  auto rise = [&](std::initializer_list<size_t> points) {
    float sum = 0.0f;
    for (size_t i : points) sum += glm::dot(motion(m, i, target), up);
    return sum / float(points.size());
  };
  const float opening = glm::dot((p[37] + p[38] + p[43] + p[44]) - (p[41] + p[40] + p[47] + p[46]), up) * 0.25f;
  return {.lipGap = (rise({61, 62, 63}) - rise({65, 66, 67})) / mouth,
          .upperLipUp = rise({61, 62, 63}) / mouth,
          .chinDown = -rise({8}) / mouth,
          .cornersDown = -rise({48, 54}) / mouth,
          .innerBrowUp = rise({21, 22}) / eye,
          .outerBrowUp = rise({17, 26}) / eye,
          .upperLidUp = rise({37, 38, 43, 44}) / opening,
          .mouthWider = glm::dot(motion(m, 54, target) - motion(m, 48, target), (p[54] - p[48]) / mouth) / mouth};
}

void print(const char* face, const char* unit, const Amounts& a) {
  std::printf("%-10s %-24s gap %6.3f (upper %6.3f) chin %6.3f corners %6.3f brow in %6.3f out %6.3f lid %6.3f wider %6.3f\n", face, unit,
              a.lipGap, a.upperLipUp, a.chinDown, a.cornersDown, a.innerBrowUp, a.outerBrowUp, a.upperLidUp, a.mouthWider);
}

constexpr const char* kUnits[] = {"AU26_JawDrop", "AU27_MouthStretch", "AU25_LipsPart", "AU1_InnerBrowRaiser",
                                  "AU2_OuterBrowRaiser_L", "AU5_UpperLidRaiser", "AU15_LipCornerDepressor",
                                  "AU4_BrowLowerer", "AU12_LipCornerPuller_L", "AU45_Blink_L", "AU7_LidTightener"};

struct StrippedAndRigged {
  eng::Model model;
  autorig::FaceLandmarks landmarks;
};

std::optional<StrippedAndRigged> rigStripped(const std::filesystem::path& file, const char* landmarksFile) {
  eng::Result<eng::Model> face = eng::loadModel(file);
  if (!face) {
    ADD_FAILURE() << face.error().message;
    return std::nullopt;
  }
  const eng::Model bare = transfer_fixture::stripped(std::move(*face));
  const autorig::PosedFace posed = autorig::poseAtRest(bare);
  StrippedAndRigged r;
  std::optional<autorig::TransferResult> result =
      transfer_fixture::rigWithFixtureLandmarks(bare, posed, landmarksFile, &r.landmarks, transfer_fixture::kShapesOnly);
  if (!result) return std::nullopt;
  r.model = std::move(result->model);
  return r;
}

TEST(ExpressionAmounts, TheMouthOpensWithoutTearingTheLips) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path shared = testing_support::sharedDir();
  for (const auto& [file, landmarks] : {std::pair{"assets/facecap.glb", "facecap.landmarks.json"},
                                        std::pair{"speech/rpm-visemes.glb", "rpm-visemes.landmarks.json"}}) {
    std::optional<StrippedAndRigged> made = rigStripped(shared / file, landmarks);
    ASSERT_TRUE(made) << file;
    const Measured m = measured(made->model, autorig::poseAtRest(made->model), made->landmarks);
    const float jaw = largestLipStretch(m, kJawOpening), anger = largestLipStretch(m, kAngerMouth),
                disgust = largestLipStretch(m, kDisgustMouth);
    std::printf("%s: an edge of the lips' skin lengthens by at most %.4f of the skin's size (jaw), %.4f (anger's lips), "
                "%.4f (disgust's)\n", file, jaw, anger, disgust);
    // Measured 0.031 on facecap and 0.044 on the avatar (the lining inside its mouth corners
    // opens with the lips, the edge across them the longest: 0.033 while the upper lip's skin
    // there could take the lower lip's motion); 0.051 and 0.061 before torn lips were mended
    // (slivers hanging inside the mouth's corners, a notch in facecap's lower lip).
    EXPECT_LT(jaw, 0.05f) << file;
    EXPECT_LT(anger, 0.04f) << file;
    EXPECT_LT(disgust, 0.04f) << file;
    // Anger's and disgust's lips part without the jaw; torn there, the lining
    // inside the avatar's mouth corners hung over its teeth as dark spikes.
    // Edges stretched past 3 times their length: 0 and 0 on both (2 and 0 on
    // the avatar while its upper lip's skin at the corners could take the
    // lower lip's motion, 18 and 20 then with the upper lip drawn back);
    // 11 and 13, 16 and 18 when only jaw units mended tears.
    const size_t angerTorn = tornLipEdges(m, kAngerMouth, 3.0f), disgustTorn = tornLipEdges(m, kDisgustMouth, 3.0f);
    std::printf("%s: anger's lips tear %zu edges, disgust's %zu\n", file, angerTorn, disgustTorn);
    EXPECT_LE(angerTorn, 4u) << file;
    EXPECT_LE(disgustTorn, 4u) << file;
  }
}

TEST(ExpressionAmounts, MadeUnitsMoveFeaturesAsFarAsTheHeads) {
  FACIAL_REQUIRE_SHARED();
  const std::optional<eng::Model> head = transfer_fixture::loadHead();
  ASSERT_TRUE(head);
  const autorig::SourceFace source = transfer_fixture::headSource(*head);
  const Measured own = measured(*head, source.posed, source.landmarks);
  const std::filesystem::path shared = testing_support::sharedDir();
  std::optional<StrippedAndRigged> facecap = rigStripped(shared / "assets/facecap.glb", "facecap.landmarks.json");
  std::optional<StrippedAndRigged> rpm = rigStripped(shared / "speech/rpm-visemes.glb", "rpm-visemes.landmarks.json");
  ASSERT_TRUE(facecap && rpm);
  const Measured madeFacecap = measured(facecap->model, autorig::poseAtRest(facecap->model), facecap->landmarks);
  const Measured madeRpm = measured(rpm->model, autorig::poseAtRest(rpm->model), rpm->landmarks);
  for (const char* unit : kUnits) {
    print("head", unit, amounts(own, unit));
    print("facecap", unit, amounts(madeFacecap, unit));
    print("rpm", unit, amounts(madeRpm, unit));
  }
  for (const Measured* made : {&madeFacecap, &madeRpm}) {
    const char* face = made == &madeFacecap ? "facecap" : "rpm";
    // The jaw turns the chin as far down for the mouth's width as the head's
    // (measured 0.92 to 0.96 of the head's), and the lips part well over two
    // thirds as wide (0.71 to 0.76: the lips' own parting beyond the jaw's
    // turn is carried, not forced to the head's; forced, facecap's made
    // jawOpen moved 1.24 times its own, now 0.99; the chin's angle alone
    // opened rpm's lips 0.29 of its width against the head's 0.44).
    for (const char* jaw : {"AU26_JawDrop", "AU27_MouthStretch"}) {
      EXPECT_NEAR(amounts(*made, jaw).chinDown / amounts(own, jaw).chinDown, 1.0f, 0.1f) << face << " " << jaw;
      EXPECT_GT(amounts(*made, jaw).lipGap / amounts(own, jaw).lipGap, 0.65f) << face << " " << jaw;
    }
    // The upper lid rises over its eyeball (rpm's half-ball eyes once put the
    // turn's centre inside the lid: 0.28 of the opening against the head's 0.51).
    EXPECT_GT(amounts(*made, "AU5_UpperLidRaiser").upperLidUp, 0.65f * amounts(own, "AU5_UpperLidRaiser").upperLidUp) << face;
    EXPECT_GT(amounts(*made, "AU1_InnerBrowRaiser").innerBrowUp, 0.75f * amounts(own, "AU1_InnerBrowRaiser").innerBrowUp) << face;
    EXPECT_GT(amounts(*made, "AU15_LipCornerDepressor").cornersDown,
              0.75f * amounts(own, "AU15_LipCornerDepressor").cornersDown) << face;
  }
}

}  // namespace
