#include "facial/runtime/graph/curve_json.h"

#include "facial/runtime/graph/detail/json_reader.h"

namespace facial {
namespace detail {

KeyInterpolation parseKeyInterpolation(const JsonNode& name) {
  auto k = keyInterpolationFromString(name.string());
  if (!k) name.fail("unknown interpolation '" + name.string() + "' (expected step, linear, cosine or hermite)");
  return *k;
}

std::vector<Keyframe> parseKeyframes(const JsonNode& keys, KeyInterpolation defaultInterpolation) {
  std::vector<Keyframe> out;
  out.reserve(keys.size());
  for (size_t i = 0; i < keys.size(); ++i) {
    const JsonNode key = keys[i];
    Keyframe k;
    k.interpolation = defaultInterpolation;
    if (key.isArray()) {
      if (key.size() != 2) key.fail("expected [time, value], got " + std::to_string(key.size()) + " numbers");
      k.time = key[0].number();
      k.value = key[1].number();
    } else {
      key.allowOnly({"t", "v", "interp", "in", "out"});
      k.time = key.at("t").number();
      k.value = key.at("v").number();
      if (auto interp = key.find("interp")) k.interpolation = parseKeyInterpolation(*interp);
      k.inTangent = key.numberOr("in", 0.0f);
      k.outTangent = key.numberOr("out", 0.0f);
    }
    if (i > 0 && !(k.time > out.back().time))
      key.fail("key time " + formatNumber(k.time) + " is not after the previous key's " +
               formatNumber(out.back().time) + " (keys must be sorted, no duplicates)");
    out.push_back(k);
  }
  if (out.empty()) keys.fail("no keys");
  return out;
}

EasingCurve parseEasingCurve(const JsonNode& curve) {
  if (curve.isString()) {
    const std::string name = curve.string();
    if (name == "linear") return EasingCurve::linear();
    if (name == "cosine") return EasingCurve::cosine();
    if (name == "smoothstep") return EasingCurve::smoothstep();
    curve.fail("unknown curve '" + name + "' (expected linear, cosine, smoothstep, or an object for bezier/keyed)");
  }
  curve.allowOnly({"type", "handles", "keys", "interpolation"});
  const std::string type = curve.at("type").string();
  if (type == "bezier") {
    const JsonNode h = curve.at("handles");
    if (h.size() != 4) h.fail("expected 4 numbers [x1, y1, x2, y2], got " + std::to_string(h.size()));
    auto c = EasingCurve::bezier({h[0].number(), h[1].number(), h[2].number(), h[3].number()});
    if (!c) h.fail(c.error());
    return std::move(c).value();
  }
  if (type == "keyed") {
    KeyInterpolation interp = KeyInterpolation::Linear;
    if (auto i = curve.find("interpolation")) interp = parseKeyInterpolation(*i);
    const JsonNode keys = curve.at("keys");
    auto c = EasingCurve::keyed(parseKeyframes(keys, interp));
    if (!c) keys.fail(c.error());
    return std::move(c).value();
  }
  auto simple = easingTypeFromString(type);
  if (simple == EasingType::Linear) return EasingCurve::linear();
  if (simple == EasingType::Cosine) return EasingCurve::cosine();
  if (simple == EasingType::Smoothstep) return EasingCurve::smoothstep();
  curve.at("type").fail("unknown curve type '" + type + "'");
}

}  // namespace detail

eng::Result<std::vector<Keyframe>> keyframesFromJson(const Json& keys, KeyInterpolation defaultInterpolation) {
  try {
    return detail::parseKeyframes(detail::JsonNode(keys, ""), defaultInterpolation);
  } catch (const detail::JsonProblem& p) {
    return detail::jsonProblemError(p, "");
  }
}

eng::Result<EasingCurve> easingCurveFromJson(const Json& curve) {
  try {
    return detail::parseEasingCurve(detail::JsonNode(curve, ""));
  } catch (const detail::JsonProblem& p) {
    return detail::jsonProblemError(p, "");
  }
}

using detail::jsonNumber;

Json keyframesToJson(std::span<const Keyframe> keys, KeyInterpolation defaultInterpolation) {
  Json out = Json::array();
  for (const Keyframe& k : keys) {
    if (k.interpolation == defaultInterpolation && k.inTangent == 0.0f && k.outTangent == 0.0f) {
      out.push_back({jsonNumber(k.time), jsonNumber(k.value)});
      continue;
    }
    Json key = {{"t", jsonNumber(k.time)}, {"v", jsonNumber(k.value)}};
    if (k.interpolation != defaultInterpolation) key["interp"] = toString(k.interpolation);
    if (k.inTangent != 0.0f) key["in"] = jsonNumber(k.inTangent);
    if (k.outTangent != 0.0f) key["out"] = jsonNumber(k.outTangent);
    out.push_back(std::move(key));
  }
  return out;
}

Json easingCurveToJson(const EasingCurve& curve) {
  switch (curve.type()) {
    case EasingType::CubicBezier: {
      const CubicBezier& h = curve.handles();
      return {{"type", "bezier"}, {"handles", {jsonNumber(h.x1), jsonNumber(h.y1), jsonNumber(h.x2), jsonNumber(h.y2)}}};
    }
    case EasingType::Keyed:
      return {{"type", "keyed"}, {"keys", keyframesToJson(curve.keys(), KeyInterpolation::Linear)}};
    default: return std::string(toString(curve.type()));
  }
}

}  // namespace facial
