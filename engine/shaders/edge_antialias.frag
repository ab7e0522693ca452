#version 450
// Edge-aware anti-aliasing of a 1-sample image (FXAA 3.11 "quality", preset
// 12: five search steps), one full-screen pass before the read-back. The
// source is an sRGB image sampled through an sRGB view, so the filter blends
// linear (premultiplied) colour as a multisample resolve does; the edges are
// found on perceptual luma (sqrt of linear luma: FXAA's own "gamma 2.0"
// input) as FXAA expects. Pixels without an edge return their texel as
// fetched, so a flat image comes back unchanged.
layout(set = 0, binding = 0) uniform sampler2D source;  // bilinear, clamp to edge

layout(location = 0) in vec2 inUv;  // unused: positions come from gl_FragCoord
layout(location = 0) out vec4 outColor;

// FXAA 3.11's defaults for its quality preset 12.
const float kSubpix = 0.75;  // how much sub-pixel aliasing is removed (0.25 and 0.5: docs/performance.md)
const float kEdgeThreshold = 0.166;    // local contrast needed, relative to the brightest neighbour
const float kEdgeThresholdMin = 0.0833;  // ... and absolute (skips dark noise)
const int kSearchSteps = 5;
const float kStep[kSearchSteps] = float[](1.0, 1.5, 2.0, 4.0, 12.0);

float luma(vec4 linearColour) { return sqrt(dot(linearColour.rgb, vec3(0.299, 0.587, 0.114))); }

ivec2 lastTexel;
float lumaAt(ivec2 texel, ivec2 offset) {
  return luma(texelFetch(source, clamp(texel + offset, ivec2(0), lastTexel), 0));
}
float lumaAt(vec2 uv) { return luma(textureLod(source, uv, 0.0)); }

void main() {
  lastTexel = textureSize(source, 0) - 1;
  const vec2 rcpFrame = 1.0 / vec2(textureSize(source, 0));
  const ivec2 texel = ivec2(gl_FragCoord.xy);
  vec2 posM = gl_FragCoord.xy * rcpFrame;
  const vec4 rgbyM = texelFetch(source, texel, 0);
  const float lumaM = luma(rgbyM);
  float lumaS = lumaAt(texel, ivec2(0, 1));
  float lumaE = lumaAt(texel, ivec2(1, 0));
  float lumaN = lumaAt(texel, ivec2(0, -1));
  float lumaW = lumaAt(texel, ivec2(-1, 0));
  const float rangeMax = max(max(lumaN, lumaW), max(lumaE, max(lumaS, lumaM)));
  const float rangeMin = min(min(lumaN, lumaW), min(lumaE, min(lumaS, lumaM)));
  const float range = rangeMax - rangeMin;
  if (range < max(kEdgeThresholdMin, rangeMax * kEdgeThreshold)) {
    outColor = rgbyM;
    return;
  }

  const float lumaNW = lumaAt(texel, ivec2(-1, -1));
  const float lumaSE = lumaAt(texel, ivec2(1, 1));
  const float lumaNE = lumaAt(texel, ivec2(1, -1));
  const float lumaSW = lumaAt(texel, ivec2(-1, 1));

  // Horizontal or vertical edge: second differences across each direction.
  const float edgeHorz = abs(-2.0 * lumaW + lumaNW + lumaSW) + 2.0 * abs(-2.0 * lumaM + lumaN + lumaS) +
                         abs(-2.0 * lumaE + lumaNE + lumaSE);
  const float edgeVert = abs(-2.0 * lumaS + lumaSW + lumaSE) + 2.0 * abs(-2.0 * lumaM + lumaW + lumaE) +
                         abs(-2.0 * lumaN + lumaNW + lumaNE);
  const bool horzSpan = edgeHorz >= edgeVert;
  float lengthSign = horzSpan ? rcpFrame.y : rcpFrame.x;
  if (!horzSpan) {
    lumaN = lumaW;
    lumaS = lumaE;
  }

  // Sub-pixel aliasing: how far the centre stands out from its 3x3 average.
  const float subpixA = 2.0 * (lumaN + lumaS + lumaW + lumaE) + (lumaNW + lumaSW + lumaNE + lumaSE);
  const float subpixC = clamp(abs(subpixA / 12.0 - lumaM) / range, 0.0, 1.0);
  const float subpixF = (-2.0 * subpixC + 3.0) * subpixC * subpixC;
  const float subpixH = subpixF * subpixF * kSubpix;

  // The side of the edge with the steeper gradient; walk along the edge,
  // half a texel towards that side, in both directions until its luma changes.
  const float gradientN = lumaN - lumaM;
  const float gradientS = lumaS - lumaM;
  const bool pairN = abs(gradientN) >= abs(gradientS);
  const float gradientScaled = max(abs(gradientN), abs(gradientS)) / 4.0;
  if (pairN) lengthSign = -lengthSign;
  const float lumaNN = (pairN ? lumaN : lumaS) + lumaM;
  vec2 posB = posM;
  if (horzSpan) posB.y += lengthSign * 0.5;
  else posB.x += lengthSign * 0.5;
  const vec2 offNP = horzSpan ? vec2(rcpFrame.x, 0.0) : vec2(0.0, rcpFrame.y);
  vec2 posN = posB - offNP * kStep[0];
  vec2 posP = posB + offNP * kStep[0];
  float lumaEndN = lumaAt(posN) - lumaNN * 0.5;
  float lumaEndP = lumaAt(posP) - lumaNN * 0.5;
  bool doneN = abs(lumaEndN) >= gradientScaled;
  bool doneP = abs(lumaEndP) >= gradientScaled;
  for (int i = 1; i < kSearchSteps && !(doneN && doneP); ++i) {
    if (!doneN) posN -= offNP * kStep[i];
    if (!doneP) posP += offNP * kStep[i];
    if (!doneN) lumaEndN = lumaAt(posN) - lumaNN * 0.5;
    if (!doneP) lumaEndP = lumaAt(posP) - lumaNN * 0.5;
    doneN = abs(lumaEndN) >= gradientScaled;
    doneP = abs(lumaEndP) >= gradientScaled;
  }

  // Nearer end of the span: blend across the edge by how close it is
  // (a stair-step's end gets half a pixel, its middle none), or by the
  // sub-pixel amount where that is more.
  const float dstN = horzSpan ? posM.x - posN.x : posM.y - posN.y;
  const float dstP = horzSpan ? posP.x - posM.x : posP.y - posM.y;
  const bool lumaMLTZero = lumaM - lumaNN * 0.5 < 0.0;
  const bool directionN = dstN < dstP;
  const bool goodSpan = directionN ? (lumaEndN < 0.0) != lumaMLTZero : (lumaEndP < 0.0) != lumaMLTZero;
  const float pixelOffset = goodSpan ? 0.5 - min(dstN, dstP) / (dstN + dstP) : 0.0;
  const float offset = max(pixelOffset, subpixH);
  if (horzSpan) posM.y += offset * lengthSign;
  else posM.x += offset * lengthSign;
  outColor = textureLod(source, posM, 0.0);
}
