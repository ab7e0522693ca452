#pragma once
// What an X11 window shows, read back from the server (XGetImage over a
// connection of the test's own): the check that frames reach the window,
// whichever way the renderer presents them.
#include <optional>
#include <string>

#include "engine/scene/image_io.h"

struct GLFWwindow;

namespace vk_test {

// RGBA8 (alpha 255) of the window's whole area; nullopt with `why` set when
// this is not an X11 window or the server will not give the pixels.
std::optional<eng::Image> x11WindowPixels(GLFWwindow* window, std::string& why);

}  // namespace vk_test
