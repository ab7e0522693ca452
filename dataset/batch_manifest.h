#pragma once
// A batch manifest: one job per line (JSON Lines), run in order by
// `facial batch`; blank lines and lines starting with '#' are skipped.
//
//   {"kind": "express", "args": ["happy", "--out", "out/happy.png"]}
//   {"kind": "render", "args": ["face.glb", "--out", "out/face.png"], "output": "out/face.png"}
//   {"kind": "dataset", "args": ["--spec", "data/datasets/example.json", "--out", "out/set"]}
//
// kind: one of kBatchKinds (the `facial` subcommand); args: its command line;
// output: what it writes (default: the value after --out / -o), for the
// result line. A line that is not such a job becomes a job that fails with
// the reason, so the rest of the manifest still runs.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace dataset {

inline constexpr std::array<std::string_view, 5> kBatchKinds{"render", "express", "say", "play", "dataset"};

struct BatchJob {
  uint64_t index = 0;  // among the manifest's jobs, from 0
  size_t line = 0;     // in the manifest, from 1
  std::string kind;
  std::vector<std::string> args;
  std::string output;
  std::string error;   // not empty: the line is not a job (the job fails with this)
};

// Errors: the file cannot be read (too large, missing), with its name.
eng::Result<std::vector<BatchJob>> readBatchManifest(const std::filesystem::path& path);
std::vector<BatchJob> parseBatchManifest(std::string_view text, std::string_view source);

struct BatchResult {
  uint64_t job = 0;
  std::string kind;
  bool ok = false;
  std::string output;
  std::string error;  // empty when ok
  double seconds = 0.0;
};

// {"job": 3, "kind": "express", "ok": false, "output": "...", "error": "...", "seconds": 1.25}
std::string resultJson(const BatchResult& result);

}  // namespace dataset
