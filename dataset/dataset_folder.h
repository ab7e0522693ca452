#pragma once
// A dataset folder and the runs that fill it:
//
//   DIR/spec.json                   the spec the folder was made from (canonical; a different spec is refused)
//   DIR/images/NNNNNN.png           item NNNNNN's image
//   DIR/labels/NNNNNN.json          its label (one line); an item is finished when both exist
//   DIR/shards/labels-I-of-N.jsonl  shard I's labels, written when the shard is complete
//   DIR/labels.jsonl, DIR/index.json  the merge: every label in index order, and what the folder holds
//
// Every file is written whole (eng::writeFileWhole), so a killed worker
// leaves finished items and nothing half-written: a rerun skips the finished
// items and makes the rest.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "dataset/dataset_spec.h"
#include "dataset/shard.h"
#include "engine/core/result.h"

namespace dataset {

struct RunOptions {
  std::filesystem::path out;
  Shard shard;
  std::string device;           // eng::vk::ContextOptions::device
  std::FILE* progress = stderr;  // null: quiet
  bool overlays = false;        // also DIR/overlays/NNNNNN.png: the image with its landmarks drawn
};

struct RunSummary {
  uint64_t owned = 0;     // items of this shard
  uint64_t skipped = 0;   // finished by an earlier run
  uint64_t rendered = 0;
  double seconds = 0.0;
  std::string device;
};

// Makes this shard's missing items, then writes its label list; an unsharded
// run (0/1) also merges. Errors name the file or the item that failed.
eng::Result<RunSummary> runDataset(const DatasetSpec& spec, const RunOptions& options);

struct MergeSummary {
  uint64_t count = 0;
  std::vector<std::string> shards;  // "0/2", "1/2": the label lists found
  std::vector<uint64_t> missing;
};

// Writes DIR/index.json, and DIR/labels.jsonl when no item is missing; fails
// naming the missing items (the first few and how many) otherwise.
eng::Result<MergeSummary> mergeDataset(const std::filesystem::path& out);

}  // namespace dataset
