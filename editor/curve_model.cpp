#include "editor/curve_model.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace editor {

using facial::KeyInterpolation;
using facial::TangentMode;

std::string_view curveKeyModeName(CurveKeyMode mode) { return eng::nameOf(kCurveKeyModeNames, mode); }

std::optional<CurveKeyMode> curveKeyModeFromName(std::string_view name) { return eng::valueNamed(kCurveKeyModeNames, name); }

std::string keyHoverText(std::string_view channel, const facial::Keyframe& key, float frameRate) {
  const float frame = key.time * frameRate;
  const bool onFrame = std::abs(frame - std::round(frame)) < 1e-3f;
  char text[192];
  std::snprintf(text, sizeof text, onFrame ? "%.*s: %.2f s (frame %.0f), value %.3f, %.*s" : "%.*s: %.2f s (frame %.1f), value %.3f, %.*s",
                int(channel.size()), channel.data(), double(key.time), double(frame), double(key.value),
                int(curveKeyModeName(curveKeyModeOf(key)).size()), curveKeyModeName(curveKeyModeOf(key)).data());
  return text;
}

CurveKeyMode curveKeyModeOf(const facial::Keyframe& key) {
  switch (key.interpolation) {
    case KeyInterpolation::Step: return CurveKeyMode::Step;
    case KeyInterpolation::Linear: return CurveKeyMode::Linear;
    case KeyInterpolation::Cosine: return CurveKeyMode::Cosine;
    case KeyInterpolation::Hermite: break;
  }
  switch (key.tangent) {
    case TangentMode::Auto: return CurveKeyMode::Auto;
    case TangentMode::Smooth: return CurveKeyMode::Smooth;
    case TangentMode::Flat: return CurveKeyMode::Flat;
    case TangentMode::Broken: return CurveKeyMode::Broken;
  }
  return CurveKeyMode::Broken;
}

CurveKeyShape curveKeyShape(CurveKeyMode mode) {
  switch (mode) {
    case CurveKeyMode::Auto: return {KeyInterpolation::Hermite, TangentMode::Auto};
    case CurveKeyMode::Smooth: return {KeyInterpolation::Hermite, TangentMode::Smooth};
    case CurveKeyMode::Flat: return {KeyInterpolation::Hermite, TangentMode::Flat};
    case CurveKeyMode::Broken: return {KeyInterpolation::Hermite, TangentMode::Broken};
    // Non-cubic segments: tangents stay auto for a cubic segment that arrives at the key.
    case CurveKeyMode::Linear: return {KeyInterpolation::Linear, TangentMode::Auto};
    case CurveKeyMode::Step: return {KeyInterpolation::Step, TangentMode::Auto};
    case CurveKeyMode::Cosine: return {KeyInterpolation::Cosine, TangentMode::Auto};
  }
  return {};
}

eng::Result<void> setCurveKeyMode(TimelineDocument& document, KeyId id, CurveKeyMode mode, std::optional<float> inSlope,
                                  std::optional<float> outSlope) {
  const DocumentKey* key = document.key(id);
  if (!key) return eng::makeError(eng::ErrorKind::InvalidArgument, "no key " + std::to_string(id));
  const CurveKeyShape shape = curveKeyShape(mode);
  if (mode == CurveKeyMode::Smooth)  // one slope both sides: the given one, else the one the key has now
    return document.setKeyShape(id, shape.interpolation, shape.tangent, {}, outSlope.value_or(key->key.outTangent));
  if (mode == CurveKeyMode::Broken) return document.setKeyShape(id, shape.interpolation, shape.tangent, inSlope, outSlope);
  return document.setKeyShape(id, shape.interpolation, shape.tangent);
}

uint32_t curveColour(size_t index) {
  // Distinct hues readable on the editor's dark background.
  static constexpr uint32_t kColours[] = {0xFFE6A03Cu, 0xFF5AC8FAu, 0xFF78DC78u, 0xFFDC78DCu,
                                          0xFF3CB4FFu, 0xFFFFDC78u, 0xFF7878FFu, 0xFFB4B4B4u};
  return kColours[index % std::size(kColours)];
}

CurveView CurveView::fit(const CurveArea& area, const TimeWindow& window, float minValue, float maxValue) {
  CurveView view;
  view.left_ = area.left;
  view.top_ = area.top;
  view.width_ = std::max(area.width, 50.0f);
  view.height_ = std::max(area.height, 2.0f * kValueMargin + 20.0f);
  view.window_ = window.span() > 0.0f ? window : TimeWindow{};
  view.pixelsPerSecond_ = view.width_ / view.window_.span();
  view.minValue_ = minValue;
  view.valueBottom_ = view.bottom() - kValueMargin;
  view.pixelsPerValue_ = (view.height_ - 2.0f * kValueMargin) / std::max(maxValue - minValue, 1e-6f);
  return view;
}

std::vector<glm::vec2> CurveView::curveSamples(std::span<const DocumentKey> keys) const {
  std::vector<glm::vec2> out;
  if (keys.empty()) return out;
  std::vector<facial::Keyframe> plain(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) plain[i] = keys[i].key;
  const float step = kSampleStep / pixelsPerSecond_;
  const int count = int(std::ceil(window_.span() / step));
  size_t nextKey = 0;
  uint32_t cursor = 0;
  auto keysUpTo = [&](float t) {  // every key's own time too, so corners (linear, step) are drawn where they are
    for (; nextKey < plain.size() && plain[nextKey].time <= t; ++nextKey)
      if (plain[nextKey].time >= window_.start)
        out.push_back({plain[nextKey].time, facial::sampleKeys(plain, plain[nextKey].time, cursor)});
  };
  for (int i = 0; i <= count; ++i) {
    const float t = std::min(window_.start + float(i) * step, window_.end);
    keysUpTo(t);
    out.push_back({t, facial::sampleKeys(plain, t, cursor)});
  }
  keysUpTo(window_.end);
  return out;
}

glm::vec2 CurveView::handle(const facial::Keyframe& key, float slope, float side) const {
  // The slope in pixels (y down), then kHandleLength along it.
  glm::vec2 direction{1.0f, -slope * pixelsPerValue_ / pixelsPerSecond_};
  direction = glm::normalize(direction) * (kHandleLength * side);
  return pixelOf(key) + direction;
}

glm::vec2 CurveView::inHandle(const facial::Keyframe& key) const { return handle(key, key.inTangent, -1.0f); }
glm::vec2 CurveView::outHandle(const facial::Keyframe& key) const { return handle(key, key.outTangent, 1.0f); }

bool CurveView::hasInHandle(std::span<const DocumentKey> keys, size_t index) {
  return index > 0 && index < keys.size() && keys[index - 1].key.interpolation == KeyInterpolation::Hermite;
}

bool CurveView::hasOutHandle(std::span<const DocumentKey> keys, size_t index) {
  return index + 1 < keys.size() && keys[index].key.interpolation == KeyInterpolation::Hermite;
}

float CurveView::slopeToward(const facial::Keyframe& key, glm::vec2 pixel, bool inSide) const {
  const glm::vec2 k = pixelOf(key);
  float dx = pixel.x - k.x;
  // A handle dragged across its key would turn the slope over: hold it just on its side.
  dx = inSide ? std::min(dx, -1.0f) : std::max(dx, 1.0f);
  return (-(pixel.y - k.y) / pixelsPerValue_) / (dx / pixelsPerSecond_);
}

std::optional<CurveView::Hit> CurveView::hitAt(const TimelineDocument& document, std::span<const size_t> tracks,
                                               glm::vec2 pixel) const {
  std::optional<Hit> best;
  float bestDistance = kKeyHitRadius;
  auto consider = [&](glm::vec2 at, Hit hit) {
    const float d = glm::length(at - pixel);
    // Handles win ties: they sit over the curve where a key's circle may overlap.
    if (d < bestDistance || (d <= bestDistance && hit.part != Part::Key)) {
      bestDistance = d;
      best = hit;
    }
  };
  for (size_t t : tracks) {
    if (t >= document.tracks().size()) continue;
    const auto keys = std::span<const DocumentKey>(document.tracks()[t].keys);
    for (size_t i = 0; i < keys.size(); ++i) {
      const DocumentKey& k = keys[i];
      consider(pixelOf(k.key), {t, k.id, Part::Key});
      if (!document.isSelected(k.id)) continue;
      if (hasInHandle(keys, i)) consider(inHandle(k.key), {t, k.id, Part::InHandle});
      if (hasOutHandle(keys, i)) consider(outHandle(k.key), {t, k.id, Part::OutHandle});
    }
  }
  return best;
}

}  // namespace editor
