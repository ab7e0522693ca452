// End to end: the study's way of handing over a face -- one OBJ per
// expression, same mesh -- through `facial convert` (folder form) to a glTF
// that `facial express` and the headless `facial demo` drive with the seven
// emotions through a rig map that says which target is which emotion.
//
// The test writes the set itself: the built-in head posed with each basic
// preset (CPU morph), exported as position-only OBJs under artist-style names
// that no built-in rig scheme recognises (smile.obj, frown.obj, ...), so the
// rig map is what makes the set usable.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "app/face_setup.h"
#include "engine/scene/gltf_loader.h"
#include "tests/cli/cli_test_support.h"
#include "tests/common/study_obj_set.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using cli_test::runFacial;

using testing_support::kStudySet;

// Mean colour distance per pixel over rows [y0, y1) of two same-size images.
double meanDifference(const eng::Image& a, const eng::Image& b, int y0, int y1) {
  double sum = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * a.width + x) * 4 + c;
        sum += std::abs(int(a.rgba8[i]) - int(b.rgba8[i]));
      }
  return sum / double(size_t(y1 - y0) * a.width);
}
double meanDifference(const eng::Image& a, const eng::Image& b) { return meanDifference(a, b, 0, a.height); }

class ObjKeyframeSet : public ::testing::Test {
 protected:
  // The seven OBJs, the rig map and the converted glTF (one per test: ctest
  // runs each test in its own process).
  void SetUp() override {
    dir_ = testing_support::freshTempDir("obj_keyframe_set");
    auto face = app::FaceSetup::load({.model = testing_support::sourceDir() / "data" / "head.glb"});
    ASSERT_TRUE(face) << face.error().message;
    testing_support::writeStudyObjSet(
        face->model(), face->weightCount(),
        [&](const char* name, std::vector<float>& weights) {
          auto preset = face->findExpression(name);
          if (!preset) ADD_FAILURE() << preset.error().message;
          return preset && face->expressionWeights(**preset, 1.0f, weights).ok();
        },
        dir_ / "set");
    testing_support::writeFile(rigmap(), testing_support::studyRigMapJson(1.0f));

    const auto converted = runFacial({"convert", (dir_ / "set").string(), "--out", glb().string()});
    ASSERT_EQ(converted.exitCode, 0) << converted.out << converted.err;
    convertOutput_ = converted.out;
  }

  fs::path glb() const { return dir_ / "study.glb"; }
  fs::path rigmap() const { return dir_ / "map.json"; }

  fs::path dir_;
  std::string convertOutput_;
};

TEST_F(ObjKeyframeSet, FolderBecomesOneGlbWithSixNamedTargets) {
  EXPECT_NE(convertOutput_.find("6 morph target(s)"), std::string::npos) << convertOutput_;
  auto model = eng::loadModel(glb());
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->meshes.size(), 1u);
  std::vector<std::string> names = model->meshes[0].targetNames;
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"dread", "frown", "gasp", "scowl", "smile", "sneer"}));
}

TEST_F(ObjKeyframeSet, ExpressNeedsTheRigMapAndThenSmilesWhereTheMouthIs) {
  // Without the map no scheme knows 'smile' or 'gasp': under --no-autorig (no
  // action units made for it on the fly) a clear error, no image.
  const fs::path refused = dir_ / "refused.png";
  const auto bare = runFacial({"express", "happy", "--no-autorig", "--model", glb().string(), "--size", "128x128",
                               "--out", refused.string()});
  EXPECT_NE(bare.exitCode, 0);
  EXPECT_NE(bare.err.find("rig map"), std::string::npos) << bare.err;
  EXPECT_FALSE(fs::exists(refused));

  const fs::path neutralPng = dir_ / "express_neutral.png", happyPng = dir_ / "express_happy.png",
                 halfPng = dir_ / "express_half.png";
  const auto neutral = runFacial({"express", "neutral", "--model", glb().string(), "--rigmap", rigmap().string(),
                                  "--size", "128x128", "--out", neutralPng.string()});
  ASSERT_TRUE(cli_test::ranCleanly(neutral));
  const auto happy = runFacial({"express", "happy", "--model", glb().string(), "--rigmap", rigmap().string(),
                                "--size", "128x128", "--out", happyPng.string()});
  ASSERT_TRUE(cli_test::ranCleanly(happy));
  const auto half = runFacial({"express", "happy", "--intensity", "0.5", "--model", glb().string(), "--rigmap",
                               rigmap().string(), "--size", "128x128", "--out", halfPng.string()});
  ASSERT_TRUE(cli_test::ranCleanly(half));

  const eng::Image a = cli_test::readPngOrFail(neutralPng), b = cli_test::readPngOrFail(happyPng),
                   h = cli_test::readPngOrFail(halfPng);
  ASSERT_EQ(a.width, 128);
  ASSERT_EQ(b.width, 128);
  ASSERT_EQ(h.width, 128);
  // The smile (AU6+12+25 baked into smile.obj) moves cheeks and mouth, not the brows.
  const double brows = meanDifference(a, b, 0, 48), mouth = meanDifference(a, b, 64, 128);
  std::printf("neutral vs happy: top rows %.2f, lower half %.2f; half smile %.2f of %.2f overall\n", brows, mouth,
              meanDifference(a, h), meanDifference(a, b));
  EXPECT_GT(mouth, 1.0) << "the smile target moved the lower face";
  EXPECT_GT(mouth, 3.0 * brows) << "the difference is in the lower face";
  // Intensity 0.5 drives the target at 0.5: about half way.
  EXPECT_GT(meanDifference(a, h), 0.2 * meanDifference(a, b));
  EXPECT_LT(meanDifference(a, h), 0.8 * meanDifference(a, b));
}

TEST_F(ObjKeyframeSet, HeadlessDemoPlaysTheSevenEmotionTransitions) {
  // A frame every 0.4 s: every time sampled below is a frame (the tour's
  // 2.4 s steps are six of them), with no more frames than that to render.
  constexpr double kFps = 2.5;
  auto runDemo = [&](const fs::path& map, const fs::path& out) {
    const auto demo = runFacial({"demo", "--headless", "--model", glb().string(), "--rigmap", map.string(), "--size",
                                 "128x128", "--fps", std::to_string(kFps), "--out", out.string()});
    EXPECT_TRUE(cli_test::ranCleanly(demo)) << demo.out;
    EXPECT_NE(demo.out.find("(7 states)"), std::string::npos) << demo.out;
    EXPECT_TRUE(fs::exists(out / "tour.gif"));
    EXPECT_TRUE(fs::exists(out / "contact_sheet.png"));
    return demo.exitCode == 0;
  };
  ASSERT_TRUE(runDemo(rigmap(), dir_ / "demo"));
  // The control: the same tour with every emotion bound at gain 0. Sway,
  // breathing and timing are identical, so any difference is the expression.
  const fs::path still = dir_ / "still.json";
  testing_support::writeFile(still, testing_support::studyRigMapJson(0.0f));
  ASSERT_TRUE(runDemo(still, dir_ / "still"));

  // The tour (data/graphs/tour.json) moves on 2.4 s after entering a state,
  // blending 0.8 s (cosine) into the next, in the order neutral, happy, sad,
  // anger, fear, surprise, disgust, neutral: state k is entered at 2.4 k s
  // and fully shown from 2.4 k + 0.8 s until 2.4 (k + 1) s.
  auto frameAt = [&](const char* run, double seconds) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.png", int(std::lround(seconds * kFps)));
    return cli_test::readPngOrFail(dir_ / run / "frames" / name);
  };
  auto expression = [&](double seconds) {
    const eng::Image a = frameAt("demo", seconds), b = frameAt("still", seconds);
    EXPECT_EQ(a.width, 128);
    EXPECT_EQ(b.width, 128);
    return a.width == b.width && a.height == b.height ? meanDifference(a, b) : 0.0;
  };
  EXPECT_LT(expression(1.6), 0.05) << "neutral at the start";
  for (int k = 1; k < 7; ++k) {
    const double held = expression(2.4 * k + 1.6), blending = expression(2.4 * k + 0.4);
    std::printf("%s ('%s'): %.2f held, %.2f half way in\n", kStudySet[k].preset, kStudySet[k].file, held, blending);
    EXPECT_GT(held, 0.5) << kStudySet[k].preset << " (target '" << kStudySet[k].file << "') shows in the tour";
    if (k == 1) {
      EXPECT_GT(blending, 0.15 * held) << "half way from neutral to happy, the smile is on its way";
      EXPECT_LT(blending, 0.85 * held) << "half way from neutral to happy, the smile is not complete";
    }
  }
  EXPECT_LT(expression(18.0), 0.05) << "the tour ends back at neutral (7 x 2.4 s, then 0.8 s blend)";
}

}  // namespace
