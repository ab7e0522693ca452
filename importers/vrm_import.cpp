#include "importers/vrm_import.h"

#include <array>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "facial/runtime/json/json_document.h"

namespace importers {
namespace {

constexpr size_t kMaxVrmFileBytes = size_t{512} << 20;

constexpr std::array<std::string_view, 18> kVrm1Presets = {
    "happy", "angry", "sad", "relaxed", "surprised", "aa", "ih", "ou", "ee", "oh",
    "blink", "blinkLeft", "blinkRight", "lookUp", "lookDown", "lookLeft", "lookRight", "neutral"};
constexpr std::array<std::string_view, 18> kVrm0Presets = {
    "unknown", "neutral", "a", "i", "u", "e", "o", "blink", "joy",
    "angry", "sorrow", "fun", "lookup", "lookdown", "lookleft", "lookright", "blink_l", "blink_r"};

template <size_t N>
bool contains(const std::array<std::string_view, N>& list, std::string_view name) {
  for (std::string_view s : list)
    if (s == name) return true;
  return false;
}

// Parsing context: source name for messages, the document, the flat target layout.
struct Context {
  std::string_view source;
  const facial::Json& gltf;
  facial::VrmExpressionSet& set;
};

eng::Result<size_t> readIndex(const Context& c, const facial::Json& object, std::string_view key, const std::string& path,
                              size_t limit, std::string_view limitWhat) {
  const std::string keyPath = facial::childPath(path, key);
  if (!object.contains(key)) return facial::jsonError(c.source, keyPath, "missing");
  const facial::Json& v = object[std::string(key)];
  if (!v.is_number_integer() || v.get<int64_t>() < 0)
    return facial::jsonError(c.source, keyPath, "must be a non-negative integer, got " + v.dump());
  const size_t index = static_cast<size_t>(v.get<int64_t>());
  if (index >= limit)
    return facial::jsonError(c.source, keyPath,
                     std::to_string(index) + " is out of range (" + std::to_string(limit) + " " + std::string(limitWhat) + ")");
  return index;
}

eng::Result<float> readBindWeight(const Context& c, const facial::Json& bind, const std::string& path, double maxWeight) {
  const std::string keyPath = facial::childPath(path, "weight");
  if (!bind.contains("weight")) return facial::jsonError(c.source, keyPath, "missing");
  const facial::Json& v = bind["weight"];
  if (!v.is_number()) return facial::jsonError(c.source, keyPath, "must be a number, got " + std::string(facial::jsonTypeName(v)));
  const double w = v.get<double>();
  if (!std::isfinite(w) || w < 0.0 || w > maxWeight)
    return facial::jsonError(c.source, keyPath, "weight " + facial::formatNumber(w) + " is outside [0, " + facial::formatNumber(maxWeight) + "]");
  return static_cast<float>(w / maxWeight);
}

eng::Result<bool> readBool(const Context& c, const facial::Json& object, std::string_view key, const std::string& path) {
  if (!object.contains(key)) return false;
  const facial::Json& v = object[std::string(key)];
  if (!v.is_boolean()) return facial::jsonError(c.source, facial::childPath(path, key), "must be true or false, got " + v.dump());
  return v.get<bool>();
}

// Flat, mesh-major target list of the document.
eng::Result<void> readTargets(const Context& c) {
  facial::VrmExpressionSet& set = c.set;
  set.meshTargetOffsets.push_back(0);
  if (!c.gltf.contains("meshes")) return {};
  const facial::Json& meshes = c.gltf["meshes"];
  if (!meshes.is_array()) return facial::jsonError(c.source, "/meshes", "must be an array");
  for (size_t m = 0; m < meshes.size(); ++m) {
    const std::string path = facial::childPath("/meshes", m);
    const facial::Json& mesh = meshes[m];
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array())
      return facial::jsonError(c.source, path, "a mesh must be an object with a primitives array");
    size_t count = 0;
    const facial::Json& primitives = mesh["primitives"];
    for (size_t p = 0; p < primitives.size(); ++p) {
      const facial::Json& prim = primitives[p];
      const size_t n = prim.is_object() && prim.contains("targets") && prim["targets"].is_array() ? prim["targets"].size() : 0;
      if (p == 0) count = n;
      else if (n != count)
        return facial::jsonError(c.source, facial::childPath(facial::childPath(facial::childPath(path, "primitives"), p), "targets"),
                         std::to_string(n) + " morph targets, primitive 0 has " + std::to_string(count));
    }
    const std::string meshName =
        mesh.contains("name") && mesh["name"].is_string() ? mesh["name"].get<std::string>() : "mesh_" + std::to_string(m);
    const facial::Json* names = nullptr;
    if (mesh.contains("extras") && mesh["extras"].is_object() && mesh["extras"].contains("targetNames") &&
        mesh["extras"]["targetNames"].is_array() && mesh["extras"]["targetNames"].size() == count)
      names = &mesh["extras"]["targetNames"];
    for (size_t t = 0; t < count; ++t) {
      const std::string targetName =
          names && (*names)[t].is_string() ? (*names)[t].get<std::string>() : "target_" + std::to_string(t);
      set.targetNames.push_back(meshName + "/" + targetName);
    }
    set.meshTargetOffsets.push_back(static_cast<uint32_t>(set.targetNames.size()));
  }
  return {};
}

size_t meshTargetCount(const facial::VrmExpressionSet& set, size_t mesh) {
  return set.meshTargetOffsets[mesh + 1] - set.meshTargetOffsets[mesh];
}

eng::Result<std::array<float, 4>> readFloats(const Context& c, const facial::Json& object, std::string_view key,
                                             const std::string& path, size_t count, bool required) {
  std::array<float, 4> out{};
  const std::string keyPath = facial::childPath(path, key);
  if (!object.contains(key)) {
    if (required) return facial::jsonError(c.source, keyPath, "missing");
    return out;
  }
  const facial::Json& v = object[std::string(key)];
  if (!v.is_array() || v.size() < count)
    return facial::jsonError(c.source, keyPath, "must be an array of " + std::to_string(count) + " numbers, got " + v.dump());
  for (size_t i = 0; i < count; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      return facial::jsonError(c.source, facial::childPath(keyPath, i), "must be a finite number, got " + v[i].dump());
    out[i] = v[i].get<float>();
  }
  return out;
}

// A material bind that cannot be applied (no such material, unknown type, a
// value that is not a finite number) is left out with one warning naming the
// file and the bind: the rest of the avatar still works.
void skipMaterialBind(const Context& c, const eng::Error& why) {
  c.set.warnings.push_back(why.message + "; bind ignored");
}

size_t materialCountOf(const facial::Json& gltf) {
  return gltf.contains("materials") && gltf["materials"].is_array() ? gltf["materials"].size() : 0;
}

// VRM 1.0 materialColorBinds [{material, type, targetValue[4]}] and
// textureTransformBinds [{material, scale[2], offset[2]}].
eng::Result<void> readVrm1MaterialBinds(const Context& c, const facial::Json& e, const std::string& path, facial::VrmExpression& expression) {
  const size_t materials = materialCountOf(c.gltf);
  expression.firstMaterialColorBind = static_cast<uint32_t>(c.set.materialColorBinds.size());
  if (e.contains("materialColorBinds")) {
    const std::string bindsPath = facial::childPath(path, "materialColorBinds");
    const facial::Json& binds = e["materialColorBinds"];
    if (!binds.is_array()) return facial::jsonError(c.source, bindsPath, "must be an array");
    for (size_t b = 0; b < binds.size(); ++b) {
      const std::string bindPath = facial::childPath(bindsPath, b);
      const facial::Json& bind = binds[b];
      if (!bind.is_object()) return facial::jsonError(c.source, bindPath, "a bind must be an object {material, type, targetValue}");
      auto material = readIndex(c, bind, "material", bindPath, materials, "materials");
      if (!material) {
        skipMaterialBind(c, material.error());
        continue;
      }
      const std::string type = bind.contains("type") && bind["type"].is_string() ? bind["type"].get<std::string>() : "";
      facial::VrmMaterialColorBind out;
      out.material = static_cast<uint32_t>(*material);
      bool known = false;
      for (auto t : {facial::VrmMaterialColorType::Color, facial::VrmMaterialColorType::EmissionColor, facial::VrmMaterialColorType::ShadeColor,
                     facial::VrmMaterialColorType::MatcapColor, facial::VrmMaterialColorType::RimColor, facial::VrmMaterialColorType::OutlineColor})
        if (facial::vrmMaterialColorTypeName(t) == type) {
          out.type = t;
          known = true;
        }
      if (!known) {
        skipMaterialBind(c, facial::jsonError(c.source, facial::childPath(bindPath, "type"),
                                      "must be color, emissionColor, shadeColor, matcapColor, rimColor or outlineColor, got " +
                                          (bind.contains("type") ? bind["type"].dump() : std::string("nothing"))));
        continue;
      }
      auto value = readFloats(c, bind, "targetValue", bindPath, 4, true);
      if (!value) {
        skipMaterialBind(c, value.error());
        continue;
      }
      out.targetValue = *value;
      c.set.materialColorBinds.push_back(out);
    }
  }
  expression.materialColorBindCount = static_cast<uint32_t>(c.set.materialColorBinds.size()) - expression.firstMaterialColorBind;

  expression.firstTextureTransformBind = static_cast<uint32_t>(c.set.textureTransformBinds.size());
  if (e.contains("textureTransformBinds")) {
    const std::string bindsPath = facial::childPath(path, "textureTransformBinds");
    const facial::Json& binds = e["textureTransformBinds"];
    if (!binds.is_array()) return facial::jsonError(c.source, bindsPath, "must be an array");
    for (size_t b = 0; b < binds.size(); ++b) {
      const std::string bindPath = facial::childPath(bindsPath, b);
      const facial::Json& bind = binds[b];
      if (!bind.is_object()) return facial::jsonError(c.source, bindPath, "a bind must be an object {material, scale, offset}");
      auto material = readIndex(c, bind, "material", bindPath, materials, "materials");
      if (!material) {
        skipMaterialBind(c, material.error());
        continue;
      }
      facial::VrmTextureTransformBind out;
      out.material = static_cast<uint32_t>(*material);
      auto scale = readFloats(c, bind, "scale", bindPath, 2, false);
      auto offset = readFloats(c, bind, "offset", bindPath, 2, false);
      if (!scale || !offset) {
        skipMaterialBind(c, !scale ? scale.error() : offset.error());
        continue;
      }
      if (bind.contains("scale")) out.scale = {(*scale)[0], (*scale)[1]};
      out.offset = {(*offset)[0], (*offset)[1]};
      c.set.textureTransformBinds.push_back(out);
    }
  }
  expression.textureTransformBindCount =
      static_cast<uint32_t>(c.set.textureTransformBinds.size()) - expression.firstTextureTransformBind;
  return {};
}

// VRM 0.x materialValues [{materialName, propertyName, targetValue[]}]:
// _Color / _EmissionColor / _ShadeColor / _SphereAdd / _RimColor / _OutlineColor
// are colours, _MainTex_ST is a texture transform (scale xy, offset zw).
eng::Result<void> readVrm0MaterialValues(const Context& c, const facial::Json& group, const std::string& path,
                                         facial::VrmExpression& expression) {
  expression.firstMaterialColorBind = static_cast<uint32_t>(c.set.materialColorBinds.size());
  expression.firstTextureTransformBind = static_cast<uint32_t>(c.set.textureTransformBinds.size());
  if (group.contains("materialValues")) {
    const std::string valuesPath = facial::childPath(path, "materialValues");
    const facial::Json& values = group["materialValues"];
    if (!values.is_array()) return facial::jsonError(c.source, valuesPath, "must be an array");
    const size_t materials = materialCountOf(c.gltf);
    for (size_t b = 0; b < values.size(); ++b) {
      const std::string valuePath = facial::childPath(valuesPath, b);
      const facial::Json& value = values[b];
      if (!value.is_object() || !value.contains("materialName") || !value["materialName"].is_string() ||
          !value.contains("propertyName") || !value["propertyName"].is_string()) {
        skipMaterialBind(c, facial::jsonError(c.source, valuePath,
                                      "a material value must be an object {materialName, propertyName, targetValue}"));
        continue;
      }
      const std::string materialName = value["materialName"].get<std::string>();
      size_t material = materials;
      for (size_t m = 0; m < materials; ++m)
        if (c.gltf["materials"][m].is_object() && c.gltf["materials"][m].value("name", std::string()) == materialName) {
          material = m;
          break;
        }
      if (material == materials) {
        skipMaterialBind(c, facial::jsonError(c.source, facial::childPath(valuePath, "materialName"),
                                      "no material is named '" + materialName + "'"));
        continue;
      }
      const std::string property = value["propertyName"].get<std::string>();
      auto target = readFloats(c, value, "targetValue", valuePath, 4, true);
      if (!target) {
        skipMaterialBind(c, target.error());
        continue;
      }
      if (property == "_MainTex_ST") {
        c.set.textureTransformBinds.push_back(
            {static_cast<uint32_t>(material), {(*target)[0], (*target)[1]}, {(*target)[2], (*target)[3]}});
        continue;
      }
      struct Property {
        std::string_view name;
        facial::VrmMaterialColorType type;
      };
      constexpr std::array kProperties = {Property{"_Color", facial::VrmMaterialColorType::Color},
                                          Property{"_EmissionColor", facial::VrmMaterialColorType::EmissionColor},
                                          Property{"_ShadeColor", facial::VrmMaterialColorType::ShadeColor},
                                          Property{"_SphereAdd", facial::VrmMaterialColorType::MatcapColor},
                                          Property{"_RimColor", facial::VrmMaterialColorType::RimColor},
                                          Property{"_OutlineColor", facial::VrmMaterialColorType::OutlineColor}};
      bool known = false;
      for (const Property& p : kProperties)
        if (p.name == property) {
          c.set.materialColorBinds.push_back({static_cast<uint32_t>(material), p.type, *target});
          known = true;
        }
      if (!known)
        c.set.warnings.push_back(std::string(c.source) + ": " + facial::childPath(valuePath, "propertyName") + ": '" + property +
                                 "' is not a colour or _MainTex_ST; ignored");
    }
  }
  expression.materialColorBindCount = static_cast<uint32_t>(c.set.materialColorBinds.size()) - expression.firstMaterialColorBind;
  expression.textureTransformBindCount =
      static_cast<uint32_t>(c.set.textureTransformBinds.size()) - expression.firstTextureTransformBind;
  return {};
}

eng::Result<facial::VrmOverride> readOverride(const Context& c, const facial::Json& expression, std::string_view key,
                                      const std::string& path) {
  if (!expression.contains(key)) return facial::VrmOverride::None;
  const facial::Json& v = expression[std::string(key)];
  const std::string text = v.is_string() ? v.get<std::string>() : std::string();
  if (text == "none") return facial::VrmOverride::None;
  if (text == "block") return facial::VrmOverride::Block;
  if (text == "blend") return facial::VrmOverride::Blend;
  return facial::jsonError(c.source, facial::childPath(path, key), "must be \"none\", \"block\" or \"blend\", got " + v.dump());
}

eng::Result<void> readVrm1Expression(const Context& c, const std::string& name, const facial::Json& e, const std::string& path,
                                     bool isPreset) {
  if (!e.is_object()) return facial::jsonError(c.source, path, "an expression must be an object");
  facial::VrmExpression expression;
  expression.name = name;
  expression.isPreset = isPreset;
  expression.group = isPreset ? facial::vrmProceduralGroup(name) : facial::VrmProceduralGroup::None;
  auto binary = readBool(c, e, "isBinary", path);
  if (!binary) return binary.error();
  expression.isBinary = *binary;
  auto blink = readOverride(c, e, "overrideBlink", path);
  if (!blink) return blink.error();
  auto lookAt = readOverride(c, e, "overrideLookAt", path);
  if (!lookAt) return lookAt.error();
  auto mouth = readOverride(c, e, "overrideMouth", path);
  if (!mouth) return mouth.error();
  expression.overrideBlink = *blink;
  expression.overrideLookAt = *lookAt;
  expression.overrideMouth = *mouth;
  if (auto r = readVrm1MaterialBinds(c, e, path, expression); !r) return r.error();

  expression.firstBind = static_cast<uint32_t>(c.set.binds.size());
  if (e.contains("morphTargetBinds")) {
    const std::string bindsPath = facial::childPath(path, "morphTargetBinds");
    const facial::Json& binds = e["morphTargetBinds"];
    if (!binds.is_array()) return facial::jsonError(c.source, bindsPath, "must be an array");
    const facial::Json* nodes = c.gltf.contains("nodes") && c.gltf["nodes"].is_array() ? &c.gltf["nodes"] : nullptr;
    for (size_t b = 0; b < binds.size(); ++b) {
      const std::string bindPath = facial::childPath(bindsPath, b);
      const facial::Json& bind = binds[b];
      if (!bind.is_object()) return facial::jsonError(c.source, bindPath, "a bind must be an object {node, index, weight}");
      auto node = readIndex(c, bind, "node", bindPath, nodes ? nodes->size() : 0, "nodes");
      if (!node) return node.error();
      const facial::Json& nodeJson = (*nodes)[*node];
      if (!nodeJson.is_object() || !nodeJson.contains("mesh") || !nodeJson["mesh"].is_number_integer())
        return facial::jsonError(c.source, facial::childPath(bindPath, "node"), "node " + std::to_string(*node) + " has no mesh");
      const int64_t mesh = nodeJson["mesh"].get<int64_t>();
      if (mesh < 0 || static_cast<size_t>(mesh) + 1 >= c.set.meshTargetOffsets.size())
        return facial::jsonError(c.source, facial::childPath(facial::childPath("/nodes", *node), "mesh"),
                         std::to_string(mesh) + " is out of range (" + std::to_string(c.set.meshTargetOffsets.size() - 1) +
                             " meshes)");
      auto index = readIndex(c, bind, "index", bindPath, meshTargetCount(c.set, size_t(mesh)),
                             "morph targets on mesh " + std::to_string(mesh));
      if (!index) return index.error();
      auto weight = readBindWeight(c, bind, bindPath, 1.0);
      if (!weight) return weight.error();
      c.set.binds.push_back({c.set.meshTargetOffsets[size_t(mesh)] + static_cast<uint32_t>(*index), *weight});
    }
  }
  expression.bindCount = static_cast<uint32_t>(c.set.binds.size()) - expression.firstBind;
  c.set.expressions.push_back(std::move(expression));
  return {};
}

// A lookAt range map: `inputKey` (degrees, (0, 180]) and `outputKey` (finite, >= 0),
// each defaulting to the map's own value when absent.
eng::Result<void> readRangeMap(const Context& c, const facial::Json& owner, std::string_view key, const std::string& path,
                               std::string_view inputKey, std::string_view outputKey, facial::VrmLookAtRangeMap& map) {
  if (!owner.contains(key)) return {};
  const std::string mapPath = facial::childPath(path, key);
  const facial::Json& m = owner[std::string(key)];
  if (!m.is_object()) return facial::jsonError(c.source, mapPath, "must be an object");
  for (auto [field, out, maxValue] : {std::tuple{inputKey, &map.inputMaxValue, 180.0}, std::tuple{outputKey, &map.outputScale, 1e6}}) {
    if (!m.contains(field)) continue;
    const facial::Json& v = m[std::string(field)];
    const double x = v.is_number() ? v.get<double>() : -1.0;
    if (!v.is_number() || !std::isfinite(x) || x < 0.0 || x > maxValue || (out == &map.inputMaxValue && x == 0.0))
      return facial::jsonError(c.source, facial::childPath(mapPath, field), "must be a number in " +
                       std::string(out == &map.inputMaxValue ? "(0, 180]" : "[0, 1e6]") + ", got " + v.dump());
    *out = static_cast<float>(x);
  }
  return {};
}

// VRMC_vrm.lookAt {type, rangeMapHorizontalInner/Outer, rangeMapVerticalDown/Up
// {inputMaxValue, outputScale}}; VRM 0.x firstPerson {lookAtTypeName,
// lookAtHorizontalInner/Outer, lookAtVerticalDown/Up {xRange, yRange, curve}}
// (the curve is taken as linear). Absent: expression type, 90 degrees -> 1;
// bone type outputs default to 10 degrees.
eng::Result<void> readLookAt(const Context& c, const facial::Json& vrm, bool vrm1) {
  const char* ownerKey = vrm1 ? "lookAt" : "firstPerson";
  if (!vrm.is_object() || !vrm.contains(ownerKey)) return {};
  const std::string path = std::string(vrm1 ? "/extensions/VRMC_vrm/" : "/extensions/VRM/") + ownerKey;
  const facial::Json& owner = vrm[ownerKey];
  if (!owner.is_object()) return facial::jsonError(c.source, path, "must be an object");
  facial::VrmLookAt lookAt;
  const char* typeKey = vrm1 ? "type" : "lookAtTypeName";
  if (owner.contains(typeKey)) {
    const facial::Json& t = owner[typeKey];
    const std::string type = t.is_string() ? t.get<std::string>() : "";
    if (type == "bone" || type == "Bone") lookAt.type = facial::VrmLookAtType::Bone;
    else if (type == "expression" || type == "BlendShape") lookAt.type = facial::VrmLookAtType::Expression;
    else return facial::jsonError(c.source, facial::childPath(path, typeKey), vrm1 ? "must be \"bone\" or \"expression\", got " + t.dump()
                                                                   : "must be \"Bone\" or \"BlendShape\", got " + t.dump());
  }
  if (lookAt.type == facial::VrmLookAtType::Bone)
    for (facial::VrmLookAtRangeMap* map : {&lookAt.horizontalInner, &lookAt.horizontalOuter, &lookAt.verticalDown, &lookAt.verticalUp})
      map->outputScale = 10.0f;
  const std::string_view inputKey = vrm1 ? "inputMaxValue" : "xRange", outputKey = vrm1 ? "outputScale" : "yRange";
  const std::array<std::pair<std::string_view, facial::VrmLookAtRangeMap*>, 4> maps = {
      std::pair{vrm1 ? "rangeMapHorizontalInner" : "lookAtHorizontalInner", &lookAt.horizontalInner},
      std::pair{vrm1 ? "rangeMapHorizontalOuter" : "lookAtHorizontalOuter", &lookAt.horizontalOuter},
      std::pair{vrm1 ? "rangeMapVerticalDown" : "lookAtVerticalDown", &lookAt.verticalDown},
      std::pair{vrm1 ? "rangeMapVerticalUp" : "lookAtVerticalUp", &lookAt.verticalUp}};
  for (const auto& [key, map] : maps)
    if (auto r = readRangeMap(c, owner, key, path, inputKey, outputKey, *map); !r) return r;
  c.set.lookAt = lookAt;
  return {};
}

eng::Result<void> readVrm1(const Context& c, const facial::Json& vrm) {
  c.set.specVersion = 1;
  if (!vrm.is_object()) return facial::jsonError(c.source, "/extensions/VRMC_vrm", "must be an object");
  if (auto r = readLookAt(c, vrm, true); !r) return r;
  if (!vrm.contains("expressions")) return {};
  const facial::Json& expressions = vrm["expressions"];
  const std::string path = "/extensions/VRMC_vrm/expressions";
  if (!expressions.is_object()) return facial::jsonError(c.source, path, "must be an object {preset, custom}");
  for (const char* kind : {"preset", "custom"}) {
    if (!expressions.contains(kind)) continue;
    const std::string kindPath = facial::childPath(path, kind);
    const facial::Json& list = expressions[kind];
    if (!list.is_object()) return facial::jsonError(c.source, kindPath, "must be an object of name: expression");
    const bool presets = std::string_view(kind) == "preset";
    for (const auto& [name, e] : list.items()) {
      const std::string ePath = facial::childPath(kindPath, name);
      bool isPreset = presets;
      if (presets && !contains(kVrm1Presets, name)) {
        c.set.warnings.push_back(std::string(c.source) + ": " + ePath + ": not a VRM 1.0 preset name; treated as custom");
        isPreset = false;
      }
      if (!presets && contains(kVrm1Presets, name))
        return facial::jsonError(c.source, ePath, "a custom expression must not reuse the preset name '" + name + "'");
      if (auto r = readVrm1Expression(c, name, e, ePath, isPreset); !r) return r.error();
    }
  }
  return {};
}

eng::Result<void> readVrm0(const Context& c, const facial::Json& vrm) {
  c.set.specVersion = 0;
  if (auto r = readLookAt(c, vrm, false); !r) return r;
  const std::string masterPath = "/extensions/VRM/blendShapeMaster";
  if (!vrm.is_object() || !vrm.contains("blendShapeMaster")) return {};
  const facial::Json& master = vrm["blendShapeMaster"];
  if (!master.is_object()) return facial::jsonError(c.source, masterPath, "must be an object");
  if (!master.contains("blendShapeGroups")) return {};
  const std::string groupsPath = facial::childPath(masterPath, "blendShapeGroups");
  const facial::Json& groups = master["blendShapeGroups"];
  if (!groups.is_array()) return facial::jsonError(c.source, groupsPath, "must be an array");
  for (size_t g = 0; g < groups.size(); ++g) {
    const std::string path = facial::childPath(groupsPath, g);
    const facial::Json& group = groups[g];
    if (!group.is_object()) return facial::jsonError(c.source, path, "a blend shape group must be an object");
    std::string preset = "unknown";
    if (group.contains("presetName")) {
      if (!group["presetName"].is_string())
        return facial::jsonError(c.source, facial::childPath(path, "presetName"), "must be a string");
      preset = group["presetName"].get<std::string>();
      if (preset.empty()) preset = "unknown";
    }
    if (!contains(kVrm0Presets, preset))
      return facial::jsonError(c.source, facial::childPath(path, "presetName"), "'" + preset + "' is not a VRM 0.x preset name");
    std::string name = preset;
    if (preset == "unknown")
      name = group.contains("name") && group["name"].is_string() && !group["name"].get<std::string>().empty()
                 ? group["name"].get<std::string>()
                 : "group_" + std::to_string(g);
    for (const facial::VrmExpression& existing : c.set.expressions) {
      if (existing.name != name) continue;
      c.set.warnings.push_back(std::string(c.source) + ": " + path + ": a second expression named '" + name +
                               "'; renamed '" + name + " (" + std::to_string(g) + ")'");
      name += " (" + std::to_string(g) + ")";
      break;
    }
    facial::VrmExpression expression;
    expression.name = name;
    expression.isPreset = preset != "unknown";
    expression.group = expression.isPreset ? facial::vrmProceduralGroup(preset) : facial::VrmProceduralGroup::None;
    auto binary = readBool(c, group, "isBinary", path);
    if (!binary) return binary.error();
    expression.isBinary = *binary;
    if (auto r = readVrm0MaterialValues(c, group, path, expression); !r) return r.error();
    expression.firstBind = static_cast<uint32_t>(c.set.binds.size());
    if (group.contains("binds")) {
      const std::string bindsPath = facial::childPath(path, "binds");
      const facial::Json& binds = group["binds"];
      if (!binds.is_array()) return facial::jsonError(c.source, bindsPath, "must be an array");
      for (size_t b = 0; b < binds.size(); ++b) {
        const std::string bindPath = facial::childPath(bindsPath, b);
        const facial::Json& bind = binds[b];
        if (!bind.is_object()) return facial::jsonError(c.source, bindPath, "a bind must be an object {mesh, index, weight}");
        auto mesh = readIndex(c, bind, "mesh", bindPath, c.set.meshTargetOffsets.size() - 1, "meshes");
        if (!mesh) return mesh.error();
        auto index = readIndex(c, bind, "index", bindPath, meshTargetCount(c.set, *mesh),
                               "morph targets on mesh " + std::to_string(*mesh));
        if (!index) return index.error();
        auto weight = readBindWeight(c, bind, bindPath, 100.0);  // VRM 0.x weights run 0..100
        if (!weight) return weight.error();
        c.set.binds.push_back({c.set.meshTargetOffsets[*mesh] + static_cast<uint32_t>(*index), *weight});
      }
    }
    expression.bindCount = static_cast<uint32_t>(c.set.binds.size()) - expression.firstBind;
    c.set.expressions.push_back(std::move(expression));
  }
  return {};
}

}  // namespace

eng::Result<facial::VrmExpressionSet> importVrmExpressions(const facial::Json& gltf, std::string_view source) {
  if (!gltf.is_object()) return facial::jsonError(source, "", "a glTF document must be an object");
  const facial::Json* extensions = gltf.contains("extensions") && gltf["extensions"].is_object() ? &gltf["extensions"] : nullptr;
  const bool hasVrm1 = extensions && extensions->contains("VRMC_vrm");
  const bool hasVrm0 = extensions && extensions->contains("VRM");
  if (!hasVrm1 && !hasVrm0)
    return facial::jsonError(source, "/extensions", "no VRMC_vrm (VRM 1.0) or VRM (VRM 0.x) extension: not a VRM model");
  facial::VrmExpressionSet set;
  set.materialCount = static_cast<uint32_t>(materialCountOf(gltf));
  const Context c{source, gltf, set};
  if (auto r = readTargets(c); !r) return r.error();
  if (auto r = hasVrm1 ? readVrm1(c, (*extensions)["VRMC_vrm"]) : readVrm0(c, (*extensions)["VRM"]); !r)
    return r.error();
  if (hasVrm1 && hasVrm0)
    set.warnings.push_back(std::string(source) + ": both VRMC_vrm and VRM extensions present; VRM 1.0 used");
  if (auto valid = set.validate(); !valid) return valid.error().prefixed(std::string(source) + ": ");
  return set;
}

bool hasVrmExtension(const facial::Json& gltf) {
  return gltf.is_object() && gltf.contains("extensions") && gltf["extensions"].is_object() &&
         (gltf["extensions"].contains("VRMC_vrm") || gltf["extensions"].contains("VRM"));
}

namespace {

// The JSON text of a GLB container or of a text document.
eng::Result<std::string_view> gltfJsonText(std::span<const uint8_t> bytes, std::string_view source) {
  if (!eng::hasGlbMagic(bytes)) return std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  eng::Result<eng::GlbChunks> chunks = eng::parseGlb(bytes);
  if (!chunks) return chunks.error().prefixed(std::string(source) + ": ");
  return std::string_view(reinterpret_cast<const char*>(chunks->json.data()), chunks->json.size());
}

}  // namespace

eng::Result<facial::VrmExpressionSet> loadVrmExpressions(const std::filesystem::path& file) {
  eng::Result<std::vector<uint8_t>> bytes = eng::readFileBytes(file, kMaxVrmFileBytes);
  if (!bytes) return bytes.error();
  eng::Result<std::string_view> text = gltfJsonText(*bytes, file.string());
  if (!text) return text.error();
  eng::Result<facial::Json> json = facial::parseJsonText(*text, file.string());
  if (!json) return json.error();
  return importVrmExpressions(*json, file.string());
}

eng::Result<std::optional<facial::VrmExpressionSet>> findVrmExpressions(std::span<const uint8_t> bytes, std::string_view source) {
  eng::Result<std::string_view> text = gltfJsonText(bytes, source);
  if (!text) return text.error();
  // Both extension names start with "VRM": a document that never spells it is
  // a plain glTF, and its JSON is not parsed a second time here.
  if (text->find("\"VRM") == std::string_view::npos) return std::optional<facial::VrmExpressionSet>();
  eng::Result<facial::Json> json = facial::parseJsonText(*text, source);
  if (!json) return json.error();
  if (!hasVrmExtension(*json)) return std::optional<facial::VrmExpressionSet>();
  auto set = importVrmExpressions(*json, source);
  if (!set) return set.error();
  return std::optional<facial::VrmExpressionSet>(std::move(*set));
}

eng::Result<std::optional<facial::VrmExpressionSet>> findVrmExpressions(const std::filesystem::path& file) {
  eng::Result<std::vector<uint8_t>> bytes = eng::readFileBytes(file, kMaxVrmFileBytes);
  if (!bytes) return bytes.error();
  return findVrmExpressions(*bytes, file.string());
}

}  // namespace importers
