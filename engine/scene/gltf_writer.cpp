#include "engine/scene/gltf_writer.h"

#include <algorithm>
#include <cstring>

#include <nlohmann/json.hpp>

#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_extensions.h"
#include "engine/scene/gltf_mtoon.h"
#include "engine/scene/gltf_sampler.h"
#include "engine/scene/image_io.h"
#include "engine/scene/model_check.h"

// Why not tinygltf's writer: 2.7 cannot serialise sparse accessors and embeds
// GLB images as base64 in the JSON. The JSON is written with nlohmann::json
// and the container by glb_container.
namespace eng {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kFloat = 5126;
constexpr int kUnsignedShort = 5123;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

const char* typeName(int components) {
  switch (components) {
    case 1: return "SCALAR";
    case 2: return "VEC2";
    case 3: return "VEC3";
    case 16: return "MAT4";
    default: return "VEC4";
  }
}

// Collects the binary chunk and the bufferView/accessor JSON that indexes it.
class BufferBuilder {
 public:
  int addView(const void* data, size_t size, int target) {
    while (bin_.size() % 4 != 0) bin_.push_back(0);
    Json view = {{"buffer", 0}, {"byteOffset", bin_.size()}, {"byteLength", size}};
    if (target != 0) view["target"] = target;
    const auto* bytes = static_cast<const uint8_t*>(data);
    bin_.insert(bin_.end(), bytes, bytes + size);
    views_.push_back(std::move(view));
    return static_cast<int>(views_.size()) - 1;
  }

  // Dense float accessor; min/max written when asked (POSITION needs them).
  int addFloats(const float* values, size_t count, int components, int target, bool minMax) {
    Json acc = {{"componentType", kFloat}, {"count", count}, {"type", typeName(components)}};
    if (count > 0) acc["bufferView"] = addView(values, count * components * sizeof(float), target);
    if (minMax) addMinMax(acc, values, count, components);
    return addAccessor(std::move(acc));
  }

  // A morph delta accessor: sparse when the few moved vertices cost less than
  // the dense array, no data at all (zeros) when nothing moves.
  int addDeltas(const std::vector<glm::vec3>& deltas, bool minMax) {
    const size_t n = deltas.size();
    std::vector<uint32_t> moved;
    for (size_t v = 0; v < n; ++v)
      if (deltas[v] != glm::vec3(0.0f)) moved.push_back(static_cast<uint32_t>(v));
    const float* flat = &deltas[0].x;
    const bool shortIndices = n <= 65536;
    const size_t indexSize = shortIndices ? 2 : 4;
    const size_t sparseBytes = moved.size() * (indexSize + sizeof(glm::vec3));
    if (!moved.empty() && sparseBytes >= n * sizeof(glm::vec3)) return addFloats(flat, n, 3, kArrayBuffer, minMax);

    Json acc = {{"componentType", kFloat}, {"count", n}, {"type", "VEC3"}};
    if (!moved.empty()) {
      std::vector<glm::vec3> values;
      values.reserve(moved.size());
      for (uint32_t v : moved) values.push_back(deltas[v]);
      int indexView;
      if (shortIndices) {
        std::vector<uint16_t> idx(moved.begin(), moved.end());
        indexView = addView(idx.data(), idx.size() * 2, 0);
      } else {
        indexView = addView(moved.data(), moved.size() * 4, 0);
      }
      const int valueView = addView(values.data(), values.size() * sizeof(glm::vec3), 0);
      acc["sparse"] = {{"count", moved.size()},
                       {"indices", {{"bufferView", indexView}, {"componentType", shortIndices ? kUnsignedShort : kUnsignedInt}}},
                       {"values", {{"bufferView", valueView}}}};
    }
    if (minMax) addMinMax(acc, flat, n, 3);
    return addAccessor(std::move(acc));
  }

  // Group `set` of four joint indices per vertex (JOINTS_n), as UNSIGNED_SHORT.
  int addJoints(const Primitive& p, size_t set) {
    const size_t sets = p.influenceSets(), n = p.vertexCount();
    std::vector<glm::u16vec4> joints(n);
    for (size_t v = 0; v < n; ++v) joints[v] = p.joints[v * sets + set];
    Json acc = {{"componentType", kUnsignedShort}, {"count", n}, {"type", "VEC4"}};
    acc["bufferView"] = addView(joints.data(), joints.size() * sizeof(glm::u16vec4), kArrayBuffer);
    return addAccessor(std::move(acc));
  }

  // Group `set` of four weights per vertex (WEIGHTS_n), as FLOAT.
  int addJointWeights(const Primitive& p, size_t set) {
    const size_t sets = p.influenceSets(), n = p.vertexCount();
    std::vector<glm::vec4> weights(n);
    for (size_t v = 0; v < n; ++v) weights[v] = p.jointWeights[v * sets + set];
    return addFloats(&weights[0].x, n, 4, kArrayBuffer, false);
  }

  int addIndices(const std::vector<uint32_t>& indices, size_t vertexCount) {
    Json acc = {{"count", indices.size()}, {"type", "SCALAR"}};
    if (vertexCount <= 65535) {
      std::vector<uint16_t> shorts(indices.begin(), indices.end());
      acc["componentType"] = kUnsignedShort;
      acc["bufferView"] = addView(shorts.data(), shorts.size() * 2, kElementArrayBuffer);
    } else {
      acc["componentType"] = kUnsignedInt;
      acc["bufferView"] = addView(indices.data(), indices.size() * 4, kElementArrayBuffer);
    }
    return addAccessor(std::move(acc));
  }

  const std::vector<uint8_t>& bin() const { return bin_; }
  Json& views() { return views_; }
  Json& accessors() { return accessors_; }

 private:
  static void addMinMax(Json& acc, const float* values, size_t count, int components) {
    Json lo = Json::array(), hi = Json::array();
    for (int c = 0; c < components; ++c) {
      float mn = count ? values[c] : 0.0f, mx = mn;
      for (size_t i = 1; i < count; ++i) {
        mn = std::min(mn, values[i * components + c]);
        mx = std::max(mx, values[i * components + c]);
      }
      lo.push_back(mn);
      hi.push_back(mx);
    }
    acc["min"] = std::move(lo);
    acc["max"] = std::move(hi);
  }

  int addAccessor(Json acc) {
    accessors_.push_back(std::move(acc));
    return static_cast<int>(accessors_.size()) - 1;
  }

  std::vector<uint8_t> bin_;
  Json views_ = Json::array();
  Json accessors_ = Json::array();
};

Json vec(const float* v, int n) {
  Json a = Json::array();
  for (int i = 0; i < n; ++i) a.push_back(v[i]);
  return a;
}

// Lists `name` in the document's extensionsUsed once.
void useExtension(Json& doc, const char* name) {
  Json& used = doc["extensionsUsed"];
  if (!used.is_array()) used = Json::array();
  if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

// Each material's textures in the document (-1: none).
struct MaterialTextures {
  int baseColor = -1;
  int others[8] = {-1, -1, -1, -1, -1, -1, -1, -1};  // by kMaterialTextures
};
static_assert(std::size(kMaterialTextures) == 8);

// VRMC_materials_mtoon 1.0 for `toon`; shadeMultiplyTexture is `shadeTexture`
// (a texture index, -1: none), the matcap and masks are the material's.
Json mtoonJson(const ToonShading& toon, int shadeTexture, const MaterialTextures& textures) {
  const auto [metallicRoughness, normal, occlusion, emissive, matcapTexture, shadingShift, rimMultiply, outlineWidth] =
      textures.others;
  Json j = {{"specVersion", "1.0"},
            {"shadeColorFactor", vec(&toon.shadeColor.x, 3)},
            {"shadingShiftFactor", toon.shadingShift},
            {"shadingToonyFactor", toon.shadingToony},
            {"giEqualizationFactor", toon.giEqualization},
            {"parametricRimColorFactor", vec(&toon.rimColor.x, 3)},
            {"parametricRimFresnelPowerFactor", toon.rimFresnelPower},
            {"parametricRimLiftFactor", toon.rimLift},
            {"rimLightingMixFactor", toon.rimLightingMix}};
  if (shadeTexture >= 0) j["shadeMultiplyTexture"] = {{"index", shadeTexture}};
  if (matcapTexture >= 0) {
    j["matcapTexture"] = {{"index", matcapTexture}};
    j["matcapFactor"] = vec(&toon.matcapFactor.x, 3);
  }
  if (shadingShift >= 0) j["shadingShiftTexture"] = {{"index", shadingShift}, {"scale", toon.shadingShiftTextureScale}};
  if (rimMultiply >= 0) j["rimMultiplyTexture"] = {{"index", rimMultiply}};
  if (outlineWidth >= 0) j["outlineWidthMultiplyTexture"] = {{"index", outlineWidth}};
  if (toon.outlineMode != ToonShading::OutlineWidth::None) {
    j["outlineWidthMode"] = toon.outlineMode == ToonShading::OutlineWidth::World ? "worldCoordinates" : "screenCoordinates";
    j["outlineWidthFactor"] = toon.outlineWidth;
    j["outlineColorFactor"] = vec(&toon.outlineColor.x, 3);
    j["outlineLightingMixFactor"] = toon.outlineLightingMix;
  }
  return j;
}

const char* interpolationName(Interpolation i) {
  switch (i) {
    case Interpolation::Step: return "STEP";
    case Interpolation::CubicSpline: return "CUBICSPLINE";
    default: return "LINEAR";
  }
}

// Percent-encodes a file name for a glTF uri (RFC 3986 unreserved kept).
std::string uriEncode(const std::string& name) {
  static const char* hex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '_' || c == '.' || c == '~') out += static_cast<char>(c);
    else {
      out += '%';
      out += hex[c >> 4];
      out += hex[c & 15];
    }
  }
  return out;
}

// The images, PNG-encoded into the binary buffer.
Result<void> writeImages(Json& doc, const Model& model, BufferBuilder& buffers) {
  if (model.images.empty()) return {};
  Json images = Json::array();
  for (size_t i = 0; i < model.images.size(); ++i) {
    const Image& img = model.images[i];
    auto png = encodePng(img.width, img.height, img.rgba8);
    if (!png) return png.error().prefixed("image " + std::to_string(i) + ": ");
    Json image = {{"bufferView", buffers.addView(png->data(), png->size(), 0)}, {"mimeType", "image/png"}};
    if (!img.name.empty()) image["name"] = img.name;
    images.push_back(std::move(image));
  }
  doc["images"] = std::move(images);
  return {};
}

// One texture per (image, sampling) a material uses, one sampler per
// sampling.
std::vector<MaterialTextures> writeTextures(Json& doc, const Model& model) {
  std::vector<TextureSampling> samplings;
  std::vector<std::pair<int, size_t>> textureKeys;  // (image, sampling index)
  auto textureOf = [&](int image, const TextureSampling& wanted) {
    if (image < 0) return -1;
    const size_t sampling = static_cast<size_t>(std::find(samplings.begin(), samplings.end(), wanted) - samplings.begin());
    if (sampling == samplings.size()) samplings.push_back(wanted);
    const std::pair<int, size_t> key{image, sampling};
    const auto found = std::find(textureKeys.begin(), textureKeys.end(), key);
    const int texture = static_cast<int>(found - textureKeys.begin());
    if (found == textureKeys.end()) textureKeys.push_back(key);
    return texture;
  };
  std::vector<MaterialTextures> textures(model.materials.size());
  for (size_t m = 0; m < model.materials.size(); ++m) {
    const Material& mat = model.materials[m];
    textures[m].baseColor = textureOf(mat.baseColorImage, mat.baseColorSampling);
    for (size_t d = 0; d < std::size(kMaterialTextures); ++d)
      textures[m].others[d] = textureOf(mat.*kMaterialTextures[d].image, mat.*kMaterialTextures[d].sampling);
  }
  if (!textureKeys.empty()) {
    Json samplers = Json::array(), list = Json::array();
    for (const TextureSampling& sampling : samplings) {
      const GltfSamplerCodes c = gltfCodesOf(sampling);
      samplers.push_back({{"magFilter", c.magFilter}, {"minFilter", c.minFilter}, {"wrapS", c.wrapS}, {"wrapT", c.wrapT}});
    }
    for (const auto& [image, sampling] : textureKeys) list.push_back({{"sampler", sampling}, {"source", image}});
    doc["samplers"] = std::move(samplers);
    doc["textures"] = std::move(list);
  }
  return textures;
}

// One material; lists the extensions it uses in the document.
Json materialJson(Json& doc, const Material& mat, const MaterialTextures& textures) {
  const int baseColorTexture = textures.baseColor;
  Json pbr = {{"baseColorFactor", vec(&mat.baseColorFactor.x, 4)},
              {"metallicFactor", mat.metallic},
              {"roughnessFactor", mat.roughness}};
  if (baseColorTexture >= 0) pbr["baseColorTexture"] = {{"index", baseColorTexture}};
  const auto [metallicRoughness, normal, occlusion, emissive, matcap, shadingShift, rimMultiply, outlineWidth] =
      textures.others;
  if (metallicRoughness >= 0) pbr["metallicRoughnessTexture"] = {{"index", metallicRoughness}};
  Json m = {{"pbrMetallicRoughness", std::move(pbr)}};
  if (normal >= 0) m["normalTexture"] = {{"index", normal}, {"scale", mat.normalScale}};
  if (occlusion >= 0) m["occlusionTexture"] = {{"index", occlusion}, {"strength", mat.occlusionStrength}};
  if (emissive >= 0) m["emissiveTexture"] = {{"index", emissive}};
  if (!mat.name.empty()) m["name"] = mat.name;
  if (mat.doubleSided) m["doubleSided"] = true;
  if (mat.alphaMode != AlphaMode::Opaque) m["alphaMode"] = alphaModeName(mat.alphaMode);
  if (mat.alphaMode == AlphaMode::Mask) m["alphaCutoff"] = mat.alphaCutoff;
  if (mat.unlit) {
    m["extensions"][kKhrMaterialsUnlit] = Json::object();
    useExtension(doc, kKhrMaterialsUnlit);
  }
  if (mat.toon) {
    m["extensions"][kVrmcMaterialsMtoon] =
        mtoonJson(*mat.toon, mat.toon->shadeFromBaseTexture ? baseColorTexture : -1, textures);
    useExtension(doc, kVrmcMaterialsMtoon);
  }
  if (mat.emissiveFactor != glm::vec3(0.0f)) m["emissiveFactor"] = vec(&mat.emissiveFactor.x, 3);
  if (!mat.detailLayers.empty()) {
    Json layers = Json::array();
    for (const DetailLayer& d : mat.detailLayers) {
      layers.push_back({{"image", d.image}, {"target", d.target}, {"strength", d.strength}});
      if (d.blend == DetailBlend::Modulate) layers.back()["blend"] = "modulate";
    }
    m["extras"] = {{"detailLayers", std::move(layers)}};
  }
  return m;
}

// One primitive: its attributes, indices and morph targets into the buffer.
Json primitiveJson(const Primitive& p, BufferBuilder& buffers) {
  const size_t n = p.vertexCount();
  Json attributes;
  attributes["POSITION"] = buffers.addFloats(&p.positions[0].x, n, 3, kArrayBuffer, true);
  if (!p.normals.empty()) attributes["NORMAL"] = buffers.addFloats(&p.normals[0].x, n, 3, kArrayBuffer, false);
  if (!p.texcoords.empty()) attributes["TEXCOORD_0"] = buffers.addFloats(&p.texcoords[0].x, n, 2, kArrayBuffer, false);
  if (!p.tangents.empty()) attributes["TANGENT"] = buffers.addFloats(&p.tangents[0].x, n, 4, kArrayBuffer, false);
  if (p.colors.size() == n) attributes["COLOR_0"] = buffers.addFloats(&p.colors[0].x, n, 4, kArrayBuffer, false);
  for (size_t set = 0; set < p.influenceSets(); ++set) {
    attributes["JOINTS_" + std::to_string(set)] = buffers.addJoints(p, set);
    attributes["WEIGHTS_" + std::to_string(set)] = buffers.addJointWeights(p, set);
  }
  Json prim = {{"attributes", std::move(attributes)}, {"indices", buffers.addIndices(p.indices, n)}, {"mode", 4}};
  if (p.material >= 0) prim["material"] = p.material;
  if (!p.targets.empty()) {
    Json targets = Json::array();
    for (const MorphTarget& t : p.targets) {
      Json target = Json::object();
      if (!t.positions.empty()) target["POSITION"] = buffers.addDeltas(t.positions, true);
      if (!t.normals.empty()) target["NORMAL"] = buffers.addDeltas(t.normals, false);
      if (!t.tangents.empty()) target["TANGENT"] = buffers.addDeltas(t.tangents, false);
      targets.push_back(std::move(target));
    }
    prim["targets"] = std::move(targets);
  }
  return prim;
}

Json meshJson(const Mesh& mesh, BufferBuilder& buffers) {
  Json prims = Json::array();
  for (const Primitive& p : mesh.primitives) prims.push_back(primitiveJson(p, buffers));
  Json m = {{"primitives", std::move(prims)}};
  if (!mesh.name.empty()) m["name"] = mesh.name;
  if (!mesh.targetNames.empty()) {
    m["weights"] = mesh.defaultWeights;
    m["extras"] = {{"targetNames", mesh.targetNames}};
  }
  return m;
}

Json nodeJson(const Node& node) {
  Json n = Json::object();
  if (!node.name.empty()) n["name"] = node.name;
  if (node.mesh >= 0) n["mesh"] = node.mesh;
  if (node.skin >= 0) n["skin"] = node.skin;
  if (!node.children.empty()) n["children"] = node.children;
  if (node.hasMatrix) {
    n["matrix"] = vec(&node.matrix[0][0], 16);
  } else {
    if (node.translation != glm::vec3(0.0f)) n["translation"] = vec(&node.translation.x, 3);
    if (node.rotation != glm::quat(1.0f, 0.0f, 0.0f, 0.0f))
      n["rotation"] = {node.rotation.x, node.rotation.y, node.rotation.z, node.rotation.w};
    if (node.scale != glm::vec3(1.0f)) n["scale"] = vec(&node.scale.x, 3);
  }
  return n;
}

Json skinJson(const Skin& skin, BufferBuilder& buffers) {
  Json sk = {{"joints", skin.joints}};
  if (!skin.name.empty()) sk["name"] = skin.name;
  if (skin.skeleton >= 0) sk["skeleton"] = skin.skeleton;
  if (!skin.inverseBindMatrices.empty())
    sk["inverseBindMatrices"] =
        buffers.addFloats(&skin.inverseBindMatrices[0][0][0], skin.inverseBindMatrices.size(), 16, 0, false);
  return sk;
}

// One animation with at least one channel: a sampler per channel.
Json animationJson(const Animation& anim, BufferBuilder& buffers) {
  Json samplers = Json::array(), channels = Json::array();
  for (const NodeChannel& ch : anim.nodeChannels) {
    static constexpr const char* kPaths[] = {"translation", "rotation", "scale"};
    const int input = buffers.addFloats(ch.times.data(), ch.times.size(), 1, 0, true);
    const int output = buffers.addFloats(ch.values.data(), ch.values.size() / ch.components(),
                                         static_cast<int>(ch.components()), 0, false);
    channels.push_back(
        {{"sampler", samplers.size()}, {"target", {{"node", ch.node}, {"path", kPaths[static_cast<int>(ch.path)]}}}});
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", interpolationName(ch.interpolation)}});
  }
  for (const WeightsChannel& ch : anim.channels) {
    const int input = buffers.addFloats(ch.times.data(), ch.times.size(), 1, 0, true);
    const int output = buffers.addFloats(ch.values.data(), ch.values.size(), 1, 0, false);
    channels.push_back({{"sampler", samplers.size()}, {"target", {{"node", ch.node}, {"path", "weights"}}}});
    samplers.push_back({{"input", input}, {"output", output}, {"interpolation", interpolationName(ch.interpolation)}});
  }
  Json a = {{"channels", std::move(channels)}, {"samplers", std::move(samplers)}};
  if (!anim.name.empty()) a["name"] = anim.name;
  return a;
}

// The document, part by part in the order their data enters the buffer.
Result<Json> buildDocument(const Model& model, BufferBuilder& buffers) {
  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", "facial eng_scene"}};
  if (!model.calibration.empty()) {
    Json calibration = Json::object();
    for (const auto& [channel, scale] : model.calibration) calibration[channel] = scale;
    doc["extras"] = {{"facialCalibration", std::move(calibration)}};
  }
  if (auto images = writeImages(doc, model, buffers); !images) return images.error();
  const std::vector<MaterialTextures> textures = writeTextures(doc, model);
  if (!model.materials.empty()) {
    Json materials = Json::array();
    for (size_t i = 0; i < model.materials.size(); ++i) materials.push_back(materialJson(doc, model.materials[i], textures[i]));
    doc["materials"] = std::move(materials);
  }
  if (!model.meshes.empty()) {
    Json meshes = Json::array();
    for (const Mesh& mesh : model.meshes) meshes.push_back(meshJson(mesh, buffers));
    doc["meshes"] = std::move(meshes);
  }
  if (!model.nodes.empty()) {
    Json nodes = Json::array();
    for (const Node& node : model.nodes) nodes.push_back(nodeJson(node));
    doc["nodes"] = std::move(nodes);
    doc["scenes"] = Json::array({{{"nodes", model.roots}}});
    doc["scene"] = 0;
  }
  if (!model.skins.empty()) {
    Json skins = Json::array();
    for (const Skin& skin : model.skins) skins.push_back(skinJson(skin, buffers));
    doc["skins"] = std::move(skins);
  }
  Json animations = Json::array();
  for (const Animation& anim : model.animations) {
    // glTF requires at least one channel; an animation with none has nothing to say.
    if (anim.channels.empty() && anim.nodeChannels.empty()) continue;
    animations.push_back(animationJson(anim, buffers));
  }
  if (!animations.empty()) doc["animations"] = std::move(animations);
  return doc;
}

}  // namespace

Result<void> saveModel(const Model& model, const std::filesystem::path& path) {
  const std::string file = path.string();
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext != ".glb" && ext != ".gltf") return makeError(ErrorKind::Unsupported, file + ": unknown extension '" + ext + "' (use .glb or .gltf)");
  if (auto ok = checkModel(model); !ok) return ok.error().prefixed(file + ": cannot save: ");

  try {
    BufferBuilder buffers;
    auto doc = buildDocument(model, buffers);
    if (!doc) return doc.error().prefixed(file + ": ");
    if (buffers.bin().size() > UINT32_MAX - 1024)
      return makeError(ErrorKind::TooLarge, file + ": " + std::to_string(buffers.bin().size()) + " bytes of data exceed glTF's 4 GiB limit");
    Json& json = *doc;
    if (!buffers.bin().empty()) {
      json["bufferViews"] = std::move(buffers.views());
      Json buffer = {{"byteLength", buffers.bin().size()}};
      if (ext == ".gltf") buffer["uri"] = uriEncode(path.stem().string() + ".bin");
      json["buffers"] = Json::array({std::move(buffer)});
    }
    if (!buffers.accessors().empty()) json["accessors"] = std::move(buffers.accessors());

    if (ext == ".glb") {
      const std::vector<uint8_t> glb = buildGlb(json.dump(-1, ' ', false, Json::error_handler_t::replace), buffers.bin());
      return writeFileBytes(path, glb.data(), glb.size());
    }
    if (!buffers.bin().empty()) {
      std::filesystem::path binPath = path;
      binPath.replace_extension(".bin");
      if (auto ok = writeFileBytes(binPath, buffers.bin().data(), buffers.bin().size()); !ok) return ok;
    }
    const std::string text = json.dump(1, ' ', false, Json::error_handler_t::replace);
    return writeFileBytes(path, text.data(), text.size());
  } catch (const std::exception& e) {
    return makeError(ErrorKind::Io, file + ": " + e.what());
  }
}

}  // namespace eng
