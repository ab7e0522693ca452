#pragma once
// Runs a batch manifest's jobs (dataset/batch_manifest.h) in order, each as
// its own `facial KIND ARGS...` process: a job that fails, or crashes, is
// recorded with its error line and the next one runs. The child's stdout and
// stderr pass through to our stderr (our stdout is the result lines); its
// last stderr line is the result's error.
#include <cstdio>
#include <filesystem>
#include <vector>

#include "dataset/batch_manifest.h"
#include "dataset/shard.h"
#include "engine/core/result.h"

namespace dataset {

struct BatchOptions {
  std::filesystem::path program;  // the `facial` executable
  Shard shard;                    // job j runs in shard j mod N
  std::filesystem::path results;  // empty: none; else every result line so far, rewritten whole after each job
  std::FILE* echo = stdout;       // each result line as it comes; null: quiet
};

struct BatchSummary {
  std::vector<BatchResult> results;
  size_t failed = 0;
};

// One job: ok when the process exits 0. The child sees no scheduler
// variables (SLURM_ARRAY_*, JOB_COMPLETION_INDEX): a dataset job in a
// sharded batch is one job, made whole, not a shard of it.
BatchResult runBatchJob(const BatchJob& job, const std::filesystem::path& program);

// Errors only when the results file cannot be written (named); failed jobs
// are counted in the summary.
eng::Result<BatchSummary> runBatch(const std::vector<BatchJob>& jobs, const BatchOptions& options);

}  // namespace dataset
