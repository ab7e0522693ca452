// The order of the glTF model builder's steps, and the extensions a file may require.
#include "engine/scene/gltf_model_builder.h"

#include <cmath>
#include <string_view>
#include <unordered_set>

#include "engine/core/work_counter.h"
#include "engine/scene/gltf_skin_reader.h"

namespace eng {

Result<Model> GltfModelBuilder::build() {
  model_.sourcePath = file_;
  if (auto ok = checkExtensions(); !ok) return ok.error();
  if (auto ok = loadImages(); !ok) return ok.error();
  loadMaterials();
  if (overBudget_) return *overBudget_;
  for (size_t m = 0; m < gltf_.meshes.size(); ++m)
    if (auto ok = loadMesh(static_cast<int>(m)); !ok) return ok.error();
  if (auto ok = loadNodes(); !ok) return ok.error();
  if (auto ok = readSkins(reader_, gltf_, model_); !ok) return fail(ok.error());
  if (auto ok = loadAnimations(); !ok) return ok.error();
  loadCalibration();
  return std::move(model_);
}

Result<void> GltfModelBuilder::checkExtensions() {
  for (const std::string& ext : gltf_.extensionsRequired)
    if (!isHandledExtension(ext))
      return fail("requires glTF extension " + ext + ", which this loader does not support", ErrorKind::Unsupported);
  // Hashed: each used name searched for among the required ones was quadratic in a long list (issue 37).
  const std::unordered_set<std::string_view> required(gltf_.extensionsRequired.begin(), gltf_.extensionsRequired.end());
  for (const std::string& ext : gltf_.extensionsUsed) {
    countWork();
    if (!required.count(ext) && !isHandledExtension(ext)) warn("optional extension " + ext + " ignored");
  }
  return {};
}

void GltfModelBuilder::loadCalibration() {
  if (!gltf_.extras.IsObject() || !gltf_.extras.Has("facialCalibration")) return;
  const tinygltf::Value& table = gltf_.extras.Get("facialCalibration");
  if (!table.IsObject()) return warn("extras.facialCalibration is not an object: ignored");
  for (const std::string& channel : table.Keys()) {
    countWork();
    const tinygltf::Value& scale = table.Get(channel);
    const double value = scale.IsNumber() ? scale.GetNumberAsDouble() : -1.0;
    if (!std::isfinite(value) || value < 0.0 || value > 1e3) {
      warn("extras.facialCalibration['" + channel + "'] is not a number from 0 to 1000: ignored");
      continue;
    }
    model_.calibration.emplace_back(channel, float(value));
  }
}

}  // namespace eng
