#include "dataset/dataset_folder.h"

#include <algorithm>
#include <chrono>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/progress_bar.h"
#include "dataset/item_renderer.h"
#include "dataset/landmark_overlay.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/image_io.h"

namespace dataset {
namespace fs = std::filesystem;
namespace {

constexpr size_t kMaxLabelBytes = size_t{1} << 20;

eng::Result<void> writeWhole(const fs::path& path, std::string_view bytes) {
  return eng::writeFileWhole(path, [&](const fs::path& partial) { return eng::writeFileBytes(partial, bytes.data(), bytes.size()); });
}

bool isFile(const fs::path& path) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

eng::Result<void> makeFolders(const fs::path& out) {
  for (const char* sub : {"images", "labels", "shards"}) {
    std::error_code ec;
    fs::create_directories(out / sub, ec);
    if (ec) return eng::makeError(eng::ErrorKind::Io, (out / sub).string() + ": cannot create the folder (" + ec.message() + ")");
  }
  return {};
}

// DIR/spec.json holds the canonical spec: written by the first run, and every
// later run (any shard, any machine) must bring the same spec.
eng::Result<void> claimFolder(const DatasetSpec& spec, const fs::path& out) {
  ENG_TRY(makeFolders(out));
  const std::string text = canonicalSpecJson(spec) + "\n";
  const fs::path file = out / "spec.json";
  if (!isFile(file)) return writeWhole(file, text);
  auto held = eng::readFileText(file, kMaxLabelBytes);
  if (!held) return held.error();
  if (*held == text) return {};
  return eng::makeError(eng::ErrorKind::InvalidArgument,
                        spec.source + ": " + out.string() + " was made from another spec (" + file.string() +
                            " differs; spec hash " + hashText(specHash(spec)) + "): use a new --out folder, or the same spec");
}

// What a killed run of this shard left: NNNNNN.<pid>.partial.png files of
// its own items (another shard's may be in the middle of being written).
void removeStalePartials(const fs::path& out, const Shard& shard) {
  for (const char* sub : {"images", "labels", "overlays"}) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(out / sub, ec)) {
      const std::string name = entry.path().filename().string();
      const size_t digits = name.find_first_not_of("0123456789");
      if (digits == 0 || digits > 18 || name.find(".partial") == std::string::npos) continue;
      if (shard.owns(std::stoull(name.substr(0, digits)))) fs::remove(entry.path(), ec);
    }
  }
}

bool finished(const fs::path& out, uint64_t index, uint64_t count) {
  return isFile(out / labelName(index, count)) && isFile(out / imageName(index, count));
}

struct Todo {
  uint32_t model = 0;
  uint64_t index = 0;
};

// The shard's unfinished items, grouped by model (one renderer at a time).
std::vector<Todo> unfinishedItems(const DatasetSpec& spec, const RunOptions& options, RunSummary& summary) {
  std::vector<Todo> todo;
  for (uint64_t k = options.shard.index; k < spec.count; k += options.shard.count) {
    ++summary.owned;
    if (finished(options.out, k, spec.count)) ++summary.skipped;
    else todo.push_back({sampleItem(spec, k).model, k});
  }
  std::stable_sort(todo.begin(), todo.end(), [](const Todo& a, const Todo& b) { return a.model < b.model; });
  return todo;
}

// The image first, then its label: an item whose label exists is whole.
eng::Result<void> writeItem(const RenderedItem& item, const DatasetSpec& spec, const RunOptions& options) {
  auto png = eng::encodePng(item.image.width, item.image.height, item.image.rgba8);
  if (!png) return png.error();
  const std::string_view bytes(reinterpret_cast<const char*>(png->data()), png->size());
  ENG_TRY(writeWhole(options.out / item.label.image, bytes));
  if (options.overlays) ENG_TRY(writeOverlay(item.image, item.label.landmarks, options.out / "overlays" / fs::path(item.label.image).filename()));
  return writeWhole(options.out / labelName(item.label.index, spec.count), labelJson(item.label) + "\n");
}

// Items in flight (ItemRenderer): one is encoded and written while the
// devices draw the next ones. On an error the items in flight are dropped;
// every item written before it is whole.
eng::Result<void> renderItems(const DatasetSpec& spec, const RunOptions& options, const std::vector<Todo>& todo,
                              RunSummary& summary) {
  std::optional<app::ProgressBar> progress;
  if (options.progress) progress.emplace("dataset shard " + options.shard.name(), todo.size(), options.progress);
  std::optional<ItemRenderer> renderer;
  uint64_t oldest = 0;  // the index in `todo` of the oldest item in flight
  const auto writeOldest = [&]() -> eng::Result<void> {
    auto item = renderer->collect();
    if (!item) return item.error().prefixed("item " + std::to_string(todo[oldest].index) + ": ");
    ENG_TRY(writeItem(*item, spec, options));
    ++oldest;
    ++summary.rendered;
    if (progress) progress->update(oldest);
    return {};
  };
  const auto finishModel = [&]() -> eng::Result<void> {
    if (!renderer) return {};
    while (renderer->pending() > 0) ENG_TRY(writeOldest());
    return renderer->checkValidation();
  };
  for (size_t i = 0; i < todo.size(); ++i) {
    if (!renderer || todo[i].model != todo[i - 1].model) {
      ENG_TRY(finishModel());
      renderer.reset();
      auto made = ItemRenderer::create(spec, todo[i].model, {.device = options.device});
      if (!made) return made.error().prefixed(spec.source + ": /models/" + std::to_string(todo[i].model) + ": ");
      renderer.emplace(std::move(*made));
      summary.device = renderer->deviceName();
    }
    if (renderer->full()) ENG_TRY(writeOldest());
    if (auto submitted = renderer->submit(sampleItem(spec, todo[i].index)); !submitted)
      return submitted.error().prefixed("item " + std::to_string(todo[i].index) + ": ");
  }
  ENG_TRY(finishModel());
  if (progress) progress->finish();
  return {};
}

std::string shardListName(const Shard& shard) {
  return "shards/labels-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".jsonl";
}

// The shard's label lines in index order, written once every item is there.
eng::Result<void> writeShardList(const DatasetSpec& spec, const RunOptions& options) {
  std::string lines;
  for (uint64_t k = options.shard.index; k < spec.count; k += options.shard.count) {
    auto line = eng::readFileText(options.out / labelName(k, spec.count), kMaxLabelBytes);
    if (!line) return line.error();
    lines += *line;
  }
  return writeWhole(options.out / shardListName(options.shard), lines);
}

}  // namespace

eng::Result<RunSummary> runDataset(const DatasetSpec& spec, const RunOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  ENG_TRY(claimFolder(spec, options.out));
  if (options.overlays) ENG_TRY(makeOverlayFolder(options.out / "overlays"));
  removeStalePartials(options.out, options.shard);
  RunSummary summary;
  const std::vector<Todo> todo = unfinishedItems(spec, options, summary);
  ENG_TRY(renderItems(spec, options, todo, summary));
  ENG_TRY(writeShardList(spec, options));
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (options.shard.whole()) ENG_TRY(mergeDataset(options.out));
  return summary;
}

}  // namespace dataset
