#pragma once
// JSON forms of keys and easing curves, shared by timeline files and graphs.
//   key:   [time, value]                    (interpolation from the enclosing default)
//          {"t": 0.5, "v": 1, "interp": "hermite", "in": 0, "out": -2}
//   curve: "linear" | "cosine" | "smoothstep"
//          {"type": "bezier", "handles": [x1, y1, x2, y2]}
//          {"type": "keyed", "keys": [[0,0], [0.3,0.7], [1,1]], "interpolation": "linear"}
#include <vector>


#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/graph/json_reader.h"

namespace facial {

// Throws JsonProblem naming the key's pointer.
std::vector<Keyframe> parseKeyframes(const JsonNode& keys, KeyInterpolation defaultInterpolation);
KeyInterpolation parseKeyInterpolation(const JsonNode& name);
EasingCurve parseEasingCurve(const JsonNode& curve);

Json keyframesToJson(std::span<const Keyframe> keys, KeyInterpolation defaultInterpolation);
Json easingCurveToJson(const EasingCurve& curve);

}  // namespace facial
