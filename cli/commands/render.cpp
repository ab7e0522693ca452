// `facial render MODEL [--weight NAME=VALUE]... [--size WxH] [--yaw DEG]
//  [--pitch DEG] [--zoom F] [--device D] --out FILE.png`
// Renders one frame headless (lavapipe or a GPU) with the model's default
// weights, overridden by --weight, and writes a PNG.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/view_options.h"
#include "app/program_error.h"
#include "app/output_paths.h"
#include "facial/runtime/graph/weight_range.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "engine/scene/weights.h"
#include "importers/load_face.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::render_command {
namespace {

struct RenderOptions {
  std::string model;
  std::vector<std::string> weights;
  std::vector<std::string> shapes;
  app::ViewOptions view;
  std::string out;
};

constexpr app::ErrorReporter fail{"facial render"};


std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// A few names to suggest: those containing the unknown name first, then the first ones.
std::string suggestNames(const std::vector<std::string>& names, const std::string& unknown) {
  std::vector<std::string> picks;
  for (const std::string& n : names) {
    if (picks.size() < 8 && lower(n).find(lower(unknown)) != std::string::npos) picks.push_back(n);
  }
  for (const std::string& n : names) {
    if (picks.size() >= 8) break;
    if (std::find(picks.begin(), picks.end(), n) == picks.end()) picks.push_back(n);
  }
  std::string text;
  for (const std::string& n : picks) text += (text.empty() ? "" : ", ") + n;
  return text + (names.size() > picks.size() ? ", ... (" + std::to_string(names.size()) + " in all)" : "");
}

int runRender(const RenderOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"model", o.model}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  auto renderOptions = app::headlessRenderOptions(o.view);
  if (!renderOptions) return fail(renderOptions.error().message);

  // The device opens while the face loads.
  auto opening = app::SequenceRenderers::open(*renderOptions, /*lanes=*/1);
  auto face = importers::loadFace(o.model, {.shapes = o.shapes, .dressForDisplay = true});
  if (!face) return fail(face.error().message);
  const eng::Model* model = &face->model;
  const eng::WeightLayout layout(*model);
  std::vector<float> weights = layout.defaults();
  for (const std::string& assignment : o.weights) {
    const eng::Result<facial::NamedWeight> parsed = facial::parseNamedWeight(assignment, "--weight");
    if (!parsed) return fail(parsed.error().message);
    const std::string& name = parsed->name;
    const eng::Result<int> matched = layout.setByName(weights, name, parsed->value);
    if (!matched) return fail(matched.error().message);
    if (*matched == 0) {
      const std::vector<std::string> names = layout.names();
      if (names.empty()) return fail(o.model + ": has no morph targets, cannot set weight '" + name + "'");
      return fail(o.model + ": no morph target named '" + name + "'; available: " + suggestNames(names, name));
    }
  }

  auto renderer = opening.finish(face->displayModel());
  if (!renderer) return fail(renderer.error().message);
  auto image = renderer->render(weights);
  if (!image) return fail(image.error().message);
  if (auto written = eng::writePng(o.out, image->width, image->height, image->rgba8); !written)
    return fail(written.error().message);
  if (auto clean = renderer->checkValidation(); !clean) return fail(clean.error().message);
  std::printf("wrote %s (%ux%u, %s)\n", o.out.c_str(), renderOptions->width, renderOptions->height,
              renderer->deviceName().c_str());
  return 0;
}

CommandRegistrar reg("render", "Render a model to a PNG, headless", [](CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  app.add_option("model", o->model, importers::kFaceFormatsHelp)->required();
  app.add_option("--weight,-w", o->weights, "Morph weight override NAME=VALUE (repeatable; all meshes with that target)");
  app::addShapeOption(app, o->shapes);
  app::addViewOptions(app, o->view);
  app.add_option("--out,-o", o->out, "Output PNG file")->required();
  return [o] { return runRender(*o); };
});

}  // namespace
}  // namespace cli::render_command
