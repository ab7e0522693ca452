// Speech on the real faces of ../shared (skipped without it), on the built-in
// head, and on the head stripped of its targets and rigged by the autorig,
// measured on the morphed CPU mesh: at the mouth centre the gap between an
// upper-lip and a lower-lip vertex is closed on p/b/m and at rest, open on aa;
// rounded vowels narrow the mouth. The lip pair is found from the face itself: the lower lip
// is the top of what aa moves down in the centre column, the upper lip the
// nearest vertex above it that aa leaves in place.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <gtest/gtest.h>

#include "autorig/builtin_source.h"
#include "autorig/face_parts.h"
#include "autorig/target_transfer.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "importers/load_face.h"
#include "tests/common/test_meshes.h"
#include "tests/common/test_support.h"

namespace facial {
namespace {

struct SpeakingFace {
  importers::LoadedFace face;
  RigMapping rig;
  eng::WeightLayout layout;
};

// `face` (named `name` for its rig map) with the rig the runtime builds from its targets.
std::optional<SpeakingFace> speakingFace(importers::LoadedFace face, const std::string& name,
                                         const std::filesystem::path& rigmap = {}) {
  eng::WeightLayout layout(face.model);
  const RigMappingOptions options{name, testing_support::sourceDir() / "data" / "rigmaps", rigmap};
  auto rig = face.vrm ? buildVrmRigMapping(face.vrm, layout.names(), options) : buildRigMapping(layout.names(), options);
  if (!rig) {
    ADD_FAILURE() << rig.error().message;
    return std::nullopt;
  }
  return SpeakingFace{std::move(face), std::move(*rig), std::move(layout)};
}

std::optional<SpeakingFace> loadSpeakingFace(const std::filesystem::path& file, const std::filesystem::path& rigmap = {}) {
  auto face = importers::loadFace(file);
  if (!face) {
    ADD_FAILURE() << face.error().message;
    return std::nullopt;
  }
  return speakingFace(std::move(*face), file.stem().string(), rigmap);
}

// The model's weights with one viseme at full weight (none: the rest pose of a
// track, sil = 1), over its default weights.
std::vector<float> weightsAt(const SpeakingFace& f, std::optional<Viseme> viseme) {
  std::vector<float> weights = f.layout.defaults();
  std::vector<float> au(actionUnits().size(), 0.0f), visemes(kVisemeCount, 0.0f);
  visemes[size_t(viseme.value_or(Viseme::sil))] = 1.0f;
  auto applied = f.rig.applyWithVisemes(au, {}, visemes, weights);
  EXPECT_TRUE(applied) << applied.error().message;
  return weights;
}

struct MouthProbe {
  int mesh = -1;
  size_t primitive = 0;
  size_t upper = 0, lower = 0;
  float height = 1.0f;  // the primitive's height, to compare faces of any scale
};

std::vector<glm::vec3> morphed(const SpeakingFace& f, int mesh, size_t primitive, const std::vector<float>& weights) {
  const eng::Primitive& prim = f.face.model.meshes[size_t(mesh)].primitives[primitive];
  std::vector<glm::vec3> out = prim.positions;
  for (size_t t = 0; t < prim.targets.size() && t < f.layout.count(mesh); ++t) {
    const float w = weights[f.layout.offset(mesh) + t];
    if (w == 0.0f) continue;
    for (size_t i = 0; i < out.size(); ++i) out[i] += w * prim.targets[t].positions[i];
  }
  return out;
}

// The primitive aa moves the most vertices of (the skin, not the teeth), and
// on it the lip pair at the mouth centre.
std::optional<MouthProbe> findLips(const SpeakingFace& f) {
  const std::vector<float> rest = weightsAt(f, std::nullopt), open = weightsAt(f, Viseme::aa);
  MouthProbe probe;
  size_t bestMoved = 0;
  std::vector<glm::vec3> at, delta;
  for (int m = 0; m < int(f.face.model.meshes.size()); ++m)
    for (size_t p = 0; p < f.face.model.meshes[size_t(m)].primitives.size(); ++p) {
      const std::vector<glm::vec3> a = morphed(f, m, p, rest), b = morphed(f, m, p, open);
      size_t moved = 0;
      float lo = 1e30f, hi = -1e30f;
      for (size_t i = 0; i < a.size(); ++i) {
        lo = std::min(lo, a[i].y), hi = std::max(hi, a[i].y);
        moved += glm::length(b[i] - a[i]) > 1e-6f * std::max(1.0f, std::abs(hi - lo)) ? 1 : 0;
      }
      if (moved <= bestMoved) continue;
      bestMoved = moved, probe.mesh = m, probe.primitive = p, probe.height = hi - lo, at = a;
      delta.resize(a.size());
      for (size_t i = 0; i < a.size(); ++i) delta[i] = b[i] - a[i];
    }
  if (probe.mesh < 0) return std::nullopt;
  // The centre column: the x of the largest drop, a band of 2 % of the height.
  size_t deepest = 0;
  for (size_t i = 0; i < at.size(); ++i)
    if (delta[i].y < delta[deepest].y) deepest = i;
  const float xc = at[deepest].x, band = 0.02f * probe.height, drop = -delta[deepest].y;
  // Lower lip: the highest front vertex of the column that aa drops by half the most.
  std::optional<size_t> lower;
  for (size_t i = 0; i < at.size(); ++i)
    if (std::abs(at[i].x - xc) < band && -delta[i].y > 0.5f * drop && (!lower || at[i].y > at[*lower].y)) lower = i;
  if (!lower) return std::nullopt;
  // Upper lip: the nearest column vertex at or above it that aa barely moves.
  std::optional<size_t> upper;
  for (size_t i = 0; i < at.size(); ++i) {
    if (std::abs(at[i].x - xc) >= band || -delta[i].y > 0.25f * drop || at[i].y < at[*lower].y - 0.002f * probe.height)
      continue;
    if (!upper || glm::length(at[i] - at[*lower]) < glm::length(at[*upper] - at[*lower])) upper = i;
  }
  if (!upper) return std::nullopt;
  probe.lower = *lower, probe.upper = *upper;
  return probe;
}

// Upper-lip y minus lower-lip y, over the face's height.
float lipGap(const SpeakingFace& f, const MouthProbe& probe, const std::vector<float>& weights) {
  const std::vector<glm::vec3> at = morphed(f, probe.mesh, probe.primitive, weights);
  return (at[probe.upper].y - at[probe.lower].y) / probe.height;
}

void expectLipsCloseAndOpen(const SpeakingFace& f, const std::string& name) {
  SCOPED_TRACE(name);
  ASSERT_TRUE(f.rig.speaks()) << f.rig.report().summary();
  auto probe = findLips(f);
  ASSERT_TRUE(probe) << "no lip pair found";
  const float rest = lipGap(f, *probe, weightsAt(f, std::nullopt));
  const float aa = lipGap(f, *probe, weightsAt(f, Viseme::aa));
  const float pp = lipGap(f, *probe, weightsAt(f, Viseme::PP));
  const float o = lipGap(f, *probe, weightsAt(f, Viseme::O));
  std::printf("%s: lip gap / face height: rest %.4f PP %.4f aa %.4f O %.4f (vertices %zu %zu)\n",
              name.c_str(), rest, pp, aa, o, probe->upper, probe->lower);
  EXPECT_GT(aa, 0.03f);             // the jaw opens on aa
  EXPECT_LT(pp, 0.03f * aa);        // p b m: closed, no gap
  EXPECT_LT(rest, 0.1f * aa);       // rest: lips together
  EXPECT_GT(o, 0.2f * aa);          // O opens, less than aa
}

void expectLipsCloseAndOpen(const std::filesystem::path& file, const std::filesystem::path& rigmap = {}) {
  SCOPED_TRACE(file.string());
  auto f = loadSpeakingFace(file, rigmap);
  ASSERT_TRUE(f);
  expectLipsCloseAndOpen(*f, file.filename().string());
}

TEST(SpeechFaces, LipsCloseOnPpAndAtRestAndOpenOnAa) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path shared = testing_support::sharedDir();
  expectLipsCloseAndOpen(shared / "assets" / "facecap.glb");
  expectLipsCloseAndOpen(shared / "speech" / "rpm-visemes.glb");
  expectLipsCloseAndOpen(shared / "candide3" / "candide3.wfm");
}

// A hand-written map that names only the three mouth channels makes facecap speak.
TEST(SpeechFaces, ARigMapOfMouthChannelsSpeaks) {
  FACIAL_REQUIRE_SHARED();
  const std::filesystem::path rigmap = testing_support::freshTempDir("speech_faces") / "mouth.json";
  std::ofstream(rigmap) << R"({"version": 1, "visemes": {"jawOpen": {"jawOpen": 0.8},
      "lipClosure": {"mouthPress_L": 0.5, "mouthPress_R": 0.5}, "lipRounding": {"mouthPucker": 1}}})";
  expectLipsCloseAndOpen(testing_support::sharedDir() / "assets" / "facecap.glb", rigmap);
}

// The shared VRMs bind their one shape key from 'aa' / 'a' only: every vowel
// still opens it (borrowing aa at its own jaw opening); p b m and rest do not.
TEST(SpeechFaces, VrmAvatarsThatBindOnlyAaSpeakEveryVowel) {
  FACIAL_REQUIRE_SHARED();
  for (const char* file : {"modifier_shapekey_vrm0.vrm", "modifier_shapekey_vrm1.vrm"}) {
    SCOPED_TRACE(file);
    auto f = loadSpeakingFace(testing_support::sharedDir() / "assets" / "vrm" / file);
    ASSERT_TRUE(f);
    ASSERT_EQ(f->layout.total(), 1u);
    EXPECT_FLOAT_EQ(weightsAt(*f, Viseme::aa)[0], 1.0f);
    EXPECT_NEAR(weightsAt(*f, Viseme::E)[0], 0.55f, 1e-5f);
    EXPECT_NEAR(weightsAt(*f, Viseme::O)[0], 0.6f, 1e-5f);
    EXPECT_NEAR(weightsAt(*f, Viseme::U)[0], 0.3f, 1e-5f);
    EXPECT_FLOAT_EQ(weightsAt(*f, Viseme::PP)[0], 0.0f);
    EXPECT_FLOAT_EQ(weightsAt(*f, std::nullopt)[0], 0.0f);
  }
}

TEST(SpeechFaces, BuiltInHeadLipsCloseOnPpAndOpenOnAa) {
  expectLipsCloseAndOpen(testing_support::sourceDir() / "data" / "head.glb");
}

// `file` stripped of its targets and given the built-in head's units by the
// autorig, from the landmarks dlib finds on it (tests/autorig/data/`landmarks`)
// and the parts found on it, as `facial` rigs a face on the fly: a face
// without targets, as a newsreader's scan is made to speak.
std::optional<SpeakingFace> rigged(const std::filesystem::path& file, const char* landmarks) {
  auto head = importers::loadFace(testing_support::sourceDir() / "data" / "head.glb");
  auto face = importers::loadFace(file);
  if (!head || !face) {
    ADD_FAILURE() << (head ? face.error().message : head.error().message);
    return std::nullopt;
  }
  auto source = autorig::builtInSource(head->model);
  if (!source) {
    ADD_FAILURE() << source.error().message;
    return std::nullopt;
  }
  face->model = testing_support::stripped(std::move(face->model));
  auto points = autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data" / landmarks);
  if (!points) {
    ADD_FAILURE() << points.error().message;
    return std::nullopt;
  }
  const autorig::PosedFace posed = autorig::poseAtRest(face->model);
  auto made = autorig::transferTargets(*source, face->model, posed, *points, autorig::findFaceParts(face->model, posed, *points),
                                       {.detailLayers = false});
  if (!made) {
    ADD_FAILURE() << made.error().message;
    return std::nullopt;
  }
  face->model = std::move(made->model);
  return speakingFace(std::move(*face), file.stem().string() + " rigged");
}

// A face without targets speaks through the action units made for it: the
// runtime's visemes as units (viseme_action_units.cpp) close its lips on p, b
// and m and open them on aa, as on the faces that have visemes of their own.
// facecap stripped and rigged closes too (its lips' rims meet at rest, and
// p/b/m press their fronts 0.03 eye spans together), but its 2,120 vertices
// give this probe no centre column: it pairs rims a row apart.
TEST(SpeechFaces, AFaceWithoutTargetsRiggedOnTheFlyClosesItsLipsOnPp) {
  auto head = rigged(testing_support::sourceDir() / "data" / "head.glb", "head.landmarks.json");
  ASSERT_TRUE(head);
  expectLipsCloseAndOpen(*head, "the built-in head stripped and rigged");
}

}  // namespace
}  // namespace facial
