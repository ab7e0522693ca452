#include "editor/sculpt_model.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/scene/normals.h"
#include "engine/scene/weights.h"

namespace editor {

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string describe(const glm::vec3& v) {
  char text[96];
  std::snprintf(text, sizeof text, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return text;
}

}  // namespace

SculptModel::SculptModel(std::span<const glm::vec3> vertices, const eng::Aabb& bounds) : vertices_(vertices) {
  if (bounds.valid()) {
    const glm::vec3 centre = bounds.center(), half = bounds.size() * 0.5f * 1.5f;
    for (int corner = 0; corner < 8; ++corner)
      pins_.push_back(centre + glm::vec3(corner & 1 ? half.x : -half.x, corner & 2 ? half.y : -half.y,
                                         corner & 4 ? half.z : -half.z));
    // Points closer than this are the same point as far as a sculptor can tell.
    minSeparation_ = std::max(bounds.diagonal() * 1e-4f, 1e-7f);
  }
}

eng::Result<size_t> SculptModel::addPoint(std::string name, const glm::vec3& rest) {
  if (!finite(rest)) return eng::makeError(eng::ErrorKind::InvalidArgument, "control point '" + name + "' has a non-finite position " + describe(rest));
  for (const SculptPoint& p : points_)
    if (glm::distance(p.rest, rest) < minSeparation_)
      return eng::makeError(eng::ErrorKind::InvalidArgument, "control point '" + name + "' is on top of '" + p.name + "' (closer than " +
                            std::to_string(minSeparation_) + ")");
  if (name.empty()) name = "point " + std::to_string(points_.size() + 1);
  points_.push_back({std::move(name), rest, glm::vec3(0.0f)});
  ++layoutRevision_;
  return points_.size() - 1;
}

eng::Result<void> SculptModel::removePoint(size_t index) {
  if (index >= points_.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "no control point " + std::to_string(index) + " (" + std::to_string(points_.size()) + " points)");
  points_.erase(points_.begin() + std::ptrdiff_t(index));
  ++layoutRevision_;
  return {};
}

eng::Result<void> SculptModel::setDisplacement(size_t index, const glm::vec3& displacement) {
  if (index >= points_.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "no control point " + std::to_string(index) + " (" + std::to_string(points_.size()) + " points)");
  if (!finite(displacement))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "control point '" + points_[index].name + "': displacement " + describe(displacement) +
                          " is not finite");
  points_[index].displacement = displacement;
  return {};
}

void SculptModel::clearDisplacements() {
  for (SculptPoint& p : points_) p.displacement = glm::vec3(0.0f);
}

void SculptModel::clearPoints() {
  if (points_.empty()) return;
  points_.clear();
  ++layoutRevision_;
}

eng::Result<void> SculptModel::setKernel(const facial::RbfKernel& kernel) {
  if (kernel.type == facial::RbfKernelType::Polyharmonic && kernel.k < 1)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "polyharmonic kernel: k must be at least 1 (r^(2k+1)), got " + std::to_string(kernel.k));
  if (kernel.type == facial::RbfKernelType::Multiquadric && !(kernel.c > 0.0f && std::isfinite(kernel.c)))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "multiquadric kernel: c must be a positive number, got " + std::to_string(kernel.c));
  if (kernel.type == kernel_.type && kernel.k == kernel_.k && kernel.c == kernel_.c) return {};
  kernel_ = kernel;
  ++layoutRevision_;
  return {};
}

eng::Result<void> SculptModel::setFalloffRadius(float radius) {
  if (!std::isfinite(radius) || radius < 0.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "falloff radius must be a finite number >= 0 (got " + std::to_string(radius) + ")");
  if (radius == falloffRadius_) return {};
  falloffRadius_ = radius;
  ++layoutRevision_;
  return {};
}

void SculptModel::setPinsEnabled(bool enabled) {
  if (enabled == pinsEnabled_) return;
  pinsEnabled_ = enabled;
  ++layoutRevision_;
}

eng::Result<void> SculptModel::prepare() {
  if (prepared()) return {};
  if (points_.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no control points: pick points on the face first");
  std::vector<glm::vec3> controls;
  for (const SculptPoint& p : points_) controls.push_back(p.rest);
  if (pinsEnabled_) controls.insert(controls.end(), pins_.begin(), pins_.end());
  auto deformer = facial::RbfDeformer::build(controls, vertices_, kernel_);
  if (!deformer) {
    deformer_.reset();
    return eng::makeError(deformer.error().kind, "RBF solve: " + deformer.error().message +
                          (pinsEnabled_ ? "" : " (turning the pins on adds eight fixed points)"));
  }
  deformer_.emplace(std::move(*deformer));
  falloff_.clear();
  if (falloffRadius_ > 0.0f) {
    // 1 within half the radius of the nearest control point, smoothly 0 at the radius.
    falloff_.resize(vertices_.size());
    const float inner = 0.5f * falloffRadius_;
    for (size_t v = 0; v < vertices_.size(); ++v) {
      float nearest = std::numeric_limits<float>::max();
      for (const SculptPoint& p : points_) nearest = std::min(nearest, glm::distance(vertices_[v], p.rest));
      const float t = std::clamp((falloffRadius_ - nearest) / (falloffRadius_ - inner), 0.0f, 1.0f);
      falloff_[v] = t * t * (3.0f - 2.0f * t);
    }
  }
  deformerRevision_ = layoutRevision_;
  solverDisplacements_.assign(controls.size(), glm::vec3(0.0f));
  return {};
}

eng::Result<void> SculptModel::vertexDisplacements(std::span<glm::vec3> out) {
  if (!prepared()) return eng::makeError(eng::ErrorKind::InvalidArgument, "sculpt: the RBF solve is out of date (call prepare first)");
  if (out.size() != vertices_.size())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "sculpt: room for " + std::to_string(out.size()) + " displacements, the surface has " +
                          std::to_string(vertices_.size()) + " vertices");
  for (size_t i = 0; i < points_.size(); ++i) solverDisplacements_[i] = points_[i].displacement;
  return deformer_->apply(solverDisplacements_, out, falloff_);
}

bool SculptModel::hasDisplacement() const {
  return std::any_of(points_.begin(), points_.end(), [](const SculptPoint& p) { return p.displacement != glm::vec3(0.0f); });
}

namespace {

// The surface primitive of (mesh, primitive), or nullptr.
const SurfacePrimitive* findSurfacePrimitive(const ModelSurface& surface, int mesh, int primitive) {
  for (const SurfacePrimitive& sp : surface.primitives())
    if (sp.mesh == mesh && sp.primitive == primitive) return &sp;
  return nullptr;
}

eng::Result<void> checkSurfaceMatches(const eng::Model& model, const ModelSurface& surface) {
  for (const SurfacePrimitive& sp : surface.primitives()) {
    if (sp.mesh < 0 || size_t(sp.mesh) >= model.meshes.size() ||
        size_t(sp.primitive) >= model.meshes[size_t(sp.mesh)].primitives.size() ||
        model.meshes[size_t(sp.mesh)].primitives[size_t(sp.primitive)].vertexCount() != sp.vertexCount)
      return eng::makeError(eng::ErrorKind::InvalidArgument, model.sourcePath + ": the sculpt surface was made from another model (mesh " +
                            std::to_string(sp.mesh) + " primitive " + std::to_string(sp.primitive) + " differs)");
  }
  return {};
}

// Weight animations keep targetCount values per key (x3 for cubic splines):
// insert `added` zeros at the end of each mesh `mesh` block.
void growWeightAnimations(eng::Model& model, int mesh, size_t added) {
  for (eng::Animation& animation : model.animations)
    for (eng::WeightsChannel& channel : animation.channels) {
      if (channel.mesh != mesh || channel.targetCount == 0) continue;
      const size_t blocks = channel.values.size() / channel.targetCount;
      std::vector<float> grown;
      grown.reserve(blocks * (channel.targetCount + added));
      for (size_t b = 0; b < blocks; ++b) {
        grown.insert(grown.end(), channel.values.begin() + std::ptrdiff_t(b * channel.targetCount),
                     channel.values.begin() + std::ptrdiff_t((b + 1) * channel.targetCount));
        grown.insert(grown.end(), added, 0.0f);
      }
      channel.values = std::move(grown);
      channel.targetCount += added;
    }
}

}  // namespace

eng::Result<void> bakeSculptTarget(eng::Model& model, const ModelSurface& surface, SculptModel& sculpt, std::string_view name) {
  if (name.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "bake: the new morph target needs a name");
  for (const eng::Mesh& mesh : model.meshes)
    if (std::find(mesh.targetNames.begin(), mesh.targetNames.end(), name) != mesh.targetNames.end())
      return eng::makeError(eng::ErrorKind::InvalidArgument, "bake: mesh '" + mesh.name + "' already has a morph target named '" + std::string(name) + "'");
  if (auto ok = checkSurfaceMatches(model, surface); !ok) return ok;
  if (auto ok = sculpt.prepare(); !ok) return ok.error().prefixed("bake: ");
  if (!sculpt.hasDisplacement()) return eng::makeError(eng::ErrorKind::InvalidArgument, "bake: every control point is at rest, nothing to bake");
  std::vector<glm::vec3> world(surface.vertexCount());
  if (auto ok = sculpt.vertexDisplacements(world); !ok) return ok.error().prefixed("bake: ");

  // Compute every target first so a failure leaves the model untouched.
  std::vector<std::vector<eng::MorphTarget>> targets(model.meshes.size());
  std::vector<bool> covered(model.meshes.size(), false);
  for (const SurfacePrimitive& sp : surface.primitives()) covered[size_t(sp.mesh)] = true;
  std::vector<glm::vec3> deformed;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (!covered[m]) continue;
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const eng::Primitive& primitive = model.meshes[m].primitives[p];
      eng::MorphTarget target;
      target.positions.assign(primitive.vertexCount(), glm::vec3(0.0f));
      target.normals.assign(primitive.vertexCount(), glm::vec3(0.0f));
      if (!primitive.tangents.empty()) target.tangents.assign(primitive.vertexCount(), glm::vec3(0.0f));
      if (const SurfacePrimitive* sp = findSurfacePrimitive(surface, int(m), int(p))) {
        for (size_t v = 0; v < sp->vertexCount; ++v) target.positions[v] = sp->worldToLocal * world[sp->firstVertex + v];
        deformed = primitive.positions;
        for (size_t v = 0; v < deformed.size(); ++v) deformed[v] += target.positions[v];
        // Normal deltas: smooth normals after minus before, the same method on both
        // sides so an authored normal plus the delta turns by the sculpted amount.
        const auto before = eng::computeSmoothNormals(primitive.positions, primitive.indices);
        const auto after = eng::computeSmoothNormals(deformed, primitive.indices);
        for (size_t v = 0; v < deformed.size(); ++v) target.normals[v] = after[v] - before[v];
      }
      targets[m].push_back(std::move(target));
    }
  }
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (!covered[m]) continue;
    eng::Mesh& mesh = model.meshes[m];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) mesh.primitives[p].targets.push_back(std::move(targets[m][p]));
    mesh.targetNames.emplace_back(name);
    mesh.defaultWeights.push_back(0.0f);
    growWeightAnimations(model, int(m), 1);
  }
  return {};
}

eng::Result<void> copyBakedTarget(const eng::Model& from, std::string_view name, eng::Model& to) {
  const std::string quoted = "'" + std::string(name) + "'";
  std::vector<std::pair<size_t, size_t>> found;  // (mesh, target index in `from`)
  for (size_t m = 0; m < from.meshes.size(); ++m) {
    const auto& names = from.meshes[m].targetNames;
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) continue;
    const bool fits = m < to.meshes.size() && to.meshes[m].primitives.size() == from.meshes[m].primitives.size() &&
                      std::equal(from.meshes[m].primitives.begin(), from.meshes[m].primitives.end(), to.meshes[m].primitives.begin(),
                                 [](const eng::Primitive& a, const eng::Primitive& b) { return a.vertexCount() == b.vertexCount(); });
    if (!fits)
      return eng::makeError(eng::ErrorKind::Malformed, from.sourcePath + ": mesh " + std::to_string(m) + " with target " + quoted +
                                                           " is not a mesh of " + to.sourcePath + " (another model?)");
    const auto& own = to.meshes[m].targetNames;
    if (std::find(own.begin(), own.end(), name) != own.end())
      return eng::makeError(eng::ErrorKind::InvalidArgument, to.sourcePath + ": already has a morph target " + quoted);
    found.emplace_back(m, size_t(it - names.begin()));
  }
  if (found.empty()) return eng::makeError(eng::ErrorKind::NotFound, from.sourcePath + ": no morph target " + quoted);
  for (const auto& [m, index] : found) {
    eng::Mesh& mesh = to.meshes[m];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) mesh.primitives[p].targets.push_back(from.meshes[m].primitives[p].targets[index]);
    mesh.targetNames.emplace_back(name);
    mesh.defaultWeights.push_back(0.0f);
    growWeightAnimations(to, int(m), 1);
  }
  return {};
}

eng::Result<SculptPreview> SculptPreview::build(const eng::Model& model, const ModelSurface& surface,
                                                const SculptModel& sculpt) {
  if (!sculpt.prepared()) return eng::makeError(eng::ErrorKind::InvalidArgument, "sculpt preview: the RBF solve is out of date");
  if (auto ok = checkSurfaceMatches(model, surface); !ok) return ok.error();
  SculptPreview preview;
  preview.model_ = model;
  preview.layoutRevision_ = sculpt.layoutRevision();
  preview.pointCount_ = sculpt.points().size();
  const eng::WeightLayout faceLayout(model);
  std::vector<bool> covered(model.meshes.size(), false);
  for (const SurfacePrimitive& sp : surface.primitives()) covered[size_t(sp.mesh)] = true;
  const size_t n = preview.pointCount_;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    preview.faceOffsets_.push_back(faceLayout.offset(int(m)));
    preview.basisOffset_.push_back(covered[m] ? uint32_t(model.meshes[m].targetNames.size()) : UINT32_MAX);
    if (!covered[m]) continue;
    eng::Mesh& mesh = preview.model_.meshes[m];
    for (size_t j = 0; j < n; ++j)
      for (const char* axis : {"x", "y", "z"}) {
        mesh.targetNames.push_back("sculpt." + std::to_string(j) + "." + axis);
        mesh.defaultWeights.push_back(0.0f);
      }
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      eng::Primitive& primitive = mesh.primitives[p];
      const SurfacePrimitive* sp = findSurfacePrimitive(surface, int(m), int(p));
      for (size_t j = 0; j < n; ++j)
        for (int axis = 0; axis < 3; ++axis) {
          eng::MorphTarget target;
          target.positions.assign(primitive.vertexCount(), glm::vec3(0.0f));
          if (sp) {
            glm::vec3 unit(0.0f);
            unit[axis] = 1.0f;
            const glm::vec3 local = sp->worldToLocal * unit;
            for (size_t v = 0; v < sp->vertexCount; ++v) target.positions[v] = sculpt.influence(sp->firstVertex + v, j) * local;
          }
          primitive.targets.push_back(std::move(target));
        }
    }
    growWeightAnimations(preview.model_, int(m), 3 * n);
  }
  preview.faceOffsets_.push_back(faceLayout.total());
  const eng::WeightLayout previewLayout(preview.model_);
  for (size_t m = 0; m < model.meshes.size(); ++m) preview.previewOffsets_.push_back(previewLayout.offset(int(m)));
  preview.previewTotal_ = previewLayout.total();
  return preview;
}

eng::Result<void> SculptPreview::weights(std::span<const float> faceWeights, std::span<const SculptPoint> points,
                                         std::span<float> out) const {
  if (faceWeights.size() != faceOffsets_.back() || out.size() != previewTotal_ || points.size() != pointCount_)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "sculpt preview weights: " + std::to_string(faceWeights.size()) + " face weights (expected " +
                          std::to_string(faceOffsets_.back()) + "), room for " + std::to_string(out.size()) + " (expected " +
                          std::to_string(previewTotal_) + "), " + std::to_string(points.size()) + " points (expected " +
                          std::to_string(pointCount_) + ")");
  for (size_t m = 0; m + 1 < faceOffsets_.size(); ++m) {
    const uint32_t count = faceOffsets_[m + 1] - faceOffsets_[m];
    std::copy_n(faceWeights.begin() + faceOffsets_[m], count, out.begin() + previewOffsets_[m]);
    if (basisOffset_[m] == UINT32_MAX) continue;
    float* basis = out.data() + previewOffsets_[m] + basisOffset_[m];
    for (size_t j = 0; j < points.size(); ++j)
      for (int axis = 0; axis < 3; ++axis) basis[3 * j + size_t(axis)] = points[j].displacement[axis];
  }
  return {};
}

}  // namespace editor
