// Set 0: what changes once per frame (camera, lights) and per instance
// (transform + the instance's slice of the active-weight list).
// Shared by every pipeline; mirrored by engine/vk/gpu_types.h.

struct InstanceData {
  mat4 model;
  mat4 normalMatrix;   // inverse-transpose of model (upper 3x3 used)
  uint activeOffset;   // first entry of this instance in activeWeights[]
  uint activeCount;    // number of non-zero weights; 0 = rest pose
  uint jointOffset;    // first joint matrix of this instance's skin in jointMatrices[] (skin.glsl)
  uint jointCount;     // joints of that skin; 0 = not skinned
  uint materialOffset; // first of this instance's records in instanceMaterials[]
  uint weightOffset;   // first of this instance's weights for the drawn mesh in targetWeights[] (morph.glsl)
  uint reserved1, reserved2;
};

// A material as one instance draws it this frame (expression-driven colour
// and texture transform, e.g. VRM material binds; else the material's own).
struct InstanceMaterial {
  vec4 baseColorFactor;  // linear RGBA
  vec4 emissive;         // linear RGB, w unused
  vec4 uvTransform;      // uv * xy + zw
  vec4 toonShade;        // MToon: linear RGB shade colour, w rim lift
  vec4 toonShading;      // MToon: shading shift, toony, GI equalization, rim lighting mix
  vec4 toonRim;          // MToon: linear RGB rim colour, w fresnel power
  vec4 toonOutline;      // MToon: linear RGB outline colour, w width (metres, or image heights)
  vec4 toonOutlineStyle; // MToon: x 1 = world width, 2 = screen width; y outline lighting mix
  vec4 toonMatcap;       // MToon: linear RGB matcap factor, w unused
};

// One non-zero morph weight: target index within the drawn mesh.
struct ActiveWeight {
  uint target;
  float weight;
};

layout(std140, set = 0, binding = 0) uniform FrameGlobals {
  mat4 view;
  mat4 proj;
  mat4 viewProj;
  vec4 cameraPosition;    // world space, w unused
  vec4 keyDirection;      // world-space direction TOWARD the light, w unused
  vec4 keyColor;          // linear rgb * intensity
  vec4 fillDirection;
  vec4 fillColor;
  vec4 rimDirection;
  vec4 rimColor;
  vec4 skyAmbient;        // hemisphere ambient, linear rgb
  vec4 groundAmbient;
  vec4 backgroundTop;     // linear rgb
  vec4 backgroundBottom;
  vec4 skin;              // x diffuse wrap, y subsurface strength, z specular strength, w exposure
  vec4 subsurfaceColor;   // warm tint added at the light terminator
  mat4 keyLightViewProj;  // world -> key light's shadow-map clip space
  vec4 shadow;            // y filter radius (shadow-map uv), z normal offset (world), w 1 = on
  vec4 shadowColor;       // what of the key light remains in its shadow (warm: light bleeding under skin)
  vec4 backdropUv;        // the backdrop's uv in the whole picture = xy + the view's uv * zw
} frame;

layout(std430, set = 0, binding = 1) readonly buffer Instances { InstanceData instances[]; };
layout(std430, set = 0, binding = 2) readonly buffer ActiveWeights { ActiveWeight activeWeights[]; };
layout(std430, set = 0, binding = 6) readonly buffer InstanceMaterials { InstanceMaterial instanceMaterials[]; };

// Per-draw constants (one primitive, its material). 68 bytes.
layout(push_constant) uniform DrawConstants {
  float roughness;
  float metallic;
  uint detailLayerCount;
  uint flags;             // DRAW_FLAG_* below
  uint vertexCount;       // vertices of the primitive: stride of one target in the delta arrays
  uint firstInstance;     // firstInstance of the draw, to number captured instances from 0
  uint captureOffset;     // first captured vertex slot of this draw (capture variant only)
  uint jointSets;         // groups of four joint influences per vertex; 0 = not skinned (skin.glsl)
  uint material;          // the primitive's material: instanceMaterials[instance's materialOffset + material]
  uint morphOffset;       // first vec4 of the draw's morphed vertices (morph.glsl)
  uint restPosition;      // float offsets of the rest attributes in the vertex buffer (morph.comp)
  uint restNormal;
  uint restTangent;
  uint detailLayerMask;   // bit l: detail layer l may show (some instance's weight for its target is not 0)
  float alphaCutoff;      // DRAW_FLAG_ALPHA_MASK: fragments with less base-colour alpha are discarded
  float normalScale;      // DRAW_FLAG_NORMAL_MAP: scales the normal texture's x and y
  float occlusionStrength;  // 0: no occlusion texture
  float toonShadingShiftScale;  // DRAW_FLAG_TOON_SHADING_SHIFT_TEXTURE: scales the texture's red
} draw;

const uint DRAW_FLAG_NORMAL_DELTAS = 1u;
const uint DRAW_FLAG_TANGENT_DELTAS = 2u;
const uint DRAW_FLAG_DOUBLE_SIDED = 4u;
const uint DRAW_FLAG_CREASES = 8u;
const uint DRAW_FLAG_MORPHED = 16u;  // the primitive has sparse deltas: morph.comp writes its vertices
const uint DRAW_FLAG_MIRRORED = 32u;  // negative-determinant transform: the pipeline's front faces wind clockwise
const uint DRAW_FLAG_ALPHA_MASK = 64u;   // glTF alphaMode MASK
const uint DRAW_FLAG_ALPHA_BLEND = 128u; // glTF alphaMode BLEND (a blending pipeline; alpha is written out)
const uint DRAW_FLAG_UNLIT = 256u;       // KHR_materials_unlit
const uint DRAW_FLAG_TOON = 512u;        // MToon toon shading (InstanceMaterial.toon*)
const uint DRAW_FLAG_TOON_SHADE_TEXTURE = 1024u;  // MToon: shade colour x the base colour's texture
const uint DRAW_FLAG_TOON_OUTLINE = 2048u;        // MToon: also drawn as an outline
const uint DRAW_FLAG_NORMAL_MAP = 4096u;          // glTF normalTexture (set 1 binding 8)
const uint DRAW_FLAG_EMISSIVE_TEXTURE = 8192u;    // glTF emissiveTexture (set 1 binding 10)
const uint DRAW_FLAG_TOON_MATCAP = 16384u;       // MToon matcap texture (set 1 binding 11)
const uint DRAW_FLAG_TOON_SHADING_SHIFT_TEXTURE = 32768u;  // MToon shadingShiftTexture (set 1 binding 12)
const uint DRAW_FLAG_TOON_RIM_MULTIPLY = 65536u;           // MToon rimMultiplyTexture (set 1 binding 13)
const uint DRAW_FLAG_TOON_OUTLINE_WIDTH_TEXTURE = 131072u; // MToon outlineWidthMultiplyTexture (set 1 binding 14)

// The outline pipelines (ScenePipelines::outline): the mesh pushed out along
// its normals, back faces only, in the outline colour.
layout(constant_id = 3) const bool OUTLINE_PIPELINE = false;
