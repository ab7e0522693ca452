// The viseme block of a rig mapping (rig_mapping.h, "Viseme block"): how each
// kind of face realises the 15 Oculus visemes. The first realisation the
// rig's names allow wins: its own viseme shapes, then vowel shapes (VRM,
// VRoid), then ARKit's mouth shapes, then the lip and jaw action units
// through the rig's own AU rows (FACS-named rigs, CANDIDE-3).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/arkit_names.h"
#include "facial/runtime/rig/candide_units.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/rig/rig_schemes.h"
#include "facial/runtime/speech/viseme_action_units.h"

namespace facial {
namespace {



float mouthShapeDistance(Viseme a, Viseme b) {
  const MouthShape& x = mouthShapeOf(a);
  const MouthShape& y = mouthShapeOf(b);
  return std::abs(x.jawOpen - y.jawOpen) + std::abs(x.lipClosure - y.lipClosure) + std::abs(x.lipRounding - y.lipRounding);
}

// Rest (sil) on a viseme face: Ready Player Me's viseme_sil is empty and its
// neutral mouth hangs parted (on rpm-visemes.glb the lip gap is 0.7 % of the
// face height, an eighth of aa's, and viseme_PP closes it at 1), so between
// words and after a line the lips would stay open; rest also takes this much
// of viseme_PP, which brings the lips together without the press.
constexpr float kRestClosure = 0.8f;

// viseme_* targets drive themselves; a viseme the face lacks borrows the
// present one closest in mouth shape (jaw, closure, rounding), so a face with
// five visemes still speaks every phoneme. sil has no shape of its own.
bool mapOculusVisemes(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  std::array<std::vector<uint32_t>, kVisemeCount> found;
  size_t present = 0;
  for (size_t v = 0; v < kVisemeCount; ++v) {
    found[v] = findShapesByKey(names, asciiLower(rigVisemeInputName(Viseme(v))));
    present += found[v].empty() ? 0 : 1;
  }
  if (present == 0) return false;
  std::string borrowed;
  for (size_t v = 0; v < kVisemeCount; ++v) {
    size_t source = v;
    if (found[v].empty()) {
      if (Viseme(v) == Viseme::sil) continue;
      float best = std::numeric_limits<float>::infinity();
      for (size_t w = 1; w < kVisemeCount; ++w)
        if (!found[w].empty() && mouthShapeDistance(Viseme(v), Viseme(w)) < best) best = mouthShapeDistance(Viseme(v), Viseme(source = w));
      borrowed += (borrowed.empty() ? "" : ", ") + std::string(visemeName(Viseme(v))) + " <- " + std::string(visemeName(Viseme(source)));
    }
    for (uint32_t t : found[source]) builder.addViseme(Viseme(v), t, 1.0f);
  }
  for (uint32_t t : found[size_t(Viseme::PP)]) builder.addViseme(Viseme::sil, t, kRestClosure);
  builder.setSpeech(std::to_string(present) + " of 15 Oculus viseme targets, identity" +
                    (found[size_t(Viseme::PP)].empty() ? "" : ", rest closes the lips (viseme_PP x0.8)") +
                    (borrowed.empty() ? std::string() : " (missing ones borrow the closest shape: " + borrowed + ")"));
  return true;
}

// Five-vowel rigs (VRM aa ih ou ee oh, VRoid's A I U E O): each viseme as a
// blend of the vowels its mouth shape is nearest to, in the order a i u e o.
// Consonants keep a small opening (the vowel the Oculus reference image of
// the consonant resembles); PP and sil are the closed mouth (all zero, or a
// closed-mouth shape when the rig has one).
constexpr std::array<std::array<float, 5>, kVisemeCount> kVowelBlend = {{
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // sil
    {0.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // PP
    {0.0f, 0.2f, 0.0f, 0.0f, 0.0f},  // FF
    {0.1f, 0.0f, 0.0f, 0.2f, 0.0f},  // TH
    {0.1f, 0.0f, 0.0f, 0.3f, 0.0f},  // DD
    {0.2f, 0.0f, 0.0f, 0.3f, 0.0f},  // kk
    {0.0f, 0.2f, 0.5f, 0.0f, 0.0f},  // CH
    {0.0f, 0.4f, 0.0f, 0.0f, 0.0f},  // SS
    {0.1f, 0.0f, 0.0f, 0.2f, 0.0f},  // nn
    {0.0f, 0.0f, 0.2f, 0.0f, 0.3f},  // RR
    {1.0f, 0.0f, 0.0f, 0.0f, 0.0f},  // aa
    {0.0f, 0.0f, 0.0f, 1.0f, 0.0f},  // E
    {0.0f, 1.0f, 0.0f, 0.0f, 0.0f},  // I
    {0.0f, 0.0f, 0.0f, 0.0f, 1.0f},  // O
    {0.0f, 0.0f, 1.0f, 0.0f, 0.0f},  // U
}};

struct VowelSpelling {
  std::string_view label;
  std::array<std::string_view, 5> vowels;  // a i u e o
  std::string_view closed;                 // a closed-mouth shape, "" when the spelling has none
  bool expressionsOnly;                    // single letters are vowels only when the names are expressions (VRM 0.x)
};
constexpr std::array kVowelSpellings = {
    VowelSpelling{"VRM 1.0 expressions aa ih ou ee oh", {"aa", "ih", "ou", "ee", "oh"}, "", false},
    VowelSpelling{"VRM 0.x expressions A I U E O", {"a", "i", "u", "e", "o"}, "", true},
    VowelSpelling{"VRoid Fcl_MTH_A I U E O", {"fcl_mth_a", "fcl_mth_i", "fcl_mth_u", "fcl_mth_e", "fcl_mth_o"},
                  "fcl_mth_close", false},
};

constexpr std::array<Viseme, 5> kVowelVisemes = {Viseme::aa, Viseme::I, Viseme::U, Viseme::E, Viseme::O};

// The controls of one vowel; on a VRM only expressions that bind something
// (many avatars bind 'aa' alone and leave the other vowels empty).
std::vector<uint32_t> vowelControls(const RigMappingBuilder& builder, std::string_view key) {
  std::vector<uint32_t> found = findShapesByKey(builder.targetNames(), key);
  if (const VrmExpressionSet* stage = builder.expressionStage())
    std::erase_if(found, [&](uint32_t c) {
      const VrmExpression& e = stage->expressions[c];
      return e.bindCount + e.materialColorBindCount + e.textureTransformBindCount == 0;
    });
  return found;
}

// A vowel the face lacks is made by the present vowel closest in mouth shape,
// no wider than its own jaw opening (e from a: a at 0.55).
std::pair<size_t, float> vowelSource(const std::array<std::vector<uint32_t>, 5>& vowels, size_t k) {
  if (!vowels[k].empty()) return {k, 1.0f};
  size_t source = k;
  for (size_t s = 0; s < 5; ++s)
    if (!vowels[s].empty() && (source == k || mouthShapeDistance(kVowelVisemes[k], kVowelVisemes[s]) <
                                                  mouthShapeDistance(kVowelVisemes[k], kVowelVisemes[source])))
      source = s;
  const float jaw = mouthShapeOf(kVowelVisemes[k]).jawOpen, sourceJaw = mouthShapeOf(kVowelVisemes[source]).jawOpen;
  return {source, std::min(1.0f, jaw / sourceJaw)};
}

bool mapVowels(RigMappingBuilder& builder, RigScheme scheme) {
  for (const VowelSpelling& spelling : kVowelSpellings) {
    if (spelling.expressionsOnly && scheme != RigScheme::Expressions) continue;
    std::array<std::vector<uint32_t>, 5> vowels;
    size_t present = 0;
    for (size_t k = 0; k < 5; ++k) present += (vowels[k] = vowelControls(builder, spelling.vowels[k])).empty() ? 0 : 1;
    if (present == 0) continue;
    std::string borrowed;
    for (size_t k = 0; k < 5; ++k) {
      const auto [source, scale] = vowelSource(vowels, k);
      if (source != k) {
        char gain[16];
        std::snprintf(gain, sizeof gain, " x%.2g", double(scale));
        borrowed += (borrowed.empty() ? "" : ", ") + std::string(spelling.vowels[k]) + " <- " +
                    std::string(spelling.vowels[source]) + gain;
      }
      for (size_t v = 0; v < kVisemeCount; ++v)
        if (kVowelBlend[v][k] > 0.0f)
          for (uint32_t t : vowels[source]) builder.addViseme(Viseme(v), t, kVowelBlend[v][k] * scale);
    }
    const std::vector<uint32_t> closed = spelling.closed.empty() ? std::vector<uint32_t>{} : vowelControls(builder, spelling.closed);
    for (uint32_t t : closed) builder.addViseme(Viseme::PP, t, 1.0f);
    builder.setSpeech(std::string(spelling.label) + " (" + std::to_string(present) + " of 5 vowels" +
                      (closed.empty() ? "" : ", closed mouth for PP") + "), a vowel blend per viseme" +
                      (borrowed.empty() ? "" : "; missing vowels borrow the closest: " + borrowed));
    return true;
  }
  return false;
}

// ARKit: each viseme composed from the mouth shapes, after the Oculus viseme
// reference images (jaw opening, lip closure and rounding as mouthShapeOf
// gives them): PP presses and rolls the lips with the jaw shut, FF rolls the
// lower lip in under the upper teeth, CH/O/U funnel and pucker, TH shows the
// tongue, aa opens the jaw. Shapes named once stand for both sides.
// Compared with TalkingHead's table (met4citizen/TalkingHead, as ported by
// VTuber tools): the same shapes per viseme, but mouthClose stays low for PP,
// since ARKit defines it as lips closed against an open jaw; with the jaw
// shut, mouthPress and mouthRoll close the lips without pulling them through.
struct ArkitPart {
  std::string_view shape;
  float weight;
};
struct ArkitViseme {
  Viseme viseme;
  std::array<ArkitPart, 4> parts;  // unused parts have an empty shape
};
constexpr std::array kArkitVisemes = {
    ArkitViseme{Viseme::PP, {{{"mouthPress", 0.5f}, {"mouthRollLower", 0.3f}, {"mouthRollUpper", 0.2f}, {"mouthClose", 0.1f}}}},
    ArkitViseme{Viseme::FF, {{{"mouthRollLower", 0.7f}, {"mouthUpperUp", 0.3f}, {"jawOpen", 0.1f}, {"mouthShrugLower", 0.2f}}}},
    ArkitViseme{Viseme::TH, {{{"jawOpen", 0.15f}, {"tongueOut", 0.4f}, {"mouthLowerDown", 0.2f}, {}}}},
    ArkitViseme{Viseme::DD, {{{"jawOpen", 0.2f}, {"mouthLowerDown", 0.2f}, {"mouthStretch", 0.1f}, {}}}},
    ArkitViseme{Viseme::kk, {{{"jawOpen", 0.25f}, {"mouthStretch", 0.2f}, {"mouthLowerDown", 0.2f}, {}}}},
    ArkitViseme{Viseme::CH, {{{"jawOpen", 0.15f}, {"mouthFunnel", 0.6f}, {"mouthUpperUp", 0.2f}, {"mouthLowerDown", 0.2f}}}},
    ArkitViseme{Viseme::SS, {{{"jawOpen", 0.1f}, {"mouthStretch", 0.4f}, {"mouthUpperUp", 0.1f}, {}}}},
    ArkitViseme{Viseme::nn, {{{"jawOpen", 0.15f}, {"mouthLowerDown", 0.2f}, {"mouthStretch", 0.1f}, {}}}},
    ArkitViseme{Viseme::RR, {{{"jawOpen", 0.2f}, {"mouthFunnel", 0.3f}, {"mouthPucker", 0.3f}, {}}}},
    ArkitViseme{Viseme::aa, {{{"jawOpen", 0.7f}, {"mouthLowerDown", 0.3f}, {}, {}}}},
    ArkitViseme{Viseme::E, {{{"jawOpen", 0.4f}, {"mouthStretch", 0.4f}, {"mouthUpperUp", 0.2f}, {}}}},
    ArkitViseme{Viseme::I, {{{"jawOpen", 0.2f}, {"mouthStretch", 0.6f}, {}, {}}}},
    ArkitViseme{Viseme::O, {{{"jawOpen", 0.45f}, {"mouthFunnel", 0.7f}, {}, {}}}},
    ArkitViseme{Viseme::U, {{{"jawOpen", 0.15f}, {"mouthPucker", 1.0f}, {"mouthFunnel", 0.15f}, {}}}},
};

bool arkitShapeIs(std::string_view canonical, std::string_view part) {
  if (canonical == part) return true;
  return canonical.size() > part.size() && canonical.substr(0, part.size()) == part &&
         (canonical.substr(part.size()) == "Left" || canonical.substr(part.size()) == "Right");
}

bool mapArkitVisemes(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  const std::span<const std::string_view> canonical = arkitBlendShapeNames();
  size_t shapes = 0;
  for (uint32_t t = 0; t < names.size(); ++t) {
    const std::optional<uint32_t> shape = arkitIndex(names[t]);
    if (!shape) continue;
    bool used = false;
    for (const ArkitViseme& row : kArkitVisemes)
      for (const ArkitPart& part : row.parts)
        if (!part.shape.empty() && arkitShapeIs(canonical[*shape], part.shape)) {
          builder.addViseme(row.viseme, t, part.weight);
          used = true;
        }
    shapes += used ? 1 : 0;
  }
  if (shapes == 0) return false;
  builder.setSpeech("composed from " + std::to_string(shapes) + " ARKit mouth shapes (jawOpen, mouthClose/Press/Roll, "
                    "mouthFunnel/Pucker, mouthStretch, mouthUpperUp/LowerDown, mouthShrug, tongueOut)");
  return true;
}

// CANDIDE-3 has no pucker or funneler; its units are linear offsets, so the
// lip stretcher run backwards draws the corners in and forward: a rounded
// viseme narrows the mouth by this much of it per unit of rounding.
constexpr float kCandideRounding = 0.6f;

void roundCandideLips(RigMappingBuilder& builder) {
  const std::span<const std::string> names = builder.targetNames();
  for (uint32_t t = 0; t < names.size(); ++t) {
    const CandideAnimationUnit* unit = findCandideUnit(names[t]);
    if (!unit || unit->facsNumber != 20) continue;
    for (size_t v = 0; v < kVisemeCount; ++v)
      if (const float rounding = mouthShapeOf(Viseme(v)).lipRounding; rounding > 0.0f)
        builder.addViseme(Viseme(v), t, -kCandideRounding * rounding);
  }
}

// Rigs driven by action units (FACS-named targets, CANDIDE-3): each viseme's
// action units (viseme_action_units.h) pushed through the rig's own AU rows.
bool mapActionUnitVisemes(RigMappingBuilder& builder) {
  size_t composed = 0;
  for (size_t v = 0; v < kVisemeCount; ++v) {
    bool any = false;
    for (const VisemeActionUnit& unit : visemeActionUnits(Viseme(v))) {
      // A unit the rig lacks gives way to its fallback (AU23 for rounding).
      const bool lacking = builder.row(*actionUnitIndex(unit.channel)).empty() && !unit.fallback.empty();
      const std::string_view channel = lacking ? unit.fallback : unit.channel;
      const float weight = lacking ? unit.fallbackWeight : unit.weight;
      for (const auto& [target, gain] : builder.row(*actionUnitIndex(channel))) {
        builder.addViseme(Viseme(v), target, weight * gain);
        any = true;
      }
    }
    composed += any ? 1 : 0;
  }
  if (composed == 0) return false;
  builder.setSpeech(std::to_string(composed) + " of 14 visemes composed from the lip and jaw action units "
                    "(AU10 AU17 AU18 AU19 AU20 AU22-AU28) through the rig's action-unit rows");
  return true;
}

// Lips cannot pucker and smile at once: a rounded viseme takes back part of
// the smile the emotion keeps through speech (mouthOwnershipTable), through
// the rig's own AU12 rows, so a happy "oo" narrows instead of stretching. The
// negative gains only lower a smile that is there: the targets clamp at 0.
// Not on signed rigs (CANDIDE-3: its smile is a negative depressor, so a
// negative smile would turn the corners down).
constexpr float kRoundingEasesSmile = 0.5f;

void easeSmileWhenRounded(RigMappingBuilder& builder) {
  if (builder.minWeight() < 0.0f || !builder.speaks()) return;
  for (const char* corner : {"AU12_LipCornerPuller_L", "AU12_LipCornerPuller_R"})
    for (const auto& [target, gain] : builder.row(*actionUnitIndex(corner)))
      for (size_t v = 0; v < kVisemeCount; ++v)
        if (const float rounding = mouthShapeOf(Viseme(v)).lipRounding; rounding > 0.0f && gain > 0.0f)
          builder.addViseme(Viseme(v), target, -kRoundingEasesSmile * rounding * gain);
}

}  // namespace

void mapSpeech(RigMappingBuilder& builder, RigScheme scheme) {
  const bool mapped = mapOculusVisemes(builder) || mapVowels(builder, scheme) ||
                      (scheme == RigScheme::Arkit52 && mapArkitVisemes(builder)) || mapActionUnitVisemes(builder);
  if (mapped && scheme == RigScheme::Candide3) roundCandideLips(builder);
  if (mapped) easeSmileWhenRounded(builder);
}

std::string cannotSpeakMessage(const RigMapping& rig, std::string_view model) {
  return std::string(model) + ": cannot speak: it has nothing to move the mouth; none of its " +
         std::to_string(rig.targetCount()) + " targets is an Oculus viseme_* shape, a VRM aa/ih/ou/ee/oh or A/I/U/E/O "
         "expression, a VRoid Fcl_MTH_A..O shape, an ARKit jawOpen/mouth* shape or a lip, jaw or tongue action unit "
         "(AU10 AU17 AU18 AU19 AU20 AU22-AU28); a rig map can name the targets that open and close it in a \"visemes\" "
         "block (data/rigmaps/README.md)";
}

}  // namespace facial
