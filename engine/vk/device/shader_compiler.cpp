#include "engine/vk/device/shader_compiler.h"

#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

namespace eng::vk {
namespace {

void initialiseGlslangOnce() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

std::optional<std::string> readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// #include "name" -> includeDir/name. Owns the text until glslang releases it.
class DirectoryIncluder : public glslang::TShader::Includer {
 public:
  explicit DirectoryIncluder(std::filesystem::path dir) : dir_(std::move(dir)) {}

  IncludeResult* includeLocal(const char* headerName, const char*, size_t) override {
    std::filesystem::path path = dir_ / headerName;
    auto text = readText(path);
    if (!text) return nullptr;  // glslang reports "cannot find include file"
    auto* owned = new std::string(std::move(*text));
    return new IncludeResult(path.string(), owned->data(), owned->size(), owned);
  }
  IncludeResult* includeSystem(const char* headerName, const char* includerName, size_t depth) override {
    return includeLocal(headerName, includerName, depth);
  }
  void releaseInclude(IncludeResult* result) override {
    if (!result) return;
    delete static_cast<std::string*>(result->userData);
    delete result;
  }

 private:
  std::filesystem::path dir_;
};

std::string preambleFor(std::string_view defines) {
  std::string preamble;
  size_t start = 0;
  while (start <= defines.size()) {
    size_t end = defines.find(',', start);
    if (end == std::string_view::npos) end = defines.size();
    std::string_view item = defines.substr(start, end - start);
    if (!item.empty()) {
      std::string define(item);
      size_t eq = define.find('=');
      if (eq != std::string::npos) define[eq] = ' ';
      preamble += "#define " + define + "\n";
    }
    start = end + 1;
  }
  return preamble;
}

}  // namespace

Result<ShaderStage> shaderStageFromPath(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  if (ext == ".vert") return ShaderStage::Vertex;
  if (ext == ".frag") return ShaderStage::Fragment;
  if (ext == ".comp") return ShaderStage::Compute;
  return makeError(ErrorKind::Unsupported, file.string() + ": unknown shader stage (expected .vert, .frag or .comp)");
}

Result<std::vector<uint32_t>> compileGlsl(std::string_view source, std::string_view displayName, ShaderStage stage,
                                          std::string_view defines, const std::filesystem::path& includeDir) {
  initialiseGlslangOnce();
  const EShLanguage language = stage == ShaderStage::Vertex     ? EShLangVertex
                               : stage == ShaderStage::Fragment ? EShLangFragment
                                                                : EShLangCompute;
  glslang::TShader shader(language);
  const char* text = source.data();
  const int length = static_cast<int>(source.size());
  std::string name(displayName);
  const char* names = name.c_str();
  shader.setStringsWithLengthsAndNames(&text, &length, &names, 1);
  std::string preamble = preambleFor(defines);
  shader.setPreamble(preamble.c_str());
  shader.setEnvInput(glslang::EShSourceGlsl, language, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_1);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_3);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  DirectoryIncluder includer(includeDir);
  if (!shader.parse(GetDefaultResources(), 100, false, messages, includer))
    return makeError(ErrorKind::Malformed, name + ": compile failed:\n" + shader.getInfoLog());

  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) return makeError(ErrorKind::Malformed, name + ": link failed:\n" + program.getInfoLog());

  std::vector<uint32_t> spirv;
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  glslang::GlslangToSpv(*program.getIntermediate(language), spirv, &logger, &options);
  if (spirv.empty()) return makeError(ErrorKind::Malformed, name + ": SPIR-V generation failed: " + logger.getAllMessages());
  return spirv;
}

Result<std::vector<uint32_t>> compileGlslFile(const std::filesystem::path& file, std::string_view defines) {
  auto stage = shaderStageFromPath(file);
  if (!stage) return stage.error();
  auto text = readText(file);
  if (!text) return makeError(ErrorKind::Io, file.string() + ": cannot read shader source");
  return compileGlsl(*text, file.string(), stage.value(), defines, file.parent_path());
}

}  // namespace eng::vk
