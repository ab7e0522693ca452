// Morphing from storage buffers of deltas (set 1, one primitive).
//
// Layout: target-major, vertex-minor, float-tight: the delta of vertex v in
// target t starts at float index (t * vertexCount + v) * 3. Why float-tight
// rather than vec4-padded: std430 pads vec3 arrays to 16 bytes, so vec4 would
// cost 33% more memory and bandwidth for the same data; neighbouring vertex
// invocations still read neighbouring addresses, so loads stay coalesced, and
// the CPU model's glm::vec3 arrays upload with one memcpy. Targets that lack
// an attribute are stored as zeros; primitives where no target has normal
// (tangent) deltas skip those loads via draw.flags.

layout(std430, set = 1, binding = 0) readonly buffer PositionDeltas { float positionDeltas[]; };
layout(std430, set = 1, binding = 1) readonly buffer NormalDeltas { float normalDeltas[]; };
layout(std430, set = 1, binding = 2) readonly buffer TangentDeltas { float tangentDeltas[]; };
// How much each target darkens each vertex at full weight (folds forming:
// engine/scene/crease_shading.h), target-major, one float per vertex.
layout(std430, set = 1, binding = 7) readonly buffer CreaseDarkening { float creaseDarkening[]; };

struct MorphedVertex {
  vec3 position;
  vec3 normal;
  vec3 tangent;
  float crease;  // summed crease darkening, 0 = none (clamped where it is used)
};

// Loops over the instance's compact active list: cost is proportional to the
// number of non-zero weights, with no cap on the number of targets.
MorphedVertex morphVertex(uint vertex, InstanceData inst, vec3 position, vec3 normal, vec3 tangent) {
  bool morphNormals = (draw.flags & DRAW_FLAG_NORMAL_DELTAS) != 0u;
  bool morphTangents = (draw.flags & DRAW_FLAG_TANGENT_DELTAS) != 0u;
  bool creases = (draw.flags & DRAW_FLAG_CREASES) != 0u;
  float crease = 0.0;
  uint end = inst.activeOffset + inst.activeCount;
  for (uint i = inst.activeOffset; i < end; ++i) {
    ActiveWeight a = activeWeights[i];
    uint base = (a.target * draw.vertexCount + vertex) * 3u;
    position += a.weight * vec3(positionDeltas[base], positionDeltas[base + 1u], positionDeltas[base + 2u]);
    if (morphNormals) {
      normal += a.weight * vec3(normalDeltas[base], normalDeltas[base + 1u], normalDeltas[base + 2u]);
    }
    if (morphTangents) {
      tangent += a.weight * vec3(tangentDeltas[base], tangentDeltas[base + 1u], tangentDeltas[base + 2u]);
    }
    if (creases) crease += a.weight * creaseDarkening[a.target * draw.vertexCount + vertex];
  }
  MorphedVertex result;
  result.position = position;
  result.crease = crease;
  // A degenerate blended normal keeps its direction undefined: fall back to
  // zero rather than NaN so one bad vertex cannot poison the whole frame.
  float n2 = dot(normal, normal);
  result.normal = n2 > 1e-24 ? normal * inversesqrt(n2) : vec3(0.0);
  float t2 = dot(tangent, tangent);
  result.tangent = t2 > 1e-24 ? tangent * inversesqrt(t2) : vec3(0.0);
  return result;
}
