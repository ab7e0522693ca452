// Batch manifests: one job a line; a line that is no job becomes a failing
// job, so the rest of the manifest still runs.
#include <gtest/gtest.h>

#include "dataset/batch_manifest.h"

namespace dataset {
namespace {

TEST(BatchManifest, ReadsJobsSkippingBlankAndCommentLines) {
  const auto jobs = parseBatchManifest(
      "# nightly\n"
      "{\"kind\": \"express\", \"args\": [\"happy\", \"--out\", \"a.png\"]}\n"
      "\n"
      "{\"kind\": \"render\", \"args\": [\"f.glb\", \"-o\", \"b.png\"], \"output\": \"elsewhere.png\"}\n"
      "{\"kind\": \"dataset\", \"args\": [\"--spec\", \"s.json\", \"--out=set\"]}",
      "m.jsonl");
  ASSERT_EQ(jobs.size(), 3u);
  EXPECT_EQ(jobs[0].index, 0u);
  EXPECT_EQ(jobs[0].line, 2u);
  EXPECT_EQ(jobs[0].kind, "express");
  EXPECT_EQ(jobs[0].output, "a.png");
  EXPECT_EQ(jobs[1].output, "elsewhere.png");
  EXPECT_EQ(jobs[2].output, "set");
  for (const BatchJob& job : jobs) EXPECT_EQ(job.error, "");
}

TEST(BatchManifest, ALineThatIsNoJobSaysWhy) {
  const auto jobs = parseBatchManifest(
      "{\"kind\": \"juggle\", \"args\": []}\n"
      "not json\n"
      "{\"kind\": \"say\"}\n"
      "{\"kind\": \"play\", \"args\": [1]}\n"
      "{\"kind\": \"play\", \"args\": [], \"when\": \"now\"}\n",
      "m.jsonl");
  ASSERT_EQ(jobs.size(), 5u);
  EXPECT_EQ(jobs[0].error, "m.jsonl: line 1: unknown kind 'juggle' (render, express, say, play, dataset)");
  EXPECT_EQ(jobs[1].error, "m.jsonl: line 2: not a JSON object");
  EXPECT_EQ(jobs[2].error, "m.jsonl: line 3: no \"args\" array (the command line)");
  EXPECT_EQ(jobs[3].error, "m.jsonl: line 4: \"args\" must hold strings only");
  EXPECT_EQ(jobs[4].error, "m.jsonl: line 5: unknown key 'when' (kind, args, output)");
}

TEST(BatchManifest, ResultLines) {
  EXPECT_EQ(resultJson({.job = 2, .kind = "express", .ok = true, .output = "a.png", .error = "", .seconds = 1.23456}),
            R"({"job":2,"kind":"express","ok":true,"output":"a.png","error":null,"seconds":1.235})");
  EXPECT_EQ(resultJson({.job = 3, .kind = "say", .ok = false, .output = "", .error = "no voice", .seconds = 0.5}),
            R"({"job":3,"kind":"say","ok":false,"output":"","error":"no voice","seconds":0.5})");
}

}  // namespace
}  // namespace dataset
