#include "tests/common/test_meshes.h"

#include <cmath>
#include <type_traits>
#include <utility>

namespace testing_support {

eng::Primitive flatSheet(int side) {
  eng::Primitive p;
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      p.positions.push_back({float(x) / float(side - 1) - 0.5f, float(y) / float(side - 1) - 0.5f, 0.0f});
      p.normals.push_back({0, 0, 1});
    }
  for (int y = 0; y + 1 < side; ++y)
    for (int x = 0; x + 1 < side; ++x) {
      const uint32_t a = uint32_t(y * side + x), b = a + 1, c = a + uint32_t(side), d = c + 1;
      p.indices.insert(p.indices.end(), {a, b, d, a, d, c});
    }
  return p;
}

eng::Model singleMeshModel(eng::Mesh mesh, std::string sourcePath) {
  eng::Model model;
  model.sourcePath = std::move(sourcePath);
  model.meshes.push_back(std::move(mesh));
  eng::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  model.roots = {0};
  return model;
}

std::string targetName(int index) { return "t" + std::to_string(index); }

eng::Model makeSphereModel(const SphereSpec& spec) {
  eng::Model model;
  model.sourcePath = "<procedural sphere>";
  eng::Mesh& mesh = model.meshes.emplace_back();
  mesh.name = "sphere";
  eng::Primitive& prim = mesh.primitives.emplace_back();
  const float pi = 3.14159265f;
  for (int r = 0; r <= spec.rings; ++r) {
    const float v = float(r) / float(spec.rings);
    const float theta = v * pi;
    for (int s = 0; s <= spec.segments; ++s) {
      const float u = float(s) / float(spec.segments);
      const float phi = u * 2.0f * pi;
      const glm::vec3 n{std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
      prim.positions.push_back(n * spec.radius);
      prim.normals.push_back(n);
      prim.texcoords.emplace_back(u, v);
      if (spec.tangents) prim.tangents.emplace_back(std::cos(phi), 0.0f, -std::sin(phi), 1.0f);
    }
  }
  const uint32_t stride = static_cast<uint32_t>(spec.segments + 1);
  for (int r = 0; r < spec.rings; ++r) {
    for (int s = 0; s < spec.segments; ++s) {
      const uint32_t a = r * stride + s, b = a + stride;
      // Counter-clockwise seen from outside (glTF front faces).
      prim.indices.insert(prim.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  }
  // Each target pushes a smooth bump out (or in) around its own direction.
  for (int t = 0; t < spec.targets; ++t) {
    const float a = 2.399963f * float(t);  // golden angle: directions spread over the sphere
    const float y = 1.0f - 2.0f * (float(t) + 0.5f) / float(spec.targets);
    const glm::vec3 centre = glm::normalize(glm::vec3(std::cos(a) * std::sqrt(1 - y * y), y,
                                                      std::sin(a) * std::sqrt(1 - y * y)));
    const float amplitude = (t % 2 == 0 ? 0.25f : -0.15f) * spec.radius;
    eng::MorphTarget& target = prim.targets.emplace_back();
    for (size_t i = 0; i < prim.positions.size(); ++i) {
      const glm::vec3 n = prim.normals[i];
      const float falloff = std::exp(-glm::dot(n - centre, n - centre) * 4.0f);
      target.positions.push_back(n * amplitude * falloff);
      if (spec.normalDeltas) target.normals.push_back((n - centre) * 0.3f * falloff);
      if (spec.tangents) target.tangents.push_back(glm::vec3(0.0f, 0.2f, 0.0f) * falloff);
    }
    mesh.targetNames.push_back(targetName(t));
    mesh.defaultWeights.push_back(0.0f);
  }
  if (spec.withMaterial) {
    eng::Material& mat = model.materials.emplace_back();
    mat.name = "sphere material";
    mat.baseColorFactor = spec.color;
    mat.doubleSided = spec.doubleSided;
    mat.alphaMode = spec.alphaMode;
    mat.alphaCutoff = spec.alphaCutoff;
    mat.unlit = spec.unlit;
    mat.toon = spec.toon;
    prim.material = 0;
  }
  eng::Node& node = model.nodes.emplace_back();
  node.name = "sphere";
  node.mesh = 0;
  model.roots.push_back(0);
  return model;
}

SphereSpec whiteSphereSpec(int targets) {
  SphereSpec spec;
  spec.targets = targets;
  spec.color = glm::vec4(1.0f);
  return spec;
}

void addPartAsRoot(eng::Model& model, eng::Model part, const std::string& name, glm::vec3 at, glm::vec3 scale) {
  const int mesh = int(model.meshes.size());
  for (eng::Primitive& prim : part.meshes[0].primitives)
    if (prim.material >= 0) prim.material += int(model.materials.size());
  for (eng::Material& m : part.materials) model.materials.push_back(m);
  model.meshes.push_back(std::move(part.meshes[0]));
  eng::Node node;
  node.name = name;
  node.mesh = mesh;
  node.translation = at;
  node.scale = scale;
  model.roots.push_back(int(model.nodes.size()));
  model.nodes.push_back(node);
}

eng::Model plasterHead() {
  eng::Model model;
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(2)), "head", {0, 0, 0}, glm::vec3(1.0f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "eyeLeft", {0.35f, 0.2f, 0.85f}, glm::vec3(0.12f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "eyeRight", {-0.35f, 0.2f, 0.85f}, glm::vec3(0.12f));
  addPartAsRoot(model, makeSphereModel(whiteSphereSpec(0)), "teeth", {0, -0.4f, 0.8f}, glm::vec3(0.2f, 0.05f, 0.1f));
  return model;
}

eng::Model stripped(eng::Model model) {
  model.animations.clear();
  for (eng::Mesh& mesh : model.meshes) {
    mesh.targetNames.clear();
    mesh.defaultWeights.clear();
    for (eng::Primitive& p : mesh.primitives) p.targets.clear();
  }
  return model;
}

eng::Model asTriangleSoup(eng::Model model) {
  for (eng::Mesh& mesh : model.meshes)
    for (eng::Primitive& p : mesh.primitives) {
      auto spread = [&p](auto& values, size_t perVertex) {
        if (values.empty()) return;
        std::remove_reference_t<decltype(values)> out;
        for (uint32_t i : p.indices)
          out.insert(out.end(), values.begin() + ptrdiff_t(i * perVertex), values.begin() + ptrdiff_t((i + 1) * perVertex));
        values = std::move(out);
      };
      const size_t sets = p.influenceSets();
      spread(p.normals, 1), spread(p.texcoords, 1), spread(p.tangents, 1), spread(p.colors, 1);
      spread(p.joints, sets), spread(p.jointWeights, sets);
      for (eng::MorphTarget& t : p.targets) spread(t.positions, 1), spread(t.normals, 1), spread(t.tangents, 1);
      spread(p.positions, 1);
      for (size_t i = 0; i < p.indices.size(); ++i) p.indices[i] = uint32_t(i);
    }
  return model;
}

eng::Model asFlatShaded(const eng::Model& model) {
  eng::Model flat = asTriangleSoup(model);
  for (eng::Mesh& mesh : flat.meshes)
    for (eng::Primitive& p : mesh.primitives)
      for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
        const glm::vec3 n = glm::normalize(glm::cross(p.positions[t + 1] - p.positions[t], p.positions[t + 2] - p.positions[t]));
        if (!std::isfinite(glm::dot(n, n))) continue;
        for (size_t k = 0; k < 3; ++k) p.normals[t + k] = n;
      }
  return flat;
}

}  // namespace testing_support
