#pragma once
// The curve view's model, without ImGui: the selected tracks' weight over
// time overlaid in one plot, each key's shape (the seven modes animators know),
// its tangent handles in pixels and the slope a dragged handle means, and
// which key or handle a click takes. The curve it draws is sampled with the
// runtime's own functions (facial::resolveTangents, facial::sampleKeys) from
// the keys the document saves, so `facial` plays exactly this curve
// (tests/editor/curve_model_test.cpp samples both and compares).
//
//   const CurveView view = CurveView::fit({x, y, w, h}, window, 0.0f, 1.0f);
//   for (glm::vec2 p : view.curveSamples(track.keys)) ...   // (time, value) pairs
//   if (auto hit = view.hitAt(doc, shownTracks, mouse)) ...
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

#include "editor/timeline_document.h"
#include "editor/timeline_view.h"
#include "engine/core/enum_names.h"

namespace editor {

// A key's mode in the curve view: the first four are cubic segments whose
// tangents come from facial::TangentMode; the last three set the segment the
// key starts (its tangents stay auto for a cubic segment arriving at it).
enum class CurveKeyMode : uint8_t { Auto, Smooth, Flat, Broken, Linear, Step, Cosine };

inline constexpr eng::EnumName<CurveKeyMode> kCurveKeyModeNames[] = {
    {CurveKeyMode::Auto, "auto"},     {CurveKeyMode::Smooth, "smooth"}, {CurveKeyMode::Flat, "flat"},
    {CurveKeyMode::Broken, "broken"}, {CurveKeyMode::Linear, "linear"}, {CurveKeyMode::Step, "step"},
    {CurveKeyMode::Cosine, "cosine"},
};
std::string_view curveKeyModeName(CurveKeyMode mode);
std::optional<CurveKeyMode> curveKeyModeFromName(std::string_view name);
CurveKeyMode curveKeyModeOf(const facial::Keyframe& key);

// What hovering a key in the dope sheet or the curve view says: its track,
// time (and frame at `frameRate`), value and mode, e.g.
// "happy: 1.00 s (frame 30), value 0.750, cosine".
std::string keyHoverText(std::string_view channel, const facial::Keyframe& key, float frameRate);

// The interpolation and tangent mode a curve key mode stands for.
struct CurveKeyShape {
  facial::KeyInterpolation interpolation = facial::KeyInterpolation::Hermite;
  facial::TangentMode tangent = facial::TangentMode::Auto;
};
CurveKeyShape curveKeyShape(CurveKeyMode mode);

// Sets key `id` to `mode` (one undo step); Smooth takes outSlope (in follows),
// Broken both; the others compute their own.
eng::Result<void> setCurveKeyMode(TimelineDocument& document, KeyId id, CurveKeyMode mode,
                                  std::optional<float> inSlope = {}, std::optional<float> outSlope = {});

// A colour per overlaid track (RGBA, 0xAABBGGRR as ImGui's IM_COL32), cycling.
uint32_t curveColour(size_t index);

struct CurveArea {
  float left = 0.0f, top = 0.0f;
  float width = 0.0f, height = 0.0f;
};

class CurveView {
 public:
  static constexpr float kHandleLength = 40.0f;  // pixels from the key to a tangent handle
  static constexpr float kKeyHitRadius = 6.0f;
  static constexpr float kSampleStep = 2.0f;     // pixels between curve samples
  static constexpr float kValueMargin = 8.0f;    // pixels above maxValue and below minValue

  static CurveView fit(const CurveArea& area, const TimeWindow& window, float minValue, float maxValue);

  float left() const { return left_; }
  float right() const { return left_ + width_; }
  float top() const { return top_; }
  float bottom() const { return top_ + height_; }
  float xAt(float time) const { return left_ + (time - window_.start) * pixelsPerSecond_; }
  float timeAt(float x) const { return window_.start + (x - left_) / pixelsPerSecond_; }
  float yAt(float value) const { return valueBottom_ - (value - minValue_) * pixelsPerValue_; }
  float valueAt(float y) const { return minValue_ + (valueBottom_ - y) / pixelsPerValue_; }
  glm::vec2 pixelOf(const facial::Keyframe& key) const { return {xAt(key.time), yAt(key.value)}; }

  // The drawn curve as (time, value) pairs: one every kSampleStep pixels over
  // the shown window plus every key's own time, in time order.
  std::vector<glm::vec2> curveSamples(std::span<const DocumentKey> keys) const;

  // Where a key's handles are drawn (kHandleLength along its slopes); a key
  // has an out handle when it starts a cubic segment, an in handle when one
  // ends at it.
  glm::vec2 inHandle(const facial::Keyframe& key) const;
  glm::vec2 outHandle(const facial::Keyframe& key) const;
  static bool hasInHandle(std::span<const DocumentKey> keys, size_t index);
  static bool hasOutHandle(std::span<const DocumentKey> keys, size_t index);
  // The slope (value per second) of the line from the key to `pixel`, the
  // handle kept on its own side of the key.
  float slopeToward(const facial::Keyframe& key, glm::vec2 pixel, bool inSide) const;

  enum class Part : uint8_t { Key, InHandle, OutHandle };
  struct Hit {
    size_t track = 0;
    KeyId key = 0;
    Part part = Part::Key;
  };
  // The handle of a selected key, else the key, nearest `pixel` over `tracks`.
  std::optional<Hit> hitAt(const TimelineDocument& document, std::span<const size_t> tracks, glm::vec2 pixel) const;

 private:
  glm::vec2 handle(const facial::Keyframe& key, float slope, float side) const;

  float left_ = 0.0f, top_ = 0.0f, width_ = 1.0f, height_ = 1.0f;
  TimeWindow window_;
  float pixelsPerSecond_ = 1.0f, pixelsPerValue_ = 1.0f;
  float minValue_ = 0.0f, valueBottom_ = 0.0f;
};

}  // namespace editor
