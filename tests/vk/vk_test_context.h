#pragma once
// The Vulkan context shared by the tests of one process: lavapipe or a GPU
// (FACIAL_DEVICE), validation ON, and every validation message fails the
// test that is running when it arrives.
#include "engine/vk/context.h"
#include "engine/vk/offscreen_renderer.h"

namespace vk_test {

eng::vk::Context& context();
// A 256x256 MSAA offscreen renderer on context(), created once per process.
eng::vk::OffscreenRenderer& renderer();

// `bounds` framed by the orbit camera, under the default light rig.
eng::vk::SceneView viewOf(const eng::Aabb& bounds);

// Fails the current test with every validation message (also counted by the context).
void failOnValidationMessage(eng::LogLevel level, std::string_view message);

}  // namespace vk_test
