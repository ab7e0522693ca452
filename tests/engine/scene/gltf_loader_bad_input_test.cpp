// Hostile and broken glTF files, each written by the test: every one must
// fail with a single-line error naming the file and the problem, never crash,
// never expand a path, never read outside the model's folder.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"

namespace {

using namespace scene_test;
using testing_support::freshTempDir;

TEST(GltfLoaderBadInput, MissingFile) {
  const auto dir = freshTempDir("bad_missing_file");
  expectLoadError(dir / "nothing.glb", "not found");
}

TEST(GltfLoaderBadInput, EmptyFile) {
  const auto dir = freshTempDir("bad_empty");
  writeBytes(dir / "empty.gltf", {});
  expectLoadError(dir / "empty.gltf", "empty");
}

TEST(GltfLoaderBadInput, TruncatedGlb) {
  const auto dir = freshTempDir("bad_truncated_glb");
  std::vector<uint8_t> glb = quadWithTarget().glbBytes();
  for (size_t keep : {size_t{3}, size_t{10}, size_t{16}, glb.size() / 2, glb.size() - 1}) {
    writeBytes(dir / "cut.glb", std::vector<uint8_t>(glb.begin(), glb.begin() + keep));
    expectLoadError(dir / "cut.glb", "truncated");
  }
}

TEST(GltfLoaderBadInput, CorruptGlbChunkLengthAndType) {
  const auto dir = freshTempDir("bad_corrupt_glb");
  const std::vector<uint8_t> good = quadWithTarget().glbBytes();
  std::vector<uint8_t> longChunk = good;
  longChunk[12] = 0xFF;  // JSON chunk length far beyond the file
  longChunk[13] = 0xFF;
  writeBytes(dir / "long_chunk.glb", longChunk);
  expectLoadError(dir / "long_chunk.glb", "runs past");
  std::vector<uint8_t> badType = good;
  badType[16] = 'X';  // first chunk type is no longer JSON
  writeBytes(dir / "bad_type.glb", badType);
  expectLoadError(dir / "bad_type.glb", "expected 'JSON'");
  std::vector<uint8_t> badVersion = good;
  badVersion[4] = 1;
  writeBytes(dir / "version1.glb", badVersion);
  expectLoadError(dir / "version1.glb", "version 1");
  std::vector<uint8_t> badJson = good;
  badJson[20] = '[';  // the JSON chunk no longer parses as an object
  badJson[21] = '!';
  writeBytes(dir / "bad_json.glb", badJson);
  expectLoadError(dir / "bad_json.glb", "invalid JSON");
}

TEST(GltfLoaderBadInput, WrongMagic) {
  const auto dir = freshTempDir("bad_magic");
  std::vector<uint8_t> glb = quadWithTarget().glbBytes();
  glb[0] = 'g';
  glb[1] = 'L';
  glb[2] = 'B';
  glb[3] = '!';
  writeBytes(dir / "magic.glb", glb);
  expectLoadError(dir / "magic.glb", "wrong magic 'gLB!'");
  writeBytes(dir / "garbage.gltf", {'P', 'K', 3, 4, 0, 0});
  expectLoadError(dir / "garbage.gltf", "neither glTF JSON nor a GLB");
}

TEST(GltfLoaderBadInput, MalformedJson) {
  const auto dir = freshTempDir("bad_json");
  const std::string text = "{\"asset\": {\"version\": \"2.0\"}, \"meshes\": [ {";
  writeBytes(dir / "broken.gltf", std::vector<uint8_t>(text.begin(), text.end()));
  expectLoadError(dir / "broken.gltf", "invalid JSON: parse error at line 1");
}

// tinygltf and nlohmann recurse while parsing: 100,000 nested arrays would overflow the stack.
TEST(GltfLoaderBadInput, DeeplyNestedExtrasAreRefusedBeforeParsing) {
  const auto dir = freshTempDir("bad_deep_nesting");
  const std::string deep = R"("extras": {"note": "]]]\"[[[", "deep": )" + std::string(100000, '[') +
                           std::string(100000, ']') + "}, ";
  quadWithTarget().writeGltf(dir / "deep.gltf");
  replaceInFile(dir / "deep.gltf", "\"asset\"", deep + "\"asset\"");
  expectLoadError(dir / "deep.gltf", "JSON nests 100002 levels deep, more than the 256 accepted");

  // The GLB's JSON chunk, also when it asks for a compression extension (the pre-pass parses those).
  GltfFileBuilder b = quadWithTarget();
  b.doc["extensionsUsed"] = {"EXT_meshopt_compression"};
  const std::vector<uint8_t> glb = b.glbBytes();
  auto chunks = eng::parseGlb(glb);
  ASSERT_TRUE(chunks.ok());
  std::string json(chunks->json.begin(), chunks->json.end());
  json.insert(1, deep);
  writeBytes(dir / "deep.glb", eng::buildGlb(json, chunks->bin));
  expectLoadError(dir / "deep.glb", "JSON nests 100002 levels deep, more than the 256 accepted");
}

TEST(GltfLoaderBadInput, AccessorOutOfRangeOfItsBufferView) {
  const auto dir = freshTempDir("bad_accessor_range");
  GltfFileBuilder b = quadWithTarget();
  b.doc["accessors"][0]["count"] = 5;  // POSITION: 5 x 12 bytes in a 48-byte view
  b.writeGlb(dir / "accessor.glb");
  expectLoadError(dir / "accessor.glb", "run past the end of bufferView");
  GltfFileBuilder c = quadWithTarget();
  c.doc["accessors"][0]["byteOffset"] = 40;
  c.writeGlb(dir / "offset.glb");
  expectLoadError(dir / "offset.glb", "run past the end of bufferView");
}

TEST(GltfLoaderBadInput, BufferViewOutOfRangeOfItsBuffer) {
  const auto dir = freshTempDir("bad_view_range");
  GltfFileBuilder b = quadWithTarget();
  b.doc["bufferViews"][0]["byteOffset"] = 1000000;
  b.writeGltf(dir / "view.gltf", "view.bin");
  expectLoadError(dir / "view.gltf", "out of range of buffer");
}

TEST(GltfLoaderBadInput, AccessorOrBufferViewIndexThatDoesNotExist) {
  const auto dir = freshTempDir("bad_indices");
  GltfFileBuilder b = quadWithTarget();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["NORMAL"] = 99;
  b.writeGlb(dir / "accessor_index.glb");
  expectLoadError(dir / "accessor_index.glb", "accessor 99");
  GltfFileBuilder c = quadWithTarget();
  c.doc["accessors"][1]["bufferView"] = 42;
  c.writeGlb(dir / "view_index.glb");
  expectLoadError(dir / "view_index.glb", "bufferView 42");
}

TEST(GltfLoaderBadInput, IndexValueBeyondTheVertexCount) {
  const auto dir = freshTempDir("bad_index_value");
  GltfFileBuilder b = quadWithTarget();
  const int idx = b.addIndices({0, 1, 7});
  b.doc["meshes"][0]["primitives"][0]["indices"] = idx;
  b.writeGlb(dir / "index.glb");
  expectLoadError(dir / "index.glb", "index 7 at position 2 is out of range of 4 vertices");
}

TEST(GltfLoaderBadInput, TargetVertexCountDiffersFromItsPrimitive) {
  const auto dir = freshTempDir("bad_target_count");
  GltfFileBuilder b = quadWithTarget();
  const int shortTarget = b.addVec3({{0, 0, 1}, {0, 0, 1}, {0, 0, 1}});
  b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = shortTarget;
  b.writeGlb(dir / "target.glb");
  expectLoadError(dir / "target.glb", "target 0 POSITION has 3 elements, its primitive has 4 vertices");
}

TEST(GltfLoaderBadInput, PrimitivesWithDifferentTargetCounts) {
  const auto dir = freshTempDir("bad_target_mismatch");
  GltfFileBuilder b = quadWithTarget();
  auto second = b.doc["meshes"][0]["primitives"][0];
  second.erase("targets");
  b.doc["meshes"][0]["primitives"].push_back(second);
  b.writeGlb(dir / "mismatch.glb");
  expectLoadError(dir / "mismatch.glb", "has 0 morph targets, the mesh's other primitives have 1");
}

TEST(GltfLoaderBadInput, NanAndInfinitePositions) {
  const auto dir = freshTempDir("bad_nan");
  for (float bad : {std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::infinity()}) {
    GltfFileBuilder b = quadWithTarget();
    const int pos = b.addVec3({{0, 0, 0}, {1, 0, 0}, {1, bad, 0}, {0, 1, 0}});
    b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = pos;
    b.writeGlb(dir / "nan.glb");
    expectLoadError(dir / "nan.glb", std::isnan(bad) ? "element 2 is NaN" : "element 2 is infinite");
  }
}

TEST(GltfLoaderBadInput, MissingBufferFile) {
  const auto dir = freshTempDir("bad_missing_buffer");
  GltfFileBuilder b = quadWithTarget();
  b.writeGltf(dir / "model.gltf", "model.bin");
  std::filesystem::remove(dir / "model.bin");
  expectLoadError(dir / "model.gltf", "'model.bin'");
  expectLoadError(dir / "model.gltf", "not found");
}

TEST(GltfLoaderBadInput, MissingImageFile) {
  const auto dir = freshTempDir("bad_missing_image");
  GltfFileBuilder b = quadWithTarget();
  b.doc["images"] = Json::array({{{"uri", "skin.png"}}});
  b.writeGlb(dir / "model.glb");
  expectLoadError(dir / "model.glb", "'skin.png' (uri of a buffer or image) not found");
}

TEST(GltfLoaderBadInput, UriClimbingOutOfTheModelFolderIsRefused) {
  const auto dir = freshTempDir("bad_climb");
  // A real file one level up, so only the confinement can stop the read.
  quadWithTarget().writeGltf(dir / "outside.gltf", "outside.bin");
  GltfFileBuilder b = quadWithTarget();
  b.writeGltf(dir / "sub" / "model.gltf", "../outside.bin");
  expectLoadError(dir / "sub" / "model.gltf", "'../outside.bin' points outside the model's folder; refused");
  GltfFileBuilder c = quadWithTarget();
  c.writeGltf(dir / "sub" / "passwd.gltf", "../../../../../../../../etc/passwd");
  expectLoadError(dir / "sub" / "passwd.gltf", "points outside the model's folder");
  GltfFileBuilder d = quadWithTarget();
  d.doc["images"] = Json::array({{{"uri", "../../etc/passwd"}}});
  d.writeGlb(dir / "sub" / "image.glb");
  expectLoadError(dir / "sub" / "image.glb", "points outside the model's folder");
  GltfFileBuilder e = quadWithTarget();
  e.writeGltf(dir / "sub" / "absolute.gltf", "model.bin");
  // Rewrite the buffer uri to an absolute path of an existing file.
  replaceInFile(dir / "sub" / "absolute.gltf", "\"model.bin\"", "\"" + (dir / "outside.bin").string() + "\"");
  expectLoadError(dir / "sub" / "absolute.gltf", "outside.bin");
}

TEST(GltfLoaderBadInput, UriWithShellMetacharactersIsNeverExpanded) {
  const auto dir = freshTempDir("bad_shell_uri");
  // A .bin that a glob or an expansion could land on.
  quadWithTarget().writeGltf(dir / "real.gltf", "real.bin");
  const std::filesystem::path cwd = std::filesystem::current_path();
  for (const char* uri : {"$(touch pwned).bin", "`touch pwned`.bin", "~/real.bin", "*.bin", "real.bin;touch pwned",
                          "${HOME}/real.bin"}) {
    GltfFileBuilder b = quadWithTarget();
    b.writeGltf(dir / "model.gltf", "placeholder.bin");
    std::filesystem::remove(dir / "placeholder.bin");
    replaceInFile(dir / "model.gltf", "placeholder.bin", uri);
    expectLoadError(dir / "model.gltf", "not found");
    EXPECT_FALSE(std::filesystem::exists(dir / "pwned")) << uri;
    EXPECT_FALSE(std::filesystem::exists(cwd / "pwned")) << uri;
  }
}

TEST(GltfLoaderBadInput, AbsurdCountIsRefusedBeforeAllocating) {
  const auto dir = freshTempDir("bad_absurd_count");
  GltfFileBuilder b = quadWithTarget();
  b.doc["accessors"][0]["count"] = 4000000000ull;  // 48 GB of positions claimed over a 48-byte view
  b.writeGlb(dir / "count.glb");
  expectLoadError(dir / "count.glb", "run past the end of bufferView");
  // Sparse without a bufferView has no buffer to check against: the decode budget stops it.
  GltfFileBuilder c = quadWithTarget();
  const int iv = c.addView(std::vector<uint8_t>{0, 0, 0, 0});
  const int vv = c.addView(std::vector<glm::vec3>{{1, 0, 0}});
  const int huge = c.addAccessor(-1, kFloat, 3000000000ull, "VEC3");
  c.doc["accessors"][huge]["sparse"] = {{"count", 1},
                                        {"indices", {{"bufferView", iv}, {"componentType", kUnsignedByte}}},
                                        {"values", {{"bufferView", vv}}}};
  c.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = huge;
  c.writeGlb(dir / "sparse_count.glb");
  expectLoadError(dir / "sparse_count.glb", "would take 36000000000 bytes, past the load budget");
}

// A 392-byte file used to take 38 s and 11.5 GB: 89 million zero positions fit the decode
// limit, the normals and indices generated for them did not count.
TEST(GltfLoaderBadInput, HugeCountWithoutABufferViewIsRefusedWithWhatIsMadeFromIt) {
  const auto dir = freshTempDir("bad_huge_zero_accessor");
  GltfFileBuilder b;
  const int huge = b.addAccessor(-1, kFloat, 89000000, "VEC3");
  b.addMeshWithNode({{"primitives", Json::array({{{"attributes", {{"POSITION", huge}}}}})}});
  b.writeGlb(dir / "zeros.glb");
  EXPECT_LT(std::filesystem::file_size(dir / "zeros.glb"), 1000u);
  expectLoadError(dir / "zeros.glb",
                  "mesh 0 primitive 0 POSITION (accessor 0, 89000000 vertices): the normals and indices made for it "
                  "would take 1779999992 bytes, past the load budget of 1073741824 bytes");
}

TEST(GltfLoaderBadInput, DecodeLimitIsConfigurable) {
  const auto dir = freshTempDir("bad_decode_limit");
  quadWithTarget().writeGlb(dir / "quad.glb");
  eng::GltfLoadLimits limits;
  limits.maxDecodedBytes = 64;  // fewer than the quad's positions + normals + indices + target
  auto model = eng::loadModel(dir / "quad.glb", limits);
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("past the load budget of 64 bytes"), std::string::npos) << model.error().message;
  limits.maxFileBytes = 16;
  model = eng::loadModel(dir / "quad.glb", limits);
  ASSERT_FALSE(model.ok());
  EXPECT_NE(model.error().message.find("exceeds the limit of 16 bytes"), std::string::npos) << model.error().message;
}

TEST(GltfLoaderBadInput, SparseIndexOutOfRangeAndShortSparseViews) {
  const auto dir = freshTempDir("bad_sparse");
  GltfFileBuilder b = quadWithTarget();
  const int iv = b.addView(std::vector<uint8_t>{9, 0, 0, 0});
  const int vv = b.addView(std::vector<glm::vec3>{{1, 0, 0}});
  const int acc = b.addAccessor(-1, kFloat, 4, "VEC3");
  b.doc["accessors"][acc]["sparse"] = {{"count", 1},
                                       {"indices", {{"bufferView", iv}, {"componentType", kUnsignedByte}}},
                                       {"values", {{"bufferView", vv}}}};
  b.doc["meshes"][0]["primitives"][0]["targets"][0]["POSITION"] = acc;
  b.writeGlb(dir / "index.glb");
  expectLoadError(dir / "index.glb", "sparse index 9 (entry 0) is out of range of 4 elements");
  b.doc["accessors"][acc]["sparse"]["count"] = 3;  // 3 values in a 12-byte view
  b.writeGlb(dir / "short.glb");
  expectLoadError(dir / "short.glb", "run past the end of bufferView");
}

TEST(GltfLoaderBadInput, ByteStrideSmallerThanTheElement) {
  const auto dir = freshTempDir("bad_stride");
  GltfFileBuilder b = quadWithTarget();
  b.doc["bufferViews"][0]["byteStride"] = 4;
  b.writeGlb(dir / "stride.glb");
  expectLoadError(dir / "stride.glb", "byteStride 4 is smaller than the element size 12");
}

TEST(GltfLoaderBadInput, WrongAccessorType) {
  const auto dir = freshTempDir("bad_type");
  GltfFileBuilder b = quadWithTarget();
  b.doc["accessors"][0]["type"] = "VEC2";
  b.writeGlb(dir / "type.glb");
  expectLoadError(dir / "type.glb", "has type VEC2, expected VEC3");
}

TEST(GltfLoaderBadInput, UnsupportedRequiredExtensionIsNamed) {
  const auto dir = freshTempDir("bad_required_ext");
  GltfFileBuilder b = quadWithTarget();
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  b.writeGlb(dir / "instancing.glb");
  expectLoadError(dir / "instancing.glb", "requires glTF extension EXT_mesh_gpu_instancing");
}

TEST(GltfLoaderBadInput, ImageBufferViewOutOfRange) {
  const auto dir = freshTempDir("bad_image_view");
  GltfFileBuilder b = quadWithTarget();
  const int view = b.addView(std::vector<uint8_t>(8, 0));
  b.doc["bufferViews"][view]["byteLength"] = 100000;
  b.doc["images"] = Json::array({{{"bufferView", view}, {"mimeType", "image/png"}}});
  b.writeGlb(dir / "image_view.glb");
  expectLoadError(dir / "image_view.glb", "out of range of buffer");
}

TEST(GltfLoaderBadInput, BadBase64DataUri) {
  const auto dir = freshTempDir("bad_data_uri");
  GltfFileBuilder b = quadWithTarget();
  b.writeGltf(dir / "data.gltf");
  replaceInFile(dir / "data.gltf", "base64,", "base64,!!!!****");
  expectLoadError(dir / "data.gltf", "Failed to decode");
  EXPECT_LT(eng::loadModel(dir / "data.gltf").error().message.size(), 300u) << "the data: URI is shortened";
}

TEST(GltfLoaderBadInput, NodeHierarchyCycleAndTwoParents) {
  const auto dir = freshTempDir("bad_nodes");
  GltfFileBuilder b = quadWithTarget();
  b.doc["nodes"].push_back({{"children", {2}}});
  b.doc["nodes"].push_back({{"children", {1}}});
  b.writeGlb(dir / "cycle.glb");
  expectLoadError(dir / "cycle.glb", "cycle");
  GltfFileBuilder c = quadWithTarget();
  c.doc["nodes"].push_back({{"children", {0}}});
  c.doc["nodes"].push_back({{"children", {0}}});
  c.writeGlb(dir / "parents.glb");
  expectLoadError(dir / "parents.glb", "node 0 has two parents");
  GltfFileBuilder d = quadWithTarget();
  d.doc["nodes"][0]["mesh"] = 5;
  d.writeGlb(dir / "mesh.glb");
  expectLoadError(dir / "mesh.glb", "refers to mesh 5");
}

}  // namespace

// The error kind is what a caller branches on: ask for another path, report a
// broken asset, or raise a limit.
namespace {

eng::ErrorKind loadErrorKind(const std::filesystem::path& path, const eng::GltfLoadLimits& limits = {}) {
  auto model = eng::loadModel(path, limits);
  EXPECT_FALSE(model.ok()) << path << " loaded but should fail";
  return model.ok() ? eng::ErrorKind::InvalidArgument : model.error().kind;
}

TEST(GltfLoaderErrorKinds, MissingFileIsNotFound) {
  const auto dir = freshTempDir("kind_missing");
  EXPECT_EQ(loadErrorKind(dir / "nothing.glb"), eng::ErrorKind::NotFound);
}

TEST(GltfLoaderErrorKinds, MissingBufferBesideTheModelIsNotFound) {
  const auto dir = freshTempDir("kind_missing_buffer");
  quadWithTarget().writeGltf(dir / "model.gltf", "model.bin");
  std::filesystem::remove(dir / "model.bin");
  EXPECT_EQ(loadErrorKind(dir / "model.gltf"), eng::ErrorKind::NotFound);
}

TEST(GltfLoaderErrorKinds, BrokenFilesAreMalformed) {
  const auto dir = freshTempDir("kind_malformed");
  writeBytes(dir / "empty.gltf", {});
  EXPECT_EQ(loadErrorKind(dir / "empty.gltf"), eng::ErrorKind::Malformed);
  std::vector<uint8_t> glb = quadWithTarget().glbBytes();
  glb.resize(glb.size() / 2);
  writeBytes(dir / "cut.glb", glb);
  EXPECT_EQ(loadErrorKind(dir / "cut.glb"), eng::ErrorKind::Malformed);
}

TEST(GltfLoaderErrorKinds, FileOverTheLimitIsTooLarge) {
  const auto dir = freshTempDir("kind_too_large");
  quadWithTarget().writeGlb(dir / "quad.glb");
  eng::GltfLoadLimits limits;
  limits.maxFileBytes = 64;
  EXPECT_EQ(loadErrorKind(dir / "quad.glb", limits), eng::ErrorKind::TooLarge);
  EXPECT_TRUE(eng::loadModel(dir / "quad.glb").ok()) << "the same file loads under the default limits";
}

TEST(GltfLoaderErrorKinds, NewerGltfIsUnsupported) {
  const auto dir = freshTempDir("kind_unsupported");
  GltfFileBuilder b = quadWithTarget();
  b.doc["asset"]["version"] = "3.0";
  b.writeGlb(dir / "future.glb");
  EXPECT_EQ(loadErrorKind(dir / "future.glb"), eng::ErrorKind::Unsupported);
}

TEST(ErrorKinds, PrefixedKeepsKindAndCode) {
  const eng::Error inner = eng::makeError(eng::ErrorKind::Device, "vkQueueSubmit failed", -4);
  const eng::Error outer = inner.prefixed("frame: ");
  EXPECT_EQ(outer.kind, eng::ErrorKind::Device);
  EXPECT_EQ(outer.code, -4);
  EXPECT_EQ(outer.message, "frame: vkQueueSubmit failed");
  EXPECT_EQ(eng::errorKindName(eng::ErrorKind::TooLarge), "too large");
}

// A rigged file's calibration ("facialCalibration" in the root's extras):
// entries that are no scale are left out with a warning each, the rest kept.
TEST(GltfLoaderBadInput, CalibrationEntriesThatAreNoScaleAreLeftOutWithAWarning) {
  const auto dir = freshTempDir("bad_calibration");
  GltfFileBuilder b = quadWithTarget();
  b.doc["extras"] = {{"facialCalibration", {{"AU1_InnerBrowRaiser", 0.8}, {"AU2_OuterBrowRaiser_L", "high"}, {"AU4_BrowLowerer", -2.0}}}};
  b.writeGlb(dir / "calibration.glb");
  auto model = eng::loadModel(dir / "calibration.glb");
  ASSERT_TRUE(model) << model.error().message;
  ASSERT_EQ(model->calibration.size(), 1u);
  EXPECT_EQ(model->calibration[0].first, "AU1_InnerBrowRaiser");
  EXPECT_FLOAT_EQ(model->calibration[0].second, 0.8f);
  ASSERT_EQ(model->warnings.size(), 2u);
  EXPECT_NE(model->warnings[0].find("AU2_OuterBrowRaiser_L"), std::string::npos) << model->warnings[0];
  GltfFileBuilder c = quadWithTarget();
  c.doc["extras"] = {{"facialCalibration", {1, 2}}};
  c.writeGlb(dir / "array.glb");
  auto array = eng::loadModel(dir / "array.glb");
  ASSERT_TRUE(array) << array.error().message;
  EXPECT_TRUE(array->calibration.empty());
  EXPECT_EQ(array->warnings.size(), 1u);
}

}  // namespace
