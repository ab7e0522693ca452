#include "facial/runtime/graph/curve_json.h"

#include "facial/runtime/graph/detail/json_reader.h"

namespace facial {
namespace detail {

eng::Result<KeyInterpolation> parseKeyInterpolation(const JsonNode& name) {
  const std::string text = ENG_TRY_VALUE(name.string());
  auto k = keyInterpolationFromName(text);
  if (!k) return name.error("unknown interpolation '" + text + "' (expected " + eng::nameList(kKeyInterpolationNames) + ")");
  return *k;
}

namespace {

eng::Result<TangentMode> parseTangentMode(const JsonNode& name) {
  const std::string text = ENG_TRY_VALUE(name.string());
  auto mode = tangentModeFromName(text);
  if (!mode) return name.error("unknown tangent mode '" + text + "' (expected " + eng::nameList(kTangentModeNames) + ")");
  return *mode;
}

// One key: [time, value], or {"t", "v", "interp", "in", "out", "tangent"}.
eng::Result<Keyframe> parseKeyframe(const JsonNode& key, KeyInterpolation defaultInterpolation) {
  Keyframe k;
  k.interpolation = defaultInterpolation;
  if (key.isArray()) {
    const size_t n = ENG_TRY_VALUE(key.size());
    if (n != 2) return key.error("expected [time, value], got " + std::to_string(n) + " numbers");
    k.time = ENG_TRY_VALUE(key.element(0).number());
    k.value = ENG_TRY_VALUE(key.element(1).number());
    return k;
  }
  ENG_TRY(key.allowOnly({"t", "v", "interp", "in", "out", "tangent"}));
  k.time = ENG_TRY_VALUE(key.numberAt("t"));
  k.value = ENG_TRY_VALUE(key.numberAt("v"));
  if (auto interp = key.find("interp")) k.interpolation = ENG_TRY_VALUE(parseKeyInterpolation(*interp));
  k.inTangent = ENG_TRY_VALUE(key.numberOr("in", 0.0f));
  k.outTangent = ENG_TRY_VALUE(key.numberOr("out", 0.0f));
  if (auto tangent = key.find("tangent")) k.tangent = ENG_TRY_VALUE(parseTangentMode(*tangent));
  return k;
}

}  // namespace

eng::Result<std::vector<Keyframe>> parseKeyframes(const JsonNode& keys, KeyInterpolation defaultInterpolation) {
  const size_t count = ENG_TRY_VALUE(keys.size());
  std::vector<Keyframe> out;
  out.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const JsonNode key = keys.element(i);
    const Keyframe k = ENG_TRY_VALUE(parseKeyframe(key, defaultInterpolation));
    if (i > 0 && !(k.time > out.back().time))
      return key.error("key time " + formatNumber(k.time) + " is not after the previous key's " +
                       formatNumber(out.back().time) + " (keys must be sorted, no duplicates)");
    out.push_back(k);
  }
  if (out.empty()) return keys.error("no keys");
  resolveTangents(out);  // the slopes the editor drew: the same function made them
  return out;
}

eng::Result<EasingCurve> parseEasingCurve(const JsonNode& curve) {
  if (curve.isString()) {
    const std::string name = ENG_TRY_VALUE(curve.string());
    if (name == "linear") return EasingCurve::linear();
    if (name == "cosine") return EasingCurve::cosine();
    if (name == "smoothstep") return EasingCurve::smoothstep();
    return curve.error("unknown curve '" + name + "' (expected linear, cosine, smoothstep, or an object for bezier/keyed)");
  }
  ENG_TRY(curve.allowOnly({"type", "handles", "keys", "interpolation"}));
  const JsonNode typeNode = ENG_TRY_VALUE(curve.at("type"));
  const std::string type = ENG_TRY_VALUE(typeNode.string());
  if (type == "bezier") {
    const JsonNode h = ENG_TRY_VALUE(curve.at("handles"));
    const size_t n = ENG_TRY_VALUE(h.size());
    if (n != 4) return h.error("expected 4 numbers [x1, y1, x2, y2], got " + std::to_string(n));
    float handles[4];
    for (size_t i = 0; i < 4; ++i) handles[i] = ENG_TRY_VALUE(h.element(i).number());
    auto c = EasingCurve::bezier({handles[0], handles[1], handles[2], handles[3]});
    if (!c) return h.error(c.error());
    return c;
  }
  if (type == "keyed") {
    KeyInterpolation interp = KeyInterpolation::Linear;
    if (auto i = curve.find("interpolation")) interp = ENG_TRY_VALUE(parseKeyInterpolation(*i));
    const JsonNode keys = ENG_TRY_VALUE(curve.at("keys"));
    auto c = EasingCurve::keyed(ENG_TRY_VALUE(parseKeyframes(keys, interp)));
    if (!c) return keys.error(c.error());
    return c;
  }
  auto simple = easingTypeFromName(type);
  if (simple == EasingType::Linear) return EasingCurve::linear();
  if (simple == EasingType::Cosine) return EasingCurve::cosine();
  if (simple == EasingType::Smoothstep) return EasingCurve::smoothstep();
  return typeNode.error("unknown curve type '" + type + "'");
}

}  // namespace detail

eng::Result<std::vector<Keyframe>> keyframesFromJson(const Json& keys, KeyInterpolation defaultInterpolation) {
  const JsonNode root(keys, "");
  ENG_TRY(detail::checkNumberRange(root));
  return detail::parseKeyframes(root, defaultInterpolation);
}

eng::Result<EasingCurve> easingCurveFromJson(const Json& curve) {
  const JsonNode root(curve, "");
  ENG_TRY(detail::checkNumberRange(root));
  return detail::parseEasingCurve(root);
}

using detail::jsonNumber;

Json keyframesToJson(std::span<const Keyframe> keys, KeyInterpolation defaultInterpolation) {
  Json out = Json::array();
  for (const Keyframe& k : keys) {
    if (k.interpolation == defaultInterpolation && k.inTangent == 0.0f && k.outTangent == 0.0f &&
        k.tangent == TangentMode::Broken) {
      out.push_back({jsonNumber(k.time), jsonNumber(k.value)});
      continue;
    }
    Json key = {{"t", jsonNumber(k.time)}, {"v", jsonNumber(k.value)}};
    if (k.interpolation != defaultInterpolation) key["interp"] = keyInterpolationName(k.interpolation);
    if (k.inTangent != 0.0f) key["in"] = jsonNumber(k.inTangent);
    if (k.outTangent != 0.0f) key["out"] = jsonNumber(k.outTangent);
    if (k.tangent != TangentMode::Broken) key["tangent"] = tangentModeName(k.tangent);
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
    default: return std::string(easingTypeName(curve.type()));
  }
}

}  // namespace facial
