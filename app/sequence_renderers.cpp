#include "app/sequence_renderers.h"

#include <sched.h>

#include <optional>
#include <shared_mutex>
#include <thread>

namespace app {
unsigned usableCores() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return static_cast<unsigned>(CPU_COUNT(&set));
  return std::thread::hardware_concurrency();
}

using Lane = std::optional<eng::Result<HeadlessModelRenderer>>;

struct SequenceRenderers::Opening::State {
  HeadlessRenderOptions options;
  uint32_t requestedLanes = 0;
  std::vector<eng::Result<std::unique_ptr<eng::vk::Context>>> contexts;  // made by makeContexts()
  std::vector<Lane> lanes;  // filled by `opener`
  std::thread opener;

  // Each lane's context, one after another on the calling thread: made while
  // another thread calls Vulkan, a context can crash the validation layer
  // (eng::vk::contextLifetimeMutex), and the caller goes on to its own work
  // (loading a face, which may render to find its landmarks) once they exist.
  void makeContexts() {
    // Announced by finish(): a program that fails before then says one line.
    contexts.push_back(HeadlessModelRenderer::createContext(options, /*announce=*/false));
    if (!contexts.front()) return;
    uint32_t count = requestedLanes;
    if (count == 0)
      count = (*contexts.front())->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU && usableCores() >= 2 ? 2 : 1;
    for (uint32_t k = 1; k < count; ++k) contexts.push_back(HeadlessModelRenderer::createContext(options, /*announce=*/false));
  }

  // The renderers on the contexts (on `opener`): the lanes after the first on
  // threads of their own while this one opens the first. No context is made
  // or destroyed meanwhile (the shared lock covers the lanes' threads too).
  void open() {
    std::shared_lock lock(eng::vk::contextLifetimeMutex());
    lanes.resize(contexts.size());
    auto openLane = [this](size_t k) {
      if (!contexts[k])
        lanes[k].emplace(contexts[k].error());
      else
        lanes[k].emplace(HeadlessModelRenderer::open(options, std::move(*contexts[k])));
    };
    std::vector<std::thread> others;
    for (size_t k = 1; k < contexts.size(); ++k) others.emplace_back(openLane, k);
    openLane(0);
    for (std::thread& thread : others) thread.join();
  }

  void wait() {
    if (opener.joinable()) opener.join();
  }
};

SequenceRenderers::Opening::Opening(std::unique_ptr<State> state) : state_(std::move(state)) {}
SequenceRenderers::Opening::Opening(Opening&&) noexcept = default;
SequenceRenderers::Opening& SequenceRenderers::Opening::operator=(Opening&& other) noexcept {
  if (state_) state_->wait();
  state_ = std::move(other.state_);
  return *this;
}
SequenceRenderers::Opening::~Opening() {
  if (state_) state_->wait();
}

SequenceRenderers::Opening SequenceRenderers::open(const HeadlessRenderOptions& options, uint32_t lanes) {
  auto state = std::make_unique<Opening::State>();
  state->options = options;
  state->requestedLanes = lanes;
  state->makeContexts();
  state->opener = std::thread([s = state.get()] { s->open(); });
  return Opening(std::move(state));
}

eng::Result<SequenceRenderers> SequenceRenderers::Opening::finish(const eng::Model& model) {
  if (!state_) return eng::makeError(eng::ErrorKind::InvalidArgument, "the sequence's renderers were finished already");
  const std::unique_ptr<State> state = std::move(state_);
  state->wait();
  for (size_t k = 0; k < state->lanes.size(); ++k)
    if (!*state->lanes[k])
      return k == 0 ? state->lanes[k]->error() : state->lanes[k]->error().prefixed("another device for the sequence: ");
  std::vector<HeadlessModelRenderer> renderers;
  for (Lane& lane : state->lanes) renderers.push_back(std::move(**lane));
  renderers.front().context_->announce();

  // The CPU half of the upload once for every lane (they share the physical device's limits).
  auto staging = eng::vk::GpuModelStaging::build(model, renderers.front().context_->deviceInfo().properties.limits);
  if (!staging) return staging.error();
  std::vector<eng::Result<void>> shown(renderers.size());
  std::vector<std::thread> others;
  for (size_t k = 1; k < renderers.size(); ++k)
    others.emplace_back([&, k] { shown[k] = renderers[k].show(model, state->options, &*staging); });
  shown[0] = renderers[0].show(model, state->options, &*staging);
  for (std::thread& thread : others) thread.join();
  for (const eng::Result<void>& result : shown)
    if (!result) return result.error();

  SequenceRenderers out;
  out.view_ = renderers.front().view();
  out.renderers_ = std::move(renderers);
  return out;
}

eng::Result<SequenceRenderers> SequenceRenderers::create(const eng::Model& model, const HeadlessRenderOptions& options,
                                                         uint32_t lanes) {
  return open(options, lanes).finish(model);
}

std::vector<SequenceLane> SequenceRenderers::lanes() {
  std::vector<SequenceLane> out;
  for (HeadlessModelRenderer& renderer : renderers_) out.push_back({&renderer.offscreen(), &view_});
  return out;
}

bool SequenceRenderers::full() const {
  const eng::vk::OffscreenRenderer& next = renderers_[nextLane_].offscreen();
  return next.pendingFrames() == next.framesInFlight();
}

eng::Result<void> SequenceRenderers::submit(std::span<const float> weights,
                                            std::span<const eng::vk::InstanceMaterial> materials) {
  if (full())
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::to_string(pending_.size()) + " pictures in flight already: collect one first");
  HeadlessModelRenderer& lane = renderers_[nextLane_];
  const eng::vk::ModelInstance instance{&lane.gpuModel(), glm::mat4(1.0f), weights, {}, materials};
  if (auto submitted = lane.offscreen().submit(view_, {&instance, 1}); !submitted)
    return submitted.error().prefixed(lane.modelName_ + ": rendering failed: ");
  pending_.push_back(nextLane_);
  nextLane_ = (nextLane_ + 1) % laneCount();
  return {};
}

eng::Result<eng::Image> SequenceRenderers::collect() {
  if (pending_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no picture is in flight");
  HeadlessModelRenderer& lane = renderers_[pending_.front()];
  pending_.pop_front();
  auto image = lane.offscreen().collect();
  if (!image) return image.error().prefixed(lane.modelName_ + ": rendering failed: ");
  return image;
}

eng::Result<eng::Image> SequenceRenderers::render(std::span<const float> weights,
                                                  std::span<const eng::vk::InstanceMaterial> materials) {
  if (!pending_.empty())
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::to_string(pending_.size()) + " pictures in flight: collect them before render()");
  ENG_TRY(submit(weights, materials));
  return collect();
}

void SequenceRenderers::discardPending() {
  for (HeadlessModelRenderer& renderer : renderers_) renderer.offscreen().discardPending();
  pending_.clear();
  nextLane_ = 0;
}

eng::Result<void> SequenceRenderers::checkValidation() const {
  for (const HeadlessModelRenderer& renderer : renderers_) ENG_TRY(renderer.checkValidation());
  return {};
}

}  // namespace app
