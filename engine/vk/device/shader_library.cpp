#include "engine/vk/device/shader_library.h"

#include <system_error>

#include "engine/core/log.h"
#include "engine/vk/device/shader_compiler.h"
#include "engine/vk/device/vk_result.h"

// Generated: the #includes of the SPIR-V headers and kEmbeddedShaders[].
#include "engine/vk/shader_manifest.inc"

namespace eng::vk {

std::span<const EmbeddedShader> embeddedShaders() { return generated::kEmbeddedShaders; }

std::filesystem::path defaultShaderSourceDir() { return ENG_SHADER_SOURCE_DIR; }

ShaderLibrary::ShaderLibrary(std::filesystem::path sourceDir)
    : sourceDir_(std::move(sourceDir)), overrides_(embeddedShaders().size()), lastSeen_(snapshotSources()) {}

std::span<const uint32_t> ShaderLibrary::spirv(std::string_view name) const {
  std::span<const EmbeddedShader> table = embeddedShaders();
  for (size_t i = 0; i < table.size(); ++i) {
    if (name != table[i].name) continue;
    if (!overrides_[i].empty()) return overrides_[i];
    return {table[i].spirv, table[i].wordCount};
  }
  return {};
}

ShaderLibrary::Snapshot ShaderLibrary::snapshotSources() const {
  Snapshot snapshot;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(sourceDir_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::filesystem::path& p = it->path();
    std::string ext = p.extension().string();
    if (ext != ".vert" && ext != ".frag" && ext != ".comp" && ext != ".glsl") continue;
    std::error_code timeError;
    auto time = std::filesystem::last_write_time(p, timeError);
    if (!timeError) snapshot[p] = time;
  }
  return snapshot;
}

bool ShaderLibrary::reloadIfChanged() {
  Snapshot now = snapshotSources();
  if (now.empty() || now == lastSeen_) return false;
  lastSeen_ = std::move(now);
  if (auto r = recompileAll(); !r) {
    logError("shader hot reload: keeping the previous shaders: " + r.error().message);
    return false;
  }
  logInfo("shader hot reload: recompiled " + std::to_string(overrides_.size()) + " programs from " +
          sourceDir_.string());
  return true;
}

Result<void> ShaderLibrary::recompileAll() {
  std::span<const EmbeddedShader> table = embeddedShaders();
  std::vector<std::vector<uint32_t>> compiled;
  compiled.reserve(table.size());
  for (const EmbeddedShader& shader : table) {
    auto spirv = compileGlslFile(sourceDir_ / shader.file, shader.defines);
    if (!spirv) return spirv.error();
    compiled.push_back(std::move(spirv).value());
  }
  overrides_ = std::move(compiled);
  ++generation_;
  return {};
}

Result<UniqueShaderModule> createShaderModule(const Context& ctx, const ShaderLibrary& shaders, const char* name) {
  std::span<const uint32_t> code = shaders.spirv(name);
  if (code.empty()) return makeError(ErrorKind::NotFound, std::string("shader program '") + name + "' is not in the shader library");
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  ENG_VK_TRY(vkCreateShaderModule(ctx.device(), &info, nullptr, &module));
  return UniqueShaderModule(ctx.device(), module);
}

}  // namespace eng::vk
