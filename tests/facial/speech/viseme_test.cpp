// The viseme set's names and mouth shapes.
#include "facial/runtime/speech/viseme.h"

#include <gtest/gtest.h>

using namespace facial;

TEST(Viseme, NamesReadBackAsTheirViseme) {
  for (size_t i = 0; i < kVisemeCount; ++i) {
    const Viseme v = static_cast<Viseme>(i);
    EXPECT_EQ(visemeFromName(visemeName(v)), v) << visemeName(v);
  }
  EXPECT_EQ(visemeName(Viseme::kk), "kk");
  EXPECT_EQ(visemeFromName("PP"), Viseme::PP);
  EXPECT_FALSE(visemeFromName("pp")) << "names are exact, as the Oculus set writes them";
  EXPECT_EQ(visemeNameList(), "sil, PP, FF, TH, DD, kk, CH, SS, nn, RR, aa, E, I, O or U");
}

TEST(Viseme, MouthShapesOrderTheOpenings) {
  EXPECT_EQ(mouthShapeOf(Viseme::PP).lipClosure, 1.0f);
  EXPECT_EQ(mouthShapeOf(Viseme::sil).jawOpen, 0.0f);
  EXPECT_GT(mouthShapeOf(Viseme::aa).jawOpen, mouthShapeOf(Viseme::E).jawOpen);
  EXPECT_GT(mouthShapeOf(Viseme::E).jawOpen, mouthShapeOf(Viseme::I).jawOpen);
  EXPECT_GT(mouthShapeOf(Viseme::U).lipRounding, mouthShapeOf(Viseme::I).lipRounding);
  EXPECT_EQ(mouthChannelName(MouthChannel::LipClosure), "lipClosure");
}
