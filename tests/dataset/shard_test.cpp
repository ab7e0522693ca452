// Shards: --shard I/N, else the scheduler's variables (Slurm arrays,
// Kubernetes Indexed Jobs), else 0/1; bad values named.
#include <map>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "dataset/shard.h"

namespace dataset {
namespace {

Environment fakeEnvironment(std::map<std::string, std::string> values) {
  auto held = std::make_shared<std::map<std::string, std::string>>(std::move(values));
  return [held](const char* name) -> const char* {
    auto it = held->find(name);
    return it == held->end() ? nullptr : it->second.c_str();
  };
}

TEST(Shard, ParsesIndexOverCount) {
  auto shard = parseShard("1/4");
  ASSERT_TRUE(shard) << shard.error().message;
  EXPECT_EQ(shard->index, 1u);
  EXPECT_EQ(shard->count, 4u);
  EXPECT_TRUE(shard->owns(5));
  EXPECT_FALSE(shard->owns(6));
}

TEST(Shard, RefusesBadTextNamingTheOption) {
  for (const char* text : {"4/4", "5/2", "1/0", "x/2", "1", "-1/2", "1/2/3", ""}) {
    auto shard = parseShard(text);
    ASSERT_FALSE(shard) << text;
    EXPECT_NE(shard.error().message.find("--shard: '" + std::string(text) + "'"), std::string::npos) << shard.error().message;
  }
  EXPECT_NE(parseShard("4/4").error().message.find("out of range"), std::string::npos);
}

TEST(Shard, TheOptionWinsOverTheEnvironment) {
  auto shard = resolveShard("0/3", fakeEnvironment({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}));
  ASSERT_TRUE(shard);
  EXPECT_EQ(shard->name(), "0/3");
}

TEST(Shard, SlurmArrayCountsFromItsFirstTask) {
  auto zeroBased = resolveShard("", fakeEnvironment({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"},
                                                     {"SLURM_ARRAY_TASK_MIN", "0"}}));
  ASSERT_TRUE(zeroBased) << zeroBased.error().message;
  EXPECT_EQ(zeroBased->name(), "2/4");
  auto oneBased = resolveShard("", fakeEnvironment({{"SLURM_ARRAY_TASK_ID", "4"}, {"SLURM_ARRAY_TASK_COUNT", "4"},
                                                    {"SLURM_ARRAY_TASK_MIN", "1"}}));
  ASSERT_TRUE(oneBased) << oneBased.error().message;
  EXPECT_EQ(oneBased->name(), "3/4");
}

TEST(Shard, KubernetesIndexedJob) {
  auto shard = resolveShard("", fakeEnvironment({{"JOB_COMPLETION_INDEX", "5"}, {"FACIAL_SHARD_COUNT", "8"}}));
  ASSERT_TRUE(shard) << shard.error().message;
  EXPECT_EQ(shard->name(), "5/8");
}

TEST(Shard, NoSchedulerMeansTheWholeList) {
  auto shard = resolveShard("", fakeEnvironment({}));
  ASSERT_TRUE(shard);
  EXPECT_TRUE(shard->whole());
}

TEST(Shard, EnvironmentOutOfRangeOrIncompleteIsNamed) {
  auto past = resolveShard("", fakeEnvironment({{"JOB_COMPLETION_INDEX", "8"}, {"FACIAL_SHARD_COUNT", "8"}}));
  ASSERT_FALSE(past);
  EXPECT_NE(past.error().message.find("JOB_COMPLETION_INDEX=8, FACIAL_SHARD_COUNT=8"), std::string::npos) << past.error().message;
  EXPECT_NE(past.error().message.find("out of range"), std::string::npos);
  auto noCount = resolveShard("", fakeEnvironment({{"JOB_COMPLETION_INDEX", "1"}}));
  ASSERT_FALSE(noCount);
  EXPECT_NE(noCount.error().message.find("FACIAL_SHARD_COUNT is not"), std::string::npos) << noCount.error().message;
  auto garbage = resolveShard("", fakeEnvironment({{"SLURM_ARRAY_TASK_ID", "two"}, {"SLURM_ARRAY_TASK_COUNT", "4"}}));
  ASSERT_FALSE(garbage);
  EXPECT_NE(garbage.error().message.find("not whole numbers"), std::string::npos) << garbage.error().message;
}

}  // namespace
}  // namespace dataset
