// One budget per glTF load (issue 37): each class of small file that made the
// loader allocate gigabytes is rebuilt here and must end in one error naming
// the file, what was being made and the limit, or load within the budget,
// measured by the bytes the load charged. The real assets in ../shared must
// stay far below the default.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using scene_test::GltfFileBuilder;
using scene_test::Json;

constexpr const char* kFile = "hostile.gltf";

std::vector<uint8_t> bytesOf(const std::string& text) { return {text.begin(), text.end()}; }
std::vector<uint8_t> bytesOf(const Json& doc) { return bytesOf(doc.dump()); }

struct Outcome {
  eng::Result<eng::Model> model;
  size_t charged = 0;
};

Outcome load(const std::vector<uint8_t>& bytes, const eng::GltfLoadLimits& limits = {}) {
  size_t charged = 0;
  auto model = eng::loadModelFromBytes(bytes, kFile, limits, &charged);
  return {std::move(model), charged};
}

// One line that names the file, what was being made and the limit.
void expectOverBudget(const Outcome& outcome, const std::string& what, size_t limit = eng::kDefaultLoadBudgetBytes) {
  ASSERT_FALSE(outcome.model.ok()) << "loaded, charging " << outcome.charged << " bytes";
  const eng::Error& error = outcome.model.error();
  EXPECT_EQ(error.kind, eng::ErrorKind::TooLarge) << error.message;
  EXPECT_EQ(error.message.rfind(std::string(kFile) + ": ", 0), 0u) << error.message;
  EXPECT_NE(error.message.find(what), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("load budget of " + std::to_string(limit) + " bytes"), std::string::npos) << error.message;
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << error.message;
  EXPECT_LE(outcome.charged, limit);
}

Json minimalDoc() { return Json{{"asset", {{"version", "2.0"}}}}; }

// 2 MB of `{}` materials: three bytes of JSON each, a full object in tinygltf and the Model.
TEST(GltfBudget, EmptyMaterialsAreChargedAsWholeObjects) {
  std::string text = R"({"asset":{"version":"2.0"},"materials":[{})";
  while (text.size() < (size_t{2} << 20)) text += ",{}";
  text += "]}";
  expectOverBudget(load(bytesOf(text)), "materials");
}

// The same entries within a budget they fit: the load's charge grows with them.
TEST(GltfBudget, ObjectsAreChargedPerEntry) {
  Json doc = minimalDoc();
  doc["materials"] = Json::array();
  const Outcome none = load(bytesOf(doc));
  ASSERT_TRUE(none.model.ok()) << none.model.error().message;
  for (int i = 0; i < 1000; ++i) doc["materials"].push_back(Json::object());
  const Outcome thousand = load(bytesOf(doc));
  ASSERT_TRUE(thousand.model.ok()) << thousand.model.error().message;
  EXPECT_EQ(thousand.model->materials.size(), 1000u);
  EXPECT_GE(thousand.charged - none.charged, 1000 * sizeof(eng::Material));
}

// A meshopt fallback buffer declares its decoded size: 1.1 GB in a few bytes, zero-filled.
TEST(GltfBudget, MeshoptFallbackBufferIsCharged) {
  Json doc = minimalDoc();
  doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  doc["buffers"] = Json::array({{{"byteLength", 1'100'000'000}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}});
  expectOverBudget(load(bytesOf(doc)), "meshopt fallback buffer 0");
}

// Accessors without a bufferView are zero-filled at any count: a primitive
// of 100000 vertices with 10000 empty morph targets is 12 GB of deltas when drawn.
GltfFileBuilder zeroFilledPrimitive(size_t vertices, Json targets) {
  GltfFileBuilder b;
  const int positions = b.addAccessor(-1, scene_test::kFloat, vertices, "VEC3");
  b.addMeshWithNode({{"primitives", Json::array({{{"attributes", {{"POSITION", positions}}}, {"targets", targets}}})}});
  return b;
}

TEST(GltfBudget, EmptyMorphTargetsAreCharged) {
  GltfFileBuilder b = zeroFilledPrimitive(100'000, Json::array());
  Json& targets = b.doc["meshes"][0]["primitives"][0]["targets"];
  for (int t = 0; t < 10'000; ++t) targets.push_back(Json::object());
  const std::vector<uint8_t> glb = b.glbBytes();
  ASSERT_LT(glb.size(), size_t{200'000});
  expectOverBudget(load(glb), "10000 morph targets of 100000 vertices");
}

TEST(GltfBudget, TargetsSharingOneAccessorAreChargedEach) {
  GltfFileBuilder b = zeroFilledPrimitive(100'000, Json::array());
  const int deltas = b.addAccessor(-1, scene_test::kFloat, 100'000, "VEC3");
  Json& targets = b.doc["meshes"][0]["primitives"][0]["targets"];
  for (int t = 0; t < 2'000; ++t) targets.push_back({{"POSITION", deltas}});
  const Outcome outcome = load(b.glbBytes());
  ASSERT_FALSE(outcome.model.ok());
  EXPECT_EQ(outcome.model.error().kind, eng::ErrorKind::TooLarge) << outcome.model.error().message;
  EXPECT_NE(outcome.model.error().message.find("load budget of"), std::string::npos) << outcome.model.error().message;
}

// One small PNG in the binary chunk, named by `images` image entries (all on
// the same bufferView) and drawn by `materials` materials through their own textures.
GltfFileBuilder sharedImage(int images, int materials, int side = 64) {
  GltfFileBuilder b = scene_test::quadWithTarget();
  auto png = eng::encodePng(side, side, std::vector<uint8_t>(size_t(side) * side * 4, 200));
  EXPECT_TRUE(png.ok());
  const int view = b.addView(png->data(), png->size());
  for (int i = 0; i < images; ++i) b.doc["images"].push_back({{"bufferView", view}, {"mimeType", "image/png"}});
  for (int m = 0; m < materials; ++m) {
    b.doc["textures"].push_back({{"source", m % images}});
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", m}}}}}});
  }
  return b;
}

TEST(GltfBudget, ImagesWithTheSameBytesAreDecodedOnce) {
  const Outcome outcome = load(sharedImage(1000, 1000).glbBytes());
  ASSERT_TRUE(outcome.model.ok()) << outcome.model.error().message;
  ASSERT_EQ(outcome.model->images.size(), 1u);
  for (const eng::Material& m : outcome.model->materials) EXPECT_EQ(m.baseColorImage, 0);
  // 1000 copies of the encoded bytes (tinygltf keeps one per image), the
  // objects and one decode: less than decoding each image would be.
  EXPECT_LT(outcome.charged, size_t{1000} * 64 * 64 * 4 / 2);
}

TEST(GltfBudget, UnusedImagesAreNotDecoded) {
  GltfFileBuilder b = sharedImage(1000, 0, 1024);
  const Outcome unused = load(b.glbBytes());
  ASSERT_TRUE(unused.model.ok()) << unused.model.error().message;
  EXPECT_TRUE(unused.model->images.empty());
  b.doc["textures"].push_back({{"source", 0}});
  b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  const Outcome used = load(b.glbBytes());
  ASSERT_TRUE(used.model.ok()) << used.model.error().message;
  EXPECT_EQ(used.model->images.size(), 1u);
  // The one decode, and the texture and material that draw it.
  EXPECT_GE(used.charged - unused.charged, size_t{1024} * 1024 * 4);
  EXPECT_LT(used.charged - unused.charged, size_t{1024} * 1024 * 4 + 16384);
}

// Different images of 1024 x 1024 each: the pixels, charged before decoding, pass a 10 MB budget.
TEST(GltfBudget, DecodedPixelsAreCharged) {
  GltfFileBuilder b = scene_test::quadWithTarget();
  for (int i = 0; i < 4; ++i) {
    auto png = eng::encodePng(1024, 1024, std::vector<uint8_t>(size_t{1024} * 1024 * 4, uint8_t(i)));
    ASSERT_TRUE(png.ok());
    b.doc["images"].push_back({{"bufferView", b.addView(png->data(), png->size())}, {"mimeType", "image/png"}});
    b.doc["textures"].push_back({{"source", i}});
    b.doc["materials"].push_back({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", i}}}}}});
  }
  eng::GltfLoadLimits limits;
  limits.maxDecodedBytes = size_t{10} << 20;
  expectOverBudget(load(b.glbBytes(), limits), "1024x1024) decoded", limits.maxDecodedBytes);
}

// The embedder's budget replaces the default, for everything one load makes.
TEST(GltfBudget, EmbedderSetsTheBudget) {
  const std::vector<uint8_t> glb = scene_test::quadWithTarget().glbBytes();
  const Outcome fits = load(glb);
  ASSERT_TRUE(fits.model.ok()) << fits.model.error().message;
  ASSERT_GT(fits.charged, 0u);
  eng::GltfLoadLimits limits;
  limits.maxDecodedBytes = fits.charged;
  EXPECT_TRUE(load(glb, limits).model.ok());
  limits.maxDecodedBytes = fits.charged - 1;
  const Outcome over = load(glb, limits);
  ASSERT_FALSE(over.model.ok());
  EXPECT_NE(over.model.error().message.find("load budget of " + std::to_string(limits.maxDecodedBytes)), std::string::npos)
      << over.model.error().message;
}

// Every real model in ../shared loads with the default budget, using a small part of it.
TEST(GltfBudget, SharedAssetsStayFarBelowTheDefault) {
  FACIAL_REQUIRE_SHARED();
  size_t files = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(testing_support::sharedDir())) {
    const std::string ext = entry.path().extension().string();
    if (ext != ".glb" && ext != ".gltf" && ext != ".vrm") continue;
    auto bytes = eng::readFileBytes(entry.path(), eng::GltfLoadLimits{}.maxFileBytes);
    ASSERT_TRUE(bytes.ok()) << bytes.error().message;
    size_t charged = 0;
    auto model = eng::loadModelFromBytes(*bytes, entry.path(), {}, &charged);
    ASSERT_TRUE(model.ok()) << model.error().message;
    EXPECT_LT(charged, eng::kDefaultLoadBudgetBytes / 8) << entry.path();
    std::printf("  %s: %zu bytes charged (file %zu)\n", entry.path().lexically_relative(testing_support::sharedDir()).c_str(),
                charged, bytes->size());
    ++files;
  }
  EXPECT_GE(files, 10u);
}

}  // namespace
