#include "dataset/landmark_tracker.h"

#include <limits>

#include "autorig/closest_point.h"
#include "autorig/posed_face.h"
#include "autorig/surface_cast.h"
#include "engine/scene/skeleton_pose.h"
#include "engine/scene/skinning.h"
#include "engine/scene/weights.h"

namespace dataset {
namespace {

struct Nearest {
  size_t primitive = 0;  // into PosedFace::primitives
  std::array<uint32_t, 3> vertices{};
  glm::vec3 barycentric{1.0f, 0.0f, 0.0f};
  float distance = std::numeric_limits<float>::infinity();
};

Nearest nearestTriangle(const eng::Model& model, const autorig::PosedFace& posed, const std::vector<bool>& among,
                        const glm::vec3& point) {
  Nearest best;
  for (size_t pi = 0; pi < posed.primitives.size(); ++pi) {
    if (!among[pi]) continue;
    const autorig::PosedPrimitive& p = posed.primitives[pi];
    const std::vector<uint32_t>& indices = model.meshes[p.mesh].primitives[p.primitive].indices;
    for (size_t i = 0; i + 2 < indices.size(); i += 3) {
      const std::array<uint32_t, 3> v{indices[i], indices[i + 1], indices[i + 2]};
      if (v[0] >= p.positions.size() || v[1] >= p.positions.size() || v[2] >= p.positions.size()) continue;
      glm::vec3 barycentric;
      const glm::vec3 onTriangle =
          autorig::closestOnTriangle(point, p.positions[v[0]], p.positions[v[1]], p.positions[v[2]], barycentric);
      const float distance = glm::length(onTriangle - point);
      if (distance < best.distance) best = {pi, v, barycentric, distance};
    }
  }
  return best;
}

}  // namespace

eng::Result<LandmarkTracker> LandmarkTracker::bind(const eng::Model& model, const autorig::FaceLandmarks& rest,
                                                   float maxDistance) {
  const autorig::PosedFace posed = autorig::poseAtRest(model);
  const std::vector<bool> skin = autorig::outerSkinPrimitives(model, posed);
  const eng::WeightLayout layout(model);
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, eng::restPose(model), world);
  LandmarkTracker tracker;
  tracker.model_ = &model;
  tracker.weightCount_ = layout.total();
  std::vector<size_t> placementOf(posed.primitives.size(), SIZE_MAX);
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const Nearest near = nearestTriangle(model, posed, skin, rest.points[i]);
    if (!(near.distance <= maxDistance))
      return eng::makeError(eng::ErrorKind::Malformed, model.sourcePath + ": landmark " + std::to_string(i) +
                                                           " of 68 lies " + std::to_string(near.distance) +
                                                           " from the face's skin (no triangle to follow)");
    const autorig::PosedPrimitive& p = posed.primitives[near.primitive];
    if (placementOf[near.primitive] == SIZE_MAX) {
      Placement placement{.primitive = &model.meshes[p.mesh].primitives[p.primitive],
                          .weightOffset = layout.offset(int(p.mesh)), .nodeWorld = world[size_t(p.node)], .joints = {}};
      const int skinIndex = model.nodes[size_t(p.node)].skin;
      if (skinIndex >= 0) eng::skinJointMatrices(model.skins[size_t(skinIndex)], world, p.node, placement.joints);
      placementOf[near.primitive] = tracker.placements_.size();
      tracker.placements_.push_back(std::move(placement));
    }
    Binding& binding = tracker.bindings_[i];
    binding.placement = uint32_t(placementOf[near.primitive]);
    for (size_t c = 0; c < 3; ++c) binding.corners[c] = {near.vertices[c], near.barycentric[int(c)]};
  }
  return tracker;
}

glm::vec3 LandmarkTracker::corner(const Placement& placement, uint32_t vertex, std::span<const float> weights) const {
  const eng::Primitive& primitive = *placement.primitive;
  glm::vec3 local = primitive.positions[vertex];
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const float w = weights[placement.weightOffset + t];
    if (w != 0.0f && vertex < primitive.targets[t].positions.size()) local += w * primitive.targets[t].positions[vertex];
  }
  glm::vec4 skinned(local, 1.0f);
  if (!placement.joints.empty() && !primitive.joints.empty())
    skinned = eng::vertexSkinMatrix(primitive, vertex, placement.joints) * skinned;
  return glm::vec3(placement.nodeWorld * skinned);
}

eng::Result<void> LandmarkTracker::evaluate(std::span<const float> weights, Landmarks3& out) const {
  if (weights.size() != weightCount_)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "landmarks: " + std::to_string(weights.size()) +
                                                               " weights for a model with " + std::to_string(weightCount_) + " targets");
  for (size_t i = 0; i < autorig::kLandmarkCount; ++i) {
    const Binding& binding = bindings_[i];
    const Placement& placement = placements_[binding.placement];
    glm::vec3 point(0.0f);
    for (const Corner& c : binding.corners) point += c.weight * corner(placement, c.vertex, weights);
    out[i] = point;
  }
  return {};
}

Landmarks2 projectLandmarks(const Landmarks3& points, const eng::OrbitCamera& camera, uint32_t width, uint32_t height) {
  const autorig::PictureCamera picture{.viewProjection = camera.projection(float(width) / float(height)) * camera.view(),
                                       .imageSize = glm::vec2(float(width), float(height))};
  Landmarks2 pixels;
  for (size_t i = 0; i < points.size(); ++i) pixels[i] = autorig::projectToPicture(picture, points[i]).value_or(glm::vec2(-1.0f));
  return pixels;
}

}  // namespace dataset
