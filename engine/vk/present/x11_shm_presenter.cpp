// Built outside the unity build (engine/vk/CMakeLists.txt): Xlib's macros
// (None, Status, Bool, Success) must not reach the files beside it.
#include "engine/vk/present/x11_shm_presenter.h"

#include <sys/ipc.h>
#include <sys/shm.h>

#include <algorithm>
#include <cstring>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <X11/extensions/XShm.h>

// GLFW 3.3's native access, declared as glfw3native.h declares it: that
// header's X11 part also pulls in Xrandr's headers, which nothing here uses.
extern "C" {
Display* glfwGetX11Display(void);
::Window glfwGetX11Window(GLFWwindow* window);
}

namespace eng::vk {
namespace {

// Xlib reports a failed request (an attach the server refuses) to a
// process-wide handler whose default exits; while attaching, one that notes it.
bool gAttachFailed = false;
int noteAttachError(Display*, XErrorEvent*) {
  gAttachFailed = true;
  return 0;
}

}  // namespace

struct X11ShmPresenter::Shared {
  Display* display = nullptr;
  ::Window window = 0;
  GC gc = nullptr;
  Visual* visual = nullptr;
  int depth = 0;
  XImage* image = nullptr;
  XShmSegmentInfo segment{};
  bool attached = false;

  ~Shared() {
    if (!display) return;
    release();
    if (gc) XFreeGC(display, gc);
    XCloseDisplay(display);
  }
  void release() {
    if (attached) {
      XShmDetach(display, &segment);
      XSync(display, False);
      attached = false;
    }
    if (image) {
      image->data = nullptr;  // the segment, not Xlib's to free
      XDestroyImage(image);
      image = nullptr;
    }
    if (segment.shmaddr && segment.shmaddr != reinterpret_cast<char*>(-1)) shmdt(segment.shmaddr);
    segment = {};
  }
  Result<void> allocate(VkExtent2D extent) {
    release();
    image = XShmCreateImage(display, visual, unsigned(depth), ZPixmap, nullptr, &segment, extent.width, extent.height);
    if (!image) return makeError(ErrorKind::Device, "X11 shared-memory present: XShmCreateImage failed");
    if (image->bits_per_pixel != 32 || image->bytes_per_line != int(extent.width * 4))
      return makeError(ErrorKind::Device, "X11 shared-memory present: the server's image is " +
                                              std::to_string(image->bits_per_pixel) + " bits a pixel, " +
                                              std::to_string(image->bytes_per_line) + " bytes a row (need 32, " +
                                              std::to_string(extent.width * 4) + ")");
    const size_t bytes = size_t(image->bytes_per_line) * extent.height;
    segment.shmid = shmget(IPC_PRIVATE, bytes, IPC_CREAT | 0600);
    if (segment.shmid < 0) return makeError(ErrorKind::Device, "X11 shared-memory present: shmget of " + std::to_string(bytes) + " bytes failed");
    segment.shmaddr = image->data = static_cast<char*>(shmat(segment.shmid, nullptr, 0));
    segment.readOnly = False;
    if (segment.shmaddr == reinterpret_cast<char*>(-1)) {
      shmctl(segment.shmid, IPC_RMID, nullptr);
      return makeError(ErrorKind::Device, "X11 shared-memory present: shmat failed");
    }
    gAttachFailed = false;
    XErrorHandler previous = XSetErrorHandler(noteAttachError);
    const bool sent = XShmAttach(display, &segment);
    XSync(display, False);
    XSetErrorHandler(previous);
    shmctl(segment.shmid, IPC_RMID, nullptr);  // freed once both sides detach
    if (!sent || gAttachFailed) return makeError(ErrorKind::Device, "X11 shared-memory present: the server refused the segment (a remote display?)");
    attached = true;
    return {};
  }
};

Result<std::unique_ptr<X11ShmPresenter>> X11ShmPresenter::create(GLFWwindow* window, VkExtent2D extent, uint32_t slots) {
  Display* shown = glfwGetX11Display();  // null when GLFW runs on another window system
  if (!shown) return makeError(ErrorKind::Unsupported, "X11 shared-memory present: not an X11 window");
  std::unique_ptr<X11ShmPresenter> p(new X11ShmPresenter());
  p->x_ = std::make_unique<Shared>();
  Shared& x = *p->x_;
  x.display = XOpenDisplay(DisplayString(shown));
  if (!x.display) return makeError(ErrorKind::Device, "X11 shared-memory present: cannot open a second connection to the display");
  if (!XShmQueryExtension(x.display)) return makeError(ErrorKind::Unsupported, "X11 shared-memory present: the server has no MIT-SHM");
  x.window = glfwGetX11Window(window);
  XWindowAttributes attributes{};
  if (!XGetWindowAttributes(x.display, x.window, &attributes))
    return makeError(ErrorKind::Device, "X11 shared-memory present: cannot read the window's attributes");
  x.visual = attributes.visual;
  x.depth = attributes.depth;
  if (x.depth != 24 || x.visual->red_mask != 0xff0000 || x.visual->green_mask != 0xff00 || x.visual->blue_mask != 0xff ||
      ImageByteOrder(x.display) != LSBFirst)
    return makeError(ErrorKind::Unsupported, "X11 shared-memory present: the window is not 24-bit BGRX (depth " +
                                                 std::to_string(x.depth) + ")");
  x.gc = XCreateGC(x.display, x.window, 0, nullptr);
  ENG_TRY(x.allocate(extent));
  p->extent_ = extent;
  p->busy_.assign(slots, false);
  p->thread_ = std::thread([raw = p.get()] { raw->run(); });
  return p;
}

X11ShmPresenter::~X11ShmPresenter() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void X11ShmPresenter::present(uint32_t slot, const void* pixels, std::function<void()> ready) {
  {
    std::lock_guard lock(mutex_);
    busy_[slot] = true;
    jobs_.push_back({slot, pixels, std::move(ready)});
  }
  changed_.notify_all();
}

void X11ShmPresenter::waitSlot(uint32_t slot) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return !busy_[slot]; });
}

void X11ShmPresenter::waitIdle() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return jobs_.empty() && std::none_of(busy_.begin(), busy_.end(), [](bool b) { return b; }); });
}

Result<void> X11ShmPresenter::resize(VkExtent2D extent) {
  waitIdle();  // the thread is parked on the condition: the connection is this thread's until the next present
  ENG_TRY(x_->allocate(extent));
  extent_ = extent;
  return {};
}

void X11ShmPresenter::run() {
  for (;;) {
    Job job;
    {
      std::unique_lock lock(mutex_);
      changed_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping, nothing left to show
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    job.ready();
    Shared& x = *x_;
    std::memcpy(x.image->data, job.pixels, size_t(x.image->bytes_per_line) * extent_.height);
    // Waited for: the next frame may overwrite the shared image once the server has copied it.
    XShmPutImage(x.display, x.window, x.gc, x.image, 0, 0, 0, 0, extent_.width, extent_.height, False);
    XSync(x.display, False);
    {
      std::lock_guard lock(mutex_);
      busy_[job.slot] = false;
    }
    changed_.notify_all();
  }
}

}  // namespace eng::vk
