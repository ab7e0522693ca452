#pragma once
// Puts finished frames into an X11 window through MIT-SHM shared memory, on
// a thread of its own with an X connection of its own. For a CPU device:
// Mesa 22.3's software WSI sends each frame through the X socket inside
// vkQueuePresentKHR (about 13 ms of a 1280x800 frame on 2 cores) and holds
// the one queue meanwhile, so the next frame could not start rendering until
// the last one was on screen. Here the renderer copies each frame into host
// memory and hands it over; the thread waits for it, puts it and waits for
// the server, while the renderer draws the next. Frames are BGRX bytes, as
// a 24-bit TrueColor window on a little-endian server holds them.
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <vulkan/vulkan.h>

#include "engine/core/result.h"

struct GLFWwindow;

namespace eng::vk {

class X11ShmPresenter {
 public:
  // Fails, saying why, where this is not an X11 window, the server has no
  // MIT-SHM (a remote display) or the window's visual is not 24-bit BGRX.
  // `slots`: frames that may be handed over at once.
  static Result<std::unique_ptr<X11ShmPresenter>> create(GLFWwindow* window, VkExtent2D extent, uint32_t slots);
  ~X11ShmPresenter();
  X11ShmPresenter(const X11ShmPresenter&) = delete;
  X11ShmPresenter& operator=(const X11ShmPresenter&) = delete;

  VkExtent2D extent() const { return extent_; }
  // Hands slot's frame over: once `ready` returns (it waits for the GPU),
  // the thread copies extent() rows of extent().width * 4 bytes from
  // `pixels` into the window. `pixels` stays untouched until waitSlot(slot).
  void present(uint32_t slot, const void* pixels, std::function<void()> ready);
  // Until the thread is done with slot's pixels.
  void waitSlot(uint32_t slot);
  // Until every frame handed over is in the window.
  void waitIdle();
  // A new window size: waits until idle, then a shared image of that size.
  Result<void> resize(VkExtent2D extent);

 private:
  struct Job {
    uint32_t slot = 0;
    const void* pixels = nullptr;
    std::function<void()> ready;
  };
  struct Shared;  // the X connection, window, GC and shared image (x11_shm_presenter.cpp)

  X11ShmPresenter() = default;
  void run();

  std::unique_ptr<Shared> x_;
  VkExtent2D extent_{0, 0};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  std::vector<bool> busy_;  // per slot: handed over, not yet copied and put
  bool stop_ = false;
  std::thread thread_;  // last: started after everything above exists, joined first
};

}  // namespace eng::vk
