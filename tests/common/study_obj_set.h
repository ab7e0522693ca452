#pragma once
// The study's way of handing over a face, written by tests themselves: one
// OBJ per expression, same mesh (a model posed with each basic preset),
// under artist-style names no built-in rig scheme recognises (smile.obj,
// frown.obj, ...), so a rig map is what makes the converted set usable.
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "engine/scene/model.h"

namespace testing_support {

struct StudySetFile {
  const char* preset;  // data/expressions.json
  const char* file;    // the OBJ's name, hence the converted target's
};
// neutral first, then the six emotions.
inline constexpr StudySetFile kStudySet[] = {{"neutral", "neutral"}, {"happy", "smile"},  {"sad", "frown"},
                                             {"anger", "scowl"},     {"fear", "dread"},   {"surprise", "gasp"},
                                             {"disgust", "sneer"}};

// The whole model (every mesh instance, world space) posed with `weights`
// (flat, eng::WeightLayout order) as one OBJ: positions and triangles, no
// normals (the converter makes them).
void writePosedObj(const eng::Model& model, std::span<const float> weights, const std::filesystem::path& path);

// Fills `weights` with preset `preset` at full intensity; false (after a test failure) when it cannot.
using PresetPose = std::function<bool(const char* preset, std::vector<float>& weights)>;
// kStudySet as <folder>/<file>.obj, the model posed by `pose`.
void writeStudyObjSet(const eng::Model& model, size_t weightCount, const PresetPose& pose,
                      const std::filesystem::path& folder);

// A rig map binding each emotion of kStudySet to its target at `gain`.
std::string studyRigMapJson(float gain);

}  // namespace testing_support
