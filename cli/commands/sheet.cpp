// `facial sheet [--model M] [--compound] [--size N] [--intensity X]
//  [--zoom F] [--device D] --out sheet.png`
// A labelled contact sheet of a model posed with the basic states (neutral
// and the six basic emotions) or, with --compound, the compound presets.
// Every tile comes from ONE headless renderer (one Vulkan context, one
// upload) and one fixed camera, so tiles compare like for like.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "engine/view/face_framing.h"
#include "cli/command.h"
#include "app/view_options.h"
#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/sequence_renderers.h"
#include "app/program_error.h"
#include "app/output_paths.h"
#include "engine/image/contact_sheet.h"
#include "engine/image/text.h"
#include "engine/scene/image_io.h"
#include "facial/runtime/rig/emotions.h"

// Each command in a namespace of its own: the commands are compiled several
// to a unit (demo/CMakeLists.txt), where their file-local names would clash.
namespace cli::sheet_command {
namespace {

struct SheetOptions {
  std::string model;
  std::string rigmap;
  bool noAutorig = false;
  std::vector<std::string> shapes;
  std::string background;
  bool compound = false;
  uint32_t size = 256;
  float intensity = 1.0f;
  // Why closer than `render`: the camera frames the model with every target
  // at full weight (neck and hair included); expressions read in the face.
  float zoom = eng::kSheetTileZoom;
  bool zoomGiven = false;  // an explicit --zoom is taken as it is
  std::string frame = "face";
  std::string device;
  std::string quality = "high";
  std::string out;
};

constexpr app::ErrorReporter fail{"facial sheet"};

// "happily_surprised" -> "happily surprised"
std::string labelOf(const std::string& presetName) {
  std::string label = presetName;
  std::replace(label.begin(), label.end(), '_', ' ');
  return label;
}

// The largest label size (at most a tenth of the tile, 12..28 px) at which
// every label fits its tile's width.
float labelHeightFor(const eng::TextRenderer& text, const std::vector<eng::ContactSheetTile>& tiles, int tileWidth) {
  float height = std::clamp(float(tileWidth) / 10.0f, 12.0f, 28.0f);
  for (const eng::ContactSheetTile& tile : tiles)
    while (height > 8.0f && text.measure(tile.label, height) > tileWidth - 4) height -= 1.0f;
  return height;
}

int runSheet(const SheetOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"--model", o.model}, {"--rigmap", o.rigmap}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  if (!std::isfinite(o.intensity)) return fail("--intensity must be a finite number in [0, 1]");
  if (o.intensity < 0.0f || o.intensity > 1.0f)
    std::fprintf(stderr, "facial sheet: note: intensity %g clamped to [0, 1]\n", o.intensity);
  auto framing = app::framingModeOption(o.frame);
  if (!framing) return fail(framing.error().message);
  auto backdrop = app::parseBackground(o.background);
  if (!backdrop) return fail(backdrop.error().message);
  auto quality = app::qualityOption(o.quality);
  if (!quality) return fail(quality.error().message);
  // The device opens while the face loads; the tiles go through it in flight,
  // one read back while the next ones draw. One device: a second one's start
  // cost more than it saved over 7 to 13 tiles (lavapipe, 2 cores: 1.98-2.27 s
  // with one, 2.10-2.32 with two).
  auto opening = app::SequenceRenderers::open({.width = o.size,
                                               .height = o.size,
                                               .framing = *framing,
                                               .device = o.device,
                                               .backdrop = *backdrop,
                                               .quality = *quality,
                                               .framesInFlight = app::kSequenceFramesInFlight},
                                              /*lanes=*/1);
  auto face = app::FaceSetup::load({.model = o.model, .rigmap = o.rigmap, .shapes = o.shapes, .autorig = !o.noAutorig, .program = "facial sheet"});
  if (!face) return fail(face.error().message);
  // Basic: exactly the emotion channels, in their order (neutral first).
  std::vector<const facial::ExpressionPreset*> presets;
  if (o.compound) {
    presets = face->presets(true);
    if (presets.empty()) return fail("the expression presets hold no compound expressions");
  } else {
    for (std::string_view emotion : facial::emotionNames()) {
      auto preset = face->findExpression(emotion);
      if (!preset) return fail(preset.error().message);
      presets.push_back(*preset);
    }
  }

  auto renderers = opening.finish(face->displayModel());
  if (!renderers) return fail(renderers.error().message);
  renderers->view().camera.zoom = o.zoomGiven ? o.zoom : faceViewZoom(face->model(), *framing, o.zoom, 1.0f);
  std::vector<float> weights(face->weightCount()), vrmExpressions(face->vrmExpressionCount());
  auto materials = app::FaceMaterials::create(*face);  // VRM material binds follow each tile's expression
  if (!materials) return fail(materials.error().message);
  std::vector<eng::ContactSheetTile> tiles;
  const auto collectTile = [&]() -> eng::Result<void> {
    auto image = renderers->collect();
    if (!image) return image.error();
    eng::ContactSheetTile& tile = tiles.emplace_back();
    tile.image.width = image->width;
    tile.image.height = image->height;
    tile.image.rgba = std::move(image->rgba8);
    tile.label = labelOf(presets[tiles.size() - 1]->name);
    return {};
  };
  for (const facial::ExpressionPreset* preset : presets) {
    if (auto posed = face->expressionWeights(*preset, o.intensity, weights, vrmExpressions); !posed)
      return fail(posed.error().message);
    if (auto moved = materials->update(vrmExpressions); !moved) return fail(moved.error().message);
    if (renderers->full())
      if (auto collected = collectTile(); !collected) return fail(collected.error().message);
    if (auto submitted = renderers->submit(weights, materials->materials()); !submitted)
      return fail(submitted.error().message);
  }
  while (renderers->pending() > 0)
    if (auto collected = collectTile(); !collected) return fail(collected.error().message);

  auto text = eng::TextRenderer::create();
  if (!text) return fail(text.error().message);
  eng::ContactSheetOptions sheetOptions;
  sheetOptions.columns = std::min<int>(5, int(tiles.size() + 1) / 2);
  sheetOptions.labelHeight = labelHeightFor(*text, tiles, int(o.size));
  // A transparent sheet keeps only the faces and the labels.
  if (backdrop->kind == eng::vk::Backdrop::Kind::Transparent) sheetOptions.background = {0, 0, 0, 0};
  sheetOptions.title = face->name() + ": " + (o.compound ? "compound expressions" : "basic expressions") +
                       ", rig: " + std::string(facial::rigSchemeName(face->rig().scheme()));
  auto sheet = eng::composeContactSheet(tiles, sheetOptions);
  if (!sheet) return fail(sheet.error().message);
  if (auto written = eng::writePng(o.out, sheet->width, sheet->height, sheet->rgba); !written)
    return fail(written.error().message);
  if (auto clean = renderers->checkValidation(); !clean) return fail(clean.error().message);
  std::printf("wrote %s (%zu %s expressions of %s, %dx%d, %s)\n", o.out.c_str(), tiles.size(),
              o.compound ? "compound" : "basic", face->name().c_str(), sheet->width, sheet->height,
              renderers->deviceName().c_str());
  return 0;
}

CommandRegistrar reg("sheet", "Render a labelled contact sheet of a model's expressions, headless", [](CLI::App& app) {
  auto o = std::make_shared<SheetOptions>();
  app::addFaceOptions(app, o->model, o->rigmap, o->noAutorig);
  app::addShapeOption(app, o->shapes);
  app::addBackgroundOption(app, o->background);
  app.add_flag("--compound", o->compound, "The compound presets instead of neutral and the six basic emotions");
  app.add_option("--size", o->size, "Tile size in pixels (square)")
      ->check(CLI::Range(16u, 4096u))
      ->capture_default_str();
  app.add_option("--intensity,-i", o->intensity, "Strength of every preset, clamped to [0, 1]")
      ->check(CLI::Number)
      ->capture_default_str();
  CLI::Option* zoom = app.add_option("--zoom", o->zoom,
                                     "Zoom factor (> 1 = closer; by default as close as keeps the face's features "
                                     "in the tile)")
                          ->capture_default_str();
  app::addFramingOption(app, o->frame);
  app::addDeviceOption(app, o->device);
  app::addQualityOption(app, o->quality);
  app.add_option("--out,-o", o->out, "Output PNG file")->required();
  return [o, zoom] {
    o->zoomGiven = zoom->count() > 0;
    return runSheet(*o);
  };
});

}  // namespace
}  // namespace cli::sheet_command
