#include "tests/engine/scene/gltf_test_files.h"

#include <cstring>
#include <fstream>

#include <gtest/gtest.h>

#include "engine/scene/gltf_loader.h"

namespace scene_test {

GltfFileBuilder::GltfFileBuilder() {
  doc["asset"] = {{"version", "2.0"}};
  doc["bufferViews"] = Json::array();
  doc["accessors"] = Json::array();
}

int GltfFileBuilder::addView(const void* data, size_t size, size_t byteStride) {
  while (bin.size() % 4 != 0) bin.push_back(0);
  Json view = {{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", size}};
  if (byteStride) view["byteStride"] = byteStride;
  const auto* p = static_cast<const uint8_t*>(data);
  bin.insert(bin.end(), p, p + size);
  doc["bufferViews"].push_back(view);
  return static_cast<int>(doc["bufferViews"].size()) - 1;
}

int GltfFileBuilder::addAccessor(int view, int componentType, size_t count, const std::string& type, bool normalized,
                                 size_t byteOffset) {
  Json acc = {{"componentType", componentType}, {"count", count}, {"type", type}};
  if (view >= 0) acc["bufferView"] = view;
  if (normalized) acc["normalized"] = true;
  if (byteOffset) acc["byteOffset"] = byteOffset;
  doc["accessors"].push_back(acc);
  return static_cast<int>(doc["accessors"].size()) - 1;
}

int GltfFileBuilder::addVec3(const std::vector<glm::vec3>& values, bool minMax) {
  const int a = addAccessor(addView(values), kFloat, values.size(), "VEC3");
  if (minMax) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& v : values) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    doc["accessors"][a]["min"] = {lo.x, lo.y, lo.z};
    doc["accessors"][a]["max"] = {hi.x, hi.y, hi.z};
  }
  return a;
}

int GltfFileBuilder::addVec2(const std::vector<glm::vec2>& values) {
  return addAccessor(addView(values), kFloat, values.size(), "VEC2");
}

int GltfFileBuilder::addScalars(const std::vector<float>& values) {
  return addAccessor(addView(values), kFloat, values.size(), "SCALAR");
}

int GltfFileBuilder::addIndices(const std::vector<uint16_t>& indices) {
  return addAccessor(addView(indices), kUnsignedShort, indices.size(), "SCALAR");
}

int GltfFileBuilder::addMeshWithNode(Json mesh) {
  doc["meshes"].push_back(std::move(mesh));
  const int m = static_cast<int>(doc["meshes"].size()) - 1;
  doc["nodes"].push_back({{"mesh", m}});
  const int n = static_cast<int>(doc["nodes"].size()) - 1;
  if (!doc.contains("scenes")) {
    doc["scenes"] = Json::array({{{"nodes", Json::array()}}});
    doc["scene"] = 0;
  }
  doc["scenes"][0]["nodes"].push_back(n);
  return m;
}

// Buffer 0 is `bin`; buffers a test added after it (meshopt fallbacks) are kept.
static void setBuffer0(Json& out, Json buffer0) {
  if (!out.contains("buffers") || !out["buffers"].is_array() || out["buffers"].empty())
    out["buffers"] = Json::array({std::move(buffer0)});
  else
    out["buffers"][0] = std::move(buffer0);
}

void GltfFileBuilder::writeGltf(const std::filesystem::path& path, const std::string& binFileName) const {
  Json out = doc;
  if (!bin.empty()) {
    if (binFileName.empty()) {
      setBuffer0(out, {{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}});
    } else {
      setBuffer0(out, {{"byteLength", bin.size()}, {"uri", binFileName}});
      writeBytes(path.parent_path() / binFileName, bin);
    }
  }
  const std::string text = out.dump(1);
  writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

std::vector<uint8_t> GltfFileBuilder::glbBytes() const {
  Json out = doc;
  if (!bin.empty()) setBuffer0(out, {{"byteLength", bin.size()}});
  std::string json = out.dump();
  while (json.size() % 4) json += ' ';
  std::vector<uint8_t> padded = bin;
  while (padded.size() % 4) padded.push_back(0);
  std::vector<uint8_t> glb;
  auto u32 = [&](uint32_t v) {
    uint8_t b[4];
    std::memcpy(b, &v, 4);
    glb.insert(glb.end(), b, b + 4);
  };
  const uint32_t total = static_cast<uint32_t>(12 + 8 + json.size() + (padded.empty() ? 0 : 8 + padded.size()));
  u32(0x46546C67);
  u32(2);
  u32(total);
  u32(static_cast<uint32_t>(json.size()));
  u32(0x4E4F534A);
  glb.insert(glb.end(), json.begin(), json.end());
  if (!padded.empty()) {
    u32(static_cast<uint32_t>(padded.size()));
    u32(0x004E4942);
    glb.insert(glb.end(), padded.begin(), padded.end());
  }
  return glb;
}

void GltfFileBuilder::writeGlb(const std::filesystem::path& path) const { writeBytes(path, glbBytes()); }

GltfFileBuilder quadWithTarget() {
  GltfFileBuilder b;
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<glm::vec3> normals(4, glm::vec3(0, 0, 1));
  const std::vector<glm::vec3> lift = {{0, 0, 0}, {0, 0, 0}, {0, 0, 1}, {0, 0, 0}};
  const int pos = b.addVec3(positions, true);
  const int nrm = b.addVec3(normals);
  const int idx = b.addIndices({0, 1, 2, 0, 2, 3});
  const int target = b.addVec3(lift, true);
  b.addMeshWithNode({{"name", "Quad"},
                     {"primitives", Json::array({{{"attributes", {{"POSITION", pos}, {"NORMAL", nrm}}},
                                                  {"indices", idx},
                                                  {"targets", Json::array({{{"POSITION", target}}})}}})},
                     {"weights", {0.25}},
                     {"extras", {{"targetNames", {"lift"}}}}});
  return b;
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += table[v >> 18];
    out += table[(v >> 12) & 63];
    out += table[(v >> 6) & 63];
    out += table[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = bytes[i] << 16;
    out += table[v >> 18];
    out += table[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += table[v >> 18];
    out += table[(v >> 12) & 63];
    out += table[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

void writeBytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

void replaceInFile(const std::filesystem::path& path, const std::string& from, const std::string& to) {
  std::string text = readText(path);
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not in " << path;
  text.replace(at, from.size(), to);
  writeBytes(path, std::vector<uint8_t>(text.begin(), text.end()));
}

eng::Model loadOk(const std::filesystem::path& path) {
  auto model = eng::loadModel(path);
  EXPECT_TRUE(model.ok()) << (model.ok() ? "" : model.error().message);
  return model.ok() ? std::move(*model) : eng::Model{};
}

void expectLoadError(const std::filesystem::path& path, const std::string& problem) {
  auto model = eng::loadModel(path);
  ASSERT_FALSE(model.ok()) << path << " loaded but should fail with: " << problem;
  const std::string& message = model.error().message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << "not one line: " << message;
  EXPECT_EQ(message.rfind(path.string(), 0), 0u) << "does not start with the file name: " << message;
  EXPECT_NE(message.find(problem), std::string::npos) << "expected '" << problem << "' in: " << message;
}

bool hasWarningContaining(const eng::Model& model, const std::string& text) {
  for (const std::string& w : model.warnings)
    if (w.find(text) != std::string::npos) return true;
  return false;
}

const eng::ExtensionUse* extensionRecord(const eng::Model& model, const std::string& name) {
  for (const eng::ExtensionUse& e : model.extensions)
    if (e.name == name) return &e;
  return nullptr;
}

}  // namespace scene_test
