#version 450
// Full-screen triangle for the background gradient; no vertex buffer. At the
// far plane: drawn after the opaque draws, it shades only the pixels they left.
layout(location = 0) out vec2 outUv;

void main() {
  vec2 uv = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  outUv = uv;
  gl_Position = vec4(uv * 2.0 - 1.0, 1.0, 1.0);
}
