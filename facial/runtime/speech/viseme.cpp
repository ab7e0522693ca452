#include "facial/runtime/speech/viseme.h"

#include "engine/core/enum_names.h"

namespace facial {
namespace {

using V = Viseme;
constexpr eng::EnumName<Viseme> kVisemeNames[] = {{V::sil, "sil"}, {V::PP, "PP"}, {V::FF, "FF"}, {V::TH, "TH"},
                                                     {V::DD, "DD"},   {V::kk, "kk"}, {V::CH, "CH"}, {V::SS, "SS"},
                                                     {V::nn, "nn"},   {V::RR, "RR"}, {V::aa, "aa"}, {V::E, "E"},
                                                     {V::I, "I"},     {V::O, "O"},   {V::U, "U"}};
static_assert(std::size(kVisemeNames) == kVisemeCount);

constexpr eng::EnumName<MouthChannel> kMouthChannelNames[] = {{MouthChannel::JawOpen, "jawOpen"},
                                                                 {MouthChannel::LipClosure, "lipClosure"},
                                                                 {MouthChannel::LipRounding, "lipRounding"}};
static_assert(std::size(kMouthChannelNames) == kMouthChannelCount);

// Jaw, closure, rounding per viseme, in enum order. Rest (sil) is the closed,
// relaxed mouth (Rhubarb's X); PP the pressed lips; the vowels open the jaw
// from I (least) over E and O to aa; O and U (and CH, RR in English) round.
constexpr std::array<MouthShape, kVisemeCount> kMouthShapes = {{
    {0.00f, 1.0f, 0.0f},  // sil
    {0.00f, 1.0f, 0.0f},  // PP
    {0.10f, 0.4f, 0.0f},  // FF: lower lip under the upper teeth
    {0.15f, 0.0f, 0.0f},  // TH
    {0.20f, 0.0f, 0.0f},  // DD
    {0.25f, 0.0f, 0.0f},  // kk
    {0.15f, 0.0f, 0.6f},  // CH: protruded lips
    {0.10f, 0.0f, 0.0f},  // SS: teeth together
    {0.15f, 0.0f, 0.0f},  // nn
    {0.20f, 0.0f, 0.4f},  // RR
    {1.00f, 0.0f, 0.0f},  // aa
    {0.55f, 0.0f, 0.0f},  // E
    {0.30f, 0.0f, 0.0f},  // I
    {0.60f, 0.0f, 0.7f},  // O
    {0.30f, 0.0f, 1.0f},  // U
}};

}  // namespace

std::string_view visemeName(Viseme viseme) { return eng::nameOf(kVisemeNames, viseme); }
std::optional<Viseme> visemeFromName(std::string_view name) { return eng::valueNamed(kVisemeNames, name); }
std::string visemeNameList() { return eng::nameList(kVisemeNames); }
std::string_view mouthChannelName(MouthChannel channel) { return eng::nameOf(kMouthChannelNames, channel); }
const MouthShape& mouthShapeOf(Viseme viseme) { return kMouthShapes[static_cast<size_t>(viseme)]; }

}  // namespace facial
