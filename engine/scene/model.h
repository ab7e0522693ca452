#pragma once
// CPU-side scene data: what a glTF face becomes after import. Flat arrays,
// no renderer types, so the facial component, tools and tests share it and
// the Vulkan layer uploads it as is.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_precision.hpp>

namespace eng {

struct Aabb {
  glm::vec3 min{std::numeric_limits<float>::max()};
  glm::vec3 max{-std::numeric_limits<float>::max()};

  void extend(const glm::vec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  void extend(const Aabb& b) { if (b.valid()) { extend(b.min); extend(b.max); } }
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  glm::vec3 center() const { return (min + max) * 0.5f; }
  glm::vec3 size() const { return max - min; }
  float diagonal() const { return valid() ? glm::length(max - min) : 0.0f; }
};

// One morph target of one primitive. Arrays are either empty (attribute not
// morphed) or exactly primitive.vertexCount() long.
struct MorphTarget {
  std::vector<glm::vec3> positions;  // deltas
  std::vector<glm::vec3> normals;    // deltas
  std::vector<glm::vec3> tangents;   // deltas of tangent.xyz
};

struct Primitive {
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;    // always filled by the loader (generated when absent)
  // The UV set its material's base colour names (TEXCOORD_0 unless the
  // texture says otherwise); empty when the primitive has none.
  std::vector<glm::vec2> texcoords;
  std::vector<glm::vec4> tangents;   // empty when the primitive has none
  // Linear RGBA multiplied into the base colour (glTF COLOR_0; baked
  // ambient occlusion of a dressed face); empty = white.
  std::vector<glm::vec4> colors;
  std::vector<uint32_t> indices;     // triangle list (generated 0..n-1 for non-indexed input)
  int material = -1;                 // index into Model::materials, -1 = default material
  std::vector<MorphTarget> targets;  // same count and order as the owning Mesh::targetNames
  // Skinning (JOINTS_n / WEIGHTS_n): influenceSets() groups of four per vertex,
  // vertex-major (vertex v, group s at v * influenceSets() + s). Joint indices
  // index the skin of the node that draws the mesh; weights sum to 1 per
  // vertex (the loader renormalises). Both empty when the primitive is not skinned.
  std::vector<glm::u16vec4> joints;
  std::vector<glm::vec4> jointWeights;

  size_t vertexCount() const { return positions.size(); }
  size_t influenceSets() const { return positions.empty() ? 0 : joints.size() / positions.size(); }
};

struct Mesh {
  std::string name;
  std::vector<Primitive> primitives;
  std::vector<std::string> targetNames;  // mesh.extras.targetNames, fallback "target_N"
  std::vector<float> defaultWeights;     // mesh.weights, zeros when absent; size == targetNames.size()
};

struct Image {
  std::string name;  // uri or image name, for messages
  int width = 0;
  int height = 0;
  std::vector<uint8_t> rgba8;  // width * height * 4
};

// How a detail layer's colour meets the surface's.
enum class DetailBlend {
  Mix,       // cross-blended towards the layer's colour (painted for this very skin)
  Modulate,  // the surface's colour times twice the layer's (0.5: unchanged), so a
             // crease darkens whatever skin is under it: layers carried onto other faces
};

// A texture that fades in with a named morph target's weight (texture
// cross-blending). The engine treats it generically: layer weight = weight of
// `target` on the drawn mesh, blended in the fragment shader.
struct DetailLayer {
  int image = -1;      // index into Model::images (RGBA: rgb colour, a coverage)
  std::string target;  // morph target name whose weight drives this layer
  float strength = 1;  // scales the weight
  DetailBlend blend = DetailBlend::Mix;
};

// glTF material.alphaMode: how the base colour's alpha is used.
enum class AlphaMode {
  Opaque,  // alpha ignored
  Mask,    // drawn where alpha >= alphaCutoff, nothing elsewhere (lashes, hair cards)
  Blend,   // blended over what is behind it (eye highlights, tear lines, glass)
};

// The glTF spelling: "OPAQUE", "MASK", "BLEND".
constexpr const char* alphaModeName(AlphaMode mode) {
  return mode == AlphaMode::Mask ? "MASK" : mode == AlphaMode::Blend ? "BLEND" : "OPAQUE";
}

// How a texture is read between and beyond its texels (glTF sampler). The
// defaults are what a texture without a sampler gets: repeat, linear within
// and between mip levels.
enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };
enum class TextureFilter { Linear, Nearest };
struct TextureSampling {
  TextureWrap wrapS = TextureWrap::Repeat;  // along u
  TextureWrap wrapT = TextureWrap::Repeat;  // along v
  TextureFilter magFilter = TextureFilter::Linear;
  TextureFilter minFilter = TextureFilter::Linear;  // within a mip level
  bool mipmaps = true;                               // false: the full-size level only
  TextureFilter mipFilter = TextureFilter::Linear;  // between mip levels
  bool operator==(const TextureSampling&) const = default;
};

// "repeat", "clamp-to-edge", "mirrored-repeat".
const char* textureWrapName(TextureWrap wrap);
// One line for listings, e.g. "clamp-to-edge x repeat, nearest, no mipmaps".
std::string describeSampling(const TextureSampling& sampling);

// MToon's toon shading (VRMC_materials_mtoon 1.0; VRM 0.x values converted
// as UniVRM migrates them). Per light, dot(N, L) + shadingShift is mapped
// through linearstep(-1 + toony, 1 - toony) and mixes the shade colour into
// the lit (base) colour; ambient light is evened out over directions by
// giEqualization; a view-dependent parametric rim is added. Colours linear.
struct ToonShading {
  glm::vec3 shadeColor{0.0f};
  // shadeMultiplyTexture: the shade colour is multiplied by a texture. Drawn
  // with the base colour's texture, which is what VRoid exports (the same
  // image); a different image is approximated by it (the loader says so).
  bool shadeFromBaseTexture = false;
  float shadingShift = 0.0f;      // [-1, 1]: moves the light/shade boundary
  float shadingToony = 0.9f;      // [0, 1]: 1 = a hard boundary, 0 = Lambert-like
  float giEqualization = 0.9f;    // [0, 1]: 1 = the same ambient from every direction
  glm::vec3 rimColor{0.0f};       // parametric rim, added
  float rimFresnelPower = 5.0f;   // pow(saturate(1 - N.V + lift), power)
  float rimLift = 0.0f;
  float rimLightingMix = 1.0f;    // 0 = the rim glows on its own, 1 = lit by the lights
  // The outline: the surface drawn again, pushed out along its normals, its
  // back faces only (an inverted hull), in outlineColor.
  enum class OutlineWidth { None, World, Screen };
  OutlineWidth outlineMode = OutlineWidth::None;
  float outlineWidth = 0.0f;      // metres (World) or a fraction of the image height (Screen)
  glm::vec3 outlineColor{0.0f};
  float outlineLightingMix = 1.0f;  // 0 = outlineColor as it is, 1 = times the shaded surface colour
  // The matcap (Material::matcapImage) is multiplied by this and added with the rim.
  glm::vec3 matcapFactor{1.0f};
  // shadingShiftTexture (Material::shadingShiftImage): its red times this is
  // added to shadingShift, point by point.
  float shadingShiftTextureScale = 1.0f;
  bool operator==(const ToonShading&) const = default;
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  int baseColorImage = -1;  // index into Model::images, sRGB encoded
  TextureSampling baseColorSampling;  // read through Primitive::texcoords
  glm::vec3 emissiveFactor{0.0f};  // linear RGB, times the emissive texture where there is one
  int emissiveImage = -1;          // index into Model::images, sRGB encoded
  TextureSampling emissiveSampling;
  float roughness = 0.6f;
  float metallic = 0.0f;
  // glTF's metallicRoughnessTexture, linear: green scales the roughness,
  // blue the metallic factor (an outfit's cloth and buckle, glasses' lenses
  // and frames in one material). Read through the base colour's UVs.
  int metallicRoughnessImage = -1;  // index into Model::images
  TextureSampling metallicRoughnessSampling;
  // glTF's normalTexture (tangent space, linear; x and y scaled by
  // normalScale) and occlusionTexture (red: how much of the ambient light
  // reaches the point, toward 1 as occlusionStrength falls). Both read through
  // the base colour's UVs.
  int normalImage = -1;  // index into Model::images
  TextureSampling normalSampling;
  float normalScale = 1.0f;
  int occlusionImage = -1;  // index into Model::images
  TextureSampling occlusionSampling;
  float occlusionStrength = 1.0f;
  bool doubleSided = false;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;  // AlphaMode::Mask only
  // KHR_materials_unlit: the base colour is shown as it is, with no lights
  // (toon and anime avatars, VRoid's MToon fallback, baked scans).
  bool unlit = false;
  // VRM's MToon (VRMC_materials_mtoon, or VRM 0.x materialProperties):
  // toon shading instead of the skin shading; takes precedence over unlit.
  // MToon's matcap (sRGB): looked up by the view-space normal, not through
  // the UVs, and added as a light the surface reflects (hair and eye shine).
  int matcapImage = -1;  // index into Model::images
  TextureSampling matcapSampling;
  // MToon's masks, read through the base colour's UVs: shadingShiftTexture
  // (linear, red: added to the shading shift, ToonShading::
  // shadingShiftTextureScale), rimMultiplyTexture (sRGB: multiplies the rim
  // and matcap) and outlineWidthMultiplyTexture (linear, green: multiplies the
  // outline's width, so an artist keeps lines off the eyes and mouth).
  int shadingShiftImage = -1;
  TextureSampling shadingShiftSampling;
  int rimMultiplyImage = -1;
  TextureSampling rimMultiplySampling;
  int outlineWidthImage = -1;
  TextureSampling outlineWidthSampling;
  std::optional<ToonShading> toon;
  std::vector<DetailLayer> detailLayers;  // material.extras.detailLayers
};

// The textures a material reads besides its base colour (through the base
// colour's UVs, the matcap excepted), for code that treats them alike:
// copying, checking, writing, uploading.
struct MaterialTexture {
  const char* name;  // glTF's name: "metallicRoughnessTexture"
  int Material::*image;
  TextureSampling Material::*sampling;
  bool colour;  // sRGB encoded colour; else linear data
};
inline constexpr MaterialTexture kMaterialTextures[] = {
    {"metallicRoughnessTexture", &Material::metallicRoughnessImage, &Material::metallicRoughnessSampling, false},
    {"normalTexture", &Material::normalImage, &Material::normalSampling, false},
    {"occlusionTexture", &Material::occlusionImage, &Material::occlusionSampling, false},
    {"emissiveTexture", &Material::emissiveImage, &Material::emissiveSampling, true},
    {"matcapTexture", &Material::matcapImage, &Material::matcapSampling, true},
    {"shadingShiftTexture", &Material::shadingShiftImage, &Material::shadingShiftSampling, false},
    {"rimMultiplyTexture", &Material::rimMultiplyImage, &Material::rimMultiplySampling, true},
    {"outlineWidthMultiplyTexture", &Material::outlineWidthImage, &Material::outlineWidthSampling, false},
};

struct Node {
  std::string name;
  int parent = -1;
  std::vector<int> children;
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  glm::vec3 scale{1.0f};
  glm::mat4 matrix{1.0f};  // used instead of T*R*S when hasMatrix
  bool hasMatrix = false;
  int mesh = -1;
  int skin = -1;  // index into Model::skins; -1 = not skinned (or its skin was dropped)

  glm::mat4 localTransform() const;
};

enum class Interpolation { Step, Linear, CubicSpline };

// A glTF skin: the joints (nodes) whose world transforms deform the vertices
// of the meshes drawn by nodes that use it.
struct Skin {
  std::string name;
  std::vector<int> joints;                      // node indices
  std::vector<glm::mat4> inverseBindMatrices;   // one per joint (identity when the file has none)
  int skeleton = -1;                            // the skeleton root node, -1 when not given
};

enum class NodePath { Translation, Rotation, Scale };

// A glTF animation channel targeting a node's translation, rotation or scale.
// values holds 3 (translation, scale) or 4 (rotation quaternion x, y, z, w)
// floats per key, x3 for CUBICSPLINE (in-tangent, value, out-tangent).
struct NodeChannel {
  int node = -1;
  NodePath path = NodePath::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;
  std::vector<float> values;

  size_t components() const { return path == NodePath::Rotation ? 4 : 3; }
};

// A glTF animation channel targeting a node's `weights`. values holds
// targetCount floats per key (x3 for CUBICSPLINE: in-tangent, value, out-tangent).
struct WeightsChannel {
  int node = -1;
  int mesh = -1;
  Interpolation interpolation = Interpolation::Linear;
  size_t targetCount = 0;
  std::vector<float> times;
  std::vector<float> values;
};

struct Animation {
  std::string name;
  std::vector<WeightsChannel> channels;  // weights channels
  std::vector<NodeChannel> nodeChannels;  // translation / rotation / scale channels (skeletal animation)
  size_t otherChannelCount = 0;          // node TRS channels in the source file (those kept are in nodeChannels)
  float duration() const;
};

// One glTF extension the file lists (extensionsUsed / extensionsRequired) and
// what the loader did with it, for `facial info` and tools.
struct ExtensionUse {
  std::string name;
  bool required = false;
  std::string outcome;  // "decoded: ...", "applied: ...", "skipped: ...", "ignored: ..."
};

struct Model {
  std::string sourcePath;
  std::vector<Node> nodes;
  std::vector<int> roots;  // nodes of the default scene (or all parentless nodes)
  std::vector<Mesh> meshes;
  std::vector<Material> materials;
  std::vector<Image> images;
  std::vector<Animation> animations;
  std::vector<Skin> skins;
  int humanoidHead = -1;  // node of the VRM humanoid `head` bone (VRMC_vrm 1.0 / VRM 0.x), -1 when absent
  std::vector<std::string> warnings;  // non-fatal problems met while loading
  std::vector<ExtensionUse> extensions;  // in the file's order, used ones first
  // Strength scales for the rig's channels (by name) stated by the tool that
  // made its targets, in the glTF root's extras as "facialCalibration"
  // (`facial autorig` writes the built-in head's); empty: measured on load.
  std::vector<std::pair<std::string, float>> calibration;

  glm::mat4 worldTransform(int node) const;
  // Per mesh, the first node (in node order) that draws it; -1 for a mesh no
  // node draws. Where one placement per mesh is enough (look-up, baking).
  std::vector<int> firstNodeOfEachMesh() const;
  // World-space bounds of every mesh instance at rest (no morphing).
  Aabb bounds() const;
  size_t totalVertexCount() const;
};

// `model` turned by `turn` at its parentless nodes, as an engine placing it
// would (a face its file holds lying, stood up), in place.
void turnAtRoots(Model& model, const glm::quat& turn);

}  // namespace eng
