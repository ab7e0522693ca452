// OBJ keyframe sets (neutral.obj + one OBJ per expression -> one model with
// morph targets), as `facial convert` and the face loader read them. One
// input holds both files: the neutral, a line "#%target", the target (no
// such line: the target is the neutral itself). A line "#%match-by-position"
// in the neutral turns on the re-pairing of re-ordered vertices.
#include <string>
#include <string_view>

#include "engine/scene/model_check.h"
#include "importers/obj_keyframes.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  constexpr std::string_view kSeparator = "\n#%target\n";
  const size_t split = text.find(kSeparator);
  const std::string_view neutral = split == std::string_view::npos ? text : text.substr(0, split);
  const std::string_view target = split == std::string_view::npos ? text : text.substr(split + kSeparator.size());

  importers::ObjKeyframeOptions options;
  options.matchByPosition = neutral.find("#%match-by-position") != std::string_view::npos;
  const auto neutralPath = fuzz::writeInput("neutral.obj", neutral);
  const importers::ObjTargetFile targets[] = {{"smile", fuzz::writeInput("smile.obj", target)}};
  auto imported = importers::importObjKeyframes(neutralPath, targets, options);
  if (imported) {
    const auto consistent = eng::checkModel(imported->model);
    FUZZ_PROPERTY(consistent.ok(), "OBJ keyframe model fails checkModel: " + consistent.error().message);
  }
  return 0;
}
