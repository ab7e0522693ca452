#include "editor/app/sculpt_panel.h"

#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstring>

#include "editor/app/tooltip.h"
#include "editor/atomic_file.h"
#include "engine/scene/gltf_writer.h"
#include "engine/view/framing_bounds.h"
#include "bake/head/head_rig_spec.h"

namespace editor {

namespace {
constexpr const char* kKernelNames[] = {"biharmonic  r", "polyharmonic  r^3", "multiquadric  sqrt(r^2+c^2)"};
}

eng::Result<void> SculptPanel::create(const app::FaceSetup& face, const std::string& landmarksFile) {
  face_ = &face;
  working_ = face.model();
  rebuildWorkingLayout();
  auto surface = ModelSurface::create(working_);
  if (!surface) return surface.error();
  surface_.emplace(std::move(*surface));
  const eng::Aabb bounds = working_.bounds();
  size_ = std::max(bounds.diagonal(), 1e-6f);
  sculpt_.emplace(surface_->restPositions(), bounds);
  multiquadricC_ = 0.05f * size_;
  if (!landmarksFile.empty()) {
    auto spec = bake::loadHeadRigSpec(landmarksFile);
    if (!spec) return spec.error();
    for (const bake::LandmarkDef& l : spec->landmarks) {
      if (l.kind == bake::LandmarkDef::Kind::Surface)
        landmarks_.push_back({l.name, glm::vec3(l.xy, bounds.max.z + size_) + l.offset, true});
      else if (l.kind == bake::LandmarkDef::Kind::Position)
        landmarks_.push_back({l.name, l.position + l.offset, false});
      // Feature landmarks are points only the head generator knows; not offered.
    }
  }
  return {};
}

void SculptPanel::rebuildWorkingLayout() {
  workingLayout_.emplace(working_);
  workingScratch_.assign(workingLayout_->total(), 0.0f);
}

void SculptPanel::workingWeights(std::span<const float> faceWeights, std::span<float> out) const {
  // The working model is the face's model with baked targets appended per mesh.
  const eng::WeightLayout& faceLayout = face_->layout();
  std::fill(out.begin(), out.end(), 0.0f);
  for (int m = 0; m < faceLayout.meshCount(); ++m)
    std::copy_n(faceWeights.begin() + faceLayout.offset(m), faceLayout.count(m), out.begin() + workingLayout_->offset(m));
  for (const auto& [name, weight] : baked_) (void)workingLayout_->setByName(out, name, weight);  // out is total() long
}

const eng::Model& SculptPanel::displayModel() const { return showingPreview_ && preview_ ? preview_->model() : working_; }

void SculptPanel::displayWeights(std::span<const float> faceWeights, std::vector<float>& out) {
  workingWeights(faceWeights, workingScratch_);
  if (showingPreview_ && preview_) {
    out.resize(preview_->weightCount());
    if (auto ok = preview_->weights(workingScratch_, sculpt_->points(), out); !ok) message_.report(ok.error().message, true);
  } else {
    out = workingScratch_;
  }
}

void SculptPanel::refresh() {
  const bool wanted = previewEnabled_ && !sculpt_->points().empty();
  if (wanted && (!preview_ || preview_->layoutRevision() != sculpt_->layoutRevision())) {
    const auto start = std::chrono::steady_clock::now();
    if (auto prepared = sculpt_->prepare(); !prepared) {
      // Keep the last good preview off; say why once per layout.
      if (preview_ || message_.text != prepared.error().message) message_.report(prepared.error().message, true);
      preview_.reset();
    } else if (auto preview = SculptPreview::build(working_, *surface_, *sculpt_); !preview) {
      message_.report(preview.error().message, true);
      preview_.reset();
    } else {
      preview_.emplace(std::move(*preview));
      solveMs_ = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    ++displayRevision_;
  }
  const bool showing = wanted && preview_.has_value();
  if (showing != showingPreview_) {
    showingPreview_ = showing;
    ++displayRevision_;
  }
}

bool SculptPanel::pick(const glm::vec3& origin, const glm::vec3& direction, std::span<const float> faceWeights) {
  workingWeights(faceWeights, workingScratch_);
  if (auto posed = surface_->pose(working_, workingScratch_); !posed) {
    message_.report(posed.error().message, true);
    return false;
  }
  const auto hit = surface_->raycast(working_, origin, direction);
  if (!hit) {
    message_.report("no face under the cursor: nothing picked", true);
    return false;
  }
  auto added = addPoint("", hit->restPoint, hit);
  if (!added) {
    message_.report(added.error().message, true);
    return false;
  }
  reportPoint(*added);
  return true;
}

eng::Result<size_t> SculptPanel::addPoint(const std::string& name, const glm::vec3& rest, const std::optional<SurfaceHit>& hit) {
  auto added = sculpt_->addPoint(name, rest);
  if (!added) return added;
  std::optional<SurfaceAnchor> anchor;
  if (hit) {
    const SurfacePrimitive& sp = surface_->primitives()[hit->primitive];
    const auto& indices = working_.meshes[size_t(sp.mesh)].primitives[size_t(sp.primitive)].indices;
    anchor = SurfaceAnchor{hit->primitive, {}, hit->barycentric};
    for (int k = 0; k < 3; ++k) anchor->corner[k] = indices[size_t(hit->triangle) * 3 + size_t(k)];
  }
  anchors_.resize(sculpt_->points().size());
  anchors_[*added] = anchor;
  selected_ = int(*added);
  return added;
}

void SculptPanel::removePoint(size_t index) {
  if (!sculpt_->removePoint(index)) return;
  if (index < anchors_.size()) anchors_.erase(anchors_.begin() + std::ptrdiff_t(index));
  selected_ = -1;
}

void SculptPanel::clearPoints() {
  sculpt_->clearPoints();
  anchors_.clear();
  selected_ = -1;
}

void SculptPanel::pointsOnFace(std::span<const float> faceWeights, std::vector<glm::vec3>& onFace, std::vector<glm::vec3>& moved) {
  const auto points = sculpt_->points();
  onFace.resize(points.size());
  moved.resize(points.size());
  workingWeights(faceWeights, workingScratch_);
  for (size_t i = 0; i < points.size(); ++i) {
    onFace[i] = points[i].rest;
    if (i < anchors_.size() && anchors_[i]) {
      // The three corners morphed by the weights on screen (the GPU's sum, for three vertices).
      const SurfaceAnchor& a = *anchors_[i];
      const SurfacePrimitive& sp = surface_->primitives()[a.primitive];
      const eng::Primitive& primitive = working_.meshes[size_t(sp.mesh)].primitives[size_t(sp.primitive)];
      const std::span<const float> weights = *workingLayout_->meshWeights(workingScratch_, sp.mesh);  // total() long
      glm::vec3 local{0.0f};
      for (int k = 0; k < 3; ++k) {
        glm::vec3 corner = primitive.positions[a.corner[k]];
        for (size_t t = 0; t < primitive.targets.size() && t < weights.size(); ++t)
          if (weights[t] != 0.0f && a.corner[k] < primitive.targets[t].positions.size())
            corner += weights[t] * primitive.targets[t].positions[a.corner[k]];
        local += a.barycentric[k] * corner;
      }
      onFace[i] = glm::vec3(sp.world * glm::vec4(local, 1.0f));
    }
    moved[i] = onFace[i] + points[i].displacement;
  }
}

void SculptPanel::reportPoint(size_t index) {
  const SculptPoint& p = sculpt_->points()[index];
  char text[160];
  const std::string name = p.name.empty() ? "point " + std::to_string(index + 1) : p.name;
  std::snprintf(text, sizeof text, "control point '%s' at (%.5f, %.5f, %.5f)", name.c_str(), p.rest.x, p.rest.y, p.rest.z);
  message_.report(text, false);
}

bool SculptPanel::hasLandmark(const std::string& name) const {
  return std::any_of(landmarks_.begin(), landmarks_.end(), [&](const Landmark& l) { return l.name == name; });
}

bool SculptPanel::pressAddLandmark(const std::string& name) {
  auto added = addLandmark(name);
  if (!added) {
    message_.report(added.error().message, true);
    return false;
  }
  reportPoint(*added);
  return true;
}

bool SculptPanel::chooseFalloff(float radius) {
  if (auto ok = sculpt_->setFalloffRadius(radius); !ok) {
    message_.report(ok.error().message, true);
    return false;
  }
  return true;
}

bool SculptPanel::chooseKernel(facial::RbfKernelType type, float c) {
  facial::RbfKernel kernel;
  kernel.type = type;
  kernel.k = 1;
  kernel.c = c > 0.0f ? c : multiquadricC_;
  if (auto ok = sculpt_->setKernel(kernel); !ok) {
    message_.report(ok.error().message, true);
    return false;
  }
  kernelChoice_ = type == facial::RbfKernelType::Biharmonic ? 0 : type == facial::RbfKernelType::Polyharmonic ? 1 : 2;
  multiquadricC_ = kernel.c;
  return true;
}

bool SculptPanel::pressBake(const std::string& name) {
  std::snprintf(bakeName_, sizeof bakeName_, "%s", name.c_str());
  if (auto baked = bake(name); !baked) {
    message_.report(baked.error().message, true);
    return false;
  }
  message_.report("baked morph target '" + name + "'", false);
  return true;
}

bool SculptPanel::pressSave(const std::string& path) {
  std::snprintf(savePath_, sizeof savePath_, "%s", path.c_str());
  if (auto saved = saveModel(path); !saved) {
    message_.report(saved.error().message, true);
    return false;
  }
  message_.report("saved " + path, false);
  return true;
}

eng::Result<size_t> SculptPanel::addLandmark(const std::string& name) {
  const auto it = std::find_if(landmarks_.begin(), landmarks_.end(), [&](const Landmark& l) { return l.name == name; });
  if (it == landmarks_.end()) return eng::makeError(eng::ErrorKind::NotFound, "no landmark named '" + name + "'");
  glm::vec3 point = it->rayOrigin;
  std::optional<SurfaceHit> hit;
  if (it->onSurface) {
    std::fill(workingScratch_.begin(), workingScratch_.end(), 0.0f);
    if (auto posed = surface_->pose(working_, workingScratch_); !posed) return posed.error();  // the rest pose
    hit = surface_->raycast(working_, it->rayOrigin, {0.0f, 0.0f, -1.0f});
    if (!hit) return eng::makeError(eng::ErrorKind::InvalidArgument, "landmark '" + name + "' does not project onto this model's surface");
    point = hit->restPoint;
  }
  return addPoint(name, point, hit);
}

bool SculptPanel::dragSelected(const glm::vec3& worldDelta) {
  if (selected_ < 0 || size_t(selected_) >= sculpt_->points().size()) {
    message_.report("no control point selected to move", true);
    return false;
  }
  const glm::vec3 d = sculpt_->points()[size_t(selected_)].displacement + worldDelta;
  if (auto ok = sculpt_->setDisplacement(size_t(selected_), d); !ok) {
    message_.report(ok.error().message, true);
    return false;
  }
  return true;
}

eng::Result<void> SculptPanel::bake(const std::string& name) {
  if (auto baked = bakeSculptTarget(working_, *surface_, *sculpt_, name); !baked) return baked;
  rebuildWorkingLayout();
  // The face keeps its look: the new target at full weight, the points back at rest.
  baked_.emplace_back(name, 1.0f);
  sculpt_->clearDisplacements();
  preview_.reset();
  ++displayRevision_;
  return {};
}

eng::Result<void> SculptPanel::restore(const eng::Model* sculpted, std::span<const std::pair<std::string, float>> targets) {
  eng::Model working = face_->model();
  for (const auto& [name, weight] : targets) {
    if (!sculpted) return eng::makeError(eng::ErrorKind::InvalidArgument, "baked target '" + name + "' without the model that holds it");
    if (auto copied = copyBakedTarget(*sculpted, name, working); !copied) return copied;
  }
  working_ = std::move(working);
  baked_.assign(targets.begin(), targets.end());
  clearPoints();
  rebuildWorkingLayout();
  preview_.reset();
  ++displayRevision_;
  return {};
}

eng::Result<void> SculptPanel::saveModel(const std::string& path) {
  return replaceFileAtomically(path, [&](const std::filesystem::path& temp) -> eng::Result<void> {
    if (auto saved = eng::saveModel(working_, temp); !saved) return saved.error().prefixed(path + ": ");
    return {};
  });
}

void SculptPanel::draw() {
  ImGui::Checkbox("Pick points on the face", &pickMode_);
  tooltip("On: a click on the face adds a control point there. Off: drag orbits, Shift+drag moves the selected point");
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", pickMode_ ? "Click the face to add a point." : "Shift+drag in the view moves the selected point.");
  ImGui::PopStyleColor();
  if (!landmarks_.empty()) {
    landmarkChoice_ = std::clamp(landmarkChoice_, 0, int(landmarks_.size()) - 1);
    ImGui::SetNextItemWidth(-ImGui::CalcTextSize("Add landmark").x - 24.0f);
    const bool choosing = ImGui::BeginCombo("##landmark", landmarks_[size_t(landmarkChoice_)].name.c_str());
    if (!choosing) tooltip("A named point of the built-in head (nose tip, lip corners...)");
    if (choosing) {
      for (size_t i = 0; i < landmarks_.size(); ++i) {
        if (ImGui::Selectable(landmarks_[i].name.c_str(), int(i) == landmarkChoice_)) landmarkChoice_ = int(i);
        tooltip("Pick this landmark for Add landmark");
      }
      ImGui::EndCombo();
    }
    ImGui::SameLine();
    if (ImGui::Button("Add landmark")) pressAddLandmark(landmarks_[size_t(landmarkChoice_)].name);
    tooltip("Add the chosen landmark as a control point (at rest: it pins that spot)");
  }

  // Control points.
  const auto points = sculpt_->points();
  if (selected_ >= int(points.size())) selected_ = int(points.size()) - 1;
  ImGui::BeginChild("points", {0.0f, 110.0f}, true);
  for (size_t i = 0; i < points.size(); ++i) {
    char label[128];
    const glm::vec3 d = points[i].displacement;
    std::snprintf(label, sizeof label, "%s  (%.4f %.4f %.4f)##%zu", points[i].name.c_str(), d.x, d.y, d.z, i);
    if (ImGui::Selectable(label, int(i) == selected_)) selected_ = int(i);
    tooltip("Select this point (its displacement in brackets): the XYZ drags and Shift+drag in the view move it");
  }
  if (points.empty()) ImGui::TextDisabled("no control points yet");
  ImGui::EndChild();
  if (selected_ >= 0) {
    glm::vec3 d = points[size_t(selected_)].displacement;
    ImGui::SetNextItemWidth(-60.0f);
    if (ImGui::DragFloat3("move", &d.x, 0.0005f * size_, -0.5f * size_, 0.5f * size_, "%.4f"))
      dragSelected(d - points[size_t(selected_)].displacement);
    tooltip("The selected point's displacement in model units (x, y, z); drag or type");
    if (ImGui::Button("Reset point")) (void)sculpt_->setDisplacement(size_t(selected_), glm::vec3(0.0f));
    tooltip("Put the selected point back at rest");
    ImGui::SameLine();
    if (ImGui::Button("Remove point")) removePoint(size_t(selected_));
    tooltip("Delete the selected point");
    ImGui::SameLine();
  }
  if (ImGui::Button("Clear all")) clearPoints();
  tooltip("Delete every control point");

  drawKernel();
  if (showingPreview_)
    ImGui::TextDisabled("solve + preview upload data: %.1f ms, %zu points", solveMs_, points.size());
  drawBakeAndSave();
  message_.draw();
}

// The kernel, its c, the falloff, pins and preview.
void SculptPanel::drawKernel() {
  ImGui::SetNextItemWidth(-60.0f);
  bool kernelChanged = ImGui::Combo("kernel", &kernelChoice_, kKernelNames, 3);
  tooltip("The radial basis function: how a point's move spreads over the face");
  if (kernelChoice_ == 2) {
    ImGui::SetNextItemWidth(-60.0f);
    kernelChanged |= ImGui::DragFloat("c", &multiquadricC_, 0.001f * size_, 1e-4f * size_, size_, "%.4f");
    tooltip("The multiquadric's shape parameter c (model units): larger is smoother and wider");
  }
  if (kernelChanged)
    chooseKernel(kernelChoice_ == 0   ? facial::RbfKernelType::Biharmonic
                 : kernelChoice_ == 1 ? facial::RbfKernelType::Polyharmonic
                                      : facial::RbfKernelType::Multiquadric,
                 multiquadricC_);
  float falloff = sculpt_->falloffRadius();
  ImGui::SetNextItemWidth(-60.0f);
  if (ImGui::SliderFloat("falloff", &falloff, 0.0f, 0.5f * size_, falloff > 0.0f ? "%.3f" : "off (whole face)"))
    chooseFalloff(falloff);
  tooltip("Vertices farther than this from every point do not move (0: the whole face follows)");
  bool pins = sculpt_->pinsEnabled();
  if (ImGui::Checkbox("Pin the box corners", &pins)) sculpt_->setPinsEnabled(pins);
  tooltip("Fixed points at the corners of the model's box keep far parts still");
  ImGui::SameLine();
  ImGui::Checkbox("Preview", &previewEnabled_);
  tooltip("Show the sculpt live on the face before it is baked");
}

void SculptPanel::drawBakeAndSave() {
  ImGui::Separator();
  ImGui::SetNextItemWidth(-60.0f);
  ImGui::InputText("##bakename", bakeName_, sizeof bakeName_);
  tooltip("The name of the morph target Bake makes");
  ImGui::SameLine();
  if (ImGui::Button("Bake")) pressBake(bakeName_);
  tooltip("Add the sculpt as a morph target with this name (the points go back to rest)");
  for (auto& [name, weight] : baked_) {
    ImGui::SliderFloat(name.c_str(), &weight, 0.0f, 1.0f);
    tooltip("This baked target's weight on the face");
  }
  ImGui::SetNextItemWidth(-90.0f);
  ImGui::InputText("##savepath", savePath_, sizeof savePath_);
  tooltip("Where Save .glb writes the model with every baked target");
  ImGui::SameLine();
  if (ImGui::Button("Save .glb")) pressSave(savePath_);
  tooltip("Write the model with every baked target (File > Export .glb adds the clips)");
}

}  // namespace editor
