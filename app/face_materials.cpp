#include "app/face_materials.h"

#include <algorithm>
#include <string>

#include "app/face_setup.h"
#include "engine/vk/draw/gpu_model.h"

namespace app {

eng::Result<FaceMaterials> FaceMaterials::create(const FaceSetup& face) {
  FaceMaterials out;
  const facial::VrmExpressionSet* vrm = face.rig().expressionStage();
  if (!vrm || !vrm->hasMaterialBinds()) return out;
  const eng::Model& model = face.model();
  if (model.materials.size() != vrm->materialCount)
    return eng::makeError(eng::ErrorKind::Malformed, model.sourcePath + ": the VRM expressions address " + std::to_string(vrm->materialCount) +
                          " materials, the model has " + std::to_string(model.materials.size()));
  out.vrm_ = face.rig().sharedExpressionStage();
  out.rest_.resize(model.materials.size());
  for (size_t m = 0; m < model.materials.size(); ++m) {
    const eng::Material& mat = model.materials[m];
    out.rest_[m].color = {mat.baseColorFactor.r, mat.baseColorFactor.g, mat.baseColorFactor.b, mat.baseColorFactor.a};
    out.rest_[m].emission = {mat.emissiveFactor.r, mat.emissiveFactor.g, mat.emissiveFactor.b};
    if (const std::optional<eng::ToonShading>& t = mat.toon) {
      out.rest_[m].shade = {t->shadeColor.r, t->shadeColor.g, t->shadeColor.b};
      out.rest_[m].rim = {t->rimColor.r, t->rimColor.g, t->rimColor.b};
      out.rest_[m].outline = {t->outlineColor.r, t->outlineColor.g, t->outlineColor.b};
      out.rest_[m].matcap = {t->matcapFactor.r, t->matcapFactor.g, t->matcapFactor.b};
    }
  }
  out.moved_ = out.rest_;
  out.effective_.assign(vrm->expressions.size(), 0.0f);
  // Each record starts as the material draws itself (its MToon values kept);
  // update() moves the bound colours and texture transforms.
  out.materials_.clear();
  for (const eng::Material& mat : model.materials) out.materials_.push_back(eng::vk::instanceMaterial(mat));
  if (auto rest = out.update(out.effective_); !rest) return rest.error();
  return out;
}

eng::Result<void> FaceMaterials::update(std::span<const float> expressionWeights) {
  if (!vrm_) return {};
  if (auto effective = vrm_->effectiveWeights(expressionWeights, effective_); !effective) return effective;
  if (auto moved = vrm_->applyMaterials(effective_, rest_, moved_); !moved) return moved;
  // Summed deltas may overshoot: a colour factor stays in [0, 1], emission non-negative.
  for (size_t m = 0; m < moved_.size(); ++m) {
    const facial::VrmMaterialState& s = moved_[m];
    eng::vk::InstanceMaterial& out = materials_[m];
    out.baseColorFactor = glm::clamp(glm::vec4(s.color[0], s.color[1], s.color[2], s.color[3]), 0.0f, 1.0f);
    out.emissive = glm::vec4(glm::max(glm::vec3(s.emission[0], s.emission[1], s.emission[2]), 0.0f), 0.0f);
    out.uvTransform = glm::vec4(s.uvScale[0], s.uvScale[1], s.uvOffset[0], s.uvOffset[1]);
    // MToon colours (drawn by toon materials only; w keeps the record's own value).
    auto rgb = [](const std::array<float, 3>& c) { return glm::max(glm::vec3(c[0], c[1], c[2]), 0.0f); };
    out.toonShade = glm::vec4(rgb(s.shade), out.toonShade.w);
    out.toonRim = glm::vec4(rgb(s.rim), out.toonRim.w);
    out.toonOutline = glm::vec4(rgb(s.outline), out.toonOutline.w);
    out.toonMatcap = glm::vec4(rgb(s.matcap), out.toonMatcap.w);
  }
  return {};
}

}  // namespace app
