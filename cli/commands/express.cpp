// `facial express EXPRESSION [--intensity X] [--model M] [--rigmap R] [--size WxH]
//  [--yaw DEG] [--pitch DEG] [--zoom F] [--device D] --out F.png`
// Poses a model with one expression preset through its rig mapping (the
// model's default weights are the base, the targets the rig drives are
// overwritten) and renders it headless to a PNG.
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/command.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/view_options.h"
#include "app/program_error.h"
#include "app/output_paths.h"
#include "engine/scene/image_io.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::express_command {
namespace {

struct ExpressOptions {
  std::string expression;
  float intensity = 1.0f;
  std::string model;
  std::string rigmap;
  bool noAutorig = false;
  std::vector<std::string> shapes;
  app::ViewOptions view;
  std::string out;
};

constexpr app::ErrorReporter fail{"facial express"};

int runExpress(const ExpressOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"--model", o.model}, {"--rigmap", o.rigmap}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  auto renderOptions = app::headlessRenderOptions(o.view);
  if (!renderOptions) return fail(renderOptions.error().message);
  if (std::isnan(o.intensity)) return fail("--intensity must be a number in [0, 1], got nan");
  if (!std::isfinite(o.intensity)) return fail("--intensity must be a finite number in [0, 1]");
  if (o.intensity < 0.0f || o.intensity > 1.0f)
    std::fprintf(stderr, "facial express: note: intensity %g clamped to [0, 1]\n", o.intensity);

  // The device opens while the face loads.
  auto opening = app::SequenceRenderers::open(*renderOptions, /*lanes=*/1);
  auto face = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial express"});
  if (!face) return fail(face.error().message);
  auto preset = face->findExpression(o.expression);
  if (!preset) return fail(preset.error().message);
  std::vector<float> weights(face->weightCount()), vrmExpressions(face->vrmExpressionCount());
  if (auto posed = face->expressionWeights(**preset, o.intensity, weights, vrmExpressions); !posed)
    return fail(posed.error().message);
  // VRM material binds (colour, texture transform) belong to the pose.
  auto materials = app::FaceMaterials::create(*face);
  if (!materials) return fail(materials.error().message);
  if (auto moved = materials->update(vrmExpressions); !moved) return fail(moved.error().message);

  auto renderer = opening.finish(face->displayModel());
  if (!renderer) return fail(renderer.error().message);
  auto image = renderer->render(weights, materials->materials());
  if (!image) return fail(image.error().message);
  if (auto written = eng::writePng(o.out, image->width, image->height, image->rgba8); !written)
    return fail(written.error().message);
  if (auto clean = renderer->checkValidation(); !clean) return fail(clean.error().message);
  std::printf("wrote %s (%s '%s' at %g, %ux%u, %s)\n", o.out.c_str(), face->name().c_str(), o.expression.c_str(),
              std::fmin(std::fmax(o.intensity, 0.0f), 1.0f), renderOptions->width, renderOptions->height,
              renderer->deviceName().c_str());
  return 0;
}

CommandRegistrar reg("express", "Render a model posed with an expression preset, headless", [](CLI::App& app) {
  auto o = std::make_shared<ExpressOptions>();
  app.add_option("expression", o->expression, "Preset name from data/expressions.json (happy, sad, ...)")->required();
  app.add_option("--intensity,-i", o->intensity, "Preset strength, clamped to [0, 1]")
      ->check(CLI::Number)
      ->capture_default_str();
  app::addFaceOptions(app, o->model, o->rigmap, o->noAutorig);
  app::addShapeOption(app, o->shapes);
  app::addViewOptions(app, o->view);
  app.add_option("--out,-o", o->out, "Output PNG file")->required();
  return [o] { return runExpress(*o); };
});

}  // namespace
}  // namespace cli::express_command
