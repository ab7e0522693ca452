// CANDIDE-3 .wfm text (Ahlberg 2001): vertices, faces, animation and shape
// units, turned into a model with morph targets on a Loop-subdivided mask.
#include <string_view>

#include "engine/scene/model_check.h"
#include "importers/candide_import.h"
#include "fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  auto model = importers::parseCandide3(text, "input.wfm");
  if (model) {
    const auto consistent = eng::checkModel(*model);
    FUZZ_PROPERTY(consistent.ok(), "CANDIDE model fails checkModel: " + consistent.error().message);
  }
  return 0;
}
