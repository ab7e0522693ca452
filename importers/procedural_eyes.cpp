#include "importers/procedural_eyes.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <string_view>

namespace importers {

// The engine's scene types (Model, Result, ...) unqualified.
using namespace eng;

namespace {

// The node and up to three ancestors (eye groups: "grp_eyeLeft" > "eyeLeft").
bool nodePathNamesAnEyeball(const Model& model, int node) {
  for (int depth = 0; node >= 0 && depth < 4; ++depth) {
    const Node& n = model.nodes[static_cast<size_t>(node)];
    if (namesAnEyeball(n.name)) return true;
    node = n.parent;
  }
  return false;
}

struct SphereFit {
  glm::vec3 centre{0.0f};
  float radius = 0.0f;
  float relativeRms = 1.0f;  // rms of (|p - c| - r) / r
};

// Linear least squares: |p|^2 = 2 c.p + k, k = r^2 - |c|^2, solved in
// coordinates centred and scaled to the unit box for conditioning.
SphereFit fitSphere(const std::vector<glm::vec3>& points) {
  SphereFit fit;
  if (points.size() < 8) return fit;
  Aabb box;
  for (const glm::vec3& p : points) box.extend(p);
  const glm::dvec3 origin(box.center());
  const double scale = std::max(double(box.diagonal()), 1e-12);
  glm::dmat4 a(0.0);
  glm::dvec4 b(0.0);
  for (const glm::vec3& p : points) {
    const glm::dvec3 q = (glm::dvec3(p) - origin) / scale;
    const glm::dvec4 row(2.0 * q.x, 2.0 * q.y, 2.0 * q.z, 1.0);
    a += glm::outerProduct(row, row);
    b += row * glm::dot(q, q);
  }
  if (std::abs(glm::determinant(a)) < 1e-18) return fit;
  const glm::dvec4 x = glm::inverse(a) * b;
  const glm::dvec3 c(x.x, x.y, x.z);
  const double r2 = x.w + glm::dot(c, c);
  if (!(r2 > 0.0)) return fit;
  const double r = std::sqrt(r2);
  double sum = 0.0;
  for (const glm::vec3& p : points) {
    const double d = glm::length((glm::dvec3(p) - origin) / scale - c) - r;
    sum += d * d;
  }
  fit.centre = glm::vec3(origin + c * scale);
  fit.radius = float(r * scale);
  fit.relativeRms = float(std::sqrt(sum / double(points.size())) / r);
  return fit;
}

// A unit vector orthogonal to `axis`, as close to `preferred` as possible.
glm::vec3 orthogonalTo(const glm::vec3& axis, const glm::vec3& preferred) {
  glm::vec3 v = preferred - axis * glm::dot(axis, preferred);
  if (glm::dot(v, v) < 1e-8f) v = glm::abs(axis.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  v -= axis * glm::dot(axis, v);
  return glm::normalize(v);
}

float smoothstepf(float e0, float e1, float x) {
  const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

glm::vec3 mix3(const glm::vec3& a, const glm::vec3& b, float t) { return a + (b - a) * t; }

// Radii in the texture's radial coordinate rho = sin(angle from the gaze
// axis): a human iris spans about 12 of the eyeball's 24 mm, the pupil about
// 40% of the iris in indoor light.
constexpr float kIrisRadius = 0.47f;
constexpr float kPupilRadius = 0.18f;

// The world direction `world` (unit) in the space of the mesh `node` draws;
// +Z where the node's transform collapses it.
glm::vec3 gazeAxisOf(const Model& model, int node, const glm::vec3& world = glm::vec3(0.0f, 0.0f, 1.0f)) {
  const glm::vec3 axis = glm::vec3(glm::inverse(model.worldTransform(node)) * glm::vec4(world, 0.0f));
  return glm::dot(axis, axis) > 1e-20f ? glm::normalize(axis) : glm::vec3(0.0f, 0.0f, 1.0f);
}

// Eyeballs that no name tells (an export that lost them): two plain white
// balls of one size, level and side by side a few radii apart (a person's
// 12 mm eyeballs are about 5 radii apart, a stylised avatar's 4), inside the
// box of another primitive, the head they sit in. Nothing when no pair is.
std::vector<EyePrimitive> eyePairByShape(const Model& model, const std::vector<int>& nodeOfMesh) {
  struct Ball {
    EyePrimitive eye;
    glm::vec3 world;
    float radius;
  };
  std::vector<Ball> balls;
  std::vector<Aabb> boxes;  // every primitive's, in world space
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const int node = nodeOfMesh[m];
    if (node < 0) continue;
    const glm::mat4 world = model.worldTransform(node);
    for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const Primitive& prim = model.meshes[m].primitives[p];
      Aabb box;
      for (const glm::vec3& v : prim.positions) box.extend(glm::vec3(world * glm::vec4(v, 1.0f)));
      boxes.push_back(box);
      // Plain only (white, or an exporter's grey): a ball its author coloured (a robot's lamp eyes) is no plaster eyeball.
      if (!unauthoredPlain(model, prim)) continue;
      const SphereFit fit = fitSphere(prim.positions);
      if (!(fit.radius > 0.0f) || fit.relativeRms > 0.12f) continue;
      const EyePrimitive eye{.mesh = int(m), .primitive = int(p), .node = node, .centre = fit.centre,
                             .radius = fit.radius, .gazeAxis = gazeAxisOf(model, node)};
      balls.push_back({eye, glm::vec3(world * glm::vec4(fit.centre, 1.0f)), fit.radius * glm::length(glm::vec3(world[0]))});
    }
  }
  for (size_t a = 0; a < balls.size(); ++a)
    for (size_t b = a + 1; b < balls.size(); ++b) {
      const float r = std::max(balls[a].radius, balls[b].radius);
      const glm::vec3 d = glm::abs(balls[a].world - balls[b].world);
      if (std::min(balls[a].radius, balls[b].radius) < 0.85f * r || d.y > 0.5f * r || d.z > 0.5f * r ||
          d.x < 2.5f * r || d.x > 8.0f * r)
        continue;
      auto inside = [](const Aabb& box, const glm::vec3& p) {
        return glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max));
      };
      const bool inAHead = std::any_of(boxes.begin(), boxes.end(), [&](const Aabb& box) {
        return box.size().x > d.x + 2.0f * r && inside(box, balls[a].world) && inside(box, balls[b].world);
      });
      if (inAHead) return {balls[a].eye, balls[b].eye};
    }
  return {};
}

bool white(const glm::vec4& c) { return c.r >= 0.99f && c.g >= 0.99f && c.b >= 0.99f; }

// What an exporter writes for a material nobody coloured: white, or a
// neutral grey of a half or more (Blender's default base colour 0.8, written
// as a glTF's baseColorFactor and an OBJ's Kd; Maya's lambert1 0.5): a face
// exported from Blender untextured was drawn undressed, a grey plaster cast.
bool exportersDefault(const glm::vec4& c) {
  const float lo = std::min({c.r, c.g, c.b}), hi = std::max({c.r, c.g, c.b});
  return lo >= 0.49f && hi - lo <= 0.01f;
}

}  // namespace

bool paintedPerVertex(const Primitive& primitive) {
  return !std::all_of(primitive.colors.begin(), primitive.colors.end(), white);
}

bool unauthoredPlain(const Model& model, const Primitive& primitive) {
  if (paintedPerVertex(primitive)) return false;
  const int material = primitive.material;
  if (material < 0 || size_t(material) >= model.materials.size()) return true;
  const Material& m = model.materials[size_t(material)];
  return m.baseColorImage < 0 && exportersDefault(m.baseColorFactor);
}

Image proceduralEyeImage(int size) {
  Image image;
  image.name = "procedural eye";
  image.width = image.height = size;
  image.rgba8.resize(size_t(size) * size_t(size) * 4);
  const float pixel = 2.0f / float(size);  // one texel in rho units, for anti-aliased edges
  const glm::vec3 sclera{0.93f, 0.91f, 0.88f};
  const glm::vec3 scleraRim{0.80f, 0.74f, 0.72f};  // toward the corners: shadowed and slightly pink
  const glm::vec3 irisInner{0.55f, 0.39f, 0.20f};  // hazel-brown collarette
  const glm::vec3 irisOuter{0.27f, 0.18f, 0.11f};
  const glm::vec3 limbus{0.10f, 0.07f, 0.05f};
  const glm::vec3 pupil{0.03f, 0.025f, 0.02f};
  // The catch-light: the key light's reflection, upper left as the default light rig places the key.
  const glm::vec2 catchCentre{-0.15f, 0.15f};
  const float catchRadius = 0.07f;
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      // (u, v) -> eye-plane coordinates: +x right, +y up (v grows downward).
      const glm::vec2 q{(float(x) + 0.5f) / float(size) * 2.0f - 1.0f, 1.0f - (float(y) + 0.5f) / float(size) * 2.0f};
      const float rho = glm::length(q);
      const float angle = std::atan2(q.y, q.x);
      glm::vec3 c = mix3(sclera, scleraRim, smoothstepf(0.55f, 1.0f, rho));
      // Iris: radial fibres (two frequencies) over a collarette-to-rim gradient.
      const float t = std::clamp(rho / kIrisRadius, 0.0f, 1.0f);
      const float fibres = 0.82f + 0.10f * std::sin(angle * 37.0f + 3.0f * t) + 0.08f * std::sin(angle * 89.0f - 5.0f * t);
      glm::vec3 iris = mix3(irisInner, irisOuter, smoothstepf(0.35f, 0.9f, t)) * fibres;
      iris = mix3(iris, limbus, smoothstepf(0.80f, 1.0f, t));  // limbal ring
      c = mix3(c, iris, 1.0f - smoothstepf(kIrisRadius - pixel, kIrisRadius + pixel, rho));
      c = mix3(c, pupil, 1.0f - smoothstepf(kPupilRadius - pixel, kPupilRadius + pixel, rho));
      const float catchLight = 1.0f - smoothstepf(catchRadius - pixel, catchRadius + pixel, glm::length(q - catchCentre));
      c = mix3(c, glm::vec3(1.0f), catchLight * 0.95f);
      uint8_t* out = &image.rgba8[(size_t(y) * size_t(size) + size_t(x)) * 4];
      for (int i = 0; i < 3; ++i) out[i] = static_cast<uint8_t>(std::lround(std::clamp(c[i], 0.0f, 1.0f) * 255.0f));
      out[3] = 255;
    }
  }
  return image;
}

std::vector<EyePrimitive> findUntexturedEyes(const Model& model) {
  // One node per mesh is enough to orient it; the first in node order.
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  std::vector<EyePrimitive> eyes;
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const int node = nodeOfMesh[m];
    if (node < 0) continue;
    const Mesh& mesh = model.meshes[m];
    const bool namedEye = namesAnEyeball(mesh.name) || nodePathNamesAnEyeball(model, node);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const Primitive& prim = mesh.primitives[p];
      const Material* material =
          prim.material >= 0 && size_t(prim.material) < model.materials.size() ? &model.materials[size_t(prim.material)]
                                                                               : nullptr;
      if ((material && material->baseColorImage >= 0) || paintedPerVertex(prim)) continue;  // textured or painted: left alone
      if (!namedEye && !(material && namesAnEyeball(material->name))) continue;
      const SphereFit fit = fitSphere(prim.positions);
      if (!(fit.radius > 0.0f) || fit.relativeRms > 0.12f) continue;  // not a ball (a lid, a lash strip...)
      EyePrimitive eye;
      eye.mesh = int(m);
      eye.primitive = int(p);
      eye.node = node;
      eye.centre = fit.centre;
      eye.radius = fit.radius;
      eye.gazeAxis = gazeAxisOf(model, node);
      eyes.push_back(eye);
    }
  }
  if (eyes.empty()) eyes = eyePairByShape(model, nodeOfMesh);
  // A face its file holds turned aside or rolled looks square to the line
  // between its eyes, its top toward +Y: forward is that line crossed with
  // +Y made square to it, on glTF's front side (a pitch is not seen).
  if (eyes.size() == 2) {
    auto worldCentre = [&](const EyePrimitive& eye) {
      return glm::vec3(model.worldTransform(eye.node) * glm::vec4(eye.centre, 1.0f));
    };
    const glm::vec3 across = worldCentre(eyes[1]) - worldCentre(eyes[0]);
    if (glm::dot(across, across) > 1e-20f) {
      const glm::vec3 line = glm::normalize(across);
      const glm::vec3 up = glm::vec3(0.0f, 1.0f, 0.0f) - line * line.y;
      glm::vec3 forward = glm::cross(line, up);
      if (forward.z < 0.0f) forward = -forward;
      if (glm::dot(up, up) > 0.25f && forward.z > 0.5f * glm::length(forward))  // within 60° of upright and of +Z
        for (EyePrimitive& eye : eyes) eye.gazeAxis = gazeAxisOf(model, eye.node, glm::normalize(forward));
    }
  }
  return eyes;
}

size_t dressUntexturedEyes(Model& model) {
  const std::vector<EyePrimitive> eyes = findUntexturedEyes(model);
  if (eyes.empty()) return 0;
  const int image = int(model.images.size());
  model.images.push_back(proceduralEyeImage());
  std::map<int, int> eyeMaterialOf;  // source material (-1: default) -> its eye material
  for (const EyePrimitive& eye : eyes) {
    Primitive& prim = model.meshes[size_t(eye.mesh)].primitives[size_t(eye.primitive)];
    auto [it, added] = eyeMaterialOf.try_emplace(prim.material, int(model.materials.size()));
    if (added) {
      Material material = prim.material >= 0 ? model.materials[size_t(prim.material)] : Material{};
      material.name = (material.name.empty() ? std::string("eye") : material.name) + " (procedural eye)";
      material.baseColorFactor = glm::vec4(1.0f, 1.0f, 1.0f, material.baseColorFactor.a);
      material.baseColorImage = image;
      material.roughness = 0.3f;  // wet: the lights leave highlights
      material.metallic = 0.0f;
      material.detailLayers.clear();
      model.materials.push_back(std::move(material));
    }
    prim.material = it->second;
    // Planar projection along the gaze axis: rho = sin(angle from the axis),
    // exact under linear interpolation across the front of the ball. The back
    // half maps to the sclera's rim so it never shows a second iris.
    const glm::mat4 toMesh = glm::inverse(model.worldTransform(eye.node));
    const glm::vec3 up = orthogonalTo(eye.gazeAxis, glm::vec3(toMesh * glm::vec4(0.0f, 1.0f, 0.0f, 0.0f)));
    const glm::vec3 right = glm::cross(up, eye.gazeAxis);
    prim.texcoords.resize(prim.positions.size());
    for (size_t v = 0; v < prim.positions.size(); ++v) {
      const glm::vec3 d = (prim.positions[v] - eye.centre) / eye.radius;
      glm::vec2 q{glm::dot(d, right), glm::dot(d, up)};
      if (glm::dot(d, eye.gazeAxis) <= 0.0f || glm::length(q) > 1.0f)
        q = glm::length(q) > 1e-6f ? glm::normalize(q) : glm::vec2(1.0f, 0.0f);
      prim.texcoords[v] = {0.5f + 0.5f * q.x, 0.5f - 0.5f * q.y};
    }
  }
  return eyes.size();
}

}  // namespace importers
