// The window demo's script format (app/window_script.h): the Speak box's
// actions, whose text is the rest of the line.
#include "app/window_script.h"

#include <gtest/gtest.h>

namespace {

using Kind = app::ScriptAction::Kind;

TEST(WindowScript, SayTakesTheRestOfTheLineAsItsText) {
  auto script = app::parseWindowScript("1.0 say-lang vi\n1.5 say Xin   chào, đây là   bản tin!  # a comment\n2 say-stop\n",
                                       "s.txt");
  ASSERT_TRUE(script) << script.error().message;
  ASSERT_EQ(script->size(), 3u);
  EXPECT_EQ((*script)[0].kind, Kind::SayLanguage);
  EXPECT_EQ((*script)[0].name, "vi");
  EXPECT_EQ((*script)[1].kind, Kind::Say);
  EXPECT_EQ((*script)[1].name, "Xin chào, đây là bản tin!");
  EXPECT_FLOAT_EQ((*script)[1].time, 1.5f);
  EXPECT_EQ((*script)[2].kind, Kind::SayStop);
}

TEST(WindowScript, SayWithoutTextOrALanguageIsRefusedNamingTheLine) {
  auto empty = app::parseWindowScript("1.0 say\n", "s.txt");
  ASSERT_FALSE(empty);
  EXPECT_EQ(empty.error().message, "s.txt:1: 'say' needs the text to speak");
  auto language = app::parseWindowScript("0.5 trigger happy\n1.0 say-lang\n", "s.txt");
  ASSERT_FALSE(language);
  EXPECT_EQ(language.error().message, "s.txt:2: 'say-lang' takes 1 argument(s), got 0");
  auto extra = app::parseWindowScript("1.0 say-stop now\n", "s.txt");
  ASSERT_FALSE(extra);
  EXPECT_EQ(extra.error().message, "s.txt:1: 'say-stop' takes 0 argument(s), got 1");
}

}  // namespace
