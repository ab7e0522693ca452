// `facial info` and `facial convert` as a user runs them: exit codes and the
// one-line error on bad input. Skips when the facial program is not built.
#include <algorithm>
#include <array>
#include <cstdio>
#include <sys/wait.h>

#include <gtest/gtest.h>

#include "tests/common/test_support.h"
#include "tests/engine/scene/gltf_test_files.h"
#include "tests/common/obj_test_files.h"

namespace {

using testing_support::binaryDir;
using testing_support::freshTempDir;

struct CommandRun {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

CommandRun facial(const std::string& args) {
  const std::filesystem::path program = binaryDir() / "bin" / "facial";
  CommandRun run;
  FILE* pipe = popen(("'" + program.string() + "' " + args + " 2>&1").c_str(), "r");
  if (!pipe) return run;
  std::array<char, 4096> buf;
  while (size_t n = fread(buf.data(), 1, buf.size(), pipe)) run.output.append(buf.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

#define REQUIRE_FACIAL_PROGRAM()                                                           \
  do {                                                                                     \
    if (!std::filesystem::exists(binaryDir() / "bin" / "facial"))                          \
      GTEST_SKIP() << "build/bin/facial is not built (target facial_cli); command test skipped"; \
  } while (0)

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

TEST(FacialInfoCommand, DescribesAModelAndItsTargets) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_info_ok");
  scene_test::quadWithTarget().writeGlb(dir / "quad.glb");
  const CommandRun text = facial("info " + quoted(dir / "quad.glb"));
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("mesh 0 'Quad': 1 primitive(s), 1 target(s)"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("lift"), std::string::npos);
  const CommandRun json = facial("info --json " + quoted(dir / "quad.glb"));
  EXPECT_EQ(json.exitCode, 0);
  const auto doc = nlohmann::json::parse(json.output);
  EXPECT_EQ(doc["meshes"][0]["targetNames"][0], "lift");
  EXPECT_EQ(doc["meshes"][0]["defaultWeights"][0], 0.25);
  EXPECT_EQ(doc["meshes"][0]["primitives"][0]["vertices"], 4);
}

TEST(FacialInfoCommand, ListsASamplerThatIsNotTheDefault) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_info_sampler");
  scene_test::GltfFileBuilder b = scene_test::quadWithTarget();
  // A 1x1 PNG, as data: the sampler is what is listed.
  b.doc["images"] = nlohmann::json::array(
      {{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg=="}}});
  b.doc["samplers"] = nlohmann::json::array({{{"wrapS", 33071}, {"wrapT", 33648}, {"magFilter", 9728}, {"minFilter", 9728}}});
  b.doc["textures"] = nlohmann::json::array({{{"source", 0}, {"sampler", 0}}});
  b.doc["materials"] = nlohmann::json::array({{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.writeGlb(dir / "sampled.glb");
  const CommandRun text = facial("info " + quoted(dir / "sampled.glb"));
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("sampled clamp-to-edge x mirrored-repeat, magnified nearest, minified nearest, no mipmaps"),
            std::string::npos)
      << text.output;
}

TEST(FacialInfoCommand, ListsAToonMaterialAndTheMtoonExtension) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_info_toon");
  scene_test::GltfFileBuilder b = scene_test::quadWithTarget();
  b.doc["extensionsUsed"] = {"VRMC_materials_mtoon"};
  b.doc["materials"] = nlohmann::json::array(
      {{{"extensions", {{"VRMC_materials_mtoon", {{"specVersion", "1.0"}, {"shadeColorFactor", {0.5, 0.25, 0.25}}}}}}}});
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.writeGlb(dir / "toon.glb");
  const CommandRun text = facial("info " + quoted(dir / "toon.glb"));
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("toon (MToon): shade (0.5, 0.25, 0.25), shift 0, toony 0.9"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("VRMC_materials_mtoon"), std::string::npos) << text.output;
  const CommandRun json = facial("info --json " + quoted(dir / "toon.glb"));
  EXPECT_EQ(json.exitCode, 0) << json.output;
  const nlohmann::json j = nlohmann::json::parse(json.output, nullptr, false);
  ASSERT_FALSE(j.is_discarded()) << json.output;
  EXPECT_FLOAT_EQ(j["materials"][0]["toon"]["shadingToony"].get<float>(), 0.9f);
}

TEST(FacialInfoCommand, BadFilesExitNonZeroWithOneLineNamingTheFile) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_info_bad");
  std::vector<uint8_t> glb = scene_test::quadWithTarget().glbBytes();
  glb.resize(glb.size() / 2);
  scene_test::writeBytes(dir / "truncated.glb", glb);
  scene_test::GltfFileBuilder climb = scene_test::quadWithTarget();
  climb.writeGltf(dir / "climb.gltf", "../../etc/passwd");
  for (const char* name : {"truncated.glb", "climb.gltf", "missing.glb"}) {
    const CommandRun run = facial("info " + quoted(dir / name));
    EXPECT_EQ(run.exitCode, 1) << name << ": " << run.output;
    EXPECT_NE(run.output.find((dir / name).string()), std::string::npos) << run.output;
    EXPECT_EQ(std::count(run.output.begin(), run.output.end(), '\n'), 1) << run.output;
  }
}

TEST(FacialInfoCommand, ListsEachExtensionWithWhatTheLoaderDidWithIt) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_info_extensions");
  scene_test::GltfFileBuilder b = scene_test::quadWithTarget();
  b.doc["extensionsUsed"] = {"KHR_materials_sheen", "KHR_mesh_quantization"};
  b.doc["extensionsRequired"] = {"KHR_mesh_quantization"};
  b.writeGlb(dir / "quad.glb");
  const CommandRun text = facial("info " + quoted(dir / "quad.glb"));
  EXPECT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("2 extension(s)"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("KHR_materials_sheen          used     ignored: not supported"), std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("KHR_mesh_quantization        required applied"), std::string::npos) << text.output;
  const CommandRun json = facial("info --json " + quoted(dir / "quad.glb"));
  ASSERT_EQ(json.exitCode, 0) << json.output;
  const auto doc = nlohmann::json::parse(json.output);
  ASSERT_EQ(doc["extensions"].size(), 2u);
  EXPECT_EQ(doc["extensions"][0]["name"], "KHR_materials_sheen");
  EXPECT_EQ(doc["extensions"][0]["required"], false);
  EXPECT_EQ(doc["extensions"][1]["name"], "KHR_mesh_quantization");
  EXPECT_EQ(doc["extensions"][1]["required"], true);
}

TEST(FacialInfoCommand, ShowsTheMeshoptRobotAsDecoded) {
  REQUIRE_FACIAL_PROGRAM();
  FACIAL_REQUIRE_SHARED();
  const CommandRun json =
      facial("info --json " + quoted(testing_support::sharedDir() / "compressed" / "RobotExpressive.meshopt.glb"));
  ASSERT_EQ(json.exitCode, 0) << json.output;
  const auto doc = nlohmann::json::parse(json.output);
  bool found = false;
  for (const auto& e : doc["extensions"])
    if (e["name"] == "EXT_meshopt_compression") {
      found = true;
      EXPECT_EQ(e["required"], true);
      EXPECT_EQ(e["outcome"].get<std::string>().rfind("decoded: ", 0), 0u) << e.dump();
    }
  EXPECT_TRUE(found) << json.output;
}

TEST(FacialConvertCommand, ConvertsAnObjFolderAndRefusesAMismatchedTarget) {
  REQUIRE_FACIAL_PROGRAM();
  const auto dir = freshTempDir("cmd_convert");
  testing_support::GridObj lifted;
  lifted.position = [](int i, glm::vec3 r) { return i == 6 ? r + glm::vec3(0, 0, 1) : r; };
  testing_support::writeFile(dir / "set" / "neutral.obj", testing_support::GridObj{}.text());
  testing_support::writeFile(dir / "set" / "smile.obj", lifted.text());
  const CommandRun ok = facial("convert " + quoted(dir / "set") + " --out " + quoted(dir / "face.glb"));
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  EXPECT_NE(ok.output.find("target smile"), std::string::npos) << ok.output;
  const CommandRun info = facial("info " + quoted(dir / "face.glb"));
  EXPECT_NE(info.output.find("smile"), std::string::npos) << info.output;

  testing_support::GridObj other;
  other.nx = 2;
  testing_support::writeFile(dir / "other.obj", other.text());
  const CommandRun bad = facial("convert " + quoted(dir / "set" / "neutral.obj") + " --target frown=" + quoted(dir / "other.obj") +
                         " --out " + quoted(dir / "bad.glb"));
  EXPECT_EQ(bad.exitCode, 1);
  EXPECT_NE(bad.output.find("other.obj: topology differs"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.glb"));
}

}  // namespace
