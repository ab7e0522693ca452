// `facial convert`: OBJ keyframe sets (neutral.obj + one OBJ per
// expression) to one glTF face with morph targets; also re-saves glTF
// (e.g. .gltf -> .glb) and writes an FBX, PLY or STL face as glTF.
//   facial convert neutral.obj --target happy=happy.obj --target sad.obj --out face.glb
//   facial convert DIR --out face.glb            (DIR/neutral.obj + every other DIR/*.obj)
//   facial convert character.fbx --out character.glb
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "app/output_paths.h"
#include "app/program_error.h"
#include "importers/load_face.h"
#include "importers/obj_keyframes.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::convert_command {
namespace {

struct ConvertArgs {
  std::string input;
  std::vector<std::string> targets;
  std::string out;
  bool matchByPosition = false;
  float tolerance = 1e-5f;
};

std::string lowerExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

constexpr app::ErrorReporter fail{"facial convert"};

int save(const eng::Model& model, const std::string& out) {
  auto saved = eng::saveModel(model, out);
  if (!saved) return fail(saved.error().message);
  for (const std::string& w : model.warnings) app::printWarning("facial convert", w);
  std::printf("wrote %s: %zu vertices, %zu morph target(s)\n", out.c_str(), model.totalVertexCount(),
              model.meshes.empty() ? size_t{0} : model.meshes[0].targetNames.size());
  return 0;
}

int run(const ConvertArgs& args) {
  app::CommandFiles files{.inputs = {{"input", args.input}}, .outputs = {{"--out", args.out}}};
  for (const std::string& spec : args.targets)  // [NAME=]FILE: npos + 1 is 0
    files.inputs.push_back({"--target", std::string_view(spec).substr(spec.find('=') + 1)});
  if (auto safe = app::checkOutputs(files); !safe) return fail(safe.error().message);
  const std::filesystem::path input(args.input);
  const std::string ext = lowerExtension(input);
  if (ext == ".gltf" || ext == ".glb") {
    if (!args.targets.empty()) return fail("--target applies to OBJ input only");
    auto model = eng::loadModel(input);
    if (!model) return fail(model.error().message);
    return save(*model, args.out);
  }

  if (ext == ".fbx" || ext == ".ply" || ext == ".stl") {
    if (!args.targets.empty()) return fail("--target applies to OBJ input only");
    auto face = importers::loadFace(input);
    if (!face) return fail(face.error().message);
    return save(face->model, args.out);
  }
  std::filesystem::path neutral;
  std::vector<importers::ObjTargetFile> targets;
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec)) {
    if (!args.targets.empty()) return fail("--target cannot be combined with a folder (its *.obj files are the targets)");
    auto folder = importers::findObjKeyframeFolder(input);
    if (!folder) return fail(folder.error().message);
    neutral = folder->neutral;
    targets = std::move(folder->targets);
  } else {
    if (ext != ".obj") return fail(args.input + ": expected a .obj, a .gltf/.glb, an .fbx, a .ply, an .stl or a folder");
    neutral = input;
    for (const std::string& spec : args.targets) {
      const size_t eq = spec.find('=');
      importers::ObjTargetFile t;
      t.path = eq == std::string::npos ? spec : spec.substr(eq + 1);
      t.name = eq == std::string::npos ? t.path.stem().string() : spec.substr(0, eq);
      targets.push_back(std::move(t));
    }
  }
  if (targets.empty()) std::fprintf(stderr, "facial convert: warning: no targets; writing the neutral mesh only\n");

  importers::ObjKeyframeOptions options;
  options.matchByPosition = args.matchByPosition;
  options.relativeTolerance = args.tolerance;
  auto imported = importers::importObjKeyframes(neutral, targets, options);
  if (!imported) return fail(imported.error().message);
  for (const importers::ObjTargetReport& r : imported->targets) {
    std::printf("target %-20s %zu vertices moved", r.name.c_str(), r.movedVertices);
    if (args.matchByPosition) std::printf(", %zu unmatched", r.unmatchedVertices);
    std::printf("\n");
    if (r.unmatchedVertices > 0)
      std::fprintf(stderr, "facial convert: warning: target '%s': %zu neutral vertices found no partner (kept at rest)\n",
                   r.name.c_str(), r.unmatchedVertices);
  }
  return save(imported->model, args.out);
}

CommandRegistrar reg("convert", "Convert an OBJ keyframe set, an FBX, a PLY or STL scan or a glTF to a glTF face with morph targets",
                     [](CLI::App& app) {
                       auto args = std::make_shared<ConvertArgs>();
                       app.add_option("input", args->input, "neutral.obj, a folder holding neutral.obj + targets, a .gltf/.glb, an .fbx, a .ply or an .stl")
                           ->required();
                       app.add_option("--target", args->targets, "NAME=FILE.obj (or FILE.obj, named after the file); repeatable");
                       app.add_option("--out", args->out, "Output .glb or .gltf")->required();
                       app.add_flag("--match-by-position", args->matchByPosition,
                                    "Pair re-ordered vertices by position instead of requiring the neutral's order");
                       app.add_option("--tolerance", args->tolerance,
                                      "Coincidence distance for --match-by-position, fraction of the bounding-box diagonal (at most 0.01)")
                           ->check(CLI::PositiveNumber);
                       return [args]() -> int { return run(*args); };
                     });

}  // namespace
}  // namespace cli::convert_command
