// Morphing, once per frame: morph.comp (a compute pre-pass) sums each
// instance's weighted deltas into the slot's morphed-vertex buffer, and every
// pass that draws the instance (shadow map, main pass, capture) reads the
// result in mesh.vert instead of morphing again.
//
// Deltas are sparse and vertex-major (set 1, one primitive): vertex v's
// entries, in target order, one per target that moves v (position, normal,
// tangent or crease non-zero). Cost follows the (vertex, target) pairs that
// move something, not vertices x targets: face targets are local (a brow
// target leaves the mouth alone). An entry is two vec4, position delta + the
// target index (as a float value) and normal delta + crease darkening (how
// much the target darkens v at full weight: engine/scene/crease_shading.h),
// then a third, the tangent delta, where the primitive has tangent deltas.
// Sliced (engine/vk/gpu_model.cpp, compactDeltas): MORPH_SLICE_LANES
// consecutive vertices form a slice whose rows morphOffsets[s] ..
// morphOffsets[s + 1] hold the k-th entry of every vertex of the slice side
// by side, plane by plane, so neighbouring invocations fetch neighbouring
// texels; shorter lists are padded with entries that add nothing.
//
// Rest attributes come from the model's vertex buffer (set 1 binding 2) at
// the float offsets draw.restPosition / restNormal / restTangent.
// Weights: set 0 binding 8, the instance's targets in order from
// inst.weightOffset, zero where the active list (frame.glsl) has no entry, so
// the sum matches the active-list loop term for term.

struct MorphedVertex {
  vec3 position;
  vec3 normal;
  vec3 tangent;
  float crease;  // summed crease darkening, 0 = none (clamped where it is used)
};

// Per morphed vertex: position + crease, normal, and the tangent only where
// the primitive has tangent deltas (without them the morphed tangent is the
// rest tangent, which mesh.vert reads from its attribute).
#if defined(MORPH_WRITE)
layout(std430, set = 0, binding = 7) writeonly buffer MorphedVertices { vec4 morphed[]; };
#else
layout(std430, set = 0, binding = 7) readonly buffer MorphedVertices { vec4 morphed[]; };
#endif

// A degenerate blended normal keeps its direction undefined: fall back to
// zero rather than NaN so one bad vertex cannot poison the whole frame.
vec3 safeNormalize(vec3 v) {
  float v2 = dot(v, v);
  return v2 > 1e-24 ? v * inversesqrt(v2) : vec3(0.0);
}

MorphedVertex finishedVertex(vec3 position, vec3 normal, vec3 tangent, float crease) {
  MorphedVertex result;
  result.position = position;
  result.normal = safeNormalize(normal);
  result.tangent = safeNormalize(tangent);
  result.crease = crease;
  return result;
}

uint morphedStride() { return (draw.flags & DRAW_FLAG_TANGENT_DELTAS) != 0u ? 3u : 2u; }

// The vertex's first vec4 (draw.morphOffset counts vec4).
uint morphedSlot(uint vertex, uint instanceInDraw) {
  return draw.morphOffset + (instanceInDraw * draw.vertexCount + vertex) * morphedStride();
}

#if defined(MORPH_WRITE)
const uint MORPH_SLICE_LANES = 8u;  // gpu_model.cpp's kMorphSliceLanes

// Texel buffers rather than storage buffers: a CPU device (lavapipe) fetches
// texels for all SIMD lanes at once but loads storage lane by lane.
layout(set = 0, binding = 8) uniform samplerBuffer targetWeights;
layout(set = 1, binding = 0) uniform usamplerBuffer morphOffsets;
layout(set = 1, binding = 1) uniform samplerBuffer morphEntries;
layout(set = 1, binding = 2) uniform samplerBuffer rest;

float restFloat(uint i) { return texelFetch(rest, int(i)).x; }

vec3 restVec3(uint base, uint vertex) {
  uint i = base + vertex * 3u;
  return vec3(restFloat(i), restFloat(i + 1u), restFloat(i + 2u));
}

// The morphed (not yet skinned) vertex of one instance.
MorphedVertex morphVertex(uint vertex, InstanceData inst) {
  vec3 position = restVec3(draw.restPosition, vertex);
  vec3 normal = restVec3(draw.restNormal, vertex);
  bool tangents = (draw.flags & DRAW_FLAG_TANGENT_DELTAS) != 0u;
  // Without tangent deltas the tangent is not written (mesh.vert reads its attribute).
  uint t4 = draw.restTangent + vertex * 4u;
  vec3 tangent = tangents ? vec3(restFloat(t4), restFloat(t4 + 1u), restFloat(t4 + 2u)) : vec3(0.0);
  float crease = 0.0;
  uint planes = tangents ? 3u : 2u;
  uint slice = vertex / MORPH_SLICE_LANES, lane = vertex % MORPH_SLICE_LANES;
  uint end = texelFetch(morphOffsets, int(slice + 1u)).x;
  for (uint row = texelFetch(morphOffsets, int(slice)).x; row < end; ++row) {
    uint e = row * planes * MORPH_SLICE_LANES + lane;
    vec4 p = texelFetch(morphEntries, int(e));
    float w = texelFetch(targetWeights, int(inst.weightOffset + uint(p.w))).x;
    if (w == 0.0) continue;  // not in the active list, or padding
    vec4 n = texelFetch(morphEntries, int(e + MORPH_SLICE_LANES));
    position += w * p.xyz;
    normal += w * n.xyz;
    crease += w * n.w;
    if (tangents) tangent += w * texelFetch(morphEntries, int(e + 2u * MORPH_SLICE_LANES)).xyz;
  }
  return finishedVertex(position, normal, tangent, crease);
}
#else
// The instance's morphed vertex as morph.comp left it (rest pose where the
// primitive has no deltas or the instance no active weight).
MorphedVertex morphedVertex(uint vertex, uint instanceInDraw, InstanceData inst, vec3 position, vec3 normal,
                            vec3 tangent) {
  if ((draw.flags & DRAW_FLAG_MORPHED) == 0u || inst.activeCount == 0u)
    return finishedVertex(position, normal, tangent, 0.0);
  uint slot = morphedSlot(vertex, instanceInDraw);
  vec4 p = morphed[slot];
  MorphedVertex result;
  result.position = p.xyz;
  result.crease = p.w;
  result.normal = morphed[slot + 1u].xyz;
  result.tangent = morphedStride() == 3u ? morphed[slot + 2u].xyz : safeNormalize(tangent);
  return result;
}
#endif
