#include "tests/engine/vk/vk_test_context.h"

#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace vk_test {

void failOnValidationMessage(eng::LogLevel level, std::string_view message) {
  ADD_FAILURE() << (level == eng::LogLevel::Error ? "Vulkan validation error: " : "Vulkan validation warning: ")
                << message;
}

eng::vk::Context& context() {
  static eng::vk::Context ctx = [] {
    eng::vk::ContextOptions options;
    options.applicationName = "test_vk";
    options.validation = true;
    options.onValidationMessage = failOnValidationMessage;
    auto created = eng::vk::Context::create(options);
    if (!created) {
      std::fprintf(stderr, "test_vk: cannot create a Vulkan context: %s\n", created.error().message.c_str());
      std::abort();
    }
    return std::move(created).value();
  }();
  return ctx;
}

eng::vk::SceneView viewOf(const eng::Aabb& bounds) {
  return {eng::OrbitCamera::frame(bounds), eng::vk::LightRig{}};
}

eng::vk::OffscreenRenderer& renderer() {
  static eng::vk::OffscreenRenderer r = [] {
    auto created = eng::vk::OffscreenRenderer::create(context(), {256, 256});
    if (!created) {
      std::fprintf(stderr, "test_vk: cannot create the offscreen renderer: %s\n", created.error().message.c_str());
      std::abort();
    }
    return std::move(created).value();
  }();
  return r;
}

void forEachSharedModel(
    const std::function<void(const std::filesystem::path&, const eng::Model&, const eng::vk::GpuModel&)>& each) {
  const std::vector<std::filesystem::path> files = testing_support::sharedModelFiles();
  ASSERT_GE(files.size(), 7u);
  for (const std::filesystem::path& file : files) {
    SCOPED_TRACE(file.string());
    auto model = eng::loadModel(file);
    EXPECT_TRUE(model) << model.error().message;
    if (!model) continue;
    auto gpu = renderer().upload(*model);
    EXPECT_TRUE(gpu) << gpu.error().message;
    if (!gpu) continue;
    each(file, *model, *gpu);
  }
}

}  // namespace vk_test
