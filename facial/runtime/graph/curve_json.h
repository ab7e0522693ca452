#pragma once
// JSON forms of keys and easing curves, shared by timeline files and graphs.
//   key:   [time, value]                    (interpolation from the enclosing default)
//          {"t": 0.5, "v": 1, "interp": "hermite", "in": 0, "out": -2}
//          {"t": 0.5, "v": 1, "interp": "hermite", "tangent": "auto"}   (tangent: broken (default:
//          "in"/"out" as given), auto, smooth ("in" follows "out"), flat; resolveTangents() in keyframe.h)
//   curve: "linear" | "cosine" | "smoothstep"
//          {"type": "bezier", "handles": [x1, y1, x2, y2]}
//          {"type": "keyed", "keys": [[0,0], [0.3,0.7], [1,1]], "interpolation": "linear"}
#include <span>
#include <vector>

#include "engine/core/result.h"
#include "facial/runtime/curves/easing_curve.h"
#include "facial/runtime/curves/keyframe.h"
#include "facial/runtime/json/json_document.h"

namespace facial {

// Errors are Malformed and read "<pointer>: <problem>", the pointer relative
// to the value given ("/3/t: expected a number, got string").
eng::Result<std::vector<Keyframe>> keyframesFromJson(const Json& keys, KeyInterpolation defaultInterpolation);
eng::Result<EasingCurve> easingCurveFromJson(const Json& curve);

Json keyframesToJson(std::span<const Keyframe> keys, KeyInterpolation defaultInterpolation);
Json easingCurveToJson(const EasingCurve& curve);

}  // namespace facial
