// Outside the unity build (deps.cmake): Xlib's macros stay in this file.
#include "tests/engine/vk/x11_window_pixels.h"

#include <X11/Xlib.h>
#include <X11/Xutil.h>

// As glfw3native.h declares it (its X11 part also wants Xrandr's headers).
extern "C" ::Window glfwGetX11Window(GLFWwindow* window);
extern "C" Display* glfwGetX11Display(void);

namespace vk_test {

std::optional<eng::Image> x11WindowPixels(GLFWwindow* window, std::string& why) {
  Display* shown = glfwGetX11Display();
  if (!shown) {
    why = "not an X11 window";
    return std::nullopt;
  }
  Display* display = XOpenDisplay(DisplayString(shown));
  if (!display) {
    why = "cannot open a second X connection";
    return std::nullopt;
  }
  const ::Window id = glfwGetX11Window(window);
  XWindowAttributes attributes{};
  XGetWindowAttributes(display, id, &attributes);
  XImage* image = XGetImage(display, id, 0, 0, unsigned(attributes.width), unsigned(attributes.height), AllPlanes, ZPixmap);
  if (!image) {
    why = "XGetImage failed";
    XCloseDisplay(display);
    return std::nullopt;
  }
  eng::Image out{.width = attributes.width, .height = attributes.height};
  out.rgba8.resize(size_t(out.width) * size_t(out.height) * 4);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x) {
      const unsigned long p = XGetPixel(image, x, y);
      uint8_t* o = &out.rgba8[(size_t(y) * size_t(out.width) + size_t(x)) * 4];
      o[0] = uint8_t((p & attributes.visual->red_mask) >> 16);
      o[1] = uint8_t((p & attributes.visual->green_mask) >> 8);
      o[2] = uint8_t(p & attributes.visual->blue_mask);
      o[3] = 255;
    }
  XDestroyImage(image);
  XCloseDisplay(display);
  return out;
}

}  // namespace vk_test
