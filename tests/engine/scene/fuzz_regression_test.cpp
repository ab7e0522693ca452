// Inputs the fuzzers (fuzz/) found, kept as files under tests/engine/scene/fuzz_inputs/
// and replayed the way the fuzzer that found them reads them.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "engine/scene/image_io.h"
#include "engine/scene/model_check.h"
#include "engine/scene/normals.h"
#include "importers/load_face.h"
#include "importers/obj_keyframes.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

std::string fuzzInput(const std::string& name) {
  std::ifstream in(testing_support::sourceDir() / "tests" / "engine" / "scene" / "fuzz_inputs" / name, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// What fuzz_image's reading of a kept input says (decodeImage with its 4 Mpixel
// cap); empty if the input decodes, "missing" if it is not the size it was kept at.
std::string fuzzImageRefusal(const std::string& name, size_t keptSize) {
  const std::string bytes = fuzzInput(name);
  if (bytes.size() != keptSize) return "missing: " + name + " holds " + std::to_string(bytes.size()) + " bytes";
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  auto image = eng::decodeImage({data, bytes.size()}, "input image", size_t{4} << 20);
  return image.ok() ? std::string() : image.error().message;
}

// fuzz_obj_set found it: a quad whose coordinates (1.1e30) are finite floats,
// but the smooth normals made for it overflowed (the float cross product and
// its squared length went to inf, the normal to NaN), so the model handed to
// the renderer held NaN normals. Normals are now made in double.
TEST(FuzzRegression, ObjSetWithHugeCoordinatesGetsFiniteNormals) {
  const std::string text = fuzzInput("obj_set_huge_coordinates.txt");
  ASSERT_FALSE(text.empty());
  // fuzz_obj_set without a "#%target" line: the file is both the neutral and the target.
  const fs::path dir = testing_support::freshTempDir("fuzz_obj_huge");
  testing_support::writeFile(dir / "neutral.obj", text);
  testing_support::writeFile(dir / "smile.obj", text);
  const importers::ObjTargetFile targets[] = {{"smile", dir / "smile.obj"}};
  auto imported = importers::importObjKeyframes(dir / "neutral.obj", targets);
  ASSERT_TRUE(imported.ok()) << imported.error().message;
  const auto consistent = eng::checkModel(imported->model);
  EXPECT_TRUE(consistent.ok()) << consistent.error().message;
  for (const glm::vec3& n : imported->model.meshes[0].primitives[0].normals) {
    EXPECT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
    EXPECT_NEAR(glm::length(n), 1.0f, 1e-4f);
  }
}

// The same overflow through the shared smooth-normal generator (the glTF
// loader uses it for primitives without normals).
TEST(FuzzRegression, SmoothNormalsOfHugeTrianglesAreFinite) {
  const std::vector<glm::vec3> positions = {{0, 0, 0}, {3e37f, 0, 0}, {0, 3e37f, 0}};
  const std::vector<uint32_t> indices = {0, 1, 2};
  for (const glm::vec3& n : eng::computeSmoothNormals(positions, indices)) {
    EXPECT_FLOAT_EQ(n.z, 1.0f);
    EXPECT_FLOAT_EQ(n.x, 0.0f);
  }
}

// fuzz_image found it (out of memory, malloc(2147483648)): after an IDAT chunk of 4096
// bytes, a second one declaring 2^30 + 1 bytes that the file does not hold. stb doubled its
// buffer to 2 GiB before reading. The chunk is now refused by what it declares.
TEST(FuzzRegressionValidity, PngChunkDeclaringMoreThanTheFileHoldsIsRefused) {
  EXPECT_EQ(fuzzImageRefusal("image_idat_past_end.png", 4157),
            "input image: PNG chunk 'IDAT' at byte 4141 declares 1073741825 bytes, only 8 follow its header (truncated or corrupt file)");
}

// fuzz_image found it too (out of memory, malloc(2147483648)): 182 bytes ending in
// "IENDIDAT", a chunk header with no data and no CRC after it, whose length field reads
// 1229278788. The check stopped 12 bytes from the end; stb reads a header from 8.
TEST(FuzzRegressionValidity, PngEndingInABareChunkHeaderIsRefused) {
  EXPECT_EQ(fuzzImageRefusal("image_bare_chunk_header.png", 182),
            "input image: PNG chunk 'IDAT' at byte 174 declares 1229278788 bytes, only 0 follow its header (truncated or corrupt file)");
}

// Validity: a target 3e38 away from its neutral vertex makes a delta no float
// holds: refused with one line naming the file, not handed on as inf.
TEST(FuzzRegressionValidity, ObjTargetMovingFurtherThanAFloatIsRefused) {
  const fs::path dir = testing_support::freshTempDir("fuzz_obj_delta_overflow");
  testing_support::writeFile(dir / "neutral.obj", "v -3e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  testing_support::writeFile(dir / "far.obj", "v 3e38 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const importers::ObjTargetFile targets[] = {{"far", dir / "far.obj"}};
  auto imported = importers::importObjKeyframes(dir / "neutral.obj", targets);
  ASSERT_FALSE(imported.ok());
  EXPECT_NE(imported.error().message.find((dir / "neutral.obj").string()), std::string::npos) << imported.error().message;
  EXPECT_NE(imported.error().message.find("non-finite"), std::string::npos) << imported.error().message;
}

// fuzz_ply found it while PLY files went through Debian's Assimp 5.2.5, which
// crashed on it: a header whose face property runs into "end_header" on one
// line, so the binary body is read as header lines. The reader of our own
// refuses it in one printable line.
TEST(FuzzRegression, PlyPropertyRunIntoEndHeaderIsOneLine) {
  const std::string bytes = fuzzInput("ply_property_run_into_end_header.ply");
  ASSERT_EQ(bytes.size(), 440u);
  auto face = importers::loadFaceFromBytes({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()}, "input.ply");
  ASSERT_FALSE(face);
  const std::string& message = face.error().message;
  EXPECT_EQ(message.rfind("input.ply: header line ", 0), 0u) << message;
  EXPECT_TRUE(std::all_of(message.begin(), message.end(), [](char c) { return c >= 0x20 && c < 0x7f; })) << message;
}

}  // namespace
