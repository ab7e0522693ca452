#pragma once
// Shared access to the built-in head for the facial_head tests: the landmark
// file from data/ and the head generated from it (once per test program).
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "engine/scene/model.h"
#include "bake/head/head_generator.h"
#include "bake/head/head_rig_spec.h"

namespace head_testing {

const bake::HeadRigSpec& builtInSpec();
const bake::GeneratedHead& builtInHead();

const eng::Mesh& headMesh(const eng::Model& model);  // mesh "Head"
const eng::Primitive& headPrimitive(const eng::Model& model, bake::HeadPrimitive p);
int targetIndex(const eng::Mesh& mesh, const std::string& name);  // -1 when absent
glm::vec3 landmark(const bake::GeneratedHead& head, const std::string& name);

// Positions of a primitive with one target applied at `weight`.
std::vector<glm::vec3> morphed(const eng::Primitive& prim, int target, float weight);
size_t nearestVertex(const std::vector<glm::vec3>& positions, const glm::vec3& p);

struct Eyeball {
  glm::vec3 centre;
  float radius;
};
// Eyeball 0 (left) or 1 (right): the primitive of mesh "EyeLeft" / "EyeRight"
// with its positions placed in head space by the node that draws it (each
// eye's node sits at the ball's centre, its joint).
eng::Primitive eyeballInHeadSpace(const eng::Model& model, int index);
// Centre and radius of eyeball 0 (left) or 1 (right) in head space, from its
// vertices (the cornea bulges forward, so the centre comes from x and y).
Eyeball eyeball(const eng::Model& model, int index);

// Front-most hit (largest z) of the ray (x, y, +inf) -> -Z on a triangle list.
std::optional<float> frontHitZ(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                               float x, float y);

// frontHitZ for many rays against one triangle list: the triangles are
// bucketed by their x-y bounds once, and each ray tests only its bucket's
// (the teeth-behind-lips test casts thousands of rays at every pose).
class FrontView {
 public:
  FrontView(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices);
  std::optional<float> hitZ(float x, float y) const;

 private:
  static constexpr int kCells = 48;
  int cellOf(float v, float lo, float size) const;
  const std::vector<glm::vec3>& positions_;
  const std::vector<uint32_t>& indices_;
  glm::vec2 lo_{0.0f}, cellSize_{1.0f};
  std::vector<std::vector<uint32_t>> buckets_;  // first index of each triangle, per cell
};

}  // namespace head_testing
