// `facial dataset --spec S.json --out DIR [--shard I/N] [--count N] [--seed S]
//  [--size WxH] [--models a,b] [--emotions a,b] [--intensity MIN:MAX] [--yaw MIN:MAX]
//  [--pitch MIN:MAX] [--device D] [--overlays]`
// `facial dataset merge --out DIR` (also `facial dataset --merge --out DIR`)
// Renders a labelled synthetic dataset (dataset/dataset_folder.h): images and
// one label line per image, this shard's items only; resumable; the merge
// writes DIR/labels.jsonl and DIR/index.json.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "app/cli_parse.h"
#include "app/face_setup.h"
#include "app/output_paths.h"
#include "app/program_error.h"
#include "cli/command.h"
#include "dataset/dataset_folder.h"
#include "dataset/dataset_spec.h"
#include "dataset/shard.h"

namespace cli::dataset_command {
namespace {

struct DatasetOptions {
  std::string spec;
  std::string out;
  std::string shard;
  bool merge = false;
  bool overlays = false;
  std::string device;
  // Flags over the spec's common fields (empty / unset: the spec's value).
  std::string count, seed, size, models, emotions, intensity, yaw, pitch;
};

constexpr app::ErrorReporter fail{"facial dataset"};

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> parts;
  size_t start = 0;
  for (size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1) parts.push_back(text.substr(start, comma - start));
  parts.push_back(text.substr(start));
  return parts;
}

eng::Result<uint64_t> wholeFlag(const std::string& text, std::string_view option) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || text[0] == '-')
    return eng::makeError(eng::ErrorKind::InvalidArgument, std::string(option) + ": '" + text + "' is not a whole number");
  return uint64_t(value);
}

// The spec file's fields, then the flags over them; checked as one.
eng::Result<dataset::DatasetSpec> specFrom(const DatasetOptions& o) {
  dataset::DatasetSpec spec{.source = "command line", .baseDir = std::filesystem::current_path()};
  if (!o.spec.empty()) spec = ENG_TRY_VALUE(dataset::readDatasetSpec(o.spec));
  if (!o.count.empty()) spec.count = ENG_TRY_VALUE(wholeFlag(o.count, "--count"));
  if (!o.seed.empty()) spec.seed = ENG_TRY_VALUE(wholeFlag(o.seed, "--seed"));
  if (!o.size.empty() && !app::parseSize(o.size, spec.width, spec.height))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "--size: '" + o.size + "' is not WIDTHxHEIGHT");
  if (!o.models.empty()) spec.models = splitList(o.models);
  if (!o.emotions.empty()) spec.emotions = splitList(o.emotions);
  for (std::string& emotion : spec.emotions) emotion = dataset::canonicalEmotionName(emotion);
  if (!o.intensity.empty()) spec.intensity = ENG_TRY_VALUE(dataset::parseRange(o.intensity, "--intensity"));
  if (!o.yaw.empty()) spec.yaw = ENG_TRY_VALUE(dataset::parseRange(o.yaw, "--yaw"));
  if (!o.pitch.empty()) spec.pitch = ENG_TRY_VALUE(dataset::parseRange(o.pitch, "--pitch"));
  ENG_TRY(dataset::checkDatasetSpec(spec, app::defaultExpressionsPath()));
  return spec;
}

int runMerge(const DatasetOptions& o) {
  auto merged = dataset::mergeDataset(o.out);
  if (!merged) return fail(merged.error().message);
  std::printf("merged %llu items of %s from %zu shard label lists: %s/labels.jsonl, %s/index.json\n",
              static_cast<unsigned long long>(merged->count), o.out.c_str(), merged->shards.size(), o.out.c_str(), o.out.c_str());
  return 0;
}

int runDataset(const DatasetOptions& o) {
  if (o.out.empty()) return fail("--out DIR is required (the dataset folder)");
  if (o.merge) return runMerge(o);
  if (auto safe = app::checkOutputs({.inputs = {{"--spec", o.spec}}, .outputs = {{"--out", o.out}}}); !safe)
    return fail(safe.error().message);
  auto shard = dataset::resolveShard(o.shard, dataset::processEnvironment());
  if (!shard) return fail(shard.error().message);
  auto spec = specFrom(o);
  if (!spec) return fail(spec.error().message);
  auto run = dataset::runDataset(*spec, {.out = o.out, .shard = *shard, .device = o.device, .progress = stderr,
                                         .overlays = o.overlays});
  if (!run) return fail(run.error().message);
  std::printf("shard %s of %s: %llu items, %llu made, %llu already there, %.1f s (%.2f images/s, %s)\n",
              shard->name().c_str(), o.out.c_str(), static_cast<unsigned long long>(run->owned),
              static_cast<unsigned long long>(run->rendered), static_cast<unsigned long long>(run->skipped), run->seconds,
              run->seconds > 0.0 ? double(run->rendered) / run->seconds : 0.0, run->device.c_str());
  return 0;
}

void addSpecOptions(CLI::App& app, DatasetOptions& o) {
  app.add_option("--spec", o.spec, "Dataset spec (JSON, data/datasets/example.json); the flags below override it");
  app.add_option("--count", o.count, "Number of images (the whole dataset, all shards)");
  app.add_option("--seed", o.seed, "Seed: item k's parameters depend only on it and k");
  app.add_option("--size", o.size, "Image size WxH");
  app.add_option("--models", o.models, "Models, comma-separated ('head' = the built-in head)");
  app.add_option("--emotions", o.emotions, "Emotions, comma-separated (data/expressions.json: happy, happily_surprised, ...)");
  app.add_option("--intensity", o.intensity, "Intensity range MIN:MAX (or one value) in [0, 1]");
  app.add_option("--yaw", o.yaw, "Head yaw range MIN:MAX in degrees");
  app.add_option("--pitch", o.pitch, "Head pitch range MIN:MAX in degrees");
}

CommandRegistrar reg("dataset", "Render a labelled synthetic face dataset (images, labels.jsonl), shardable", [](CLI::App& app) {
  auto o = std::make_shared<DatasetOptions>();
  addSpecOptions(app, *o);
  app.add_option("--out,-o", o->out, "Dataset folder (required)");
  app.add_option("--shard", o->shard, "I/N: make only items k with k mod N == I (default: from Slurm or Kubernetes, else 0/1)");
  app.add_flag("--merge", o->merge, "Merge the shards' label lists into labels.jsonl and index.json");
  app.add_flag("--overlays", o->overlays, "Also write overlays/NNNNNN.png: each image with its landmarks drawn");
  app.add_option("--device", o->device, "Vulkan device (index or name part)");
  auto* merge = app.add_subcommand("merge", "Merge the shards' label lists into labels.jsonl and index.json");
  merge->add_option("--out,-o", o->out, "Dataset folder")->required();
  merge->callback([o] { o->merge = true; });
  app.require_subcommand(0, 1);
  app.fallthrough(false);
  return [o] { return runDataset(*o); };
});

}  // namespace
}  // namespace cli::dataset_command
