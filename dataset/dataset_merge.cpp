// mergeDataset (dataset/dataset_folder.h): the shards' label lists into one
// labels.jsonl in index order, and index.json describing the folder.
#include <algorithm>
#include <map>
#include <regex>

#include <nlohmann/json.hpp>

#include "dataset/dataset_folder.h"
#include "dataset/item_label.h"
#include "engine/scene/file_bytes.h"

namespace dataset {
namespace fs = std::filesystem;
namespace {

constexpr size_t kMaxSpecBytes = size_t{1} << 20;
constexpr size_t kMaxShardListBytes = size_t{16} << 30;
constexpr size_t kMissingListed = 1000;   // in index.json (the count is always there)
constexpr size_t kMissingInMessage = 10;  // in the error line

struct FolderSpec {
  uint64_t count = 0;
  std::string hash;
};

eng::Result<FolderSpec> readFolderSpec(const fs::path& out) {
  const fs::path file = out / "spec.json";
  auto text = eng::readFileText(file, kMaxSpecBytes);
  if (!text) return text.error().prefixed(out.string() + ": not a dataset folder (no spec.json from a `facial dataset` run): ");
  const nlohmann::json spec = nlohmann::json::parse(*text, nullptr, false);
  if (!spec.is_object() || !spec.contains("count") || !spec["count"].is_number_unsigned())
    return eng::makeError(eng::ErrorKind::Malformed, file.string() + ": not a dataset spec written by `facial dataset` (no count)");
  // The file is the canonical spec and a newline: its hash is specHash's.
  const std::string_view canonical = std::string_view(*text).substr(0, text->size() - 1);
  return FolderSpec{spec["count"].get<uint64_t>(), hashText(textHash(canonical))};
}

// Each line of one shard's list into lines[index]; errors name the file and line.
eng::Result<void> readShardList(const fs::path& file, uint64_t count, std::vector<std::string>& lines) {
  auto text = eng::readFileText(file, kMaxShardListBytes);
  if (!text) return text.error();
  size_t start = 0, lineNumber = 0;
  for (size_t end; (end = text->find('\n', start)) != std::string::npos; start = end + 1) {
    ++lineNumber;
    const std::string line = text->substr(start, end - start + 1);
    const nlohmann::json label = nlohmann::json::parse(line, nullptr, false);
    if (!label.is_object() || !label.contains("index") || !label["index"].is_number_unsigned() ||
        label["index"].get<uint64_t>() >= count)
      return eng::makeError(eng::ErrorKind::Malformed, file.string() + ": line " + std::to_string(lineNumber) +
                                                           ": not a label with an index below " + std::to_string(count));
    lines[label["index"].get<uint64_t>()] = line;
  }
  return {};
}

// The label lists in DIR/shards, by name: "0/2" -> its file.
std::map<std::pair<uint32_t, uint32_t>, fs::path> shardLists(const fs::path& out) {
  std::map<std::pair<uint32_t, uint32_t>, fs::path> lists;
  static const std::regex name(R"(labels-(\d{1,9})-of-(\d{1,9})\.jsonl)");
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(out / "shards", ec)) {
    std::smatch match;
    const std::string file = entry.path().filename().string();
    if (std::regex_match(file, match, name))
      lists[{uint32_t(std::stoul(match[1])), uint32_t(std::stoul(match[2]))}] = entry.path();
  }
  return lists;
}

std::vector<uint64_t> missingItems(const fs::path& out, const std::vector<std::string>& lines) {
  std::vector<uint64_t> missing;
  std::error_code ec;
  for (uint64_t k = 0; k < lines.size(); ++k)
    if (lines[k].empty() || !fs::is_regular_file(out / imageName(k, lines.size()), ec)) missing.push_back(k);
  return missing;
}

eng::Result<void> writeIndex(const fs::path& out, const FolderSpec& spec, const MergeSummary& summary) {
  nlohmann::ordered_json index{{"format", "facial-dataset-index"}, {"version", 1}, {"specHash", spec.hash},
                               {"count", spec.count}, {"complete", summary.missing.empty()},
                               {"labels", "labels.jsonl"}, {"images", "images"}, {"shards", summary.shards},
                               {"missingCount", summary.missing.size()}};
  const size_t listed = std::min(summary.missing.size(), kMissingListed);
  index["missing"] = std::vector<uint64_t>(summary.missing.begin(), summary.missing.begin() + long(listed));
  const std::string text = index.dump(2) + "\n";
  return eng::writeFileWhole(out / "index.json", [&](const fs::path& partial) {
    return eng::writeFileBytes(partial, text.data(), text.size());
  });
}

eng::Error missingError(const fs::path& out, const MergeSummary& summary) {
  std::string list;
  for (size_t i = 0; i < std::min(summary.missing.size(), kMissingInMessage); ++i)
    list += (i ? ", " : "") + std::to_string(summary.missing[i]);
  if (summary.missing.size() > kMissingInMessage) list += ", ...";
  std::string shards;
  for (const std::string& s : summary.shards) shards += (shards.empty() ? "" : " ") + s;
  return eng::makeError(eng::ErrorKind::NotFound,
                        out.string() + ": " + std::to_string(summary.missing.size()) + " of " + std::to_string(summary.count) +
                            " items missing (" + list + "); shard label lists seen: " + (shards.empty() ? "none" : shards) +
                            "; rerun the shards that own them (item k is shard k mod N), then merge");
}

}  // namespace

eng::Result<MergeSummary> mergeDataset(const fs::path& out) {
  auto spec = readFolderSpec(out);
  if (!spec) return spec.error();
  MergeSummary summary;
  summary.count = spec->count;
  std::vector<std::string> lines(spec->count);
  for (const auto& [shard, file] : shardLists(out)) {
    ENG_TRY(readShardList(file, spec->count, lines));
    summary.shards.push_back(std::to_string(shard.first) + "/" + std::to_string(shard.second));
  }
  summary.missing = missingItems(out, lines);
  ENG_TRY(writeIndex(out, *spec, summary));
  if (!summary.missing.empty()) return missingError(out, summary);
  std::string all;
  for (const std::string& line : lines) all += line;
  ENG_TRY(eng::writeFileWhole(out / "labels.jsonl", [&](const fs::path& partial) {
    return eng::writeFileBytes(partial, all.data(), all.size());
  }));
  return summary;
}

}  // namespace dataset
