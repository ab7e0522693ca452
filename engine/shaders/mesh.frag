#version 450
// Base colour (texture x factor), material detail layers blended by morph
// weights (texture cross-blending), then three-point skin shading.
#extension GL_GOOGLE_include_directive : require

#include "frame.glsl"
#include "lighting.glsl"
#include "base_colour.glsl"

layout(set = 1, binding = 4) uniform sampler2DArray detailTextures;   // one layer per detail layer
// glTF's metallicRoughnessTexture (linear): G scales the roughness, B the metallic factor.
layout(set = 1, binding = 7) uniform sampler2D metallicRoughnessTexture;
// glTF's normalTexture (tangent space, linear) and occlusionTexture (R), white when absent.
layout(set = 1, binding = 8) uniform sampler2D normalTexture;
layout(set = 1, binding = 9) uniform sampler2D occlusionTexture;
layout(set = 1, binding = 10) uniform sampler2D emissiveTexture;  // sRGB; read under DRAW_FLAG_EMISSIVE_TEXTURE
layout(set = 1, binding = 11) uniform sampler2D matcapTexture;    // sRGB; read under DRAW_FLAG_TOON_MATCAP
// MToon's masks: the shading shift's (linear, R) and the rim's (sRGB).
layout(set = 1, binding = 12) uniform sampler2D shadingShiftTexture;
layout(set = 1, binding = 13) uniform sampler2D rimMultiplyTexture;

// True only in the MASK pipelines: a shader that can discard loses early
// depth testing, so the others compile the test away.
layout(constant_id = 2) const bool ALPHA_MASK_PIPELINE = false;

struct DetailLayer {
  uint target;     // morph target of the drawn mesh whose weight drives the layer
  float strength;  // scales that weight
  uint modulate;   // 1: the base times twice the layer's colour (DetailBlend::Modulate)
};
layout(std430, set = 1, binding = 5) readonly buffer DetailLayers { DetailLayer detailLayers[]; };

layout(location = 0) in vec3 inWorldPosition;
layout(location = 1) in vec3 inWorldNormal;
layout(location = 2) in vec2 inTexcoord;
layout(location = 3) flat in uint inInstance;
layout(location = 4) in vec4 inColor;
layout(location = 5) flat in uint inMaterial;
layout(location = 6) in vec4 inWorldTangent;

layout(location = 0) out vec4 outColor;

// Every instance's weights for the drawn mesh, as the morph pre-pass read
// them (zero below the active threshold, morph.glsl).
layout(set = 0, binding = 8) uniform samplerBuffer targetWeights;

// The weight of `target` for this instance: one fetch, where searching the
// active list cost every fragment of a face a loop per detail layer.
float activeWeight(InstanceData inst, uint target) {
  return texelFetch(targetWeights, int(inst.weightOffset + target)).x;
}

// Layer l of the material over `base`, by its target's weight.
vec3 blendDetailLayer(vec3 base, InstanceData inst, uint l) {
  float w = clamp(activeWeight(inst, detailLayers[l].target) * detailLayers[l].strength, 0.0, 1.0);
  if (w > 0.0) {
    vec4 layer = texture(detailTextures, vec3(inTexcoord, float(l)));
    base = detailLayers[l].modulate != 0u ? base * mix(vec3(1.0), 2.0 * layer.rgb, layer.a * w)
                                          : mix(base, layer.rgb, layer.a * w);
  }
  return base;
}

// The normal texture's normal in world space around the unit normal n. glTF's
// tangent space: x along the tangent (toward +u), y along the bitangent
// cross(n, tangent) * handedness, z out of the surface. Without vertex tangents
// the frame comes from the screen derivatives of position and UV (Mikkelsen's
// cotangent frame, as three.js builds it), whose second axis runs toward +v,
// the opposite of glTF's: y is negated there, as three.js's glTF loader does.
// The derivatives come in from main(): taken in control flow that varies
// between neighbouring pixels (or after a discard) they are undefined. Along
// y they are taken upward, as in OpenGL, where Vulkan's window y runs down.
struct ScreenDerivatives {
  vec3 q0, q1;    // of the world position along x and y
  vec2 st0, st1;  // of the texture coordinate
};

vec3 normalMapped(vec3 n, ScreenDerivatives d) {
  vec3 texel = texture(normalTexture, inTexcoord).xyz * 2.0 - 1.0;
  texel.xy *= draw.normalScale;
  vec3 t = inWorldTangent.xyz - n * dot(n, inWorldTangent.xyz);
  float t2 = dot(t, t);
  mat3 tbn;
  if (t2 > 1e-24) {
    t *= inversesqrt(t2);
    tbn = mat3(t, cross(n, t) * (inWorldTangent.w < 0.0 ? -1.0 : 1.0), n);
  } else {
    vec3 q1perp = cross(d.q1, n), q0perp = cross(n, d.q0);
    vec3 tangent = q1perp * d.st0.x + q0perp * d.st1.x;
    vec3 bitangent = q1perp * d.st0.y + q0perp * d.st1.y;
    float larger = max(dot(tangent, tangent), dot(bitangent, bitangent));
    float scale = larger > 0.0 ? inversesqrt(larger) : 0.0;
    tbn = mat3(tangent * scale, bitangent * scale, n);
    texel.y = -texel.y;
  }
  vec3 bent = tbn * texel;
  float b2 = dot(bent, bent);
  return b2 > 1e-24 ? bent * inversesqrt(b2) : n;
}

float linearstep(float a, float b, float t) { return clamp((t - a) / max(b - a, 1e-5), 0.0, 1.0); }

// MToon (VRMC_materials_mtoon 1.0): for each light, dot(N, L) + shading shift
// through linearstep(-1 + toony, 1 - toony) mixes the shade colour into the
// lit (base) colour, the key light's shadow darkening toward the shade; the
// ambient light is evened out over directions by GI equalization; the
// parametric rim is added on top. The portrait rig's back light is left out:
// MToon's own rim takes its place.
vec3 shadeToon(InstanceMaterial material, vec3 lit, vec3 n, vec3 toViewer, float keyVisibility) {
  vec3 shade = material.toonShade.rgb;
  if ((draw.flags & DRAW_FLAG_TOON_SHADE_TEXTURE) != 0u) shade *= texture(baseColorTexture, inTexcoord).rgb;
  float shift = material.toonShading.x, toony = material.toonShading.y;
  if ((draw.flags & DRAW_FLAG_TOON_SHADING_SHIFT_TEXTURE) != 0u)
    shift += texture(shadingShiftTexture, inTexcoord).r * draw.toonShadingShiftScale;
  float key = linearstep(-1.0 + toony, 1.0 - toony, dot(n, frame.keyDirection.xyz) + shift) * keyVisibility;
  float fill = linearstep(-1.0 + toony, 1.0 - toony, dot(n, frame.fillDirection.xyz) + shift);
  vec3 color = mix(shade, lit, key) * frame.keyColor.rgb + mix(shade, lit, fill) * frame.fillColor.rgb;
  vec3 rawGi = mix(frame.groundAmbient.rgb, frame.skyAmbient.rgb, n.y * 0.5 + 0.5);
  vec3 gi = mix(rawGi, 0.5 * (frame.groundAmbient.rgb + frame.skyAmbient.rgb), material.toonShading.z);
  color += gi * lit;
  float rim = pow(clamp(1.0 - dot(n, toViewer) + material.toonShade.w, 0.0, 1.0), max(material.toonRim.w, 1e-5));
  vec3 rimLight = rim * material.toonRim.rgb;
  if ((draw.flags & DRAW_FLAG_TOON_MATCAP) != 0u) {
    // The matcap by the view-space normal (the spec's axes; the image's top row
    // lights the surface that faces up, as matcaps are painted).
    vec3 across = vec3(toViewer.z, 0.0, -toViewer.x);
    vec3 viewX = dot(across, across) > 1e-10 ? normalize(across) : vec3(1.0, 0.0, 0.0);  // seen from straight above
    vec3 viewY = cross(toViewer, viewX);
    vec2 matcapUv = vec2(dot(viewX, n), -dot(viewY, n)) * 0.495 + 0.5;
    rimLight += material.toonMatcap.rgb * texture(matcapTexture, matcapUv).rgb;
  }
  if ((draw.flags & DRAW_FLAG_TOON_RIM_MULTIPLY) != 0u) rimLight *= texture(rimMultiplyTexture, inTexcoord).rgb;
  vec3 lighting = frame.keyColor.rgb * keyVisibility + frame.fillColor.rgb + gi;
  return color + rimLight * mix(vec3(1.0), lighting, material.toonShading.w);
}

void main() {
  // Taken only for a normal texture: the flag is the same for the whole draw,
  // so the branch is uniform, and other draws pay nothing for them.
  ScreenDerivatives derivatives = ScreenDerivatives(vec3(0.0), vec3(0.0), vec2(0.0), vec2(0.0));
  if ((draw.flags & DRAW_FLAG_NORMAL_MAP) != 0u)
    derivatives = ScreenDerivatives(dFdx(inWorldPosition), -dFdy(inWorldPosition), dFdx(inTexcoord), -dFdy(inTexcoord));
  InstanceMaterial material = instanceMaterials[inMaterial];
  vec3 emission = material.emissive.rgb;
  if ((draw.flags & DRAW_FLAG_EMISSIVE_TEXTURE) != 0u) emission *= texture(emissiveTexture, inTexcoord).rgb;
  // Detail layers are other textures for the same UVs: they blend into the
  // texel, and the material's factor and the vertex colour tint the result,
  // so a layer painted for the texture follows a skin recoloured by its factor.
  vec4 texel = texture(baseColorTexture, inTexcoord);
  const vec4 tint = baseTint(inMaterial, inColor);
  if (ALPHA_MASK_PIPELINE && cutOut(texel.a * tint.a)) discard;

  if (draw.detailLayerCount > 0u) {
    InstanceData inst = instances[inInstance];
    // Only the layers some instance of the draw can show, in layer order: a
    // CPU rasteriser runs both sides of the `w > 0` branch below, sampling
    // every layer it loops over for every pixel. Layers past 32 (no mask bit)
    // are all visited.
    for (uint bits = draw.detailLayerMask; bits != 0u; bits &= bits - 1u)
      texel.rgb = blendDetailLayer(texel.rgb, inst, uint(findLSB(bits)));
    for (uint l = 32u; l < draw.detailLayerCount; ++l) texel.rgb = blendDetailLayer(texel.rgb, inst, l);
  }
  const vec4 base = texel * tint;

  // BLEND draws go through a blending pipeline; every other mode is opaque.
  const float alpha = (draw.flags & DRAW_FLAG_ALPHA_BLEND) != 0u ? clamp(base.a, 0.0, 1.0) : 1.0;
  // Unlit (KHR_materials_unlit): the colour the artist painted, untouched by
  // the lights and the exposure and tone curve that are there for them.
  if ((draw.flags & DRAW_FLAG_UNLIT) != 0u) {
    outColor = vec4(clamp(base.rgb + emission, 0.0, 1.0), alpha);
    return;
  }

  SurfacePoint s;
  s.albedo = base.rgb;
  s.toViewer = normalize(frame.cameraPosition.xyz - inWorldPosition);
  vec3 n = inWorldNormal;
  float n2 = dot(n, n);
  // Degenerate normals (collapsed morph) fall back to facing the viewer.
  n = n2 > 1e-24 ? n * inversesqrt(n2) : s.toViewer;
  // The back of a double-sided shell seen through an opening is the inside
  // of the head (an open mouth without a mouth bag, nostrils, eye holes): a
  // cavity that the lights cannot reach. Lit like the outside, it fills an
  // open mouth with skin; darkened, the mouth reads as open.
  // A mirrored transform (glTF: negative determinant) turns the winding, so
  // the rasteriser's front is the primitive's back.
  const bool frontFacing = gl_FrontFacing != ((draw.flags & DRAW_FLAG_MIRRORED) != 0u);
  const bool inside = !OUTLINE_PIPELINE && (draw.flags & DRAW_FLAG_DOUBLE_SIDED) != 0u && !frontFacing;
  if (inside) n = -n;
  // The inside of the head is darkened, not modelled, and an outline is a
  // hull: their normals stay.
  if ((draw.flags & DRAW_FLAG_NORMAL_MAP) != 0u && !inside && !OUTLINE_PIPELINE) n = normalMapped(n, derivatives);
  s.normal = n;
  if (OUTLINE_PIPELINE) {
    // The hull's back faces: the outline colour, toward it times the shaded
    // surface as much as the lighting mix says.
    vec3 toon = shadeToon(material, base.rgb, n, s.toViewer, keyLightVisibility(inWorldPosition, n)) + emission;
    outColor = vec4(toneMap(material.toonOutline.rgb * mix(vec3(1.0), toon, material.toonOutlineStyle.y)), 1.0);
    return;
  }
  if ((draw.flags & DRAW_FLAG_TOON) != 0u) {
    vec3 toon = shadeToon(material, base.rgb, n, s.toViewer, inside ? 0.0 : keyLightVisibility(inWorldPosition, n));
    outColor = vec4(toneMap(inside ? toon * 0.12 : toon + emission), alpha);
    return;
  }
  const vec2 roughnessMetal = texture(metallicRoughnessTexture, inTexcoord).gb;
  s.roughness = clamp(draw.roughness * roughnessMetal.x, 0.05, 1.0);
  s.metallic = clamp(draw.metallic * roughnessMetal.y, 0.0, 1.0);
  s.occlusion = draw.occlusionStrength > 0.0 ? 1.0 + draw.occlusionStrength * (texture(occlusionTexture, inTexcoord).r - 1.0)
                                              : 1.0;  // a CPU rasteriser samples what it is told to, white or not

  float keyVisibility = keyLightVisibility(inWorldPosition, s.normal);
  vec3 lit = shadeThreePoint(s, inside ? 0.0 : keyVisibility);
  outColor = vec4(toneMap(inside ? lit * 0.12 : lit + emission), alpha);
}
