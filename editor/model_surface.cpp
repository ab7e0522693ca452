#include "editor/model_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/ray_triangle.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/weights.h"

namespace editor {

eng::Result<ModelSurface> ModelSurface::create(const eng::Model& model) {
  ModelSurface surface;
  std::vector<bool> placed(model.meshes.size(), false);
  const std::vector<glm::mat4> worlds = eng::restWorldMatrices(model);
  for (size_t n = 0; n < model.nodes.size(); ++n) {
    const int mesh = model.nodes[n].mesh;
    if (mesh < 0 || size_t(mesh) >= model.meshes.size() || placed[size_t(mesh)]) continue;
    placed[size_t(mesh)] = true;
    const glm::mat4& world = worlds[n];
    const glm::mat3 linear(world);
    if (!eng::isInvertible(linear)) continue;  // collapsed node: nothing to pick
    for (size_t p = 0; p < model.meshes[size_t(mesh)].primitives.size(); ++p) {
      const eng::Primitive& primitive = model.meshes[size_t(mesh)].primitives[p];
      if (primitive.indices.size() < 3) continue;
      surface.primitives_.push_back({mesh, int(p), surface.rest_.size(), primitive.vertexCount(), world, glm::inverse(linear)});
      for (const glm::vec3& v : primitive.positions) surface.rest_.push_back(glm::vec3(world * glm::vec4(v, 1.0f)));
    }
  }
  if (surface.primitives_.empty())
    return eng::makeError(eng::ErrorKind::Malformed, model.sourcePath + ": no node places a mesh with triangles, nothing to pick or sculpt");
  surface.posed_ = surface.rest_;
  return surface;
}

eng::Result<void> ModelSurface::pose(const eng::Model& model, std::span<const float> weights) {
  const eng::WeightLayout layout(model);
  if (weights.size() != layout.total())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "surface pose: " + std::to_string(weights.size()) + " weights given, the model has " +
                          std::to_string(layout.total()));
  for (const SurfacePrimitive& sp : primitives_) {
    const eng::Primitive& primitive = model.meshes[size_t(sp.mesh)].primitives[size_t(sp.primitive)];
    scratch_.resize(primitive.vertexCount());
    eng::morphPrimitiveCpu(primitive, *layout.meshWeights(weights, sp.mesh), scratch_, {});
    for (size_t v = 0; v < scratch_.size(); ++v) posed_[sp.firstVertex + v] = glm::vec3(sp.world * glm::vec4(scratch_[v], 1.0f));
  }
  return {};
}

namespace {
constexpr float kEdgeSlack = 1e-5f;
}  // namespace

std::optional<SurfaceHit> ModelSurface::raycast(const eng::Model& model, const glm::vec3& origin,
                                                const glm::vec3& direction) const {
  std::optional<SurfaceHit> best;
  float bestDistance = std::numeric_limits<float>::max();
  for (size_t p = 0; p < primitives_.size(); ++p) {
    const SurfacePrimitive& sp = primitives_[p];
    const auto& indices = model.meshes[size_t(sp.mesh)].primitives[size_t(sp.primitive)].indices;
    const glm::vec3* v = posed_.data() + sp.firstVertex;
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
      const uint32_t i0 = indices[t], i1 = indices[t + 1], i2 = indices[t + 2];
      if (i0 >= sp.vertexCount || i1 >= sp.vertexCount || i2 >= sp.vertexCount) continue;
      // Either face (a click on a back-facing lip still counts), the bounds
      // widened by kEdgeSlack: a ray over an edge shared by two triangles
      // (the mirror plane of a symmetric face) must not fall through both.
      const std::optional<eng::RayTriangleHit> found =
          eng::intersectRayTriangle(origin, direction, v[i0], v[i1], v[i2], kEdgeSlack);
      if (!found || found->distance >= bestDistance) continue;
      const float s = found->distance, u = found->u, w = found->v;
      bestDistance = s;
      SurfaceHit hit;
      hit.distance = s;
      hit.primitive = p;
      hit.triangle = uint32_t(t / 3);
      const float bu = std::clamp(u, 0.0f, 1.0f), bw = std::clamp(w, 0.0f, 1.0f - bu);
      hit.barycentric = {1.0f - bu - bw, bu, bw};
      hit.posedPoint = origin + s * direction;
      const glm::vec3* r = rest_.data() + sp.firstVertex;
      hit.restPoint = hit.barycentric.x * r[i0] + hit.barycentric.y * r[i1] + hit.barycentric.z * r[i2];
      best = hit;
    }
  }
  return best;
}

}  // namespace editor
