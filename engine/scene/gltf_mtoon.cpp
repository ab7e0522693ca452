#include "engine/scene/gltf_mtoon.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>

namespace eng {
namespace {

// UV animation scrolls or turns the textures over time; they are drawn still.
constexpr const char* kUvAnimationNotDrawn = "its UV animation is not drawn (the textures stay still)";

float srgbToLinear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// Reads named numbers off one JSON object, keeping the default (and saying
// so) where a value is missing its type, is not finite or is out of range.
class Fields {
 public:
  Fields(const tinygltf::Value& object, std::string where, std::vector<std::string>& problems)
      : object_(object), where_(std::move(where)), problems_(problems) {}

  void number(const char* name, float& out, float lo, float hi) {
    if (!object_.IsObject() || !object_.Has(name)) return;
    const tinygltf::Value& v = object_.Get(name);
    const float x = v.IsNumber() ? static_cast<float>(v.GetNumberAsDouble()) : NAN;
    if (!std::isfinite(x) || x < lo || x > hi) {
      problems_.push_back(where_ + ": " + name + " is not a number in [" + format(lo) + ", " + format(hi) + "]; " +
                          format(out) + " used");
      return;
    }
    out = x;
  }

  // n >= 3 numbers; the first three are a colour, linear unless `srgb`.
  void colour(const char* name, glm::vec3& out, bool srgb) {
    if (!object_.IsObject() || !object_.Has(name)) return;
    const tinygltf::Value& v = object_.Get(name);
    glm::vec3 c(0.0f);
    bool ok = v.IsArray() && v.ArrayLen() >= 3;
    for (int i = 0; ok && i < 3; ++i) {
      ok = v.Get(i).IsNumber();
      if (ok) c[i] = static_cast<float>(v.Get(i).GetNumberAsDouble());
      ok = ok && std::isfinite(c[i]) && c[i] >= 0.0f;
    }
    if (!ok) {
      problems_.push_back(where_ + ": " + name + " is not a colour (three numbers >= 0); black used");
      return;
    }
    out = srgb ? glm::vec3(srgbToLinear(c.x), srgbToLinear(c.y), srgbToLinear(c.z)) : c;
  }

  int texture(const char* name) const {
    if (!object_.IsObject() || !object_.Has(name)) return -1;
    const tinygltf::Value& v = object_.Get(name);
    const tinygltf::Value& index = v.IsObject() && v.Has("index") ? v.Get("index") : v;  // 1.0 textureInfo, 0.x index
    return index.IsNumber() ? static_cast<int>(index.GetNumberAsDouble()) : -1;
  }

  // A texture with its UV set and extensions: 1.0's textureInfo, or 0.x's bare index.
  MtoonRead::Texture textureInfo(const char* name) const {
    MtoonRead::Texture t;
    t.index = texture(name);
    if (t.index < 0) return t;
    const tinygltf::Value& v = object_.Get(name);
    if (!v.IsObject()) return t;
    if (v.Has("texCoord") && v.Get("texCoord").IsNumber())
      t.texCoord = static_cast<int>(v.Get("texCoord").GetNumberAsDouble());
    if (v.Has("extensions") && v.Get("extensions").IsObject())
      for (const std::string& key : v.Get("extensions").Keys()) t.extensions[key] = v.Get("extensions").Get(key);
    return t;
  }

  // The named member, an object, for fields of its own ("shadingShiftTexture"'s scale).
  Fields nested(const char* name) const {
    static const tinygltf::Value kNone;
    return Fields(has(name) ? object_.Get(name) : kNone, where_ + " " + name, problems_);
  }

  bool has(const char* name) const { return object_.IsObject() && object_.Has(name); }

  // Whether any of the named numbers is set and not 0 (UV animation's speeds).
  bool anyNonZero(std::initializer_list<const char*> names) {
    bool any = false;
    for (const char* name : names) {
      float x = 0.0f;
      number(name, x, -1e6f, 1e6f);
      any = any || x != 0.0f;
    }
    return any;
  }

 private:
  static std::string format(float x) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", x);
    return text;
  }
  const tinygltf::Value& object_;
  std::string where_;
  std::vector<std::string>& problems_;
};

const tinygltf::Value* member(const tinygltf::Value& object, const char* name) {
  return object.IsObject() && object.Has(name) ? &object.Get(name) : nullptr;
}

MtoonRead readVersion1(const tinygltf::Value& ext, const std::string& where) {
  MtoonRead r;
  ToonShading t;
  Fields f(ext, where + " " + kVrmcMaterialsMtoon, r.problems);
  f.colour("shadeColorFactor", t.shadeColor, false);
  f.number("shadingShiftFactor", t.shadingShift, -1.0f, 1.0f);
  f.number("shadingToonyFactor", t.shadingToony, 0.0f, 1.0f);
  f.number("giEqualizationFactor", t.giEqualization, 0.0f, 1.0f);
  f.colour("parametricRimColorFactor", t.rimColor, false);
  f.number("parametricRimFresnelPowerFactor", t.rimFresnelPower, 0.0f, 100.0f);
  f.number("parametricRimLiftFactor", t.rimLift, -1.0f, 1.0f);
  f.number("rimLightingMixFactor", t.rimLightingMix, 0.0f, 1.0f);
  r.shadeTexture = f.texture("shadeMultiplyTexture");
  t.shadeFromBaseTexture = r.shadeTexture >= 0;
  if (const tinygltf::Value* mode = member(ext, "outlineWidthMode")) {
    const std::string name = mode->IsString() ? mode->Get<std::string>() : "";
    if (name == "worldCoordinates") t.outlineMode = ToonShading::OutlineWidth::World;
    else if (name == "screenCoordinates") t.outlineMode = ToonShading::OutlineWidth::Screen;
    else if (name != "none")
      r.problems.push_back(where + " " + kVrmcMaterialsMtoon + ": outlineWidthMode '" + name +
                           "' is not none, worldCoordinates or screenCoordinates; no outline");
  }
  f.number("outlineWidthFactor", t.outlineWidth, 0.0f, 1.0f);
  f.colour("outlineColorFactor", t.outlineColor, false);
  f.number("outlineLightingMixFactor", t.outlineLightingMix, 0.0f, 1.0f);
  f.colour("matcapFactor", t.matcapFactor, false);
  r.matcapTexture = f.texture("matcapTexture");
  r.shadingShiftTexture = f.textureInfo("shadingShiftTexture");
  f.nested("shadingShiftTexture").number("scale", t.shadingShiftTextureScale, -100.0f, 100.0f);
  r.rimMultiplyTexture = f.textureInfo("rimMultiplyTexture");
  r.outlineWidthTexture = f.textureInfo("outlineWidthMultiplyTexture");
  if (f.anyNonZero({"uvAnimationScrollXSpeedFactor", "uvAnimationScrollYSpeedFactor", "uvAnimationRotationSpeedFactor"}))
    r.problems.push_back(where + " " + kVrmcMaterialsMtoon + ": " + kUvAnimationNotDrawn);
  r.toon = t;
  return r;
}

// VRM 0.x MToon, converted as UniVRM's MToon10Migrator does: the 0.x shade
// range runs from _ShadeShift to lerp(1, _ShadeShift, _ShadeToony); 1.0's
// toony is that range's margin and its shift the range's centre, negated.
// 0.x colours are sRGB-encoded.
MtoonRead readVersion0(const tinygltf::Value& props, const std::string& where) {
  MtoonRead r;
  ToonShading t;
  const std::string at = where + " VRM materialProperties (VRM/MToon)";
  static const tinygltf::Value kNone;
  const tinygltf::Value* floats = member(props, "floatProperties");
  const tinygltf::Value* vectors = member(props, "vectorProperties");
  const tinygltf::Value* textures = member(props, "textureProperties");
  Fields ff(floats ? *floats : kNone, at, r.problems);
  Fields fv(vectors ? *vectors : kNone, at, r.problems);
  Fields ft(textures ? *textures : kNone, at, r.problems);
  float shift0 = 0.0f, toony0 = 0.9f, gi0 = 0.1f;
  ff.number("_ShadeShift", shift0, -1.0f, 1.0f);
  ff.number("_ShadeToony", toony0, 0.0f, 1.0f);
  ff.number("_IndirectLightIntensity", gi0, 0.0f, 1.0f);
  const float rangeMin = shift0, rangeMax = 1.0f + (shift0 - 1.0f) * toony0;
  t.shadingToony = std::clamp((2.0f - (rangeMax - rangeMin)) * 0.5f, 0.0f, 1.0f);
  t.shadingShift = std::clamp(-(rangeMax + rangeMin) * 0.5f, -1.0f, 1.0f);
  t.giEqualization = std::clamp(1.0f - gi0, 0.0f, 1.0f);
  fv.colour("_ShadeColor", t.shadeColor, true);
  fv.colour("_RimColor", t.rimColor, true);
  ff.number("_RimFresnelPower", t.rimFresnelPower, 0.0f, 100.0f);
  ff.number("_RimLift", t.rimLift, -1.0f, 1.0f);
  ff.number("_RimLightingMix", t.rimLightingMix, 0.0f, 1.0f);
  // A 0.x shade without its own texture is multiplied by _MainTex (UniVRM's migration).
  r.shadeTexture = ft.texture("_ShadeTexture");
  if (r.shadeTexture < 0) r.shadeTexture = ft.texture("_MainTex");
  t.shadeFromBaseTexture = r.shadeTexture >= 0;
  // Outline: _OutlineWidth in centimetres (world) or percent of the image
  // height (screen); a fixed colour mode (_OutlineColorMode 0) ignores the lighting.
  float widthMode = 0.0f, width = 0.0f, colourMode = 0.0f;
  ff.number("_OutlineWidthMode", widthMode, 0.0f, 2.0f);
  ff.number("_OutlineWidth", width, 0.0f, 100.0f);
  ff.number("_OutlineColorMode", colourMode, 0.0f, 1.0f);
  t.outlineMode = widthMode == 1.0f   ? ToonShading::OutlineWidth::World
                  : widthMode == 2.0f ? ToonShading::OutlineWidth::Screen
                                      : ToonShading::OutlineWidth::None;
  t.outlineWidth = width * 0.01f;
  fv.colour("_OutlineColor", t.outlineColor, true);
  ff.number("_OutlineLightingMix", t.outlineLightingMix, 0.0f, 1.0f);
  if (colourMode == 0.0f) t.outlineLightingMix = 0.0f;
  r.normalTexture = ft.texture("_BumpMap");
  ff.number("_BumpScale", r.normalScale, -10.0f, 10.0f);
  r.matcapTexture = ft.texture("_SphereAdd");  // added as it is (UniVRM: matcapFactor white)
  r.rimMultiplyTexture = ft.textureInfo("_RimTexture");
  r.outlineWidthTexture = ft.textureInfo("_OutlineWidthTexture");
  // 0.x scales dot(N, L) by its shading grade where 1.0 shifts it: no 1.0
  // equivalent (the grade rate's default is 1).
  float gradeRate = 1.0f;
  ff.number("_ShadingGradeRate", gradeRate, 0.0f, 1.0f);
  if (ft.texture("_ShadingGradeTexture") >= 0 && gradeRate > 0.0f)
    r.problems.push_back(at + ": its _ShadingGradeTexture is not drawn (0.x's shading grade has no 1.0 equivalent)");
  if (ff.anyNonZero({"_UvAnimScrollX", "_UvAnimScrollY", "_UvAnimRotation"})) r.problems.push_back(at + ": " + kUvAnimationNotDrawn);
  r.toon = t;
  return r;
}

}  // namespace

MtoonRead readMtoon(const tinygltf::Model& gltf, size_t index) {
  if (index >= gltf.materials.size()) return {};
  const std::string where = "material " + std::to_string(index);
  const tinygltf::Material& material = gltf.materials[index];
  if (auto it = material.extensions.find(kVrmcMaterialsMtoon); it != material.extensions.end())
    return readVersion1(it->second, where);
  const auto vrm = gltf.extensions.find("VRM");
  if (vrm == gltf.extensions.end()) return {};
  const tinygltf::Value* list = member(vrm->second, "materialProperties");
  if (!list || !list->IsArray() || index >= list->ArrayLen()) return {};
  const tinygltf::Value& props = list->Get(static_cast<int>(index));
  const tinygltf::Value* shader = member(props, "shader");
  if (!shader || !shader->IsString() || shader->Get<std::string>() != "VRM/MToon") return {};
  return readVersion0(props, where);
}

}  // namespace eng
