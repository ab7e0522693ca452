// Linear blend skinning, applied after morphing (see mesh.vert).
//
// Joint matrices: set 0 binding 5, mat4 per joint, one slice per (instance,
// skinned mesh node) written each frame by the scene renderer
// (InstanceData.jointOffset / jointCount; jointCount 0 = not skinned).
// Influences: set 1 binding 6, per primitive, vertex-major: vertex v's group
// s of four influences is influences[(v * draw.jointSets + s) * 2] (joint
// indices) and [... + 1] (weights as float bits). draw.jointSets 0 = the
// primitive has no JOINTS_n / WEIGHTS_n. Mirrors eng::vertexSkinMatrix
// (engine/scene/skinning.cpp), the CPU reference.

layout(std430, set = 0, binding = 5) readonly buffer JointMatrices { mat4 jointMatrices[]; };
layout(std430, set = 1, binding = 6) readonly buffer SkinInfluences { uvec4 influences[]; };

bool isSkinned(InstanceData inst) { return inst.jointCount > 0u && draw.jointSets > 0u; }

// Identity when the vertex's weights sum to zero; influences naming a joint
// past the skin are skipped (the loader refuses such skins; this keeps a bad
// upload from reading another instance's matrices).
mat4 vertexSkinMatrix(uint vertex, InstanceData inst) {
  mat4 sum = mat4(0.0);
  float total = 0.0;
  for (uint s = 0u; s < draw.jointSets; ++s) {
    uint base = (vertex * draw.jointSets + s) * 2u;
    uvec4 joints = influences[base];
    vec4 weights = uintBitsToFloat(influences[base + 1u]);
    for (int i = 0; i < 4; ++i) {
      if (weights[i] == 0.0 || joints[i] >= inst.jointCount) continue;
      sum += weights[i] * jointMatrices[inst.jointOffset + joints[i]];
      total += weights[i];
    }
  }
  return total > 0.0 ? sum : mat4(1.0);
}

// Skins a morphed vertex in place (position, normal, tangent).
void skinVertex(uint vertex, InstanceData inst, inout MorphedVertex m) {
  if (!isSkinned(inst)) return;
  mat4 skin = vertexSkinMatrix(vertex, inst);
  m.position = (skin * vec4(m.position, 1.0)).xyz;
  mat3 linear = mat3(skin);
  vec3 n = linear * m.normal;
  float n2 = dot(n, n);
  m.normal = n2 > 1e-24 ? n * inversesqrt(n2) : vec3(0.0);
  vec3 t = linear * m.tangent;
  float t2 = dot(t, t);
  m.tangent = t2 > 1e-24 ? t * inversesqrt(t2) : vec3(0.0);
}
