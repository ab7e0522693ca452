#version 450
// The morph pre-pass: one invocation per vertex of one primitive for one
// instance (workgroup y = instance within the draw), writing the morphed
// vertex that the shadow, main and capture passes read (morph.glsl).
#extension GL_GOOGLE_include_directive : require
#define MORPH_WRITE 1

#include "frame.glsl"
#include "morph.glsl"

layout(local_size_x = 64) in;

void main() {
  uint instanceInDraw = gl_WorkGroupID.y;
  InstanceData inst = instances[draw.firstInstance + instanceInDraw];
  if (inst.activeCount == 0u) return;  // rest pose: mesh.vert reads the vertex buffer
  // Strided: the renderer may dispatch fewer invocations than vertices (two
  // vertices each on a CPU device, and a primitive with more vertices than
  // the device's group count times 64). The stride is a multiple of the
  // delta slices' 8 lanes, so neighbouring invocations stay on neighbouring
  // vertices.
  uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  for (uint vertex = gl_GlobalInvocationID.x; vertex < draw.vertexCount; vertex += stride) {
    MorphedVertex m = morphVertex(vertex, inst);
    uint slot = morphedSlot(vertex, instanceInDraw);
    morphed[slot] = vec4(m.position, m.crease);
    morphed[slot + 1u] = vec4(m.normal, 0.0);
    if (morphedStride() == 3u) morphed[slot + 2u] = vec4(m.tangent, 0.0);
  }
}
