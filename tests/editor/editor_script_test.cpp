// facial-editor --script under xvfb-run: the sculpt panel (a pick by window
// pixel, moving the point, the live preview, bake, Save .glb) and timeline
// editing (key all, move, delete, undo / redo, save, a save that cannot
// write) through the same handlers as the UI, checked from the outside: the
// log, the screenshots, and the files the editor saved.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "editor/timeline_document.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;
using editor_test::meanDifference;
using editor_test::runEditor;

eng::Image readShot(const fs::path& path) {
  auto image = eng::readImage(path);
  if (!image) {
    ADD_FAILURE() << image.error().message;
    return {};
  }
  if (image->width != 1280 || image->height != 800) ADD_FAILURE() << path << " is " << image->width << "x" << image->height;
  return std::move(*image);
}

// Lines of the log matching `pattern`, each as its submatches.
std::vector<std::smatch> logMatches(const std::string& log, const std::string& pattern) {
  std::vector<std::smatch> found;
  const std::regex re(pattern);
  for (std::sregex_iterator it(log.begin(), log.end(), re), end; it != end; ++it) found.push_back(*it);
  return found;
}

// ---------------------------------------------------------------------------
// Sculpt

// At 1280x800 the face fills the viewport (x 320..960, y 0..560): the nose
// tip is about here.
constexpr int kNoseX = 640, kNoseY = 316;
const glm::vec3 kMove{0.008f, 0.0f, 0.006f};  // to the face's left (screen right) and out

TEST(EditorScript, SculptPickMovePreviewBakeAndSave) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_sculpt");
  // Zero-displacement points around the nose (landmarks of the built-in
  // head) keep the bend local, as a sculptor pins what must not move; then
  // the nose tip, picked by its pixel.
  std::string anchors;
  for (const char* name : {"nose_root", "ala_L", "ala_R", "philtrum", "infraorbital_L", "infraorbital_R", "cheek_L",
                           "cheek_R", "chin", "forehead_centre"})
    anchors += std::string("0.2 sculpt-landmark ") + name + "\n";
  testing_support::writeFile(dir / "sculpt.txt",
                             anchors +
                             "0.3 sculpt-pick " + std::to_string(kNoseX) + " " + std::to_string(kNoseY) + "  # the nose tip\n"
                             "0.4 screenshot unsculpted.png\n"
                             "0.5 sculpt-move " + std::to_string(kMove.x) + " " + std::to_string(kMove.y) + " " +
                             std::to_string(kMove.z) + "\n"
                             "0.6 screenshot sculpted.png\n"
                             "0.7 sculpt-kernel multiquadric 0.02\n"
                             "0.8 screenshot multiquadric.png\n"
                             "0.9 sculpt-kernel biharmonic\n"
                             "1.0 sculpt-bake crooked_nose\n"
                             "1.1 screenshot baked.png\n"
                             "1.2 sculpt-save crooked.glb\n"
                             "1.3 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script sculpt.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));

  // The pixel pick landed on the nose tip, the front-most point of the face.
  const auto picks = logMatches(run.log, R"(control point '([^']+)' at \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))");
  ASSERT_EQ(picks.size(), 11u) << run.log;
  const std::smatch& nosePick = picks.back();
  const glm::vec3 picked{std::stof(nosePick[2]), std::stof(nosePick[3]), std::stof(nosePick[4])};
  auto original = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(original) << original.error().message;
  const eng::Aabb bounds = original->bounds();
  EXPECT_NEAR(picked.x, 0.0f, 0.002f) << run.log;
  EXPECT_GT(picked.z, bounds.max.z - 0.004f) << "the nose tip, not somewhere behind it:\n" << run.log;

  // The preview bends the nose and leaves the face away from it alone.
  const eng::Image before = readShot(dir / "unsculpted.png"), after = readShot(dir / "sculpted.png");
  const eng::Image multiquadric = readShot(dir / "multiquadric.png"), baked = readShot(dir / "baked.png");
  ASSERT_FALSE(HasFailure());
  // Pixels that changed clearly (the texture under a sub-pixel shift changes a little everywhere).
  const auto changed = [](const eng::Image& a, const eng::Image& b, int x0, int y0, int x1, int y1) {
    size_t count = 0, total = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++total)
        if (editor_test::colourDistance(editor_test::pixel(a, x, y), editor_test::pixel(b, x, y)) > 48) ++count;
    return double(count) / double(total);
  };
  const int nx0 = kNoseX - 40, ny0 = kNoseY - 50, nx1 = kNoseX + 40, ny1 = kNoseY + 30;
  const double nose = changed(before, after, nx0, ny0, nx1, ny1);
  const double forehead = changed(before, after, 580, 70, 700, 150);
  const double otherCheek = changed(before, after, 530, 280, 575, 380);
  const double noseMean = meanDifference(before, after, nx0, ny0, nx1, ny1);
  const double bakedMean = meanDifference(before, baked, nx0, ny0, nx1, ny1);
  const double kernels = meanDifference(after, multiquadric, nx0, ny0, nx1, ny1);
  std::printf("preview vs unsculpted, pixels changed: nose %.3f, forehead %.3f, other cheek %.3f; mean colour change at "
              "the nose: preview %.2f, baked %.2f, multiquadric vs biharmonic %.2f\n",
              nose, forehead, otherCheek, noseMean, bakedMean, kernels);
  EXPECT_GT(nose, 0.04) << "the preview shows the moved nose";
  EXPECT_GT(noseMean, 6.0) << "the preview shows the moved nose";
  EXPECT_LT(forehead, 0.2 * nose) << "the forehead stays";
  EXPECT_LT(otherCheek, 0.2 * nose) << "the cheek away from the move stays";
  EXPECT_GT(kernels, 0.5) << "another kernel bends the face differently";
  // The bake keeps the look: the new target at weight 1, the points back at
  // rest (shading differs a little: the preview moves positions only, the
  // baked target has normal deltas too).
  EXPECT_GT(bakedMean, 0.6 * noseMean) << "the baked nose is still bent";


  // The saved model: the head's targets plus the baked one, largest at the
  // picked point, where it is the moved displacement.
  ASSERT_NE(run.log.find("saved crooked.glb"), std::string::npos) << run.log;
  auto saved = eng::loadModel(dir / "crooked.glb");
  ASSERT_TRUE(saved) << saved.error().message;
  int node = -1;
  for (size_t n = 0; n < saved->nodes.size(); ++n)
    if (saved->nodes[n].mesh == 0) node = int(n);
  ASSERT_GE(node, 0);
  const eng::Mesh& head = saved->meshes[0];
  ASSERT_EQ(head.targetNames.size(), original->meshes[0].targetNames.size() + 1);
  ASSERT_EQ(head.targetNames.back(), "crooked_nose");
  const glm::mat4 world = saved->worldTransform(node);
  float largest = 0.0f, nearest = 1e9f;
  glm::vec3 largestAt{0.0f}, deltaNearest{0.0f};
  for (const eng::Primitive& primitive : head.primitives) {
    const eng::MorphTarget& target = primitive.targets.back();
    ASSERT_EQ(target.positions.size(), primitive.vertexCount());
    for (size_t v = 0; v < primitive.vertexCount(); ++v) {
      const glm::vec3 at = glm::vec3(world * glm::vec4(primitive.positions[v], 1.0f));
      const glm::vec3 delta = glm::mat3(world) * target.positions[v];
      if (glm::length(delta) > largest) {
        largest = glm::length(delta);
        largestAt = at;
      }
      if (glm::length(at - picked) < nearest) {
        nearest = glm::length(at - picked);
        deltaNearest = delta;
      }
    }
  }
  std::printf("baked: largest delta %.5f at %.4f from the pick; nearest vertex (%.4f away) moved (%.5f %.5f %.5f)\n", largest,
              glm::length(largestAt - picked), nearest, deltaNearest.x, deltaNearest.y, deltaNearest.z);
  EXPECT_LT(glm::length(largestAt - picked), 0.006f) << "the largest delta is at the picked point";
  EXPECT_NEAR(largest, glm::length(kMove), 0.1f * glm::length(kMove));
  EXPECT_LT(glm::length(deltaNearest - kMove), 0.1f * glm::length(kMove)) << "the picked point moved by the scripted move";

  // `facial render` poses the saved target by name.
  const fs::path facial = fs::path(FACIAL_BINARY_DIR) / "bin" / "facial";
  const auto render = [&](const std::string& weight, const fs::path& out) {
    const std::string command = "'" + facial.string() + "' render '" + (dir / "crooked.glb").string() + "' --size 320x320 " +
                                weight + " --out '" + out.string() + "' >>'" + (dir / "render.log").string() + "' 2>&1";
    return std::system(command.c_str());
  };
  ASSERT_EQ(render("--weight crooked_nose=1", dir / "crooked.png"), 0) << editor_test::readText(dir / "render.log");
  ASSERT_EQ(render("", dir / "straight.png"), 0) << editor_test::readText(dir / "render.log");
  auto crooked = eng::readImage(dir / "crooked.png"), straight = eng::readImage(dir / "straight.png");
  ASSERT_TRUE(crooked && straight);
  const double rendered = meanDifference(*crooked, *straight, 0, 0, 320, 320);
  const double renderedCorner = meanDifference(*crooked, *straight, 0, 0, 60, 60);
  std::printf("facial render crooked_nose=1 vs 0: %.3f over the image, %.3f in the corner\n", rendered, renderedCorner);
  EXPECT_GT(rendered, 0.2) << "the render shows the baked target";
  EXPECT_LT(renderedCorner, 0.05);
}

}  // namespace
