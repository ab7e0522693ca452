// Skin-friendly three-point lighting (key, fill, rim), in linear space.
// Wrapped diffuse softens the light/shadow transition the way light
// scattering under skin does; a warm tint is added where the wrapped term
// exceeds plain Lambert (the terminator) to fake the red bleed of subsurface
// scattering; the specular lobe is a normalised Blinn-Phong with a low,
// skin-like Fresnel reflectance so highlights stay gentle.

const float PI = 3.14159265;

// The key light's shadow map (depth compare, bilinear: each tap is 2x2 PCF).
layout(set = 0, binding = 4) uniform sampler2DShadow keyShadowMap;

// Quality tier (engine/vk/render_quality.h), fixed per pipeline: the shadow
// filter is (2r+1)^2 taps over the same penumbra; without secondary specular
// only the key light has a highlight.
layout(constant_id = 0) const int SHADOW_FILTER_RADIUS = 1;
layout(constant_id = 1) const bool SECONDARY_SPECULAR = true;

// Soft key-light visibility: a 5x5 grid of bilinear depth-compare taps (each
// already a 2x2 PCF) spread over the penumbra radius: a smooth tent-shaped
// falloff without the grain of rotated random taps.
// Self-shadowing (acne, and the faceted "terminator" pattern of low-poly
// skin) is avoided three ways: the receiver is pushed along its normal, the
// compared depth is biased by how far a surface of this slope recedes
// across the filter's footprint, and surfaces turned away from the key keep
// their wrapped (subsurface) light: they are not lit directly anyway, and the
// shadow map cannot tell the surface's own back from an occluder.
float keyLightVisibility(vec3 worldPosition, vec3 normal) {
  if (frame.shadow.w < 0.5) return 1.0;
  float nDotL = dot(normal, frame.keyDirection.xyz);
  float facing = smoothstep(0.0, 0.2, nDotL);
  if (facing <= 0.0) return 1.0;
  vec4 clip = frame.keyLightViewProj * vec4(worldPosition + normal * frame.shadow.z, 1.0);
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  // Depth spans 4 scene radii, uv 2.1: a slope of tan(theta) recedes 0.525 tan(theta) depth per uv.
  float cosTheta = clamp(nDotL, 0.2, 1.0);
  float tanTheta = sqrt(1.0 - cosTheta * cosTheta) / cosTheta;
  float depth = ndc.z - frame.shadow.y * 0.525 * tanTheta - 0.0005;
  float spacing = frame.shadow.y / float(max(SHADOW_FILTER_RADIUS, 1));
  float lit = 0.0;
  for (int y = -SHADOW_FILTER_RADIUS; y <= SHADOW_FILTER_RADIUS; ++y) {
    for (int x = -SHADOW_FILTER_RADIUS; x <= SHADOW_FILTER_RADIUS; ++x)
      lit += texture(keyShadowMap, vec3(uv + vec2(x, y) * spacing, depth));
  }
  const int taps = (2 * SHADOW_FILTER_RADIUS + 1) * (2 * SHADOW_FILTER_RADIUS + 1);
  return mix(1.0, lit / float(taps), facing);
}

struct SurfacePoint {
  vec3 albedo;      // linear base colour
  vec3 normal;      // unit, facing the viewer side for double-sided surfaces
  vec3 toViewer;    // unit
  float roughness;  // perceptual, [0.05, 1]
  float metallic;
  float occlusion;  // share of the ambient light that reaches the point (glTF occlusionTexture)
};

vec3 shadeLight(SurfacePoint s, vec3 toLight, vec3 lightColor, bool withSpecular) {
  float wrap = frame.skin.x;
  float nDotL = dot(s.normal, toLight);
  float lambert = max(nDotL, 0.0);
  float wrapped = max((nDotL + wrap) / (1.0 + wrap), 0.0);
  // Positive only in the band the wrap adds around the terminator.
  float terminator = max(wrapped - lambert, 0.0);

  vec3 diffuseColor = s.albedo * (1.0 - s.metallic);
  vec3 diffuse = diffuseColor * wrapped + frame.subsurfaceColor.rgb * s.albedo * terminator * frame.skin.y;
  if (!withSpecular) return diffuse * lightColor;

  vec3 h = normalize(toLight + s.toViewer);
  float nDotH = max(dot(s.normal, h), 0.0);
  float alpha = max(s.roughness * s.roughness, 0.02);
  // pow(x, y) is undefined for x < 0, and for x = 0 with y <= 0: at roughness 1
  // (glTF's default) the exponent is 0, and where nDotH is 0 (every surface
  // turned from the light) an NVIDIA driver returns NaN, which the tone curve
  // turns black: half of facecap's face rendered black on an H200, while
  // lavapipe returned 1. Hence an exponent kept above 0 and a base kept >= 0.
  float shininess = max(2.0 / (alpha * alpha) - 2.0, 1e-3);
  float normalisation = (shininess + 8.0) / (8.0 * PI);
  vec3 f0 = mix(vec3(0.028), s.albedo, s.metallic);  // 0.028: skin's reflectance at normal incidence
  float vDotH = clamp(dot(s.toViewer, h), 0.0, 1.0);
  vec3 fresnel = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
  // The gentle strength is skin's; a metal's colour is its reflection, at full strength.
  float lobe = normalisation * pow(nDotH, shininess);
  if (s.metallic > 0.0) {
    // A metal's lobe is glTF's own, GGX with Smith's visibility (Schlick's
    // fit), as three.js draws it: its long tail lights thin metal (glasses
    // frames, a chain) along its length where Blinn-Phong's narrow peak
    // leaves it dark.
    float a2 = alpha * alpha;
    float d = nDotH * nDotH * (a2 - 1.0) + 1.0;
    float k = 0.5 * alpha;
    float nDotV = max(dot(s.normal, s.toViewer), 1e-3);
    float ggx = a2 / (PI * d * d) * 0.25 / ((lambert * (1.0 - k) + k) * (nDotV * (1.0 - k) + k));
    lobe = mix(lobe, ggx, s.metallic);
  }
  vec3 specular = fresnel * lobe * lambert * mix(frame.skin.z, 1.0, s.metallic);

  return (diffuse + specular) * lightColor;
}

vec3 shadeThreePoint(SurfacePoint s, float keyVisibility) {
  vec3 keyColor = frame.keyColor.rgb * mix(frame.shadowColor.rgb, vec3(1.0), keyVisibility);
  vec3 color = shadeLight(s, frame.keyDirection.xyz, keyColor, true);
  color += shadeLight(s, frame.fillDirection.xyz, frame.fillColor.rgb, SECONDARY_SPECULAR);
  color += shadeLight(s, frame.rimDirection.xyz, frame.rimColor.rgb, SECONDARY_SPECULAR);
  // Hemisphere ambient: sky from above, bounce from below.
  float up = s.normal.y * 0.5 + 0.5;
  color += s.albedo * (1.0 - s.metallic) * s.occlusion * mix(frame.groundAmbient.rgb, frame.skyAmbient.rgb, up);
  // The same hemisphere seen in reflection (Karis's analytic split-sum fit for
  // the BRDF's share): without it a metal, which has no diffuse colour, is
  // black wherever no light's highlight falls on it (gold frames, a buckle).
  vec3 reflected = reflect(-s.toViewer, s.normal);
  vec3 sky = mix(frame.groundAmbient.rgb, frame.skyAmbient.rgb, reflected.y * 0.5 + 0.5);
  sky = mix(sky, 0.5 * (frame.groundAmbient.rgb + frame.skyAmbient.rgb), s.roughness);
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022), c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = s.roughness * c0 + c1;
  float nDotV = clamp(dot(s.normal, s.toViewer), 0.0, 1.0);
  float a004 = min(r.x * r.x, exp2(-9.28 * nDotV)) * r.x + r.y;
  vec2 scaleBias = vec2(-1.04, 1.04) * a004 + r.zw;
  color += s.metallic * (s.albedo * scaleBias.x + scaleBias.y) * sky * s.occlusion;
  return color;
}

// Filmic curve (Narkowicz's ACES fit) applied to the brightest channel and
// the colour scaled to match: highlights roll off smoothly instead of clipping
// to flat white on a pale face, and hue is kept (per-channel ACES would push
// skin toward orange).
float filmic(float x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

vec3 toneMap(vec3 color) {
  color *= frame.skin.w;
  float peak = max(max(color.r, color.g), color.b);
  return peak > 1e-6 ? color * (filmic(peak) / peak) : vec3(0.0);
}
