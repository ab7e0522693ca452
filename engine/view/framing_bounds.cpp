#include "engine/view/framing_bounds.h"

#include <algorithm>
#include <cmath>

#include "engine/scene/posed_bounds.h"
#include "engine/view/camera.h"
#include "engine/view/scene_mesh_nodes.h"

namespace eng {
namespace {

Aabb wholeModelBounds(const std::vector<MeshNode>& nodes, const Model& model) {
  Aabb box;
  for (const MeshNode& node : nodes) {
    for (const Primitive& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives) {
      const size_t n = prim.positions.size();
      auto extend = [&](const glm::vec3& p) { box.extend(glm::vec3(node.world * glm::vec4(p, 1.0f))); };
      for (const glm::vec3& p : prim.positions) extend(p);
      for (const MorphTarget& target : prim.targets) {
        if (target.positions.size() != n) continue;  // no position deltas (or inconsistent: GpuModel rejects it)
        for (size_t v = 0; v < n; ++v) extend(prim.positions[v] + target.positions[v]);
      }
    }
  }
  return box;
}

// The model without its flat primitives (a floor, a backdrop, a card: the
// smallest side of its box under 2% of its largest), when anything else is
// left: a face exported standing on a floor 60 units wide was framed with
// the floor, a speck no face detector finds.
Aabb withoutFlatParts(const std::vector<MeshNode>& nodes, const Model& model) {
  Aabb box;
  for (const MeshNode& node : nodes) {
    for (const Primitive& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives) {
      Aabb own;
      for (const glm::vec3& p : prim.positions) own.extend(glm::vec3(node.world * glm::vec4(p, 1.0f)));
      if (!own.valid()) continue;
      const glm::vec3 size = own.size();
      if (std::min({size.x, size.y, size.z}) < 0.02f * std::max({size.x, size.y, size.z})) continue;
      box.extend(own.min), box.extend(own.max);
    }
  }
  return box.valid() ? box : wholeModelBounds(nodes, model);
}

Aabb morphedBounds(const std::vector<MeshNode>& nodes, const Model& model) {
  Aabb box;
  for (const MeshNode& node : nodes) {
    for (const Primitive& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives) {
      const size_t n = prim.positions.size();
      Aabb local;
      for (const glm::vec3& p : prim.positions) local.extend(p);
      // Deltas below a thousandth of the primitive's size are noise (quantised exports).
      const float threshold = std::max(local.diagonal() * 1e-3f, 1e-12f);
      for (const MorphTarget& target : prim.targets) {
        if (target.positions.size() != n) continue;
        for (size_t v = 0; v < n; ++v) {
          if (glm::length(target.positions[v]) <= threshold) continue;
          box.extend(glm::vec3(node.world * glm::vec4(prim.positions[v], 1.0f)));
          box.extend(glm::vec3(node.world * glm::vec4(prim.positions[v] + target.positions[v], 1.0f)));
        }
      }
    }
  }
  return box;
}

// The head around a face region: the model's vertices inside a box reaching
// from the face centre about a face height up (skull, hair) and down (chin,
// neck) and three quarters of one to the sides (ears), clipped to what is
// there, so a bare head mask is framed as itself and a full body as its head.
Aabb headAround(const Aabb& face, const std::vector<MeshNode>& nodes, const Model& model) {
  const float size = std::max({face.size().x, face.size().y, 1e-6f});
  const glm::vec3 c = face.center();
  Aabb reach;
  reach.min = c - glm::vec3(0.75f * size, 1.0f * size, 0.9f * size);
  reach.max = c + glm::vec3(0.75f * size, 0.85f * size, 0.9f * size);
  Aabb head = face;
  for (const MeshNode& node : nodes) {
    for (const Primitive& prim : model.meshes[static_cast<size_t>(node.mesh)].primitives) {
      for (const glm::vec3& p : prim.positions) {
        const glm::vec3 w(node.world * glm::vec4(p, 1.0f));
        if (glm::all(glm::greaterThanEqual(w, reach.min)) && glm::all(glm::lessThanEqual(w, reach.max))) head.extend(w);
      }
    }
  }
  return head;
}

}  // namespace

std::string_view framingModeName(FramingMode mode) { return nameOf(kFramingModeNames, mode); }

std::optional<FramingMode> framingModeFromName(std::string_view name) { return valueNamed(kFramingModeNames, name); }

Aabb morphedRegionBounds(const Model& model) { return morphedBounds(sceneMeshNodes(model), model); }

Aabb faceFeatureBounds(const Model& model) { return posedMorphedBounds(model, restPose(model)); }

float zoomShowing(const Aabb& framed, const Aabb& shown, float wanted, float aspect, float fovYDegrees) {
  if (!framed.valid() || !shown.valid() || !(wanted > 1.0f)) return wanted;
  const OrbitCamera camera = OrbitCamera::frame(framed, aspect, fovYDegrees);
  const glm::vec3 c = camera.target;
  // Half extents of `shown` around the camera's target, the width in units
  // of height; the nearest point sits closer to the camera and looks larger.
  const float halfY = std::max(shown.max.y - c.y, c.y - shown.min.y);
  const float halfX = std::max(shown.max.x - c.x, c.x - shown.min.x) / std::max(aspect, 1e-3f);
  const float nearer = std::max(0.0f, shown.max.z - c.z);
  const float tanHalf = std::tan(glm::radians(fovYDegrees) * 0.5f);
  const float margin = 1.05f;
  const float needed = std::max(halfY, halfX) * margin / tanHalf + nearer;
  if (!(needed > 0.0f)) return wanted;
  return std::clamp(camera.distance / needed, 1.0f, wanted);
}

Aabb framingBounds(const Model& model, FramingMode mode) {
  const std::vector<MeshNode> nodes = sceneMeshNodes(model);
  if (model.skins.empty()) {
    if (mode == FramingMode::Face) {
      const Aabb face = morphedBounds(nodes, model);
      if (face.valid()) return headAround(face, nodes, model);
      return withoutFlatParts(nodes, model);
    }
    return wholeModelBounds(nodes, model);
  }
  // A skinned model stands in the pose its skeleton defines (a mesh's own
  // vertices may lie in an A-pose or in another frame altogether): framed
  // posed, at rest. Its face is the part the head joint moves, with the neck
  // below it.
  const Pose pose = restPose(model);
  if (mode == FramingMode::Face) {
    if (const int head = findHeadJoint(model); head >= 0) {
      Aabb region = posedJointRegionBounds(model, pose, head);
      if (region.valid()) {
        // Long hair skinned to the head reaches the chest: framed whole, it
        // leaves the face a quarter of the image. The head joint sits at the
        // skull's base; the chin is less than half the joint's depth under
        // the crown below it.
        std::vector<glm::mat4> world;
        poseWorldMatrices(model, pose, world);
        const float joint = world[size_t(head)][3].y, crown = region.max.y;
        if (joint < crown) region.min.y = std::max(region.min.y, joint - 0.45f * (crown - joint));
        const float height = region.size().y;
        region.min.y -= 0.3f * height;  // the neck
        region.max.y += 0.05f * height;  // room above the crown
        return region;
      }
    }
  }
  return posedBounds(model, pose);
}

}  // namespace eng
