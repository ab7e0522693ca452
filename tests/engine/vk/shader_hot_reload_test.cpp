// Run-time shader compilation and hot reload: a changed source is
// recompiled and the pipelines rebuilt; a broken source logs glslang's
// message and the previous shaders keep drawing.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "engine/core/log.h"
#include "engine/vk/device/shader_compiler.h"
#include "engine/vk/device/shader_library.h"
#include "tests/common/test_support.h"
#include "tests/engine/vk/image_probe.h"
#include "tests/common/test_meshes.h"
#include "tests/engine/vk/vk_test_context.h"

namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rewrites a file and moves its mtime forward, so a poll sees the change even
// within the file system's timestamp granularity.
void rewrite(const fs::path& p, const std::string& text) {
  const auto before = fs::last_write_time(p);
  testing_support::writeFile(p, text);
  fs::last_write_time(p, before + std::chrono::seconds(2));
}

fs::path copyShaders(const std::string& name) {
  const fs::path dir = testing_support::freshTempDir(name);
  for (const auto& entry : fs::directory_iterator(eng::vk::defaultShaderSourceDir()))
    fs::copy_file(entry.path(), dir / entry.path().filename());
  return dir;
}

TEST(ShaderCompiler, CompilesEveryEmbeddedProgramLikeTheBuild) {
  for (const eng::vk::EmbeddedShader& shader : eng::vk::embeddedShaders()) {
    auto spirv = eng::vk::compileGlslFile(eng::vk::defaultShaderSourceDir() / shader.file, shader.defines);
    ASSERT_TRUE(spirv) << spirv.error().message;
    ASSERT_GT(spirv->size(), 5u);
    EXPECT_EQ((*spirv)[0], 0x07230203u) << "SPIR-V magic";
    EXPECT_EQ(spirv->size(), shader.wordCount) << shader.name << ": same glslang, same options, same code";
  }
}

TEST(ShaderCompilerValidity, ErrorsCarryGlslangTextAndTheFileName) {
  auto spirv = eng::vk::compileGlsl("#version 450\nvoid main() { undefinedThing = 1.0; }\n", "broken.frag",
                                    eng::vk::ShaderStage::Fragment, "", ".");
  ASSERT_FALSE(spirv);
  EXPECT_NE(spirv.error().message.find("broken.frag"), std::string::npos) << spirv.error().message;
  EXPECT_NE(spirv.error().message.find("undefinedThing"), std::string::npos) << spirv.error().message;
  auto stage = eng::vk::shaderStageFromPath("shader.geom");
  ASSERT_FALSE(stage);
  auto missing = eng::vk::compileGlslFile("/nonexistent/dir/x.vert", "");
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("/nonexistent/dir/x.vert"), std::string::npos);
}

TEST(ShaderLibrary, UnchangedSourcesDoNotRecompile) {
  eng::vk::ShaderLibrary library(copyShaders("hot_reload_unchanged"));
  EXPECT_FALSE(library.reloadIfChanged());
  EXPECT_EQ(library.generation(), 0u);
  EXPECT_FALSE(library.spirv("mesh_frag").empty());
  EXPECT_TRUE(library.spirv("no_such_program").empty());
}

TEST(ShaderHotReload, ChangedShaderIsUsedAndBrokenShaderKeepsThePrevious) {
  const fs::path dir = copyShaders("hot_reload_renderer");
  eng::vk::OffscreenOptions options;
  options.width = options.height = 64;
  options.shaderSourceDir = dir;
  auto renderer = eng::vk::OffscreenRenderer::create(vk_test::context(), options);
  ASSERT_TRUE(renderer) << renderer.error().message;
  const eng::Model model = testing_support::makeSphereModel({});
  auto gpu = renderer->upload(model);
  ASSERT_TRUE(gpu) << gpu.error().message;
  const std::vector<float> weights(gpu->weightCount(), 0.0f);
  const eng::vk::ModelInstance instance{&*gpu, glm::mat4(1.0f), weights};
  const eng::vk::SceneView view{eng::OrbitCamera::frame(model.bounds()), {}};
  auto centre = [&] {
    auto image = renderer->render(view, {&instance, 1});
    EXPECT_TRUE(image) << (image ? "" : image.error().message);
    return image ? vk_test::pixel(*image, 32, 32) : glm::ivec4(-1);
  };
  const glm::ivec4 before = centre();
  ASSERT_NE(before, glm::ivec4(0, 255, 0, 255));

  // Edit: main() of the fragment shader now ends by writing pure green.
  const fs::path frag = dir / "mesh.frag";
  std::string source = readText(frag);
  const size_t end = source.rfind('}');
  ASSERT_NE(end, std::string::npos);
  source.insert(end, "  outColor = vec4(0.0, 1.0, 0.0, 1.0);\n");
  rewrite(frag, source);
  EXPECT_TRUE(renderer->reloadChangedShaders());
  EXPECT_EQ(centre(), glm::ivec4(0, 255, 0, 255));

  // Break it: logged with glslang's message, the green pipeline stays.
  std::vector<std::string> errors;
  const eng::LogSink previous = eng::setLogSink([&](eng::LogLevel level, std::string_view m) {
    if (level == eng::LogLevel::Error) errors.emplace_back(m);
  });
  rewrite(frag, source + "\nthis is not GLSL;\n");
  const bool reloaded = renderer->reloadChangedShaders();
  eng::setLogSink(previous);
  EXPECT_FALSE(reloaded);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors[0].find("mesh.frag"), std::string::npos) << errors[0];
  EXPECT_NE(errors[0].find("ERROR"), std::string::npos) << errors[0];
  EXPECT_EQ(centre(), glm::ivec4(0, 255, 0, 255)) << "previous pipeline kept";
}

}  // namespace
