#include "dataset/shard.h"

#include <charconv>
#include <cstdlib>
#include <optional>

namespace dataset {
namespace {

std::optional<uint32_t> parseCount(std::string_view text) {
  uint32_t value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

eng::Error badShard(std::string_view option, std::string_view text, std::string_view why) {
  return eng::makeError(eng::ErrorKind::InvalidArgument,
                        std::string(option) + ": '" + std::string(text) + "' " + std::string(why));
}

// index/count from two variables; nullopt when `indexName` is unset.
eng::Result<std::optional<Shard>> shardFromVariables(const Environment& env, const char* indexName,
                                                     const char* countName, const char* minName) {
  const char* index = env(indexName);
  if (!index) return std::optional<Shard>{};
  const char* count = env(countName);
  if (!count)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::string(indexName) + " is set but " + countName + " is not: cannot tell the shard count");
  const std::string label = std::string(indexName) + "=" + index + ", " + countName + "=" + count;
  auto i = parseCount(index);
  auto n = parseCount(count);
  std::optional<uint32_t> first = 0u;
  if (minName && env(minName)) first = parseCount(env(minName));
  if (!i || !n || !first) return badShard("environment", label, "are not whole numbers");
  if (*i < *first) return badShard("environment", label, "puts the index below the array's first task");
  Shard shard{*i - *first, *n};
  if (shard.count == 0 || shard.index >= shard.count)
    return badShard("environment", label, "is out of range (needs 0 <= index < count)");
  return std::optional<Shard>{shard};
}

}  // namespace

eng::Result<Shard> parseShard(std::string_view text, std::string_view option) {
  const size_t slash = text.find('/');
  if (slash == std::string_view::npos) return badShard(option, text, "is not I/N (shard index / shard count)");
  auto i = parseCount(text.substr(0, slash));
  auto n = parseCount(text.substr(slash + 1));
  if (!i || !n) return badShard(option, text, "is not I/N with whole numbers");
  if (*n == 0) return badShard(option, text, "has a shard count of 0");
  if (*i >= *n) return badShard(option, text, "is out of range: the index must be below the count (0.." + std::to_string(*n - 1) + ")");
  return Shard{*i, *n};
}

Environment processEnvironment() {
  return [](const char* name) { return static_cast<const char*>(std::getenv(name)); };
}

eng::Result<Shard> resolveShard(std::string_view option, const Environment& environment) {
  if (!option.empty()) return parseShard(option);
  auto slurm = shardFromVariables(environment, "SLURM_ARRAY_TASK_ID", "SLURM_ARRAY_TASK_COUNT", "SLURM_ARRAY_TASK_MIN");
  if (!slurm) return slurm.error();
  if (*slurm) return **slurm;
  auto indexed = shardFromVariables(environment, "JOB_COMPLETION_INDEX", "FACIAL_SHARD_COUNT", nullptr);
  if (!indexed) return indexed.error();
  if (*indexed) return **indexed;
  return Shard{};
}

}  // namespace dataset
