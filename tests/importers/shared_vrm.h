#pragma once
// The rig of one of ../shared's small VRM avatars (modifier_shapekey_vrm0/1:
// one shape key "A" bound by their expressions), for the tests that check how
// a VRM's expressions drive it. Callers check FACIAL_REQUIRE_SHARED() first.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "facial/runtime/rig/rig_mapping.h"
#include "importers/vrm_import.h"
#include "tests/common/test_support.h"

namespace vrm_test {

struct SharedVrmRig {
  std::shared_ptr<const facial::VrmExpressionSet> expressions;
  facial::RigMapping rig;
};

// Fails the calling test (and returns nullopt) when the file or its rig does not load.
inline std::optional<SharedVrmRig> sharedVrmRig(const std::string& file) {
  auto set = importers::findVrmExpressions(testing_support::sharedDir() / "assets" / "vrm" / file);
  if (!set || !set->has_value()) {
    ADD_FAILURE() << file << ": " << (set ? "no VRM expressions" : set.error().message);
    return std::nullopt;
  }
  auto shared = std::make_shared<const facial::VrmExpressionSet>(std::move(**set));
  auto rig = facial::buildVrmRigMapping(shared, std::vector<std::string>{"A"});
  if (!rig) {
    ADD_FAILURE() << file << ": " << rig.error().message;
    return std::nullopt;
  }
  return SharedVrmRig{shared, std::move(*rig)};
}

}  // namespace vrm_test
