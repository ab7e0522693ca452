#include "importers/vrm_import.h"

#include <array>
#include <optional>
#include <string>
#include <utility>

#include "engine/core/name_index.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "facial/runtime/json/json_node.h"

namespace importers {
namespace {

using facial::JsonNode;

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

// Parsing context: the source for warnings, the document, the set being filled.
// Errors carry only their JSON pointer; importVrmExpressions puts the source in front.
struct Context {
  std::string_view source;
  JsonNode gltf;
  facial::VrmExpressionSet& set;
  const eng::NameIndex& materialNames;  // VRM 0.x binds name materials: one look-up each

  // A warning names the source, the pointer and the problem like an error, then what was done about it.
  void warn(const eng::Error& problem, std::string_view consequence) const {
    set.warnings.push_back(std::string(source) + ": " + problem.message + std::string(consequence));
  }
};

// A non-negative integer below `limit`: an index into the document's nodes, meshes, materials or targets.
eng::Result<size_t> readIndex(const JsonNode& object, std::string_view key, size_t limit, std::string_view limitWhat) {
  const JsonNode v = ENG_TRY_VALUE(object.at(key));
  if (!v.raw().is_number_integer() || v.raw().get<int64_t>() < 0)
    return v.error("must be a non-negative integer, got " + v.raw().dump());
  const size_t index = static_cast<size_t>(v.raw().get<int64_t>());
  if (index >= limit)
    return v.error(std::to_string(index) + " is out of range (" + std::to_string(limit) + " " + std::string(limitWhat) + ")");
  return index;
}

// A morph bind's "weight" in [0, maxWeight], scaled to [0, 1].
eng::Result<float> readBindWeight(const JsonNode& bind, float maxWeight) {
  const JsonNode v = ENG_TRY_VALUE(bind.at("weight"));
  const float w = ENG_TRY_VALUE(v.number());
  if (w < 0.0f || w > maxWeight)
    return v.error("weight " + facial::formatNumber(w) + " is outside [0, " + facial::formatNumber(maxWeight) + "]");
  return w / maxWeight;
}

// A material value's component. Serialisers write a NaN as null, so the message shows the value.
eng::Result<float> readFiniteNumber(const JsonNode& v) {
  auto x = v.number();
  if (!x) return v.error("must be a finite number, got " + v.raw().dump());
  return *x;
}

// The first N numbers of an array (a colour, a UV scale or offset).
template <size_t N>
eng::Result<std::array<float, N>> readFloats(const JsonNode& v) {
  if (!v.isArray() || v.raw().size() < N)
    return v.error("must be an array of " + std::to_string(N) + " numbers, got " + v.raw().dump());
  std::array<float, N> out{};
  for (size_t i = 0; i < N; ++i) out[i] = ENG_TRY_VALUE(readFiniteNumber(v.element(i)));
  return out;
}

size_t materialCountOf(const JsonNode& gltf) {
  const auto materials = gltf.find("materials");
  return materials && materials->isArray() ? materials->raw().size() : 0;
}

size_t meshTargetCount(const facial::VrmExpressionSet& set, size_t mesh) {
  return set.meshTargetOffsets[mesh + 1] - set.meshTargetOffsets[mesh];
}

// ---- targets ----

// How many morph targets a mesh has: every primitive must have as many.
eng::Result<size_t> meshMorphTargetCount(const JsonNode& mesh) {
  const auto primitives = mesh.find("primitives");
  if (!primitives || !primitives->isArray()) return mesh.error("a mesh must be an object with a primitives array");
  size_t count = 0;
  for (size_t p = 0; p < primitives->raw().size(); ++p) {
    const JsonNode primitive = primitives->element(p);
    const auto targets = primitive.find("targets");
    const size_t n = targets && targets->isArray() ? targets->raw().size() : 0;
    if (p == 0) count = n;
    else if (n != count)
      return (targets ? *targets : primitive)
          .error(std::to_string(n) + " morph targets, primitive 0 has " + std::to_string(count));
  }
  return count;
}

// One mesh's targets, "<mesh name>/<target name>" from mesh.extras.targetNames
// when it names them all ("mesh_M", "target_N" without).
eng::Result<void> readMeshTargets(const JsonNode& mesh, size_t m, facial::VrmExpressionSet& set) {
  const size_t count = ENG_TRY_VALUE(meshMorphTargetCount(mesh));
  std::string meshName = "mesh_" + std::to_string(m);
  if (auto name = mesh.find("name"); name && name->isString()) meshName = name->raw().get<std::string>();
  std::optional<JsonNode> names;
  if (auto extras = mesh.find("extras"))
    if (auto list = extras->find("targetNames"); list && list->isArray() && list->raw().size() == count) names = list;
  for (size_t t = 0; t < count; ++t) {
    std::string targetName = "target_" + std::to_string(t);
    if (names && names->element(t).isString()) targetName = names->element(t).raw().get<std::string>();
    set.targetNames.push_back(meshName + "/" + targetName);
  }
  set.meshTargetOffsets.push_back(static_cast<uint32_t>(set.targetNames.size()));
  return {};
}

// Flat, mesh-major target list of the document.
eng::Result<void> readTargets(const Context& c) {
  c.set.meshTargetOffsets.push_back(0);
  const auto meshes = c.gltf.find("meshes");
  if (!meshes) return {};
  const size_t count = ENG_TRY_VALUE(meshes->size());
  for (size_t m = 0; m < count; ++m) ENG_TRY(readMeshTargets(meshes->element(m), m, c.set));
  return {};
}

// ---- material binds ----
// A material bind that cannot be applied (no such material, unknown type, a
// value that is not a finite number) is left out with one warning naming the
// file and the bind: the rest of the avatar still works.

constexpr std::string_view kBindIgnored = "; bind ignored";

eng::Result<facial::VrmMaterialColorType> readColorType(const JsonNode& bind) {
  const JsonNode type = ENG_TRY_VALUE(bind.at("type"));
  for (auto t : {facial::VrmMaterialColorType::Color, facial::VrmMaterialColorType::EmissionColor,
                 facial::VrmMaterialColorType::ShadeColor, facial::VrmMaterialColorType::MatcapColor,
                 facial::VrmMaterialColorType::RimColor, facial::VrmMaterialColorType::OutlineColor})
    if (type.isString() && facial::vrmMaterialColorTypeName(t) == type.raw().get<std::string>()) return t;
  return type.error("must be color, emissionColor, shadeColor, matcapColor, rimColor or outlineColor, got " + type.raw().dump());
}

// VRM 1.0 materialColorBinds[i]: {material, type, targetValue[4]}.
eng::Result<facial::VrmMaterialColorBind> readColorBind(const JsonNode& bind, size_t materials) {
  facial::VrmMaterialColorBind out;
  out.material = static_cast<uint32_t>(ENG_TRY_VALUE(readIndex(bind, "material", materials, "materials")));
  out.type = ENG_TRY_VALUE(readColorType(bind));
  out.targetValue = ENG_TRY_VALUE(readFloats<4>(ENG_TRY_VALUE(bind.at("targetValue"))));
  return out;
}

// VRM 1.0 textureTransformBinds[i]: {material, scale[2], offset[2]}.
eng::Result<facial::VrmTextureTransformBind> readTextureTransformBind(const JsonNode& bind, size_t materials) {
  facial::VrmTextureTransformBind out;
  out.material = static_cast<uint32_t>(ENG_TRY_VALUE(readIndex(bind, "material", materials, "materials")));
  if (auto scale = bind.find("scale")) out.scale = ENG_TRY_VALUE(readFloats<2>(*scale));
  if (auto offset = bind.find("offset")) out.offset = ENG_TRY_VALUE(readFloats<2>(*offset));
  return out;
}

// A VRM 1.0 bind list: each bind must be an object; one that cannot be applied is skipped.
template <class Bind, class ReadBind>
eng::Result<void> readVrm1MaterialBindList(const Context& c, const JsonNode& binds, std::string_view shape,
                                           std::vector<Bind>& out, ReadBind readBind) {
  const size_t count = ENG_TRY_VALUE(binds.size());
  const size_t materials = materialCountOf(c.gltf);
  for (size_t b = 0; b < count; ++b) {
    const JsonNode bind = binds.element(b);
    if (!bind.isObject()) return bind.error("a bind must be an object " + std::string(shape));
    auto read = readBind(bind, materials);
    if (read) out.push_back(std::move(read).value());
    else c.warn(read.error(), kBindIgnored);
  }
  return {};
}

eng::Result<void> readVrm1MaterialBinds(const Context& c, const JsonNode& e, facial::VrmExpression& expression) {
  expression.firstMaterialColorBind = static_cast<uint32_t>(c.set.materialColorBinds.size());
  if (auto binds = e.find("materialColorBinds"))
    ENG_TRY(readVrm1MaterialBindList(c, *binds, "{material, type, targetValue}", c.set.materialColorBinds, readColorBind));
  expression.materialColorBindCount = static_cast<uint32_t>(c.set.materialColorBinds.size()) - expression.firstMaterialColorBind;
  expression.firstTextureTransformBind = static_cast<uint32_t>(c.set.textureTransformBinds.size());
  if (auto binds = e.find("textureTransformBinds"))
    ENG_TRY(readVrm1MaterialBindList(c, *binds, "{material, scale, offset}", c.set.textureTransformBinds,
                                     readTextureTransformBind));
  expression.textureTransformBindCount =
      static_cast<uint32_t>(c.set.textureTransformBinds.size()) - expression.firstTextureTransformBind;
  return {};
}

// The glTF materials by name (an unnamed material is called ""; of two with
// one name, the first).
eng::NameIndex materialNameIndex(const JsonNode& gltf) {
  eng::NameIndex index;
  const auto materials = gltf.find("materials");
  const size_t count = materialCountOf(gltf);
  for (size_t m = 0; m < count; ++m) {
    const JsonNode material = materials->element(m);
    if (!material.isObject()) continue;
    const auto own = material.find("name");
    index.add(own && own->isString() ? own->raw().get<std::string>() : std::string(), static_cast<uint32_t>(m));
  }
  return index;
}

// The colour a VRM 0.x material property sets (nullopt: not a colour).
std::optional<facial::VrmMaterialColorType> vrm0ColorProperty(std::string_view property) {
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
  for (const Property& p : kProperties)
    if (p.name == property) return p.type;
  return std::nullopt;
}

// VRM 0.x materialValues[i]: {materialName, propertyName, targetValue[4]}; a
// colour property or _MainTex_ST (a texture transform: scale xy, offset zw).
// An error skips the value; a property that is neither is ignored with a warning.
eng::Result<void> readVrm0MaterialValue(const Context& c, const JsonNode& value) {
  const JsonNode materialName = ENG_TRY_VALUE(value.at("materialName"));
  const JsonNode propertyName = ENG_TRY_VALUE(value.at("propertyName"));
  const std::string name = ENG_TRY_VALUE(materialName.string());
  const std::string property = ENG_TRY_VALUE(propertyName.string());
  const std::optional<uint32_t> material = c.materialNames.find(name);
  if (!material) return materialName.error("no material is named '" + name + "'");
  const std::array<float, 4> target = ENG_TRY_VALUE(readFloats<4>(ENG_TRY_VALUE(value.at("targetValue"))));
  const auto index = static_cast<uint32_t>(*material);
  if (property == "_MainTex_ST") {
    c.set.textureTransformBinds.push_back({index, {target[0], target[1]}, {target[2], target[3]}});
  } else if (const auto type = vrm0ColorProperty(property)) {
    c.set.materialColorBinds.push_back({index, *type, target});
  } else {
    c.warn(propertyName.error("'" + property + "' is not a colour or _MainTex_ST"), "; ignored");
  }
  return {};
}

eng::Result<void> readVrm0MaterialValues(const Context& c, const JsonNode& group, facial::VrmExpression& expression) {
  expression.firstMaterialColorBind = static_cast<uint32_t>(c.set.materialColorBinds.size());
  expression.firstTextureTransformBind = static_cast<uint32_t>(c.set.textureTransformBinds.size());
  if (auto values = group.find("materialValues")) {
    const size_t count = ENG_TRY_VALUE(values->size());
    for (size_t b = 0; b < count; ++b)
      if (auto read = readVrm0MaterialValue(c, values->element(b)); !read) c.warn(read.error(), kBindIgnored);
  }
  expression.materialColorBindCount = static_cast<uint32_t>(c.set.materialColorBinds.size()) - expression.firstMaterialColorBind;
  expression.textureTransformBindCount =
      static_cast<uint32_t>(c.set.textureTransformBinds.size()) - expression.firstTextureTransformBind;
  return {};
}

// ---- VRM 1.0 expressions ----

eng::Result<facial::VrmOverride> readOverride(const JsonNode& expression, std::string_view key) {
  const auto v = expression.find(key);
  if (!v) return facial::VrmOverride::None;
  const std::string text = v->isString() ? v->raw().get<std::string>() : std::string();
  if (text == "none") return facial::VrmOverride::None;
  if (text == "block") return facial::VrmOverride::Block;
  if (text == "blend") return facial::VrmOverride::Blend;
  return v->error("must be \"none\", \"block\" or \"blend\", got " + v->raw().dump());
}

// The flat target of a morphTargetBinds entry {node, index, weight}: the node's mesh, then the index on it.
eng::Result<facial::VrmMorphBind> readVrm1MorphBind(const Context& c, const JsonNode& bind) {
  const auto nodes = c.gltf.find("nodes");
  const size_t nodeCount = nodes && nodes->isArray() ? nodes->raw().size() : 0;
  const size_t node = ENG_TRY_VALUE(readIndex(bind, "node", nodeCount, "nodes"));
  const auto meshRef = nodes->element(node).find("mesh");
  if (!meshRef || !meshRef->raw().is_number_integer())
    return ENG_TRY_VALUE(bind.at("node")).error("node " + std::to_string(node) + " has no mesh");
  const int64_t mesh = meshRef->raw().get<int64_t>();
  const size_t meshCount = c.set.meshTargetOffsets.size() - 1;
  if (mesh < 0 || static_cast<size_t>(mesh) >= meshCount)
    return meshRef->error(std::to_string(mesh) + " is out of range (" + std::to_string(meshCount) + " meshes)");
  const size_t index = ENG_TRY_VALUE(readIndex(bind, "index", meshTargetCount(c.set, size_t(mesh)),
                                               "morph targets on mesh " + std::to_string(mesh)));
  const float weight = ENG_TRY_VALUE(readBindWeight(bind, 1.0f));
  return facial::VrmMorphBind{c.set.meshTargetOffsets[size_t(mesh)] + static_cast<uint32_t>(index), weight};
}

eng::Result<void> readVrm1MorphBinds(const Context& c, const JsonNode& binds) {
  const size_t count = ENG_TRY_VALUE(binds.size());
  for (size_t b = 0; b < count; ++b) {
    const JsonNode bind = binds.element(b);
    if (!bind.isObject()) return bind.error("a bind must be an object {node, index, weight}");
    c.set.binds.push_back(ENG_TRY_VALUE(readVrm1MorphBind(c, bind)));
  }
  return {};
}

eng::Result<void> readVrm1Expression(const Context& c, std::string_view name, const JsonNode& e, bool isPreset) {
  if (!e.isObject()) return e.error("an expression must be an object");
  facial::VrmExpression expression;
  expression.name = name;
  expression.isPreset = isPreset;
  expression.group = isPreset ? facial::vrmProceduralGroup(name) : facial::VrmProceduralGroup::None;
  expression.isBinary = ENG_TRY_VALUE(e.booleanOr("isBinary", false));
  expression.overrideBlink = ENG_TRY_VALUE(readOverride(e, "overrideBlink"));
  expression.overrideLookAt = ENG_TRY_VALUE(readOverride(e, "overrideLookAt"));
  expression.overrideMouth = ENG_TRY_VALUE(readOverride(e, "overrideMouth"));
  ENG_TRY(readVrm1MaterialBinds(c, e, expression));
  expression.firstBind = static_cast<uint32_t>(c.set.binds.size());
  if (auto binds = e.find("morphTargetBinds")) ENG_TRY(readVrm1MorphBinds(c, *binds));
  expression.bindCount = static_cast<uint32_t>(c.set.binds.size()) - expression.firstBind;
  c.set.expressions.push_back(std::move(expression));
  return {};
}

// expressions.preset or expressions.custom: {name: expression}.
eng::Result<void> readVrm1Expressions(const Context& c, const JsonNode& list, bool presets) {
  for (const auto& [name, e] : ENG_TRY_VALUE(list.members())) {
    const bool presetName = contains(kVrm1Presets, name);
    if (presets && !presetName) c.warn(e.error("not a VRM 1.0 preset name"), "; treated as custom");
    if (!presets && presetName)
      return e.error("a custom expression must not reuse the preset name '" + std::string(name) + "'");
    ENG_TRY(readVrm1Expression(c, name, e, presets && presetName));
  }
  return {};
}

// ---- lookAt ----

// A lookAt range map: `inputKey` (degrees, (0, 180]) and `outputKey` (finite, >= 0),
// each defaulting to the map's own value when absent.
eng::Result<void> readRangeMap(const JsonNode& m, std::string_view inputKey, std::string_view outputKey,
                               facial::VrmLookAtRangeMap& map) {
  if (!m.isObject()) return m.error("must be an object");
  if (auto v = m.find(inputKey)) {
    const double x = v->isNumber() ? v->raw().get<double>() : -1.0;
    if (!(x > 0.0 && x <= 180.0)) return v->error("must be a number in (0, 180], got " + v->raw().dump());
    map.inputMaxValue = static_cast<float>(x);
  }
  if (auto v = m.find(outputKey)) {
    const double x = v->isNumber() ? v->raw().get<double>() : -1.0;
    if (!(x >= 0.0 && x <= 1e6)) return v->error("must be a number in [0, 1e6], got " + v->raw().dump());
    map.outputScale = static_cast<float>(x);
  }
  return {};
}

// Either spelling in either version: "bone" / "Bone", "expression" / "BlendShape".
eng::Result<facial::VrmLookAtType> readLookAtType(const JsonNode& t, bool vrm1) {
  const std::string type = t.isString() ? t.raw().get<std::string>() : std::string();
  if (type == "bone" || type == "Bone") return facial::VrmLookAtType::Bone;
  if (type == "expression" || type == "BlendShape") return facial::VrmLookAtType::Expression;
  return t.error(std::string(vrm1 ? "must be \"bone\" or \"expression\", got " : "must be \"Bone\" or \"BlendShape\", got ") +
                 t.raw().dump());
}

// VRMC_vrm.lookAt {type, rangeMapHorizontalInner/Outer, rangeMapVerticalDown/Up
// {inputMaxValue, outputScale}}; VRM 0.x firstPerson {lookAtTypeName,
// lookAtHorizontalInner/Outer, lookAtVerticalDown/Up {xRange, yRange, curve}}
// (the curve is taken as linear). Absent: expression type, 90 degrees -> 1;
// bone type outputs default to 10 degrees.
eng::Result<void> readLookAt(const Context& c, const JsonNode& vrm, bool vrm1) {
  const auto owner = vrm.find(vrm1 ? "lookAt" : "firstPerson");
  if (!owner) return {};
  if (!owner->isObject()) return owner->error("must be an object");
  facial::VrmLookAt lookAt;
  if (auto type = owner->find(vrm1 ? "type" : "lookAtTypeName")) lookAt.type = ENG_TRY_VALUE(readLookAtType(*type, vrm1));
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
    if (auto m = owner->find(key)) ENG_TRY(readRangeMap(*m, inputKey, outputKey, *map));
  c.set.lookAt = lookAt;
  return {};
}

eng::Result<void> readVrm1(const Context& c, const JsonNode& vrm) {
  c.set.specVersion = 1;
  if (!vrm.isObject()) return vrm.error("must be an object");
  ENG_TRY(readLookAt(c, vrm, true));
  const auto expressions = vrm.find("expressions");
  if (!expressions) return {};
  if (!expressions->isObject()) return expressions->error("must be an object {preset, custom}");
  if (auto presets = expressions->find("preset")) ENG_TRY(readVrm1Expressions(c, *presets, true));
  if (auto custom = expressions->find("custom")) ENG_TRY(readVrm1Expressions(c, *custom, false));
  return {};
}

// ---- VRM 0.x blend shape groups ----

// presetName: a VRM 0.x preset, "unknown" when absent or empty.
eng::Result<std::string> readVrm0PresetName(const JsonNode& group) {
  const auto node = group.find("presetName");
  if (!node) return std::string("unknown");
  std::string preset = ENG_TRY_VALUE(node->string());
  if (preset.empty()) preset = "unknown";
  if (!contains(kVrm0Presets, preset)) return node->error("'" + preset + "' is not a VRM 0.x preset name");
  return preset;
}

// A group is called by its presetName, or its own name for "unknown" ("group_G"
// without one); a name already taken gets " (G)" after it, with a warning.
std::string vrm0GroupName(const Context& c, const JsonNode& group, const std::string& preset, size_t g) {
  std::string name = preset;
  if (preset == "unknown") {
    const auto own = group.find("name");
    name = own && own->isString() && !own->raw().get<std::string>().empty() ? own->raw().get<std::string>()
                                                                             : "group_" + std::to_string(g);
  }
  for (const facial::VrmExpression& existing : c.set.expressions) {
    if (existing.name != name) continue;
    const std::string renamed = name + " (" + std::to_string(g) + ")";
    c.warn(group.error("a second expression named '" + name + "'"), "; renamed '" + renamed + "'");
    return renamed;
  }
  return name;
}

// binds [{mesh, index, weight}]; VRM 0.x weights run 0..100.
eng::Result<void> readVrm0Binds(const Context& c, const JsonNode& binds) {
  const size_t count = ENG_TRY_VALUE(binds.size());
  for (size_t b = 0; b < count; ++b) {
    const JsonNode bind = binds.element(b);
    if (!bind.isObject()) return bind.error("a bind must be an object {mesh, index, weight}");
    const size_t mesh = ENG_TRY_VALUE(readIndex(bind, "mesh", c.set.meshTargetOffsets.size() - 1, "meshes"));
    const size_t index = ENG_TRY_VALUE(
        readIndex(bind, "index", meshTargetCount(c.set, mesh), "morph targets on mesh " + std::to_string(mesh)));
    const float weight = ENG_TRY_VALUE(readBindWeight(bind, 100.0f));
    c.set.binds.push_back({c.set.meshTargetOffsets[mesh] + static_cast<uint32_t>(index), weight});
  }
  return {};
}

eng::Result<void> readVrm0Group(const Context& c, const JsonNode& group, size_t g) {
  if (!group.isObject()) return group.error("a blend shape group must be an object");
  const std::string preset = ENG_TRY_VALUE(readVrm0PresetName(group));
  facial::VrmExpression expression;
  expression.name = vrm0GroupName(c, group, preset, g);
  expression.isPreset = preset != "unknown";
  expression.group = expression.isPreset ? facial::vrmProceduralGroup(preset) : facial::VrmProceduralGroup::None;
  expression.isBinary = ENG_TRY_VALUE(group.booleanOr("isBinary", false));
  ENG_TRY(readVrm0MaterialValues(c, group, expression));
  expression.firstBind = static_cast<uint32_t>(c.set.binds.size());
  if (auto binds = group.find("binds")) ENG_TRY(readVrm0Binds(c, *binds));
  expression.bindCount = static_cast<uint32_t>(c.set.binds.size()) - expression.firstBind;
  c.set.expressions.push_back(std::move(expression));
  return {};
}

eng::Result<void> readVrm0(const Context& c, const JsonNode& vrm) {
  c.set.specVersion = 0;
  ENG_TRY(readLookAt(c, vrm, false));
  const auto master = vrm.find("blendShapeMaster");
  if (!master) return {};
  if (!master->isObject()) return master->error("must be an object");
  const auto groups = master->find("blendShapeGroups");
  if (!groups) return {};
  const size_t count = ENG_TRY_VALUE(groups->size());
  for (size_t g = 0; g < count; ++g) ENG_TRY(readVrm0Group(c, groups->element(g), g));
  return {};
}

eng::Result<void> readVrmDocument(const JsonNode& gltf, std::string_view source, facial::VrmExpressionSet& set) {
  if (!gltf.isObject()) return gltf.error("a glTF document must be an object");
  const auto extensions = gltf.find("extensions");
  const auto vrm1 = extensions ? extensions->find("VRMC_vrm") : std::nullopt;
  const auto vrm0 = extensions ? extensions->find("VRM") : std::nullopt;
  if (!vrm1 && !vrm0)
    return extensions.value_or(gltf).error("no VRMC_vrm (VRM 1.0) or VRM (VRM 0.x) extension: not a VRM model");
  set.materialCount = static_cast<uint32_t>(materialCountOf(gltf));
  const eng::NameIndex materialNames = materialNameIndex(gltf);
  const Context c{source, gltf, set, materialNames};
  ENG_TRY(readTargets(c));
  ENG_TRY(vrm1 ? readVrm1(c, *vrm1) : readVrm0(c, *vrm0));
  if (vrm1 && vrm0) set.warnings.push_back(std::string(source) + ": both VRMC_vrm and VRM extensions present; VRM 1.0 used");
  return {};
}

}  // namespace

eng::Result<facial::VrmExpressionSet> importVrmExpressions(const facial::Json& gltf, std::string_view source) {
  facial::VrmExpressionSet set;
  if (auto read = readVrmDocument(JsonNode(gltf, ""), source, set); !read) return read.error().prefixed(std::string(source) + ": ");
  if (auto valid = set.validate(); !valid) return valid.error().prefixed(std::string(source) + ": ");
  return set;
}

bool hasVrmExtension(const facial::Json& gltf) {
  const auto extensions = JsonNode(gltf, "").find("extensions");
  return extensions && (extensions->has("VRMC_vrm") || extensions->has("VRM"));
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
