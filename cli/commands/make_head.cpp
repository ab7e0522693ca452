// `facial make-head [--out data/head.glb] [--landmarks data/head_landmarks.json]`
// Regenerates the built-in head: procedural skin, eyes, teeth, ears and
// textures, with one morph target per FACS action unit baked from the
// landmark file by RBF deformation. Deterministic: same input, same file.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "cli/command.h"
#include "engine/scene/gltf_writer.h"
#include "bake/head/head_generator.h"
#include "bake/head/head_rig_spec.h"
#include "app/program_error.h"
#include "app/output_paths.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::make_head_command {
namespace {

struct MakeHeadOptions {
  std::string out = "data/head.glb";
  std::string landmarks;
};

constexpr app::ErrorReporter fail{"facial make-head"};

// The landmark file beside the sources, unless the working directory has one.
std::filesystem::path defaultLandmarks() {
  const std::filesystem::path local = "data/head_landmarks.json";
  if (std::filesystem::exists(local)) return local;
  return std::filesystem::path(FACIAL_SOURCE_DIR) / "data" / "head_landmarks.json";
}

int runMakeHead(const MakeHeadOptions& o) {
  const std::filesystem::path landmarks = o.landmarks.empty() ? defaultLandmarks() : std::filesystem::path(o.landmarks);
  if (auto safe = app::checkOutputs({.inputs = {{"--landmarks", landmarks.native()}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  eng::Result<bake::HeadRigSpec> spec = bake::loadHeadRigSpec(landmarks);
  if (!spec) return fail(spec.error().message);
  eng::Result<bake::GeneratedHead> head = bake::generateHead(*spec);
  if (!head) return fail(head.error().message);
  if (auto saved = eng::saveModel(head->model, o.out); !saved) return fail(saved.error().message);
  size_t vertices = 0, triangles = 0;
  for (const eng::Mesh& mesh : head->model.meshes)
    for (const eng::Primitive& p : mesh.primitives) {
      vertices += p.vertexCount();
      triangles += p.indices.size() / 3;
    }
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(o.out, ec);
  std::printf("wrote %s: %zu vertices, %zu triangles, %zu action-unit targets, %zu landmarks, %.2f MiB\n",
              o.out.c_str(), vertices, triangles, head->model.meshes[0].targetNames.size(),
              head->landmarks.names.size(), ec ? 0.0 : double(bytes) / (1024.0 * 1024.0));
  return 0;
}

CommandRegistrar reg("make-head", "Regenerate the built-in head (data/head.glb) from data/head_landmarks.json",
                     [](CLI::App& app) {
                       auto o = std::make_shared<MakeHeadOptions>();
                       app.add_option("--out,-o", o->out, "Output glTF file (.glb or .gltf)")->capture_default_str();
                       app.add_option("--landmarks", o->landmarks,
                                      "Landmark and action-unit file (default: data/head_landmarks.json)");
                       return [o] { return runMakeHead(*o); };
                     });

}  // namespace
}  // namespace cli::make_head_command
