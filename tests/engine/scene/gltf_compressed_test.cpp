// Compressed and extended glTF on files the tests write themselves: meshopt
// (EXT_ and KHR_ names, every mode and filter, fallback buffers without data,
// in .glb and .gltf), every KHR_mesh_quantization component type, WebP and
// KTX2 textures, KHR_texture_transform, and corrupt or truncated streams (one
// clear line, no crash). The unknown-extension policy is tested with the
// other loader tests (gltf_loader_test.cpp, gltf_loader_bad_input_test.cpp).
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <meshoptimizer.h>
#include <webp/encode.h>

#include "engine/scene/gltf_loader.h"
#include "engine/scene/model_check.h"
#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using namespace scene_test;
using testing_support::freshTempDir;

// ---------------------------------------------------------------------------
// A meshopt-compressed file: encoded bytes in buffer 0 (the GLB BIN chunk or
// a data: URI), the views that decode into buffer 1, a placeholder with no
// data (fallback: true).
class MeshoptFileBuilder {
 public:
  explicit MeshoptFileBuilder(std::string extension) : ext_(std::move(extension)) {
    b.doc["extensionsUsed"] = {ext_, "KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {ext_, "KHR_mesh_quantization"};
  }

  // Encodes count x stride bytes in `mode` (filter already applied by the
  // caller) and returns the index of the view they decode into.
  int addView(const void* data, size_t count, size_t stride, const std::string& mode, const std::string& filter = "") {
    std::vector<uint8_t> encoded;
    if (mode == "ATTRIBUTES") {
      encoded.resize(meshopt_encodeVertexBufferBound(count, stride));
      encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), data, count, stride));
    } else {
      std::vector<unsigned int> indices(count);
      for (size_t i = 0; i < count; ++i)
        indices[i] = stride == 2 ? static_cast<const uint16_t*>(data)[i] : static_cast<const uint32_t*>(data)[i];
      if (mode == "TRIANGLES") {
        encoded.resize(meshopt_encodeIndexBufferBound(count, 1 << 16));
        encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), count));
      } else {
        encoded.resize(meshopt_encodeIndexSequenceBound(count, 1 << 16));
        encoded.resize(meshopt_encodeIndexSequence(encoded.data(), encoded.size(), indices.data(), count));
      }
    }
    EXPECT_FALSE(encoded.empty());
    const int raw = b.addView(encoded);
    Json ext = {{"buffer", 0},
                {"byteOffset", b.doc["bufferViews"][raw]["byteOffset"]},
                {"byteLength", encoded.size()},
                {"byteStride", stride},
                {"mode", mode},
                {"count", count}};
    if (!filter.empty()) ext["filter"] = filter;
    Json view = {{"buffer", 1}, {"byteOffset", fallbackBytes_}, {"byteLength", count * stride},
                 {"extensions", {{ext_, ext}}}};
    if (mode == "ATTRIBUTES") view["byteStride"] = stride;
    fallbackBytes_ += (count * stride + 3) / 4 * 4;
    b.doc["bufferViews"].push_back(view);
    b.doc["buffers"] = Json::array({{{"byteLength", 0}},
                                    {{"byteLength", fallbackBytes_}, {"extensions", {{ext_, {{"fallback", true}}}}}}});
    return static_cast<int>(b.doc["bufferViews"].size()) - 1;
  }

  GltfFileBuilder b;

 private:
  std::string ext_;
  size_t fallbackBytes_ = 0;
};

// An 8 x 8 vertex grid with curved normals, quantized texcoords, tangents
// that are unit quaternions (to carry the QUATERNION filter) and a morph
// target; the reference values the decoded file is compared with.
struct GridMesh {
  static constexpr int kSide = 8;
  std::vector<glm::vec3> positions, normals, deltas;
  std::vector<glm::vec4> tangents;
  std::vector<uint16_t> uvs;  // normalized, 2 per vertex
  std::vector<uint16_t> triangles;
  std::vector<uint32_t> fan;  // a second primitive's index sequence

  GridMesh() {
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        const float u = x / float(kSide - 1), v = y / float(kSide - 1);
        positions.push_back({u, v, 0.1f * std::sin(3.0f * u)});
        normals.push_back(glm::normalize(glm::vec3(u - 0.5f, v - 0.5f, 1.0f)));
        deltas.push_back({0.0f, 0.0f, 0.25f * u * v});
        tangents.push_back(glm::normalize(glm::vec4(u - 0.3f, 0.5f, v - 0.6f, 0.8f)));
        uvs.push_back(static_cast<uint16_t>(u * 65535.0f));
        uvs.push_back(static_cast<uint16_t>(v * 65535.0f));
      }
    for (int y = 0; y + 1 < kSide; ++y)
      for (int x = 0; x + 1 < kSide; ++x) {
        const uint16_t i = static_cast<uint16_t>(y * kSide + x);
        triangles.insert(triangles.end(), {i, uint16_t(i + 1), uint16_t(i + kSide), uint16_t(i + 1),
                                           uint16_t(i + kSide + 1), uint16_t(i + kSide)});
      }
    fan = {0, 1, 9, 8, 16};
  }
};

// Writes the grid meshopt-compressed (normals OCTAHEDRAL, tangents
// QUATERNION, deltas EXPONENTIAL, indices TRIANGLES and INDICES). Each
// addView adds the raw encoded view, then the view it decodes into: the
// decoded views are 1 positions, 3 normals, 5 tangents, 7 texcoords, 9 deltas,
// 11 triangles, 13 the fan's indices.
MeshoptFileBuilder meshoptGrid(const GridMesh& grid, const std::string& extension) {
  MeshoptFileBuilder f(extension);
  const size_t n = grid.positions.size();
  const int pos = f.b.addAccessor(f.addView(grid.positions.data(), n, 12, "ATTRIBUTES"), kFloat, n, "VEC3");
  f.b.doc["accessors"][pos]["min"] = {0, 0, 0};
  f.b.doc["accessors"][pos]["max"] = {1, 1, 0.1};

  std::vector<float> normal4;
  for (const glm::vec3& v : grid.normals) normal4.insert(normal4.end(), {v.x, v.y, v.z, 0.0f});
  std::vector<int8_t> octa(n * 4);
  meshopt_encodeFilterOct(octa.data(), n, 4, 8, normal4.data());
  const int nrm = f.b.addAccessor(f.addView(octa.data(), n, 4, "ATTRIBUTES", "OCTAHEDRAL"), kByte, n, "VEC3", true);

  std::vector<int16_t> quat(n * 4);
  meshopt_encodeFilterQuat(quat.data(), n, 8, 16, &grid.tangents[0].x);
  const int tan = f.b.addAccessor(f.addView(quat.data(), n, 8, "ATTRIBUTES", "QUATERNION"), kShort, n, "VEC4", true);

  const int uv = f.b.addAccessor(f.addView(grid.uvs.data(), n, 4, "ATTRIBUTES"), kUnsignedShort, n, "VEC2", true);

  std::vector<uint32_t> expo(n * 3);
  meshopt_encodeFilterExp(expo.data(), n, 12, 20, &grid.deltas[0].x);
  const int delta = f.b.addAccessor(f.addView(expo.data(), n, 12, "ATTRIBUTES", "EXPONENTIAL"), kFloat, n, "VEC3");
  f.b.doc["accessors"][delta]["min"] = {0, 0, 0};
  f.b.doc["accessors"][delta]["max"] = {0, 0, 0.25};

  const int tri = f.b.addAccessor(f.addView(grid.triangles.data(), grid.triangles.size(), 2, "TRIANGLES"),
                                  kUnsignedShort, grid.triangles.size(), "SCALAR");
  const int fan = f.b.addAccessor(f.addView(grid.fan.data(), grid.fan.size(), 4, "INDICES"), kUnsignedInt,
                                  grid.fan.size(), "SCALAR");
  const Json attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TANGENT", tan}, {"TEXCOORD_0", uv}};
  f.b.addMeshWithNode({{"name", "Grid"},
                       {"primitives", Json::array({{{"attributes", attributes},
                                                    {"indices", tri},
                                                    {"targets", Json::array({{{"POSITION", delta}}})}},
                                                   {{"attributes", attributes},
                                                    {"indices", fan},
                                                    {"mode", 6},
                                                    {"targets", Json::array({{{"POSITION", delta}}})}}})},
                       {"extras", {{"targetNames", {"bulge"}}}}});
  return f;
}

void expectGridDecoded(const eng::Model& model, const GridMesh& grid) {
  ASSERT_EQ(model.meshes.size(), 1u);
  ASSERT_EQ(model.meshes[0].primitives.size(), 2u);
  const eng::Primitive& p = model.meshes[0].primitives[0];
  ASSERT_EQ(p.vertexCount(), grid.positions.size());
  EXPECT_EQ(p.positions, grid.positions) << "no filter: bit exact";
  // The TRIANGLES codec keeps triangle order and winding but may rotate a triangle's corners.
  ASSERT_EQ(p.indices.size(), grid.triangles.size());
  for (size_t t = 0; t < p.indices.size(); t += 3) {
    const uint32_t* got = &p.indices[t];
    const int r = got[0] == grid.triangles[t] ? 0 : got[1] == grid.triangles[t] ? 1 : 2;
    for (int c = 0; c < 3; ++c) EXPECT_EQ(got[(r + c) % 3], grid.triangles[t + c]) << "triangle " << t / 3;
  }
  ASSERT_EQ(p.texcoords.size(), grid.positions.size());
  ASSERT_EQ(p.tangents.size(), grid.positions.size());
  ASSERT_EQ(p.targets.size(), 1u);
  for (size_t v = 0; v < grid.positions.size(); ++v) {
    EXPECT_NEAR(glm::length(p.normals[v] - grid.normals[v]), 0.0f, 0.03f) << "8-bit octahedral, vertex " << v;
    EXPECT_NEAR(glm::length(p.tangents[v] - grid.tangents[v]), 0.0f, 2e-3f) << "16-bit quaternion, vertex " << v;
    EXPECT_NEAR(p.texcoords[v].x, grid.uvs[v * 2] / 65535.0f, 1e-6f);
    EXPECT_NEAR(p.texcoords[v].y, grid.uvs[v * 2 + 1] / 65535.0f, 1e-6f);
    EXPECT_NEAR(glm::length(p.targets[0].positions[v] - grid.deltas[v]), 0.0f, 1e-5f) << "20-bit exponential";
  }
  const eng::Primitive& fan = model.meshes[0].primitives[1];
  EXPECT_EQ(fan.indices, (std::vector<uint32_t>{0, 1, 9, 0, 9, 8, 0, 8, 16})) << "INDICES stream as a fan";
  EXPECT_EQ(model.meshes[0].targetNames, std::vector<std::string>{"bulge"});
}

TEST(GltfCompressed, MeshoptGlbWithEveryModeAndFilterDecodes) {
  const auto dir = freshTempDir("compressed_meshopt_glb");
  const GridMesh grid;
  meshoptGrid(grid, "EXT_meshopt_compression").b.writeGlb(dir / "grid.glb");
  const eng::Model model = loadOk(dir / "grid.glb");
  expectGridDecoded(model, grid);
  EXPECT_TRUE(model.warnings.empty()) << model.warnings.front();
  const eng::ExtensionUse* meshopt = extensionRecord(model, "EXT_meshopt_compression");
  ASSERT_NE(meshopt, nullptr);
  EXPECT_TRUE(meshopt->required);
  EXPECT_EQ(meshopt->outcome.rfind("decoded: 7 buffer view(s)", 0), 0u) << meshopt->outcome;
  const eng::ExtensionUse* quantization = extensionRecord(model, "KHR_mesh_quantization");
  ASSERT_NE(quantization, nullptr);
  EXPECT_EQ(quantization->outcome.rfind("applied", 0), 0u);
}

TEST(GltfCompressed, MeshoptInGltfWithDataUriAndTheKhrNameDecodes) {
  const auto dir = freshTempDir("compressed_meshopt_gltf");
  const GridMesh grid;
  meshoptGrid(grid, "KHR_meshopt_compression").b.writeGltf(dir / "grid.gltf");
  const eng::Model model = loadOk(dir / "grid.gltf");
  expectGridDecoded(model, grid);
  const eng::ExtensionUse* meshopt = extensionRecord(model, "KHR_meshopt_compression");
  ASSERT_NE(meshopt, nullptr);
  EXPECT_EQ(meshopt->outcome.rfind("decoded", 0), 0u) << meshopt->outcome;
}

TEST(GltfCompressed, MeshoptWithAnUncompressedFallbackBufferStillDecodes) {
  // A fallback buffer with real (here: deliberately wrong, zero) data: the
  // decoder's output wins over it.
  const auto dir = freshTempDir("compressed_meshopt_fallback");
  const GridMesh grid;
  MeshoptFileBuilder f = meshoptGrid(grid, "EXT_meshopt_compression");
  const size_t fallbackBytes = f.b.doc["buffers"][1]["byteLength"];
  writeBytes(dir / "fallback.bin", std::vector<uint8_t>(fallbackBytes, 0));
  f.b.doc["buffers"][1]["uri"] = "fallback.bin";
  f.b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  f.b.writeGlb(dir / "grid.glb");
  expectGridDecoded(loadOk(dir / "grid.glb"), grid);
}

// ---------------------------------------------------------------------------
// Validity: corrupt, truncated and impossible meshopt data.

TEST(GltfCompressedBadInput, TruncatedMeshoptStreamIsRefusedInOneLine) {
  const auto dir = freshTempDir("compressed_meshopt_truncated");
  const GridMesh grid;
  MeshoptFileBuilder f = meshoptGrid(grid, "EXT_meshopt_compression");
  Json& ext = f.b.doc["bufferViews"][1]["extensions"]["EXT_meshopt_compression"];  // positions
  ext["byteLength"] = ext["byteLength"].get<size_t>() / 2;
  f.b.writeGlb(dir / "truncated.glb");
  expectLoadError(dir / "truncated.glb", "bufferView 1 EXT_meshopt_compression: the ATTRIBUTES stream");
  expectLoadError(dir / "truncated.glb", "is corrupt or truncated");
}

TEST(GltfCompressedBadInput, GarbledMeshoptStreamsAreRefusedOrStayInBounds) {
  // Garbage that still parses may decode to garbage (the decoder promises
  // safety, not detection); indices then fail the loader's range check.
  const auto dir = freshTempDir("compressed_meshopt_garbled");
  const GridMesh grid;
  for (int view : {1, 11, 13}) {  // positions, TRIANGLES, INDICES
    MeshoptFileBuilder f = meshoptGrid(grid, "EXT_meshopt_compression");
    const Json& ext = f.b.doc["bufferViews"][view]["extensions"]["EXT_meshopt_compression"];
    const size_t at = ext["byteOffset"], length = ext["byteLength"];
    for (size_t i = 1; i < length; ++i) f.b.bin[at + i] = static_cast<uint8_t>(0xA5 ^ (i * 37));
    const auto path = dir / ("garbled_" + std::to_string(view) + ".glb");
    f.b.writeGlb(path);
    auto model = eng::loadModel(path);
    if (!model) {
      EXPECT_EQ(model.error().message.find('\n'), std::string::npos) << model.error().message;
      EXPECT_EQ(model.error().message.rfind(path.string(), 0), 0u) << model.error().message;
      continue;
    }
    // Decoded garbage that loads must still be a model the renderer can trust:
    // indices in range, finite vertices, matching counts.
    auto consistent = eng::checkModel(*model);
    EXPECT_TRUE(consistent.ok()) << path << ": " << (consistent ? "" : consistent.error().message);
  }
}

TEST(GltfCompressedBadInput, ImpossibleMeshoptLayoutsAreNamed) {
  const auto dir = freshTempDir("compressed_meshopt_layout");
  const GridMesh grid;
  struct Case {
    int view;
    const char* key;
    Json value;
    const char* problem;
  };
  const std::vector<Case> cases = {
      {1, "byteStride", 6, "ATTRIBUTES byteStride 6 must be a multiple of 4"},
      {3, "byteStride", 12, "OCTAHEDRAL filter needs byteStride 4 or 8"},
      {3, "filter", "COLOR", "filter COLOR (KHR_meshopt_compression) needs a newer meshoptimizer than this build's"},
      {3, "filter", "SHARPEN", "unknown filter 'SHARPEN'"},
      {11, "mode", "STRIPS", "unknown mode 'STRIPS'"},
      {11, "count", 4, "TRIANGLES count 4 is not a multiple of 3"},
      {1, "count", 63, "does not match the view's byteLength"},
      {1, "buffer", 7, "refers to buffer 7, the file has 2"},
      {1, "byteOffset", 1 << 30, "are out of range of buffer 0"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.problem);
    MeshoptFileBuilder f = meshoptGrid(grid, "EXT_meshopt_compression");
    f.b.doc["bufferViews"][c.view]["extensions"]["EXT_meshopt_compression"][c.key] = c.value;
    f.b.writeGlb(dir / "layout.glb");
    expectLoadError(dir / "layout.glb", c.problem);
  }
}

TEST(GltfCompressedBadInput, MeshoptAttributeStreamOfANewerVersionIsNamed) {
  const auto dir = freshTempDir("compressed_meshopt_version");
  const GridMesh grid;
  MeshoptFileBuilder f = meshoptGrid(grid, "KHR_meshopt_compression");
  const size_t at = f.b.doc["bufferViews"][1]["extensions"]["KHR_meshopt_compression"]["byteOffset"];
  f.b.bin[at] = 0xa1;  // header of the version 1 attribute codec
  f.b.writeGlb(dir / "v1.glb");
  expectLoadError(dir / "v1.glb", "attribute stream version 1 (KHR_meshopt_compression) needs a newer meshoptimizer");
}

TEST(GltfCompressedBadInput, HugeMeshoptFallbackBufferIsRefusedBeforeAllocating) {
  const auto dir = freshTempDir("compressed_meshopt_huge");
  const GridMesh grid;
  MeshoptFileBuilder f = meshoptGrid(grid, "EXT_meshopt_compression");
  f.b.doc["buffers"][1]["byteLength"] = uint64_t{1} << 50;
  f.b.writeGlb(dir / "huge.glb");
  expectLoadError(dir / "huge.glb", "meshopt fallback buffer 1 would take 1125899906842624 bytes, past the load budget");
}

// ---------------------------------------------------------------------------
// KHR_mesh_quantization: every component type the extension allows, for
// positions, normals, tangents, texcoords and morph target deltas.

struct QuantizedType {
  int componentType;
  bool normalized;
  float scale;  // value = stored / scale (normalized), = stored otherwise
};

TEST(GltfCompressed, EveryQuantizedComponentTypeReadsByTheSpecRules) {
  const auto dir = freshTempDir("compressed_quantization");
  const std::vector<QuantizedType> types = {{kByte, false, 1.0f},          {kByte, true, 127.0f},
                                            {kUnsignedByte, false, 1.0f},  {kUnsignedByte, true, 255.0f},
                                            {kShort, false, 1.0f},         {kShort, true, 32767.0f},
                                            {kUnsignedShort, false, 1.0f}, {kUnsignedShort, true, 65535.0f}};
  for (const QuantizedType& t : types) {
    SCOPED_TRACE(std::to_string(t.componentType) + (t.normalized ? " normalized" : ""));
    const bool isSigned = t.componentType == kByte || t.componentType == kShort;
    const size_t size = t.componentType == kByte || t.componentType == kUnsignedByte ? 1 : 2;
    // Three vertices, four components each (4-byte aligned elements as the spec requires).
    const std::vector<int> stored = {0, 1, 2, 3, 10, 20, 30, isSigned ? -1 : 1, isSigned ? -5 : 5, 7, 100, 1};
    std::vector<uint8_t> bytes;
    for (int v : stored) {
      if (size == 1) {
        bytes.push_back(static_cast<uint8_t>(v));
      } else {
        const uint16_t u = static_cast<uint16_t>(v);
        bytes.push_back(static_cast<uint8_t>(u & 0xff));
        bytes.push_back(static_cast<uint8_t>(u >> 8));
      }
    }
    GltfFileBuilder b;
    b.doc["extensionsUsed"] = {"KHR_mesh_quantization"};
    b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
    const size_t stride = 4 * size;
    const int view = b.addView(bytes, stride);
    const int vec3 = b.addAccessor(view, t.componentType, 3, "VEC3", t.normalized);
    const int vec2 = b.addAccessor(view, t.componentType, 3, "VEC2", t.normalized);
    const int vec4 = b.addAccessor(view, t.componentType, 3, "VEC4", t.normalized);
    const Json attributes = {{"POSITION", vec3}, {"NORMAL", vec3}, {"TEXCOORD_0", vec2}, {"TANGENT", vec4}};
    b.addMeshWithNode({{"primitives", Json::array({{{"attributes", attributes},
                                                    {"targets", Json::array({{{"POSITION", vec3},
                                                                              {"NORMAL", vec3},
                                                                              {"TANGENT", vec3}}})}}})}});
    b.writeGlb(dir / "quantized.glb");
    const eng::Model model = loadOk(dir / "quantized.glb");
    ASSERT_EQ(model.meshes.size(), 1u);
    const eng::Primitive& p = model.meshes[0].primitives.at(0);
    ASSERT_EQ(p.vertexCount(), 3u);
    auto expected = [&](size_t v, int c) {
      const float raw = static_cast<float>(stored[v * 4 + c]);
      return t.normalized ? std::max(raw / t.scale, -1.0f) : raw;
    };
    for (size_t v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) {
        EXPECT_FLOAT_EQ(p.positions[v][c], expected(v, c));
        EXPECT_FLOAT_EQ(p.normals[v][c], expected(v, c));
        EXPECT_FLOAT_EQ(p.tangents[v][c], expected(v, c));
        EXPECT_FLOAT_EQ(p.targets[0].positions[v][c], expected(v, c));
        EXPECT_FLOAT_EQ(p.targets[0].normals[v][c], expected(v, c));
        EXPECT_FLOAT_EQ(p.targets[0].tangents[v][c], expected(v, c));
        if (c < 2) {
          EXPECT_FLOAT_EQ(p.texcoords[v][c], expected(v, c));
        }
      }
    for (size_t v = 0; v < 3; ++v) EXPECT_FLOAT_EQ(p.tangents[v][3], expected(v, 3));
  }
}

// ---------------------------------------------------------------------------
// Textures: EXT_texture_webp, KHR_texture_basisu (KTX2), KHR_texture_transform.

GltfFileBuilder texturedQuad() {
  GltfFileBuilder b = quadWithTarget();
  const int uv = b.addVec2({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_0"] = uv;
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["materials"] = Json::array({{{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.25, 1, 1}},
                                                              {"baseColorTexture", {{"index", 0}}}}}}});
  return b;
}

TEST(GltfCompressed, WebpTextureDecodesToItsPixels) {
  const auto dir = freshTempDir("compressed_webp");
  const std::vector<uint8_t> pixels = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 128};
  uint8_t* encoded = nullptr;
  const size_t size = WebPEncodeLosslessRGBA(pixels.data(), 2, 2, 8, &encoded);
  ASSERT_GT(size, 0u);
  const std::vector<uint8_t> webp(encoded, encoded + size);
  WebPFree(encoded);
  GltfFileBuilder b = texturedQuad();
  b.doc["extensionsUsed"] = {"EXT_texture_webp"};
  b.doc["extensionsRequired"] = {"EXT_texture_webp"};
  b.doc["images"] = Json::array({{{"bufferView", b.addView(webp)}, {"mimeType", "image/webp"}}});
  b.doc["textures"] = Json::array({{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}});
  b.writeGlb(dir / "webp.glb");
  const eng::Model model = loadOk(dir / "webp.glb");
  ASSERT_EQ(model.images.size(), 1u);
  EXPECT_EQ(model.images[0].width, 2);
  EXPECT_EQ(model.images[0].rgba8, pixels) << "lossless WebP round trip";
  EXPECT_EQ(model.materials.at(0).baseColorImage, 0);
  const eng::ExtensionUse* record = extensionRecord(model, "EXT_texture_webp");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome, "decoded: 1 WebP image(s) (libwebp)");

  // Truncated WebP: the image is skipped with a warning, the model loads.
  GltfFileBuilder broken = texturedQuad();
  broken.doc["images"] = Json::array(
      {{{"bufferView", broken.addView(std::vector<uint8_t>(webp.begin(), webp.begin() + 20))}, {"mimeType", "image/webp"}}});
  broken.doc["textures"] = Json::array({{{"extensions", {{"EXT_texture_webp", {{"source", 0}}}}}}});
  broken.writeGlb(dir / "truncated_webp.glb");
  const eng::Model partial = loadOk(dir / "truncated_webp.glb");
  EXPECT_TRUE(partial.images.empty());
  EXPECT_TRUE(hasWarningContaining(partial, "WebP")) << (partial.warnings.empty() ? "" : partial.warnings[0]);
}

TEST(GltfCompressed, Ktx2TextureIsSkippedWithAWarningAndTheModelLoads) {
  const auto dir = freshTempDir("compressed_ktx2");
  std::vector<uint8_t> ktx2 = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  ktx2.resize(80, 0);
  GltfFileBuilder b = texturedQuad();
  b.doc["extensionsUsed"] = {"KHR_texture_basisu"};
  b.doc["extensionsRequired"] = {"KHR_texture_basisu"};
  b.doc["images"] = Json::array({{{"bufferView", b.addView(ktx2)}, {"mimeType", "image/ktx2"}}});
  b.doc["textures"] = Json::array({{{"extensions", {{"KHR_texture_basisu", {{"source", 0}}}}}}});
  b.writeGlb(dir / "ktx2.glb");
  const eng::Model model = loadOk(dir / "ktx2.glb");
  EXPECT_TRUE(model.images.empty());
  ASSERT_EQ(model.materials.size(), 1u);
  EXPECT_EQ(model.materials[0].baseColorImage, -1);
  EXPECT_EQ(model.materials[0].baseColorFactor, glm::vec4(0.5f, 0.25f, 1, 1)) << "factors kept";
  EXPECT_TRUE(hasWarningContaining(model, "KHR_texture_basisu"));
  const eng::ExtensionUse* record = extensionRecord(model, "KHR_texture_basisu");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome.rfind("skipped: 1 KTX2 image(s)", 0), 0u) << record->outcome;
}

TEST(GltfCompressed, TextureTransformIsBakedIntoTexcoords) {
  const auto dir = freshTempDir("compressed_texture_transform");
  auto png = eng::encodePng(2, 2, std::vector<uint8_t>(16, 255));
  ASSERT_TRUE(png.ok());
  GltfFileBuilder b = texturedQuad();
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  b.doc["images"] = Json::array({{{"bufferView", b.addView(*png)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = Json::array({{{"source", 0}}});
  Json& info = b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"];
  info["extensions"] = {{"KHR_texture_transform", {{"offset", {0.5, 0.25}}, {"rotation", M_PI / 2}, {"scale", {2, 1}}}}};
  b.writeGlb(dir / "transform.glb");
  const eng::Model model = loadOk(dir / "transform.glb");
  // uv' = T * R * S * uv with R = [cos sin; -sin cos]: (u, v) -> (v + 0.5, -2u + 0.25).
  const std::vector<glm::vec2> expected = {{0.5f, 0.25f}, {0.5f, -1.75f}, {1.5f, -1.75f}, {1.5f, 0.25f}};
  const eng::Primitive& p = model.meshes.at(0).primitives.at(0);
  ASSERT_EQ(p.texcoords.size(), 4u);
  for (size_t v = 0; v < 4; ++v) {
    EXPECT_NEAR(p.texcoords[v].x, expected[v].x, 1e-6f) << v;
    EXPECT_NEAR(p.texcoords[v].y, expected[v].y, 1e-6f) << v;
  }
  const eng::ExtensionUse* record = extensionRecord(model, "KHR_texture_transform");
  ASSERT_NE(record, nullptr);
  EXPECT_EQ(record->outcome.rfind("applied: baked into the UV set of 1 material", 0), 0u) << record->outcome;
  EXPECT_FALSE(record->required);

  // A transform that selects another UV set applies to that set, which the
  // primitive then reads instead of TEXCOORD_0.
  info["extensions"]["KHR_texture_transform"]["texCoord"] = 1;
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = b.addVec2({{0, 0}, {0, 1}, {0, 1}, {0, 0}});
  b.writeGlb(dir / "transform_uv1.glb");
  const eng::Model other = loadOk(dir / "transform_uv1.glb");
  // (0, 1) -> (1.5, 0.25).
  EXPECT_LT(glm::distance(other.meshes.at(0).primitives.at(0).texcoords.at(1), glm::vec2(1.5f, 0.25f)), 1e-6f);
  EXPECT_TRUE(other.warnings.empty()) << other.warnings[0];

  // Without that set the primitive falls back to TEXCOORD_0, and says so.
  b.doc["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
  b.writeGlb(dir / "transform_uv1_missing.glb");
  const eng::Model missing = loadOk(dir / "transform_uv1_missing.glb");
  EXPECT_LT(glm::distance(missing.meshes.at(0).primitives.at(0).texcoords.at(1), glm::vec2(0.5f, -1.75f)), 1e-6f);
  EXPECT_TRUE(hasWarningContaining(missing, "base colour reads TEXCOORD_1, which the primitive lacks"));
}

TEST(GltfCompressed, BaseColorReadsTheUvSetItsTextureNames) {
  const auto dir = freshTempDir("texcoord_set");
  auto png = eng::encodePng(2, 2, std::vector<uint8_t>(16, 255));
  ASSERT_TRUE(png.ok());
  GltfFileBuilder b = texturedQuad();
  b.doc["images"] = Json::array({{{"bufferView", b.addView(*png)}, {"mimeType", "image/png"}}});
  b.doc["textures"] = Json::array({{{"source", 0}}});
  b.doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1;
  const std::vector<glm::vec2> second = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.75f, 0.75f}, {0.25f, 0.75f}};
  b.doc["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = b.addVec2(second);
  b.writeGlb(dir / "uv1.glb");
  const eng::Model model = loadOk(dir / "uv1.glb");
  EXPECT_EQ(model.meshes.at(0).primitives.at(0).texcoords, second);
  EXPECT_TRUE(model.warnings.empty()) << model.warnings[0];
}

}  // namespace
