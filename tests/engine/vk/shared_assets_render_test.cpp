// Every glTF file in ../shared/assets and ../shared/compressed loads, uploads and renders something
// (framed from its bounds, default weights).
#include <algorithm>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/weights.h"
#include "engine/view/framing_bounds.h"
#include "tests/common/test_support.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

TEST(SharedAssetsRender, EveryFileRendersNonEmpty) {
  FACIAL_REQUIRE_SHARED();
  vk_test::forEachSharedModel([](const std::filesystem::path& file, const eng::Model& model,
                                 const eng::vk::GpuModel& gpu) {
    const std::vector<float> weights = eng::WeightLayout(model).defaults();
    const eng::vk::ModelInstance instance{&gpu, glm::mat4(1.0f), weights};
    // Seen from slightly above: flat samples (MorphPrimitivesTest) are planes seen edge-on from the front.
    eng::vk::SceneView view{eng::OrbitCamera::frame(eng::framingBounds(model)), {}};
    view.camera.pitchDegrees = 30.0f;
    auto background = vk_test::renderer().render(view, {});
    auto image = vk_test::renderer().render(view, {&instance, 1});
    ASSERT_TRUE(image) << image.error().message;
    ASSERT_TRUE(background) << background.error().message;
    const double coverage = vk_test::coverageAgainst(*image, *background);
    EXPECT_GT(coverage, 0.02) << "the model covers part of the image";
    std::printf("  %s: %.0f%% of the image\n", file.filename().string().c_str(), coverage * 100.0);
  });
}

}  // namespace
