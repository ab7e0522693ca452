#pragma once
// The renderer's shader programs: SPIR-V compiled at build time from
// engine/shaders and embedded in the binary, plus hot reload for window mode
// (poll the sources' modification times, recompile with glslang, keep the
// previous code when anything fails to compile).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"
#include "engine/vk/device/context.h"
#include "engine/vk/device/unique_handle.h"

namespace eng::vk {

// One build-time program (see ENG_SHADER_VARIANTS in engine/vk/CMakeLists.txt).
struct EmbeddedShader {
  const char* name;     // e.g. "mesh_vert"
  const char* file;     // source file in the shader directory, e.g. "mesh.vert"
  const char* defines;  // comma-separated, e.g. "MORPH_CAPTURE"
  const uint32_t* spirv;
  size_t wordCount;
};

// The embedded table, in build order.
std::span<const EmbeddedShader> embeddedShaders();
// engine/shaders of the source tree this binary was built from.
std::filesystem::path defaultShaderSourceDir();

class ShaderLibrary {
 public:
  explicit ShaderLibrary(std::filesystem::path sourceDir = defaultShaderSourceDir());

  // Current SPIR-V of program `name`; empty span for an unknown name.
  std::span<const uint32_t> spirv(std::string_view name) const;
  // Bumped whenever new SPIR-V is installed.
  uint64_t generation() const { return generation_; }
  const std::filesystem::path& sourceDir() const { return sourceDir_; }

  // Polls the sources (*.vert, *.frag, *.comp, *.glsl) in sourceDir; when any changed
  // since the last poll, recompiles every program. Returns true when new
  // SPIR-V was installed. A compile error is logged with glslang's text and
  // the previous SPIR-V stays (returns false). No source dir: returns false.
  bool reloadIfChanged();
  // Recompiles every program from sourceDir now; on error nothing changes.
  Result<void> recompileAll();

 private:
  using Snapshot = std::map<std::filesystem::path, std::filesystem::file_time_type>;
  Snapshot snapshotSources() const;

  std::filesystem::path sourceDir_;
  std::vector<std::vector<uint32_t>> overrides_;  // per embedded program; empty = embedded code
  Snapshot lastSeen_;
  uint64_t generation_ = 0;
};

// A shader module of program `name`'s current SPIR-V (NotFound for an unknown name).
Result<UniqueShaderModule> createShaderModule(const Context& ctx, const ShaderLibrary& shaders, const char* name);

}  // namespace eng::vk
