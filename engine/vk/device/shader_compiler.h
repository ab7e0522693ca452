#pragma once
// Run-time GLSL -> SPIR-V with the glslang library, with the same settings
// as the build-time glslangValidator step (Vulkan 1.1, #include support), so
// hot-reloaded shaders behave exactly like embedded ones.
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace eng::vk {

enum class ShaderStage { Vertex, Fragment, Compute };

// Stage from the extension: .vert / .frag.
Result<ShaderStage> shaderStageFromPath(const std::filesystem::path& file);

// `defines`: comma-separated NAME or NAME=VALUE. #include "x" resolves
// relative to `includeDir`. Errors carry glslang's log, prefixed with the name.
Result<std::vector<uint32_t>> compileGlsl(std::string_view source, std::string_view displayName, ShaderStage stage,
                                          std::string_view defines, const std::filesystem::path& includeDir);

// Reads `file` and compiles it (includes resolve next to the file).
Result<std::vector<uint32_t>> compileGlslFile(const std::filesystem::path& file, std::string_view defines);

}  // namespace eng::vk
