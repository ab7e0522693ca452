// `facial batch MANIFEST.jsonl [--shard I/N] [--results R.jsonl]`
// Runs a manifest's jobs (render, express, say, play, dataset: one JSON line
// each, dataset/batch_manifest.h) in order, each as its own process; prints
// one result line per job and exits 1 when any failed (the rest still run).
#include <cstdio>
#include <memory>
#include <string>

#include "app/output_paths.h"
#include "app/program_error.h"
#include "cli/command.h"
#include "dataset/batch_runner.h"
#include "dataset/shard.h"

namespace cli::batch_command {
namespace {

struct BatchOptions {
  std::string manifest;
  std::string shard;
  std::string results;
};

constexpr app::ErrorReporter fail{"facial batch"};

int runBatchCommand(const BatchOptions& o) {
  if (auto safe = app::checkOutputs({.inputs = {{"manifest", o.manifest}}, .outputs = {{"--results", o.results}}}); !safe)
    return fail(safe.error().message);
  auto shard = dataset::resolveShard(o.shard, dataset::processEnvironment());
  if (!shard) return fail(shard.error().message);
  auto jobs = dataset::readBatchManifest(o.manifest);
  if (!jobs) return fail(jobs.error().message);
  std::error_code ec;
  const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return fail("cannot tell where the facial program is (/proc/self/exe: " + ec.message() + ")");
  auto summary = dataset::runBatch(*jobs, {.program = program, .shard = *shard, .results = o.results, .echo = stdout});
  if (!summary) return fail(summary.error().message);
  std::fprintf(stderr, "facial batch: %zu of %zu jobs ran in shard %s, %zu failed\n", summary->results.size(), jobs->size(),
               shard->name().c_str(), summary->failed);
  return summary->failed == 0 ? 0 : 1;
}

CommandRegistrar reg("batch", "Run a manifest of jobs (render, express, say, play, dataset), one result line each", [](CLI::App& app) {
  auto o = std::make_shared<BatchOptions>();
  app.add_option("manifest", o->manifest, "Jobs, one JSON object a line: {\"kind\": \"express\", \"args\": [...]}")->required();
  app.add_option("--shard", o->shard, "I/N: run only jobs j with j mod N == I (default: from Slurm or Kubernetes, else 0/1)");
  app.add_option("--results", o->results, "Also write the result lines to this file (rewritten whole after each job)");
  return [o] { return runBatchCommand(*o); };
});

}  // namespace
}  // namespace cli::batch_command
