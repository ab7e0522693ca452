// The material's base colour as the fragment stages read it: texture x
// instance factor x vertex colour, and glTF's alphaMode MASK test. Shared by
// the colour pass (mesh.frag) and the masked shadow casters
// (shadow_mask.frag), so a lash card's shadow is cut where the lash is.
// Needs frame.glsl.

layout(set = 1, binding = 3) uniform sampler2D baseColorTexture;  // sRGB, white when absent

// What multiplies the texture: the material's factor and the vertex colour.
vec4 baseTint(uint material, vec4 vertexColour) { return instanceMaterials[material].baseColorFactor * vertexColour; }

vec4 baseColour(vec2 uv, uint material, vec4 vertexColour) {
  return texture(baseColorTexture, uv) * baseTint(material, vertexColour);
}

// glTF alphaMode MASK: lashes, brows and hair cards cut out of their quads.
bool cutOut(float alpha) { return (draw.flags & DRAW_FLAG_ALPHA_MASK) != 0u && alpha < draw.alphaCutoff; }
