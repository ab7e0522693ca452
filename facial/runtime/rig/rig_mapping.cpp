#include "facial/runtime/rig/rig_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "facial/runtime/rig/action_units.h"
#include "facial/runtime/rig/rig_schemes.h"

namespace facial {
namespace {

std::string formatGain(float gain) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", double(gain));
  return text;
}

// The expression stage in the report: its size, its binds, expressions that cannot show.
void describeStage(const VrmExpressionSet& vrm, RigMappingReport& report) {
  report.stage = "VRM " + std::string(vrm.specVersion == 0 ? "0.x blend shape groups" : "1.0 expressions") + ", " +
                 std::to_string(vrm.expressions.size()) + " expressions over " + std::to_string(vrm.targetCount()) +
                 " morph targets (binds: " + std::to_string(vrm.binds.size()) + " morph target, " +
                 std::to_string(vrm.materialColorBinds.size()) + " material colour, " +
                 std::to_string(vrm.textureTransformBinds.size()) + " texture transform)";
  std::string empty;
  for (const VrmExpression& e : vrm.expressions)
    if (e.bindCount == 0 && e.materialColorBindCount == 0 && e.textureTransformBindCount == 0)
      empty += (empty.empty() ? "'" : ", '") + e.name + "'";
  if (!empty.empty()) report.notes.push_back("expressions that bind nothing (no visible change on this model): " + empty);
  if (vrm.hasMaterialBinds())
    report.notes.push_back("material colour (base colour, emission; MToon shade, matcap, rim, outline) and texture transform "
                           "binds follow the expression weights in every view (per-instance material overrides)");
  for (const std::string& w : vrm.warnings) report.notes.push_back(w);
}

}  // namespace

std::string_view rigSchemeName(RigScheme scheme) {
  switch (scheme) {
    case RigScheme::ActionUnits: return "FACS action units";
    case RigScheme::Candide3: return "CANDIDE-3";
    case RigScheme::Arkit52: return "ARKit 52 blend shapes";
    case RigScheme::Expressions: return "emotion expressions (VRM)";
    case RigScheme::VRoid: return "VRoid Studio blend shapes";
    case RigScheme::Visemes: return "visemes (lip sync)";
    case RigScheme::Custom: return "custom rig map";
  }
  return "?";
}

uint32_t rigInputCount() { return static_cast<uint32_t>(actionUnits().size() + kEmotionCount); }

uint32_t emotionInput(Emotion emotion) {
  return static_cast<uint32_t>(actionUnits().size()) + static_cast<uint32_t>(emotion);
}

std::string_view rigInputName(uint32_t input) {
  const size_t channels = actionUnits().size();
  if (input < channels) return actionUnits()[input].name;
  if (input < channels + kEmotionCount) return emotionNames()[input - channels];
  return "?";
}

std::optional<uint32_t> rigInputIndex(std::string_view name) {
  if (std::optional<uint32_t> au = actionUnitIndex(name)) return au;
  if (std::optional<uint32_t> e = emotionIndex(name)) return static_cast<uint32_t>(actionUnits().size()) + *e;
  return std::nullopt;
}

std::string rigVisemeInputName(Viseme viseme) { return "viseme_" + std::string(visemeName(viseme)); }

std::optional<Viseme> rigVisemeIndex(std::string_view name) {
  const std::string key = asciiLower(name);
  const std::string_view bare = std::string_view(key).substr(key.compare(0, 7, "viseme_") == 0 ? 7 : 0);
  for (size_t v = 0; v < kVisemeCount; ++v)
    if (asciiLower(visemeName(Viseme(v))) == bare) return Viseme(v);
  return std::nullopt;
}

std::string RigMappingReport::summary() const {
  auto list = [](const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
    return out.empty() ? std::string("none") : out;
  };
  std::string text = "scheme: " + std::string(rigSchemeName(scheme));
  if (!detail.empty()) text += " (" + detail + ")";
  if (!stage.empty()) text += "\nexpression stage: " + stage;
  for (const std::string& e : emotions) text += "\nemotion " + e;
  if (!visemes.empty()) text += "\nvisemes (" + std::to_string(visemes.size()) + ", lip sync): " + list(visemes);
  text += "\nspeech: " + (speech.empty() ? std::string("none (nothing on the rig moves the mouth)") : speech);
  if (!stage.empty())
    text += "\nunmapped expressions (" + std::to_string(unmappedControls.size()) + "): " + list(unmappedControls);
  text += "\nunmapped targets (" + std::to_string(unmappedTargets.size()) + "): " + list(unmappedTargets);
  text += "\nunmapped inputs (" + std::to_string(unmappedInputs.size()) + "): " + list(unmappedInputs);
  for (const std::string& n : notes) text += "\nnote: " + n;
  return text;
}

std::span<const uint32_t> RigMapping::targets(uint32_t input) const {
  if (input + 1 >= offsets_.size()) return {};
  return std::span<const uint32_t>(entryTargets_).subspan(offsets_[input], offsets_[input + 1] - offsets_[input]);
}

std::span<const float> RigMapping::gains(uint32_t input) const {
  if (input + 1 >= offsets_.size()) return {};
  return std::span<const float>(entryGains_).subspan(offsets_[input], offsets_[input + 1] - offsets_[input]);
}

std::span<const uint32_t> RigMapping::visemeTargets(Viseme viseme) const {
  const size_t v = static_cast<size_t>(viseme);
  if (v + 1 >= visemeOffsets_.size()) return {};
  return std::span<const uint32_t>(visemeEntryTargets_).subspan(visemeOffsets_[v], visemeOffsets_[v + 1] - visemeOffsets_[v]);
}

std::span<const float> RigMapping::visemeGains(Viseme viseme) const {
  const size_t v = static_cast<size_t>(viseme);
  if (v + 1 >= visemeOffsets_.size()) return {};
  return std::span<const float>(visemeEntryGains_).subspan(visemeOffsets_[v], visemeOffsets_[v + 1] - visemeOffsets_[v]);
}

eng::Result<void> RigMapping::validate() const {
  const size_t inputs = rigInputCount();
  if (offsets_.size() != inputs + 1)
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: " + std::to_string(offsets_.size()) + " row offsets, expected " +
                          std::to_string(inputs + 1));
  if (entryTargets_.size() != entryGains_.size())
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: " + std::to_string(entryTargets_.size()) + " entry targets but " +
                          std::to_string(entryGains_.size()) + " gains");
  if (offsets_.front() != 0 || offsets_.back() != entryTargets_.size())
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: row offsets span [" + std::to_string(offsets_.front()) + ", " +
                          std::to_string(offsets_.back()) + "), expected [0, " +
                          std::to_string(entryTargets_.size()) + ")");
  for (size_t i = 0; i < inputs; ++i)
    if (offsets_[i] > offsets_[i + 1])
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: row offsets decrease at input " + std::to_string(i) + " (" +
                            std::string(rigInputName(static_cast<uint32_t>(i))) + ")");
  const size_t controls = controlNames().size();
  for (size_t e = 0; e < entryTargets_.size(); ++e) {
    if (entryTargets_[e] >= controls)
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: entry " + std::to_string(e) + " drives " + (stage_ ? "expression " : "target ") +
                            std::to_string(entryTargets_[e]) + " of " + std::to_string(controls));
    if (!std::isfinite(entryGains_[e]))
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: entry " + std::to_string(e) + " has a non-finite gain");
  }
  if (visemeOffsets_.size() != kVisemeCount + 1 || visemeOffsets_.back() != visemeEntryTargets_.size() ||
      visemeEntryTargets_.size() != visemeEntryGains_.size())
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: the viseme block has " + std::to_string(visemeOffsets_.size()) +
                          " row offsets for " + std::to_string(visemeEntryTargets_.size()) + " entries");
  for (size_t e = 0; e < visemeEntryTargets_.size(); ++e)
    if (visemeEntryTargets_[e] >= controls || !std::isfinite(visemeEntryGains_[e]))
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: viseme entry " + std::to_string(e) + " drives control " +
                            std::to_string(visemeEntryTargets_[e]) + " of " + std::to_string(controls) + " or is not finite");
  for (uint32_t t : speechDrivenTargets_)
    if (t >= targetNames_.size())
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: speech-driven target " + std::to_string(t) + " of " +
                            std::to_string(targetNames_.size()));
  for (uint32_t t : drivenTargets_)
    if (t >= targetNames_.size())
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: driven target " + std::to_string(t) + " of " +
                            std::to_string(targetNames_.size()));
  if (!(minWeight_ < maxWeight_))
    return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: empty weight range [" + std::to_string(minWeight_) + ", " +
                          std::to_string(maxWeight_) + "]");
  if (stage_) {
    if (stage_->expressions.size() != controlNames_.size() || stage_->targetCount() != targetNames_.size())
      return eng::makeError(eng::ErrorKind::Malformed, "rig mapping: the expression stage has " + std::to_string(stage_->expressions.size()) +
                            " expressions and " + std::to_string(stage_->targetCount()) + " targets, the mapping " +
                            std::to_string(controlNames_.size()) + " and " + std::to_string(targetNames_.size()));
    if (auto valid = stage_->validate(); !valid) return valid;
  }
  return {};
}

eng::Result<void> RigMapping::checkInputs(std::span<const float> auWeights, std::span<const float> emotionWeights) const {
  const size_t channels = actionUnits().size();
  if (auWeights.size() != channels || (!emotionWeights.empty() && emotionWeights.size() != kEmotionCount))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: got " + std::to_string(auWeights.size()) + " AU weights, " +
                          std::to_string(emotionWeights.size()) + " emotion weights; expected " +
                          std::to_string(channels) + ", 0 or " + std::to_string(kEmotionCount));
  for (size_t i = 0; i < auWeights.size(); ++i)
    if (!std::isfinite(auWeights[i]))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: AU weight " + std::string(actionUnits()[i].name) + " is not finite");
  for (size_t i = 0; i < emotionWeights.size(); ++i)
    if (!std::isfinite(emotionWeights[i]))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: emotion weight " + std::string(emotionNames()[i]) + " is not finite");
  return {};
}

void RigMapping::accumulate(std::span<const float> auWeights, std::span<const float> emotionWeights,
                            std::span<const float> visemeWeights, std::span<float> rows) const {
  const uint32_t channels = static_cast<uint32_t>(actionUnits().size());
  auto add = [&](uint32_t input, float weight) {
    if (weight == 0.0f) return;
    for (uint32_t e = offsets_[input]; e < offsets_[input + 1]; ++e) rows[entryTargets_[e]] += weight * entryGains_[e];
  };
  for (uint32_t i = 0; i < channels; ++i) add(i, auWeights[i]);
  for (uint32_t i = 0; i < emotionWeights.size(); ++i) add(channels + i, emotionWeights[i]);
  for (uint32_t v = 0; v < visemeWeights.size(); ++v) {
    if (visemeWeights[v] == 0.0f) continue;
    for (uint32_t e = visemeOffsets_[v]; e < visemeOffsets_[v + 1]; ++e)
      rows[visemeEntryTargets_[e]] += visemeWeights[v] * visemeEntryGains_[e];
  }
}

eng::Result<void> RigMapping::apply(std::span<const float> auWeights, std::span<const float> emotionWeights,
                                    std::span<float> targetWeights, std::span<float> expressionWeights) const {
  return applyWithVisemes(auWeights, emotionWeights, {}, targetWeights, expressionWeights);
}

eng::Result<void> RigMapping::applyWithVisemes(std::span<const float> auWeights, std::span<const float> emotionWeights,
                                               std::span<const float> visemeWeights, std::span<float> targetWeights,
                                               std::span<float> expressionWeights) const {
  if (!visemeWeights.empty() && visemeWeights.size() != kVisemeCount)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: got " + std::to_string(visemeWeights.size()) +
                          " viseme weights; expected 0 or " + std::to_string(kVisemeCount));
  for (size_t v = 0; v < visemeWeights.size(); ++v)
    if (!std::isfinite(visemeWeights[v]))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: viseme weight " + rigVisemeInputName(Viseme(v)) + " is not finite");
  const size_t channels = actionUnits().size();
  if (auWeights.size() != channels || (!emotionWeights.empty() && emotionWeights.size() != kEmotionCount) ||
      targetWeights.size() != targetNames_.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: apply got " + std::to_string(auWeights.size()) + " AU weights, " +
                          std::to_string(emotionWeights.size()) + " emotion weights, " +
                          std::to_string(targetWeights.size()) + " target weights; expected " +
                          std::to_string(channels) + ", 0 or " + std::to_string(kEmotionCount) + ", " +
                          std::to_string(targetNames_.size()));
  if (!expressionWeights.empty() && (!stage_ || expressionWeights.size() != controlNames_.size()))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping: room for " + std::to_string(expressionWeights.size()) +
                          " expression weights, the rig has " +
                          (stage_ ? std::to_string(controlNames_.size()) : std::string("no expression stage")));
  if (auto valid = checkInputs(auWeights, emotionWeights); !valid) return valid;
  // Without visemes exactly the pose-driven targets are written, as before the viseme block.
  const std::span<const uint32_t> written = visemeWeights.empty() ? drivenTargets_ : speechDrivenTargets_;
  if (!stage_) {
    for (uint32_t t : written) targetWeights[t] = 0.0f;
    accumulate(auWeights, emotionWeights, visemeWeights, targetWeights);
    for (uint32_t t : written) targetWeights[t] = std::clamp(targetWeights[t], minWeight_, maxWeight_);
    return {};
  }
  // Rows land on the expressions; the stage resolves them (it writes every
  // target, only the driven ones are kept).
  std::fill(controlScratch_.begin(), controlScratch_.end(), 0.0f);
  accumulate(auWeights, emotionWeights, visemeWeights, controlScratch_);
  for (float& w : controlScratch_) w = std::clamp(w, 0.0f, 1.0f);
  if (auto resolved = stage_->apply(controlScratch_, stageScratch_); !resolved) return resolved;
  if (!expressionWeights.empty()) std::copy(controlScratch_.begin(), controlScratch_.end(), expressionWeights.begin());
  for (uint32_t t : written) targetWeights[t] = std::clamp(stageScratch_[t], minWeight_, maxWeight_);
  return {};
}

namespace {
template <class Entry>
void layOutSparseRows(const std::vector<Entry>& entries, size_t inputs, std::vector<uint32_t>& offsets,
                      std::vector<uint32_t>& targets, std::vector<float>& gains) {
  std::vector<Entry> sorted = entries;
  std::sort(sorted.begin(), sorted.end(), [](const Entry& a, const Entry& b) {
    return a.input != b.input ? a.input < b.input : a.target < b.target;
  });
  offsets.assign(inputs + 1, 0);
  for (size_t i = 0; i < sorted.size(); ++i) {
    const Entry& e = sorted[i];
    if (i > 0 && sorted[i - 1].input == e.input && sorted[i - 1].target == e.target) {
      gains.back() += e.gain;
      continue;
    }
    targets.push_back(e.target);
    gains.push_back(e.gain);
    ++offsets[e.input + 1];
  }
  for (size_t i = 0; i < inputs; ++i) offsets[i + 1] += offsets[i];
}
}  // namespace

RigMappingBuilder::RigMappingBuilder(RigScheme scheme, std::span<const std::string> targetNames)
    : scheme_(scheme), targetNames_(targetNames.begin(), targetNames.end()) {}

RigMappingBuilder RigMappingBuilder::startingFrom(const RigMapping& rig, bool withRows, bool withVisemes) {
  RigMappingBuilder builder(rig.scheme(), rig.controlNames());
  if (rig.expressionStage())
    builder.setExpressionStage(rig.sharedExpressionStage(),
                               std::vector<std::string>(rig.targetNames().begin(), rig.targetNames().end()));
  builder.setDetail(rig.report().detail);
  for (const std::string& note : rig.report().notes) builder.note(note);
  builder.setWeightRange(rig.minWeight(), rig.maxWeight());
  for (uint32_t input = 0; withRows && input < rigInputCount(); ++input) {
    const auto targets = rig.targets(input);
    const auto gains = rig.gains(input);
    for (size_t i = 0; i < targets.size(); ++i) builder.add(input, targets[i], gains[i]);
  }
  for (size_t v = 0; withVisemes && v < kVisemeCount; ++v) {
    const auto targets = rig.visemeTargets(Viseme(v));
    const auto gains = rig.visemeGains(Viseme(v));
    for (size_t i = 0; i < targets.size(); ++i) builder.addViseme(Viseme(v), targets[i], gains[i]);
  }
  if (withVisemes) builder.setSpeech(rig.report().speech);
  return builder;
}

void RigMappingBuilder::add(uint32_t input, uint32_t target, float gain) { entries_.push_back({input, target, gain}); }

void RigMappingBuilder::addViseme(Viseme viseme, uint32_t target, float gain) {
  visemeEntries_.push_back({static_cast<uint32_t>(viseme), target, gain});
}

std::vector<std::pair<uint32_t, float>> RigMappingBuilder::row(uint32_t input) const {
  std::vector<std::pair<uint32_t, float>> out;
  for (const Entry& e : entries_) {
    if (e.input != input) continue;
    auto same = std::find_if(out.begin(), out.end(), [&](const auto& p) { return p.first == e.target; });
    if (same != out.end()) same->second += e.gain;
    else out.emplace_back(e.target, e.gain);
  }
  return out;
}

void RigMappingBuilder::setWeightRange(float minWeight, float maxWeight) {
  minWeight_ = minWeight;
  maxWeight_ = maxWeight;
}

void RigMappingBuilder::setExpressionStage(std::shared_ptr<const VrmExpressionSet> stage,
                                           std::vector<std::string> morphTargetNames) {
  stage_ = std::move(stage);
  morphTargetNames_ = std::move(morphTargetNames);
}

// The steps: entries checked, laid out as rows, which targets the rows
// drive (through the stage's binds when there is one), how each emotion is
// realised; then the mapping checks itself.
eng::Result<RigMapping> RigMappingBuilder::build() const {
  if (auto ok = checkEntries(); !ok) return ok.error();
  RigMapping mapping;
  layOutRows(mapping);
  layOutVisemeRows(mapping);
  if (auto ok = markDrivenTargets(mapping); !ok) return ok.error();
  markSpeechTargets(mapping);
  mapping.report_.speech = mapping.speaks() ? speech_ : std::string();
  describeEmotions(mapping);
  mapping.report_.scheme = scheme_;
  mapping.report_.detail = detail_;
  mapping.report_.notes = notes_;
  if (stage_) describeStage(*stage_, mapping.report_);
  if (eng::Result<void> valid = mapping.validate(); !valid) return valid.error();
  return mapping;
}

eng::Result<void> RigMappingBuilder::checkEntries() const {
  const uint32_t inputs = rigInputCount();
  for (const Entry& e : entries_) {
    if (e.input >= inputs)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping builder: input " + std::to_string(e.input) + " of " + std::to_string(inputs));
    if (e.target >= targetNames_.size())
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping builder: target " + std::to_string(e.target) + " of " +
                            std::to_string(targetNames_.size()) + " for input " + std::string(rigInputName(e.input)));
    if (!std::isfinite(e.gain))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping builder: non-finite gain for " + std::string(rigInputName(e.input)) + " -> " +
                            targetNames_[e.target]);
  }
  for (const Entry& e : visemeEntries_)
    if (e.input >= kVisemeCount || e.target >= targetNames_.size() || !std::isfinite(e.gain))
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping builder: viseme entry " + std::to_string(e.input) + " -> target " +
                            std::to_string(e.target) + " of " + std::to_string(targetNames_.size()) + " (gain " +
                            formatGain(e.gain) + ") is out of range");
  return {};
}

// Sorted by (input, target) with repeats merged, so every row is ascending and unique.
void RigMappingBuilder::layOutRows(RigMapping& mapping) const {
  mapping.targetNames_ = targetNames_;
  mapping.minWeight_ = minWeight_;
  mapping.maxWeight_ = maxWeight_;
  layOutSparseRows(entries_, rigInputCount(), mapping.offsets_, mapping.entryTargets_, mapping.entryGains_);
}

// The viseme block laid out as the pose rows are.
void RigMappingBuilder::layOutVisemeRows(RigMapping& mapping) const {
  layOutSparseRows(visemeEntries_, kVisemeCount, mapping.visemeOffsets_, mapping.visemeEntryTargets_,
                   mapping.visemeEntryGains_);
}

// speechDrivenTargets_: the pose-driven targets plus what the viseme rows
// reach (through the stage's binds when there is one). Runs after markDrivenTargets.
void RigMappingBuilder::markSpeechTargets(RigMapping& mapping) const {
  std::vector<bool> driven(mapping.targetNames_.size(), false);
  for (uint32_t t : mapping.drivenTargets_) driven[t] = true;
  for (uint32_t c : mapping.visemeEntryTargets_) {
    if (!stage_) {
      driven[c] = true;
      continue;
    }
    const VrmExpression& e = stage_->expressions[c];
    for (uint32_t b = e.firstBind; b < e.firstBind + e.bindCount && b < stage_->binds.size(); ++b)
      if (stage_->binds[b].target < driven.size()) driven[stage_->binds[b].target] = true;
  }
  for (uint32_t t = 0; t < driven.size(); ++t)
    if (driven[t]) mapping.speechDrivenTargets_.push_back(t);
}

// VRM's mouth presets (aa..oh, 0.x a..o) are visemes too when they are expressions.
bool RigMappingBuilder::isViseme(const std::string& name) const {
  return isVisemeName(name) || (stage_ && vrmProceduralGroup(name) == VrmProceduralGroup::Mouth);
}

// Rows address targetNames_ (the controls); with a stage they reach the
// morph targets through the driven expressions' binds. Fills the driven
// targets and the report's unmapped lists and visemes.
eng::Result<void> RigMappingBuilder::markDrivenTargets(RigMapping& mapping) const {
  std::vector<bool> drivenControl(targetNames_.size(), false);
  for (uint32_t t : mapping.entryTargets_) drivenControl[t] = true;
  std::vector<bool> driven = drivenControl;
  if (stage_) {
    if (stage_->expressions.size() != targetNames_.size() || stage_->targetCount() != morphTargetNames_.size())
      return eng::makeError(eng::ErrorKind::InvalidArgument, "rig mapping builder: the expression stage has " +
                            std::to_string(stage_->expressions.size()) + " expressions and " +
                            std::to_string(stage_->targetCount()) + " morph targets; the builder was given " +
                            std::to_string(targetNames_.size()) + " and " + std::to_string(morphTargetNames_.size()));
    mapping.stage_ = stage_;
    mapping.controlNames_ = targetNames_;
    mapping.targetNames_ = morphTargetNames_;
    mapping.controlScratch_.assign(targetNames_.size(), 0.0f);
    mapping.stageScratch_.assign(morphTargetNames_.size(), 0.0f);
    driven.assign(morphTargetNames_.size(), false);
    for (uint32_t c = 0; c < stage_->expressions.size(); ++c) {
      if (!drivenControl[c]) {
        if (!isViseme(targetNames_[c])) mapping.report_.unmappedControls.push_back(targetNames_[c]);
        continue;
      }
      const VrmExpression& e = stage_->expressions[c];
      for (uint32_t b = e.firstBind; b < e.firstBind + e.bindCount && b < stage_->binds.size(); ++b)
        if (stage_->binds[b].target < driven.size()) driven[stage_->binds[b].target] = true;
    }
  }
  // A name the model has on several meshes (a head, its teeth, its beard) is named once.
  auto once = [](std::vector<std::string>& names, const std::string& name) {
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  };
  for (const std::string& name : targetNames_)
    if (isViseme(name)) once(mapping.report_.visemes, name);
  for (uint32_t t = 0; t < driven.size(); ++t) {
    if (driven[t]) mapping.drivenTargets_.push_back(t);
    else if (stage_ || !isViseme(mapping.targetNames_[t])) once(mapping.report_.unmappedTargets, mapping.targetNames_[t]);
  }
  const uint32_t inputs = rigInputCount();
  for (uint32_t i = 0; i < inputs; ++i)
    if (mapping.offsets_[i] == mapping.offsets_[i + 1]) mapping.report_.unmappedInputs.emplace_back(rigInputName(i));
  return {};
}

// How each emotion is realised ("happy <- 'smile' x0.5 (composed)"), when the rig binds emotions at all.
void RigMappingBuilder::describeEmotions(RigMapping& mapping) const {
  bool bindsEmotions = false;
  for (uint32_t e = 0; e < kEmotionCount; ++e) {
    const uint32_t input = emotionInput(Emotion(e));
    bindsEmotions |= mapping.offsets_[input] != mapping.offsets_[input + 1];
  }
  for (uint32_t e = 0; bindsEmotions && e < kEmotionCount; ++e) {
    const uint32_t input = emotionInput(Emotion(e));
    std::string line = std::string(emotionName(Emotion(e))) + " <- ";
    if (mapping.offsets_[input] == mapping.offsets_[input + 1]) line += "nothing (the rig has no such expression)";
    for (uint32_t k = mapping.offsets_[input]; k < mapping.offsets_[input + 1]; ++k) {
      line += (k == mapping.offsets_[input] ? "'" : " + '") + targetNames_[mapping.entryTargets_[k]] + "'";
      if (mapping.entryGains_[k] != 1.0f) line += " x" + formatGain(mapping.entryGains_[k]);
    }
    const uint32_t first = mapping.offsets_[input], end = mapping.offsets_[input + 1];
    if (end - first > 1 || (end - first == 1 && mapping.entryGains_[first] != 1.0f)) line += " (composed)";
    mapping.report_.emotions.push_back(std::move(line));
  }
}

}  // namespace facial
