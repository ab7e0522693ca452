#pragma once
// Hand-built glTF files for the scene tests: a JSON document plus one binary
// buffer, written as .gltf (external .bin or data: URI) or .glb. Tests edit
// `doc` directly to make exactly the (broken) file they need.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "engine/scene/model.h"

namespace scene_test {

using Json = nlohmann::json;

constexpr int kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123, kUnsignedInt = 5125,
              kFloat = 5126;

class GltfFileBuilder {
 public:
  GltfFileBuilder();

  Json doc;
  std::vector<uint8_t> bin;

  // Appends bytes (4-aligned) and a bufferView over them; returns the view index.
  int addView(const void* data, size_t size, size_t byteStride = 0);
  template <class T>
  int addView(const std::vector<T>& values, size_t byteStride = 0) {
    return addView(values.data(), values.size() * sizeof(T), byteStride);
  }
  // Appends an accessor; view -1 = no bufferView. Returns its index.
  int addAccessor(int view, int componentType, size_t count, const std::string& type, bool normalized = false,
                  size_t byteOffset = 0);
  int addVec3(const std::vector<glm::vec3>& values, bool minMax = false);
  int addVec2(const std::vector<glm::vec2>& values);
  int addScalars(const std::vector<float>& values);
  int addIndices(const std::vector<uint16_t>& indices);
  // mesh + node (+ scene 0 listing the node); returns the mesh index.
  int addMeshWithNode(Json mesh);

  // Buffer 0's JSON is filled in at write time (from `bin`); any further
  // entries a test puts in doc["buffers"] are written as they are.
  void writeGltf(const std::filesystem::path& path, const std::string& binFileName = "") const;  // "" = data: URI
  std::vector<uint8_t> glbBytes() const;
  void writeGlb(const std::filesystem::path& path) const;
};

// A unit quad in the XY plane (4 vertices, 2 triangles) with one morph
// target that lifts vertex 2 by +1 in Z (sparse-friendly) -- the base for
// most hand-built files.
GltfFileBuilder quadWithTarget();

std::string base64(const std::vector<uint8_t>& bytes);
void writeBytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes);
std::string readText(const std::filesystem::path& path);
// Replaces the first occurrence of `from` in a text file (fails the test when absent).
void replaceInFile(const std::filesystem::path& path, const std::string& from, const std::string& to);

// Loading checks shared by the loader tests.
eng::Model loadOk(const std::filesystem::path& path);  // fails the test (and returns an empty model) on error
// Loads `path` and checks the failure is one line naming the file and containing `problem`.
void expectLoadError(const std::filesystem::path& path, const std::string& problem);
bool hasWarningContaining(const eng::Model& model, const std::string& text);
const eng::ExtensionUse* extensionRecord(const eng::Model& model, const std::string& name);  // nullptr when absent

}  // namespace scene_test
