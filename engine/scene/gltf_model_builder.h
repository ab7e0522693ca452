#pragma once
// Builds an eng::Model from a parsed tinygltf::Model whose compressed views
// are already decoded (gltf_loader.cpp does that, then calls build()). Private
// to the glTF loader. One class; its steps live in files a reader holds at once:
//   gltf_model_builder.cpp      the order of the steps, required extensions
//   gltf_builder_materials.cpp  images, textures, materials, KHR_texture_transform
//   gltf_builder_meshes.cpp     primitives: attributes, indices, morph targets, generated normals
//   gltf_builder_nodes.cpp      the node hierarchy and animations
// Accessors are decoded by gltf_accessor_reader, skins by gltf_skin_reader.
#include <optional>
#include <string_view>
#include <unordered_map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/gltf_accessor_reader.h"
#include "engine/scene/gltf_extensions.h"
#include "engine/scene/gltf_file_access.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/model.h"

namespace eng {

class GltfModelBuilder {
 public:
  GltfModelBuilder(std::string file, const tinygltf::Model& gltf, const GltfLoadLimits& limits, LoadBudget& budget,
                   const GltfFileAccess& files, ExtensionOutcomes& outcomes)
      : file_(std::move(file)), gltf_(gltf), limits_(limits), budget_(budget), files_(files), outcomes_(outcomes),
        reader_(gltf, budget) {}

  Result<Model> build();

 private:
  Error fail(const std::string& message, ErrorKind kind = ErrorKind::Malformed) const {
    return makeError(kind, file_ + ": " + message);
  }
  // A failure of a reader that does not know the file name: same kind, with the file in front.
  Error fail(const Error& inner) const { return inner.prefixed(file_ + ": "); }
  void warn(std::string message) { model_.warnings.push_back(std::move(message)); }

  std::string meshLabel(int m) const {
    const std::string& name = gltf_.meshes[m].name;
    return "mesh " + std::to_string(m) + (name.empty() ? "" : " '" + name + "'");
  }

  // gltf_model_builder.cpp
  Result<void> checkExtensions();
  void loadCalibration();  // the root's extras.facialCalibration (Model::calibration)

  // gltf_builder_materials.cpp: images (checked up front, decoded once when a
  // material first uses them), textures and materials.
  Result<void> loadImages();
  std::string imageLabel(size_t gltfImage) const;
  int decodedImage(size_t gltfImage);  // Model::images index, or kImageSkipped
  int imageOfTexture(int texture, const std::string& where);
  int modelImage(int gltfImage, const std::string& where);
  void loadMaterials();
  // MToon (VRM 1.0 extension or VRM 0.x materialProperties) of material `index`.
  void readToonShading(size_t index, Material& mat, const std::string& where);

  // gltf_builder_meshes.cpp: primitives (attributes, indices, morph targets,
  // generated normals) and meshes.
  // Triangle list from the primitive's vertex order (indices or 0..n-1) and mode.
  static std::vector<uint32_t> triangulate(const std::vector<uint32_t>& order, int mode);

  template <int N>
  Result<std::vector<glm::vec<N, float>>> readAttribute(int accessor, size_t expectedCount, const std::string& what);

  // What a primitive of `vertices` vertices makes beyond its accessors (generated
  // normals, the 0..n-1 order of a non-indexed primitive, the triangle list,
  // normals for each generated-normal target) counts against the decode budget
  // too, and is charged before anything is read: an accessor without a
  // bufferView declares any count in a few bytes of JSON (zero-filled per the
  // spec), and everything made from it is as large.
  Result<void> chargeDerivedData(const tinygltf::Primitive& src, int mode, size_t vertices, const std::string& label);

  // Returns false (with a warning) for primitives we skip.
  Result<bool> loadPrimitive(int m, int p, Primitive& out, size_t& targetCount, bool& targetCountKnown);
  // The steps of loadPrimitive once out.positions is read. NORMAL (left empty
  // when the file has none: generated after the triangles), TEXCOORD_0,
  // TANGENT, COLOR_0, JOINTS_n / WEIGHTS_n:
  Result<void> readVertexAttributes(const tinygltf::Primitive& src, const std::string& label, Primitive& out);
  // COLOR_0 (VEC3 or VEC4; float, or normalized unsigned byte or short) into
  // out.colors; an accessor of any other kind is skipped with a warning.
  Result<void> readVertexColours(int accessor, const std::string& what, Primitive& out);
  // The triangle list from the indices (or 0..n-1) and the mode:
  Result<void> readTriangles(const tinygltf::Primitive& src, int mode, const std::string& label, Primitive& out);
  // The material (default when out of range) and its baked KHR_texture_transform:
  void assignMaterial(const tinygltf::Primitive& src, const std::string& label, Primitive& out);
  // POSITION / NORMAL / TANGENT deltas; generated normals get deltas of their own:
  Result<void> readMorphTargets(const tinygltf::Primitive& src, const std::string& label, bool generatedNormals,
                                Primitive& out);

  Result<void> loadMesh(int m);

  // gltf_builder_nodes.cpp: the node hierarchy and animations (skins are
  // read by gltf_skin_reader).
  Result<void> loadNodes();
  Result<void> loadAnimations();

  // gltf_builder_materials.cpp
  // The engine samples every texture of a material through one UV set,
  // Primitive::texcoords: the set its base colour names, with the texture's
  // KHR_texture_transform baked in.
  struct BaseColorUv {
    int set = 0;  // TEXCOORD_<set>
    std::optional<UvTransform> transform;
  };
  BaseColorUv baseColorUv(const tinygltf::TextureInfo& info, int image, const std::string& where);
  // Parts of loadMaterials(), in the order it reads them.
  void readAlphaMode(const tinygltf::Material& src, Material& mat, const std::string& where);
  void readFactorsAndEmission(const tinygltf::Material& src, const BaseColorUv& uvs, Material& mat, const std::string& where);
  void readDetailLayers(const tinygltf::Material& src, Material& mat, const std::string& where);
  void readMaterialTexture(const MaterialTexture& slot, int texture, int texCoord, const tinygltf::ExtensionMap& extensions,
                       const BaseColorUv& base, Material& mat, const std::string& where);
  TextureSampling textureSampling(int texture, const std::string& where);

  std::string file_;
  const tinygltf::Model& gltf_;
  const GltfLoadLimits& limits_;
  LoadBudget& budget_;
  const GltfFileAccess& files_;
  ExtensionOutcomes& outcomes_;
  GltfAccessorReader reader_;
  Model model_;
  static constexpr int kImageSkipped = -1, kImagePending = -2;
  std::vector<int> imageRemap_;  // glTF image -> Model::images index, or one of the two above
  std::unordered_map<std::string_view, int> imagesByBytes_;  // encoded bytes -> Model::images index
  std::optional<Error> overBudget_;  // set where a step that only warns ran out of budget
  std::vector<BaseColorUv> baseColorUvs_;  // per material
  int ktx2Skipped_ = 0, webpDecoded_ = 0, uvTransformed_ = 0, unlitMaterials_ = 0, toonMaterials_ = 0;
};

}  // namespace eng
