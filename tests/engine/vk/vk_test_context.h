#pragma once
// The Vulkan context shared by the tests of one process: lavapipe or a GPU
// (FACIAL_DEVICE), validation ON, and every validation message fails the
// test that is running when it arrives.
#include <filesystem>
#include <functional>

#include "engine/scene/model.h"
#include "engine/vk/device/context.h"
#include "engine/vk/draw/gpu_model.h"
#include "engine/vk/draw/offscreen_renderer.h"

namespace vk_test {

eng::vk::Context& context();
// A 256x256 MSAA offscreen renderer on context(), created once per process.
eng::vk::OffscreenRenderer& renderer();

// `bounds` framed by the orbit camera, under the default light rig.
eng::vk::SceneView viewOf(const eng::Aabb& bounds);

// Every model file in ../shared (testing_support::sharedModelFiles(); at least
// the seven the tests were written against) loaded and uploaded to renderer(),
// each under a SCOPED_TRACE naming the file. A file that does not load or
// upload fails the test and is skipped. Call FACIAL_REQUIRE_SHARED() first.
void forEachSharedModel(
    const std::function<void(const std::filesystem::path&, const eng::Model&, const eng::vk::GpuModel&)>& each);

// Fails the current test with every validation message (also counted by the context).
void failOnValidationMessage(eng::LogLevel level, std::string_view message);

}  // namespace vk_test
