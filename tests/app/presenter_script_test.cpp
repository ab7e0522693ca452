// The presenter script of `facial say --script`: emotions switched at their
// tag (mid-line too) and held, pauses, comments, the JSON form, and every
// malformed script refused in one line naming the source and line.
#include "app/presenter_script.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/common/test_support.h"

namespace app {
namespace {

using Kind = ScriptSegment::Kind;

PresenterScript parsed(std::string_view text, const ScriptDefaults& defaults = {}) {
  auto script = parsePresenterScript(text, "bulletin.txt", defaults);
  EXPECT_TRUE(script.ok()) << script.error().message;
  return script.ok() ? *script : PresenterScript{};
}

std::string refusal(std::string_view text) {
  auto script = parsePresenterScript(text, "bulletin.txt");
  EXPECT_FALSE(script.ok()) << text;
  return script.ok() ? std::string() : script.error().message;
}

TEST(PresenterScript, TagsSwitchTheEmotionMidLineAndHoldAcrossLines) {
  const PresenterScript script = parsed("[happy] Good evening.\nThe sun is out, [sad 0.6] but the final was lost.\n");
  ASSERT_EQ(script.segments.size(), 4u);
  EXPECT_EQ(script.segments[0].text, "Good evening.");
  EXPECT_EQ(script.segments[0].emotion, "happy");
  EXPECT_EQ(script.segments[0].intensity, 1.0f);
  EXPECT_EQ(script.segments[1].kind, Kind::Pause);
  EXPECT_FLOAT_EQ(script.segments[1].seconds, kLinePauseSeconds);
  EXPECT_EQ(script.segments[2].text, "The sun is out,");
  EXPECT_EQ(script.segments[2].emotion, "happy");  // held from line 1
  EXPECT_EQ(script.segments[2].line, 2);
  // The pieces of one line follow each other without a pause.
  EXPECT_EQ(script.segments[3].kind, Kind::Speech);
  EXPECT_EQ(script.segments[3].text, "but the final was lost.");
  EXPECT_EQ(script.segments[3].emotion, "sad");
  EXPECT_FLOAT_EQ(script.segments[3].intensity, 0.6f);
}

TEST(PresenterScript, DefaultsStartTheScriptAndFillTagsWithoutIntensity) {
  const PresenterScript script = parsed("Hello.\n[anger] Stop.", {.emotion = "fear", .intensity = 0.5f});
  ASSERT_EQ(script.segments.size(), 3u);
  EXPECT_EQ(script.segments[0].emotion, "fear");
  EXPECT_FLOAT_EQ(script.segments[0].intensity, 0.5f);
  EXPECT_EQ(script.segments[2].emotion, "anger");
  EXPECT_FLOAT_EQ(script.segments[2].intensity, 0.5f);
}

TEST(PresenterScript, PausesCommentsAndParagraphs) {
  const PresenterScript script = parsed(
      "# a comment line\n\n\nFirst.\n[pause 1.5]\nSecond.\n\nThird.[pause 0]\nFourth. [pause 0.25] Fifth.\n\n[pause 2]\n");
  std::vector<float> pauses;
  std::vector<std::string> said;
  for (const ScriptSegment& s : script.segments)
    (s.kind == Kind::Pause ? (void)pauses.push_back(s.seconds) : (void)said.push_back(s.text));
  EXPECT_EQ(said, (std::vector<std::string>{"First.", "Second.", "Third.", "Fourth.", "Fifth."}));
  // The explicit pause replaces the line's; a blank line is a paragraph; [pause 0] joins lines; none trails.
  EXPECT_EQ(pauses, (std::vector<float>{1.5f, kParagraphPauseSeconds, 0.25f}));
  EXPECT_EQ(script.segments.front().kind, Kind::Speech);
  EXPECT_EQ(script.segments.back().kind, Kind::Speech);
}

TEST(PresenterScript, JsonFormReadsLinesWithEmotionIntensityAndPause) {
  const PresenterScript script = parsed(R"({"version": 1, "lines": [
      {"text": "Good evening.", "emotion": "happy", "intensity": 0.8, "pause": 1.0},
      {"text": "Sadly, [sad] the final was lost."}]})");
  ASSERT_EQ(script.segments.size(), 4u);
  EXPECT_EQ(script.segments[0].emotion, "happy");
  EXPECT_FLOAT_EQ(script.segments[0].intensity, 0.8f);
  EXPECT_FLOAT_EQ(script.segments[1].seconds, 1.0f);
  EXPECT_EQ(script.segments[2].text, "Sadly,");
  EXPECT_EQ(script.segments[2].emotion, "happy");
  EXPECT_EQ(script.segments[3].emotion, "sad");
  EXPECT_EQ(script.segments[3].line, 2);
}

TEST(PresenterScript, MalformedScriptsAreOneLineNamingSourceAndLine) {
  EXPECT_EQ(refusal("Hello.\n[bored] Hi."), "bulletin.txt:2: unknown tag '[bored]': not pause or an emotion "
                                            "(neutral, happy, sad, surprise, fear, anger, disgust)");
  EXPECT_EQ(refusal("Hello [pause x] there"), "bulletin.txt:1: pause 'x' is not a number of seconds in [0, 60]");
  EXPECT_NE(refusal("Hello [pause 61]").find("bulletin.txt:1: pause '61'"), std::string::npos);
  EXPECT_NE(refusal("Hello [pause -1]").find("pause '-1'"), std::string::npos);
  EXPECT_NE(refusal("Hello [pause nan]").find("pause 'nan'"), std::string::npos);
  EXPECT_NE(refusal("Hello [pause]").find("[pause] needs its seconds"), std::string::npos);
  EXPECT_EQ(refusal("\n\nHello [happy there"), "bulletin.txt:3: '[' is not closed by ']'");
  EXPECT_EQ(refusal("Hello [happy [sad] there"), "bulletin.txt:1: '[' is not closed by ']'");
  EXPECT_EQ(refusal("Hello ] there"), "bulletin.txt:1: ']' without its '['");
  EXPECT_EQ(refusal("[happy 1.5] Hi"), "bulletin.txt:1: intensity '1.5' is not a number in [0, 1]");
  EXPECT_NE(refusal("[happy 0.5 1] Hi").find("more than one number"), std::string::npos);
  EXPECT_NE(refusal("[] Hi").find("empty tag"), std::string::npos);
  EXPECT_EQ(refusal(""), "bulletin.txt: the script says nothing (no text to speak)");
  EXPECT_EQ(refusal("# only a comment\n[happy] [pause 1]\n"), "bulletin.txt: the script says nothing (no text to speak)");
  EXPECT_EQ(refusal(std::string(kMaxPresenterScriptBytes + 1, 'a')),
            "bulletin.txt: 1048577 bytes, over the script limit of 1 MB");
  for (const std::string& message : {refusal("[bored]"), refusal("[pause 1"), refusal("")})
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

TEST(PresenterScript, MalformedJsonNamesTheMember) {
  EXPECT_NE(refusal(R"({"version": 1, "lines": [{"text": "Hi", "emotion": "bored"}]})")
                .find("bulletin.txt: /lines/0/emotion: unknown emotion 'bored'"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": [{"text": "Hi", "pause": -2}]})").find("/lines/0/pause"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": [{"text": "Hi", "emotion": "sad", "intensity": 2}]})")
                .find("/lines/0/intensity"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": [{"text": "Hi [sad"}]})").find("/lines/0/text: '[' is not closed"),
            std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": [{"txt": "Hi"}]})").find("bulletin.txt: /lines/0"), std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": []})").find("says nothing"), std::string::npos);
  EXPECT_NE(refusal(R"({"version": 1, "lines": [)").find("bulletin.txt"), std::string::npos);
}

TEST(PresenterScript, FilesOverTheLimitAreRefusedBeforeReading) {
  const std::filesystem::path dir = testing_support::freshTempDir("presenter_script");
  const std::filesystem::path big = dir / "big.txt";
  std::ofstream(big) << std::string(kMaxPresenterScriptBytes + 10, 'a');
  auto script = loadPresenterScript(big);
  ASSERT_FALSE(script.ok());
  EXPECT_NE(script.error().message.find("over the script limit of 1 MB"), std::string::npos);
  auto missing = loadPresenterScript(dir / "missing.txt");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("missing.txt: cannot open the script"), std::string::npos);
}

}  // namespace
}  // namespace app
