// Files from a newer format version are refused with a message naming the
// file, the file's version and the version this build reads -- never misread.
// Every format the editor and the runtime read carries a version: graphs,
// timelines (the editor's documents and autosaves), rig maps, expression
// presets (an integer "version"), and glTF (asset.version / asset.minVersion,
// which the editor's sculpt saves as .glb).
#include <gtest/gtest.h>

#include "editor/timeline_document.h"
#include "engine/scene/gltf_loader.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/timeline_json.h"
#include "facial/runtime/rig/expression_library.h"
#include "facial/runtime/rig/rigmap_file.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

fs::path write(const std::string& dirName, const std::string& name, const std::string& text) {
  const fs::path path = testing_support::freshTempDir(dirName) / name;
  testing_support::writeFile(path, text);
  return path;
}

void expectNewerRefused(const std::string& message, const fs::path& file, const std::string& version) {
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  EXPECT_NE(message.find("unsupported version " + version + ": written by a newer release"), std::string::npos)
      << message;
  EXPECT_NE(message.find("this build reads version 1"), std::string::npos) << message;
}

const char* kTimeline = R"({"version": %s, "name": "t", "duration": 1, "tracks": [{"channel": "jawOpen", "keys": [[0, 0], [1, 1]]}]})";

std::string timelineText(const char* version) {
  char text[256];
  std::snprintf(text, sizeof text, kTimeline, version);
  return text;
}

TEST(NewerFormat, TimelineAndEditorDocumentRefuseVersion2) {
  const fs::path file = write("newer_timeline", "clip.json", timelineText("2"));
  auto timeline = facial::loadTimeline(file);
  ASSERT_FALSE(timeline.ok());
  expectNewerRefused(timeline.error().message, file, "2");
  auto document = editor::TimelineDocument::load(file);
  ASSERT_FALSE(document.ok());
  expectNewerRefused(document.error().message, file, "2");
}

TEST(NewerFormat, CurrentVersionStillLoads) {
  const fs::path file = write("current_timeline", "clip.json", timelineText("1"));
  EXPECT_TRUE(facial::loadTimeline(file).ok());
  EXPECT_TRUE(editor::TimelineDocument::load(file).ok());
}

TEST(NewerFormat, GraphRefusesVersion3) {
  const fs::path file = write("newer_graph", "g.json",
                              R"({"version": 3, "channels": ["a"], "root": {"type": "pose", "weights": [1]}})");
  auto graph = facial::loadGraph(file);
  ASSERT_FALSE(graph.ok());
  expectNewerRefused(graph.error().message, file, "3");
}

TEST(NewerFormat, RigMapRefusesVersion2) {
  const fs::path file = write("newer_rigmap", "face.json", R"({"version": 2, "map": {}})");
  const std::vector<std::string> targets = {"jawOpen"};
  auto rig = facial::loadRigMapFile(file, targets);
  ASSERT_FALSE(rig.ok());
  expectNewerRefused(rig.error().message, file, "2");
}

TEST(NewerFormat, ExpressionPresetsRefuseVersion2) {
  const fs::path file = write("newer_presets", "expressions.json", R"({"version": 2, "expressions": {}})");
  auto library = facial::ExpressionLibrary::load(file);
  ASSERT_FALSE(library.ok());
  expectNewerRefused(library.error().message, file, "2");
}

TEST(NewerFormat, OlderOrMalformedVersionsSaySo) {
  const fs::path file = write("odd_timeline", "clip.json", timelineText("\"1\""));
  auto timeline = facial::loadTimeline(file);
  ASSERT_FALSE(timeline.ok());
  EXPECT_NE(timeline.error().message.find("unsupported version \"1\" (this build reads version 1)"), std::string::npos)
      << timeline.error().message;
}

const char* kTriangle =
    R"({"asset": {%s}, "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
        "bufferViews": [{"buffer": 0, "byteLength": 36}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}], "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})";

std::string triangle(const char* asset) {
  char text[1024];
  std::snprintf(text, sizeof text, kTriangle, asset);
  return text;
}

TEST(NewerFormat, GltfAssetVersions) {
  const fs::path ok = write("gltf_2_0", "face.gltf", triangle(R"("version": "2.0")"));
  auto loaded = eng::loadModel(ok);
  ASSERT_TRUE(loaded.ok()) << loaded.error().message;
  // A later 2.x minor version is compatible by the glTF rules.
  EXPECT_TRUE(eng::loadModel(write("gltf_2_1", "face.gltf", triangle(R"("version": "2.1")"))).ok());

  const fs::path major = write("gltf_3_0", "face.gltf", triangle(R"("version": "3.0")"));
  auto refused = eng::loadModel(major);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message,
            major.string() + ": glTF version 3.0 is not supported (this loader reads glTF 2.x)");

  const fs::path minVersion = write("gltf_min_2_1", "face.gltf", triangle(R"("version": "2.1", "minVersion": "2.1")"));
  refused = eng::loadModel(minVersion);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().message, minVersion.string() +
                                         ": the file needs glTF 2.1 (asset.minVersion), newer than the 2.0 this loader reads");
}

}  // namespace
