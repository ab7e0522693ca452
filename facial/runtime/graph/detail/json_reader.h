#pragma once
// Not installed (cmake/install.cmake leaves out every detail/ folder): the
// readers of the forms that graphs, timelines and curves share, used by
// graph_json.cpp, timeline_json.cpp, curve_json.cpp and the node readers.
// They read through JsonNode (json/json_node.h): each failure is an
// eng::Error at the offending value's JSON pointer; the public entry points
// (loadGraph, parseGraph, loadTimeline, timelineFromJson, keyframesFromJson,
// easingCurveFromJson) put the file in front.
#include <string>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/timeline.h"
#include "facial/runtime/json/json_node.h"

namespace facial::detail {

// Every number a graph, timeline or curve holds (times, durations, weights,
// tangents, thresholds, positions, defaults) lies within +-kMaxFileNumber:
// real files stay far below (seconds, weights of a few units) while 1e30
// overflows to infinity once scaled by a clip's length or summed.
inline constexpr double kMaxFileNumber = kMaxKeyMagnitude;
// Fails at the first number outside that range (or not finite), naming its
// JSON pointer: "/tracks/0/keys/3/out: number 1e+30 is outside [-1e+06, 1e+06]".
// Walks the document once, without recursion, holding a frame per level.
eng::Result<void> checkNumberRange(const JsonNode& root);

// The shortest decimal that reads back as `value` (0.1f is written 0.1, not 0.10000000149).
double jsonNumber(float value);

eng::Result<std::vector<Keyframe>> parseKeyframes(const JsonNode& keys, KeyInterpolation defaultInterpolation);
eng::Result<KeyInterpolation> parseKeyInterpolation(const JsonNode& name);
eng::Result<EasingCurve> parseEasingCurve(const JsonNode& curve);
// A timeline object (without "version" when inline in a graph).
eng::Result<Timeline> parseTimeline(const JsonNode& node, std::string defaultName);

}  // namespace facial::detail
