// The shared VRM 0.x and 1.0 avatars speak through their mouth expressions
// (0.x 'a', 1.0 'aa' bind the shape key): the rig's viseme block reaches the
// morph target through the expression stage.
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "importers/vrm_import.h"
#include "tests/common/test_support.h"
#include "tests/importers/shared_vrm.h"

namespace facial {
namespace {

TEST(VrmSpeech, SharedVrm0And1AvatarsOpenTheMouthOnAa) {
  FACIAL_REQUIRE_SHARED();
  for (const char* file : {"modifier_shapekey_vrm0.vrm", "modifier_shapekey_vrm1.vrm"}) {
    auto loaded = vrm_test::sharedVrmRig(file);
    ASSERT_TRUE(loaded);
    const std::shared_ptr<const VrmExpressionSet>& shared = loaded->expressions;
    RigMapping* rig = &loaded->rig;
    ASSERT_TRUE(rig->speaks()) << file << "\n" << rig->report().summary();
    EXPECT_NE(rig->report().speech.find(shared->specVersion == 0 ? "VRM 0.x" : "VRM 1.0"), std::string::npos)
        << rig->report().speech;
    std::vector<float> au(actionUnits().size(), 0.0f), visemes(kVisemeCount, 0.0f), out(1, 0.0f);
    visemes[size_t(Viseme::aa)] = 1.0f;
    ASSERT_TRUE(rig->applyWithVisemes(au, {}, visemes, out));
    EXPECT_FLOAT_EQ(out[0], 1.0f) << file;
    visemes[size_t(Viseme::aa)] = 0.0f;
    visemes[size_t(Viseme::PP)] = 1.0f;
    ASSERT_TRUE(rig->applyWithVisemes(au, {}, visemes, out));
    EXPECT_FLOAT_EQ(out[0], 0.0f) << file;
  }
}

}  // namespace
}  // namespace facial
