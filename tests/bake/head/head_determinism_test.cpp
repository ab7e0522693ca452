// Generating the built-in head twice gives the same model, and writing it
// gives the same bytes: `facial make-head` is reproducible.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "engine/scene/gltf_writer.h"
#include "tests/common/test_support.h"
#include "tests/bake/head/built_in_head.h"

namespace {

std::string readBytes(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(HeadDeterminism, SecondGenerationIsIdentical) {
  const bake::GeneratedHead& first = head_testing::builtInHead();
  auto second = bake::generateHead(head_testing::builtInSpec());
  ASSERT_TRUE(second.ok()) << second.error().message;
  const eng::Model &a = first.model, &b = second->model;
  ASSERT_EQ(a.meshes.size(), b.meshes.size());
  for (size_t m = 0; m < a.meshes.size(); ++m) {
    ASSERT_EQ(a.meshes[m].primitives.size(), b.meshes[m].primitives.size());
    for (size_t p = 0; p < a.meshes[m].primitives.size(); ++p) {
      const eng::Primitive &pa = a.meshes[m].primitives[p], &pb = b.meshes[m].primitives[p];
      EXPECT_EQ(pa.positions, pb.positions);
      EXPECT_EQ(pa.normals, pb.normals);
      EXPECT_EQ(pa.texcoords, pb.texcoords);
      EXPECT_EQ(pa.indices, pb.indices);
      ASSERT_EQ(pa.targets.size(), pb.targets.size());
      for (size_t t = 0; t < pa.targets.size(); ++t) {
        EXPECT_EQ(pa.targets[t].positions, pb.targets[t].positions);
        EXPECT_EQ(pa.targets[t].normals, pb.targets[t].normals);
      }
    }
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) EXPECT_EQ(a.images[i].rgba8, b.images[i].rgba8) << a.images[i].name;
  EXPECT_EQ(first.landmarks.positions, second->landmarks.positions);
}

TEST(HeadDeterminism, WrittenFilesAreByteIdentical) {
  const auto dir = testing_support::freshTempDir("head_determinism");
  const eng::Model& model = head_testing::builtInHead().model;
  ASSERT_TRUE(eng::saveModel(model, dir / "a.glb").ok());
  ASSERT_TRUE(eng::saveModel(model, dir / "b.glb").ok());
  const std::string a = readBytes(dir / "a.glb"), b = readBytes(dir / "b.glb");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_LT(a.size(), size_t{5} << 20) << "the built-in head should stay well under 5 MiB";
}

}  // namespace
