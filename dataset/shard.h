#pragma once
// Which part of a job list one worker does: item k belongs to shard k mod N.
// The shard comes from --shard I/N, else from the scheduler's environment:
// a Slurm array (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN of
// SLURM_ARRAY_TASK_COUNT), a Kubernetes Indexed Job (JOB_COMPLETION_INDEX of
// FACIAL_SHARD_COUNT, which the manifest sets), else the whole list (0/1).
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "engine/core/result.h"

namespace dataset {

struct Shard {
  uint32_t index = 0;
  uint32_t count = 1;
  bool owns(uint64_t item) const { return item % count == index; }
  bool whole() const { return count == 1; }
  std::string name() const { return std::to_string(index) + "/" + std::to_string(count); }
};

// "I/N" with 0 <= I < N; the error names `option` and the text.
eng::Result<Shard> parseShard(std::string_view text, std::string_view option = "--shard");

// Reads a variable by name (std::getenv in the programs, a map in tests).
using Environment = std::function<const char*(const char*)>;
Environment processEnvironment();

// `option` when given, else the scheduler's variables, else 0/1. Errors name
// the option or the variables and their values (an index past the count).
eng::Result<Shard> resolveShard(std::string_view option, const Environment& environment);

}  // namespace dataset
