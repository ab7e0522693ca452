// `facial info MODEL`: what a glTF file holds, as the engine sees it after
// import (meshes, morph targets and their default weights, materials,
// images, weights animations, the glTF extensions the file lists and what
// the loader did with each, import warnings). --json for tools.
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "app/face_setup.h"
#include "app/program_error.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/weights.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::info_command {
namespace {

constexpr app::ErrorReporter fail{"facial info"};

const char* interpolationName(eng::Interpolation i) {
  switch (i) {
    case eng::Interpolation::Step: return "STEP";
    case eng::Interpolation::CubicSpline: return "CUBICSPLINE";
    default: return "LINEAR";
  }
}

// A material's MToon values, or null.
nlohmann::ordered_json toonJson(const std::optional<eng::ToonShading>& toon) {
  if (!toon) return nullptr;
  return {{"shadeColor", {toon->shadeColor.r, toon->shadeColor.g, toon->shadeColor.b}},
          {"shadeFromBaseTexture", toon->shadeFromBaseTexture},
          {"shadingShift", toon->shadingShift},
          {"shadingToony", toon->shadingToony},
          {"giEqualization", toon->giEqualization},
          {"rimColor", {toon->rimColor.r, toon->rimColor.g, toon->rimColor.b}},
          {"rimFresnelPower", toon->rimFresnelPower},
          {"rimLift", toon->rimLift},
          {"rimLightingMix", toon->rimLightingMix},
          {"outlineWidthMode", toon->outlineMode == eng::ToonShading::OutlineWidth::World    ? "world"
                               : toon->outlineMode == eng::ToonShading::OutlineWidth::Screen ? "screen"
                                                                                            : "none"},
          {"outlineWidth", toon->outlineWidth},
          {"outlineColor", {toon->outlineColor.r, toon->outlineColor.g, toon->outlineColor.b}},
          {"outlineLightingMix", toon->outlineLightingMix}};
}

nlohmann::ordered_json toJson(const eng::Model& model) {
  using Json = nlohmann::ordered_json;
  Json j;
  j["file"] = model.sourcePath;
  j["vertexCount"] = model.totalVertexCount();
  const eng::Aabb box = model.bounds();
  if (box.valid()) j["bounds"] = {{"min", {box.min.x, box.min.y, box.min.z}}, {"max", {box.max.x, box.max.y, box.max.z}}};
  j["nodeCount"] = model.nodes.size();
  const eng::WeightLayout layout(model);
  j["weightCount"] = layout.total();
  Json meshes = Json::array();
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const eng::Mesh& mesh = model.meshes[m];
    Json prims = Json::array();
    for (const eng::Primitive& p : mesh.primitives)
      prims.push_back({{"vertices", p.vertexCount()},
                       {"triangles", p.indices.size() / 3},
                       {"material", p.material},
                       {"texcoords", !p.texcoords.empty()},
                       {"tangents", !p.tangents.empty()},
                       {"colors", !p.colors.empty()}});
    meshes.push_back({{"name", mesh.name},
                      {"weightOffset", layout.offset(static_cast<int>(m))},
                      {"primitives", std::move(prims)},
                      {"targetNames", mesh.targetNames},
                      {"defaultWeights", mesh.defaultWeights}});
  }
  j["meshes"] = std::move(meshes);
  Json materials = Json::array();
  for (const eng::Material& mat : model.materials) {
    Json layers = Json::array();
    for (const eng::DetailLayer& d : mat.detailLayers)
      layers.push_back({{"image", d.image}, {"target", d.target}, {"strength", d.strength}});
    materials.push_back({{"name", mat.name},
                         {"baseColorFactor", {mat.baseColorFactor.r, mat.baseColorFactor.g, mat.baseColorFactor.b,
                                              mat.baseColorFactor.a}},
                         {"baseColorImage", mat.baseColorImage},
                         {"roughness", mat.roughness},
                         {"metallic", mat.metallic},
                         {"metallicRoughnessImage", mat.metallicRoughnessImage},
                         {"normalImage", mat.normalImage},
                         {"normalScale", mat.normalScale},
                         {"occlusionImage", mat.occlusionImage},
                         {"occlusionStrength", mat.occlusionStrength},
                         {"emissiveFactor", {mat.emissiveFactor.r, mat.emissiveFactor.g, mat.emissiveFactor.b}},
                         {"emissiveImage", mat.emissiveImage},
                         {"doubleSided", mat.doubleSided},
                         {"alphaMode", eng::alphaModeName(mat.alphaMode)},
                         {"alphaCutoff", mat.alphaCutoff},
                         {"baseColorSampling", eng::describeSampling(mat.baseColorSampling)},
                         {"unlit", mat.unlit},
                         {"toon", toonJson(mat.toon)},
                         {"detailLayers", std::move(layers)}});
  }
  j["materials"] = std::move(materials);
  Json images = Json::array();
  for (const eng::Image& img : model.images)
    images.push_back({{"name", img.name}, {"width", img.width}, {"height", img.height}});
  j["images"] = std::move(images);
  Json animations = Json::array();
  for (const eng::Animation& anim : model.animations) {
    Json channels = Json::array();
    for (const eng::WeightsChannel& ch : anim.channels)
      channels.push_back({{"node", ch.node},
                          {"mesh", ch.mesh},
                          {"interpolation", interpolationName(ch.interpolation)},
                          {"keys", ch.times.size()},
                          {"weightsPerKey", ch.targetCount}});
    animations.push_back({{"name", anim.name},
                          {"duration", anim.duration()},
                          {"weightsChannels", std::move(channels)},
                          {"otherChannels", anim.otherChannelCount}});
  }
  j["animations"] = std::move(animations);
  Json extensions = Json::array();
  for (const eng::ExtensionUse& e : model.extensions)
    extensions.push_back({{"name", e.name}, {"required", e.required}, {"outcome", e.outcome}});
  j["extensions"] = std::move(extensions);
  j["warnings"] = model.warnings;
  return j;
}

void printText(const eng::Model& model) {
  const eng::WeightLayout layout(model);
  std::printf("%s\n", model.sourcePath.c_str());
  std::printf("  %zu mesh(es), %zu node(s), %zu vertices, %u morph weight(s)\n", model.meshes.size(), model.nodes.size(),
              model.totalVertexCount(), layout.total());
  const eng::Aabb box = model.bounds();
  if (box.valid())
    std::printf("  bounds (%.4g, %.4g, %.4g) .. (%.4g, %.4g, %.4g)\n", box.min.x, box.min.y, box.min.z, box.max.x,
                box.max.y, box.max.z);
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const eng::Mesh& mesh = model.meshes[m];
    std::printf("  mesh %zu%s%s%s: %zu primitive(s), %zu target(s)\n", m, mesh.name.empty() ? "" : " '",
                mesh.name.c_str(), mesh.name.empty() ? "" : "'", mesh.primitives.size(), mesh.targetNames.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const eng::Primitive& prim = mesh.primitives[p];
      std::printf("    primitive %zu: %zu vertices, %zu triangles, material %d%s%s%s\n", p, prim.vertexCount(),
                  prim.indices.size() / 3, prim.material, prim.texcoords.empty() ? "" : ", uv",
                  prim.tangents.empty() ? "" : ", tangents", prim.colors.empty() ? "" : ", vertex colours");
    }
    for (size_t t = 0; t < mesh.targetNames.size(); ++t)
      std::printf("    target %3zu  %-24s default %.4g\n", t, mesh.targetNames[t].c_str(), mesh.defaultWeights[t]);
  }
  std::printf("  %zu material(s)\n", model.materials.size());
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const eng::Material& mat = model.materials[i];
    std::printf("    material %zu '%s': base colour (%.3g, %.3g, %.3g, %.3g), image %d, roughness %.3g, metallic %.3g%s",
                i, mat.name.c_str(), mat.baseColorFactor.r, mat.baseColorFactor.g, mat.baseColorFactor.b,
                mat.baseColorFactor.a, mat.baseColorImage, mat.roughness, mat.metallic,
                mat.doubleSided ? ", double-sided" : "");
    if (mat.metallicRoughnessImage >= 0) std::printf(", metallic-roughness image %d", mat.metallicRoughnessImage);
    if (mat.normalImage >= 0) std::printf(", normal image %d (scale %.3g)", mat.normalImage, mat.normalScale);
    if (mat.occlusionImage >= 0)
      std::printf(", occlusion image %d (strength %.3g)", mat.occlusionImage, mat.occlusionStrength);
    if (mat.emissiveFactor != glm::vec3(0.0f))
      std::printf(", emissive (%.3g, %.3g, %.3g)", mat.emissiveFactor.r, mat.emissiveFactor.g, mat.emissiveFactor.b);
    if (mat.emissiveImage >= 0) std::printf(", emissive image %d", mat.emissiveImage);
    if (mat.unlit) std::printf(", unlit");
    if (const std::optional<eng::ToonShading>& t = mat.toon)
      std::printf(", toon (MToon): shade (%.3g, %.3g, %.3g)%s, shift %.3g, toony %.3g, rim (%.3g, %.3g, %.3g)",
                  t->shadeColor.r, t->shadeColor.g, t->shadeColor.b, t->shadeFromBaseTexture ? " x texture" : "",
                  t->shadingShift, t->shadingToony, t->rimColor.r, t->rimColor.g, t->rimColor.b);
    if (const std::optional<eng::ToonShading>& t = mat.toon; t && t->outlineMode != eng::ToonShading::OutlineWidth::None)
      std::printf(", outline %.3g %s", t->outlineWidth,
                  t->outlineMode == eng::ToonShading::OutlineWidth::World ? "m" : "of the image height");
    if (mat.alphaMode != eng::AlphaMode::Opaque) std::printf(", alpha %s", eng::alphaModeName(mat.alphaMode));
    if (mat.alphaMode == eng::AlphaMode::Mask) std::printf(" below %.3g", mat.alphaCutoff);
    if (mat.baseColorImage >= 0 && mat.baseColorSampling != eng::TextureSampling{})
      std::printf(", sampled %s", eng::describeSampling(mat.baseColorSampling).c_str());
    for (const eng::DetailLayer& d : mat.detailLayers)
      std::printf(", detail layer image %d driven by '%s' x%.3g", d.image, d.target.c_str(), d.strength);
    std::printf("\n");
  }
  std::printf("  %zu image(s)\n", model.images.size());
  for (size_t i = 0; i < model.images.size(); ++i)
    std::printf("    image %zu '%s': %dx%d\n", i, model.images[i].name.c_str(), model.images[i].width,
                model.images[i].height);
  std::printf("  %zu animation(s)\n", model.animations.size());
  for (const eng::Animation& anim : model.animations) {
    std::printf("    '%s': %.3f s, %zu weights channel(s), %zu other channel(s) ignored\n", anim.name.c_str(),
                anim.duration(), anim.channels.size(), anim.otherChannelCount);
    for (const eng::WeightsChannel& ch : anim.channels)
      std::printf("      node %d (mesh %d): %zu keys x %zu weights, %s\n", ch.node, ch.mesh, ch.times.size(),
                  ch.targetCount, interpolationName(ch.interpolation));
  }
  if (!model.extensions.empty()) {
    std::printf("  %zu extension(s)\n", model.extensions.size());
    for (const eng::ExtensionUse& e : model.extensions)
      std::printf("    %-28s %-8s %s\n", e.name.c_str(), e.required ? "required" : "used", e.outcome.c_str());
  }
  if (!model.warnings.empty()) {
    std::printf("  %zu warning(s)\n", model.warnings.size());
    for (const std::string& w : model.warnings) std::printf("    %s\n", app::shortenNames(w).c_str());
  }
}

CommandRegistrar reg("info", "Describe a glTF model: meshes, morph targets, materials, images, animations, extensions",
                     [](CLI::App& app) {
                       auto path = std::make_shared<std::string>();
                       auto json = std::make_shared<bool>(false);
                       app.add_option("model", *path, importers::kFaceFormatsHelp)->required();
                       app.add_flag("--json", *json, "Print machine-readable JSON instead of text");
                       return [path, json]() -> int {
                         auto face = importers::loadFace(*path);
                         if (!face) return fail(face.error().message);
                         const eng::Model* model = &face->model;
                         if (*json) std::printf("%s\n", toJson(*model).dump(2, ' ', false,
                                                                           nlohmann::ordered_json::error_handler_t::replace).c_str());
                         else printText(*model);
                         return 0;
                       };
                     });

}  // namespace
}  // namespace cli::info_command
