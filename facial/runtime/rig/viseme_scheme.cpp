// Visemes: lip-sync shapes. They are recognised in every scheme's report (so
// a Ready Player Me avatar's viseme_* targets are listed as visemes, not as
// unmapped emotions), and a model that has nothing but visemes gets the
// Visemes scheme: the jaw and lip units drive the closest mouth shapes.
#include <array>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

// Oculus OVRLipSync / Ready Player Me, lower case without the "viseme_" prefix.
constexpr std::array<std::string_view, 15> kOculusVisemes = {"sil", "pp", "ff", "th", "dd", "kk", "ch", "ss",
                                                             "nn",  "rr", "aa", "e",  "i",  "o",  "u"};

std::vector<uint32_t> findOculus(std::span<const std::string> names, std::string_view viseme) {
  return findShapesByKey(names, "viseme_" + std::string(viseme));
}

}  // namespace

std::string shapeKey(std::string_view name) {
  if (const size_t cut = name.find_last_of(".:|"); cut != std::string_view::npos) name = name.substr(cut + 1);
  return asciiLower(name);
}

std::vector<uint32_t> findShapesByKey(std::span<const std::string> names, std::string_view key) {
  std::vector<uint32_t> found;
  for (uint32_t t = 0; t < names.size(); ++t)
    if (shapeKey(names[t]) == key) found.push_back(t);
  return found;
}

bool isVisemeName(std::string_view name) {
  const std::string key = shapeKey(name);
  if (key.compare(0, 7, "viseme_") == 0) {
    for (std::string_view v : kOculusVisemes)
      if (key.size() == 7 + v.size() && key.compare(7, std::string::npos, v) == 0) return true;
    return false;
  }
  for (std::string_view v : {"aa", "ih", "ou", "ee", "oh"})
    if (key == v) return true;
  for (std::string_view v : {"fcl_mth_a", "fcl_mth_i", "fcl_mth_u", "fcl_mth_e", "fcl_mth_o"})
    if (key == v) return true;
  return false;
}

SchemeRecognition recogniseVisemes(std::span<const std::string> targetNames) {
  SchemeRecognition r;
  for (const std::string& name : targetNames) r.recognised += isVisemeName(name) ? 1 : 0;
  r.detail = std::to_string(r.recognised) + " of " + std::to_string(targetNames.size()) + " targets are visemes";
  return r;
}

void mapVisemes(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  struct Row {
    std::string_view channel;
    std::string_view viseme;
    float gain;
  };
  // The open vowel for the jaw, the bilabial closure for pressed lips, the
  // spread vowel for stretched lips: the shapes a face also makes without speech.
  constexpr std::array kRows = {Row{"AU26_JawDrop", "aa", 0.7f}, Row{"AU25_LipsPart", "aa", 0.2f},
                                Row{"AU24_LipPressor", "pp", 0.6f}, Row{"AU20_LipStretcher", "e", 0.4f}};
  for (const Row& row : kRows)
    for (uint32_t t : findOculus(names, row.viseme)) builder.add(*actionUnitIndex(row.channel), t, row.gain);
  builder.note("a lip-sync (viseme) rig: only the jaw and lips follow the action units (AU26/AU25 -> viseme_aa, "
               "AU24 -> viseme_PP, AU20 -> viseme_E); emotions have no shapes to drive");
}

}  // namespace facial
