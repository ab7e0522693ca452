#pragma once
// The built-in rig-mapping schemes behind buildRigMapping(). Each one says how
// many of a model's target names it recognises (detection) and fills a
// builder with (input, target, gain) entries (mapping). One scheme per .cpp.
#include <cctype>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "facial/runtime/rig/rig_mapping.h"

namespace facial {

struct SchemeRecognition {
  size_t recognised = 0;  // target names the scheme understands
  std::string detail;     // for RigMappingReport::detail
};

SchemeRecognition recogniseActionUnitNames(std::span<const std::string> targetNames);
void mapActionUnitNames(RigMappingBuilder& builder);

SchemeRecognition recogniseCandide3(std::span<const std::string> targetNames);
void mapCandide3(RigMappingBuilder& builder);

SchemeRecognition recogniseArkit52(std::span<const std::string> targetNames);
void mapArkit52(RigMappingBuilder& builder);

SchemeRecognition recogniseExpressions(std::span<const std::string> targetNames);
void mapExpressions(RigMappingBuilder& builder);

SchemeRecognition recogniseVRoid(std::span<const std::string> targetNames);
void mapVRoid(RigMappingBuilder& builder);

SchemeRecognition recogniseVisemes(std::span<const std::string> targetNames);
void mapVisemes(RigMappingBuilder& builder);

// A target name as lip-sync shapes are matched: after the last '.', ':' or
// '|' (mesh prefixes), lower case; and the targets whose key is `key`.
std::string shapeKey(std::string_view name);
std::vector<uint32_t> findShapesByKey(std::span<const std::string> names, std::string_view key);

inline std::string asciiLower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace facial
