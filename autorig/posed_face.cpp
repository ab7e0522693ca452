#include "autorig/posed_face.h"

#include "engine/scene/skeleton_pose.h"
#include "engine/scene/skinning.h"

namespace autorig {

const PosedPrimitive* PosedFace::find(size_t mesh, size_t primitive) const {
  for (const PosedPrimitive& p : primitives)
    if (p.mesh == mesh && p.primitive == primitive) return &p;
  return nullptr;
}

size_t PosedFace::vertexCount() const {
  size_t count = 0;
  for (const PosedPrimitive& p : primitives) count += p.positions.size();
  return count;
}

namespace {

// A matrix that cannot be inverted (a joint scaled to zero) leaves its
// vertices' deltas as they are rather than sending them to infinity.
glm::mat3 safeInverse(const glm::mat3& m) { return eng::isInvertible(m) ? glm::inverse(m) : glm::mat3(1.0f); }

}  // namespace

PosedFace poseAtRest(const eng::Model& model) {
  PosedFace face;
  eng::Pose pose = eng::restPose(model);
  std::vector<glm::mat4> world;
  eng::poseWorldMatrices(model, pose, world);
  std::vector<glm::mat4> joints;
  std::vector<bool> seen(model.meshes.size(), false);
  for (int node : eng::sceneMeshNodeIndices(model)) {
    size_t meshIndex = static_cast<size_t>(model.nodes[static_cast<size_t>(node)].mesh);
    if (meshIndex >= model.meshes.size() || seen[meshIndex]) continue;
    seen[meshIndex] = true;
    const eng::Mesh& mesh = model.meshes[meshIndex];
    const glm::mat4& nodeWorld = world[static_cast<size_t>(node)];
    int skinIndex = model.nodes[static_cast<size_t>(node)].skin;
    joints.clear();
    if (skinIndex >= 0) eng::skinJointMatrices(model.skins[static_cast<size_t>(skinIndex)], world, node, joints);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const eng::Primitive& primitive = mesh.primitives[p];
      PosedPrimitive posed{.mesh = meshIndex, .primitive = p, .node = node};
      posed.positions.resize(primitive.vertexCount());
      std::vector<glm::vec3> normals;  // posePrimitiveCpu's normals are not needed here
      if (!eng::posePrimitiveCpu(model, node, primitive, mesh.defaultWeights, world, posed.positions, normals)) continue;
      posed.worldToLocal.resize(primitive.vertexCount());
      for (size_t v = 0; v < primitive.vertexCount(); ++v) {
        glm::vec4 local = nodeWorld * glm::vec4(posed.positions[v], 1.0f);
        posed.positions[v] = glm::vec3(local);
        glm::mat3 linear(nodeWorld);
        if (!joints.empty() && !primitive.joints.empty())
          linear = linear * glm::mat3(eng::vertexSkinMatrix(primitive, v, joints));
        posed.worldToLocal[v] = safeInverse(linear);
      }
      face.primitives.push_back(std::move(posed));
    }
  }
  return face;
}

}  // namespace autorig
