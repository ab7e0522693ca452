#include "engine/scene/inner_face_parts.h"

#include "engine/scene/skeleton_pose.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <limits>

namespace eng {
namespace {

std::string lowercase(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

}  // namespace

// "eye" in a name, but not the parts around an eye that are named after it.
bool namesAnEyeball(const std::string& name) {
  const std::string n = lowercase(name);
  if (n.find("eye") == std::string::npos) return false;
  static constexpr std::array<std::string_view, 12> kNotTheBall = {
      "brow", "lash", "lid", "socket", "shadow", "line", "highlight", "wet", "tear", "occlusion", "cornea", "spec"};
  return std::none_of(kNotTheBall.begin(), kNotTheBall.end(),
                      [&](std::string_view part) { return n.find(part) != std::string::npos; });
}

bool materialNamesAnEyeball(const Model& model, int material) {
  return material >= 0 && size_t(material) < model.materials.size() && namesAnEyeball(model.materials[size_t(material)].name);
}

std::vector<std::string_view> meshAndNodeNames(const Model& model, size_t mesh, int node) {
  std::vector<std::string_view> names{model.meshes[mesh].name};
  for (int depth = 0; node >= 0 && depth < 4; ++depth, node = model.nodes[size_t(node)].parent)
    names.push_back(model.nodes[size_t(node)].name);
  return names;
}

bool anyNameContains(const std::vector<std::string_view>& names, std::string_view needle) {
  return std::any_of(names.begin(), names.end(),
                     [&](std::string_view n) { return lowercase(n).find(needle) != std::string::npos; });
}

std::vector<std::vector<bool>> partsInsideTheHead(const Model& model) {
  struct Box {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{std::numeric_limits<float>::lowest()};
  };
  // World-space rest bounds, each mesh placed by the first node drawing it.
  const std::vector<int> nodeOfMesh = model.firstNodeOfEachMesh();
  std::vector<std::vector<Box>> boxes(model.meshes.size());
  const std::vector<glm::mat4> worlds = restWorldMatrices(model);
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const glm::mat4 world = nodeOfMesh[m] >= 0 ? worlds[size_t(nodeOfMesh[m])] : glm::mat4(1.0f);
    for (const Primitive& prim : model.meshes[m].primitives) {
      Box& box = boxes[m].emplace_back();
      for (const glm::vec3& p : prim.positions) {
        const glm::vec3 placed = glm::vec3(world * glm::vec4(p, 1.0f));
        box.lo = glm::min(box.lo, placed);
        box.hi = glm::max(box.hi, placed);
      }
    }
  }
  auto enclosed = [&](const Box& inner, size_t mesh, size_t primitive) {
    for (size_t m = 0; m < boxes.size(); ++m)
      for (size_t p = 0; p < boxes[m].size(); ++p) {
        const Box& outer = boxes[m][p];
        if ((m != mesh || p != primitive) && glm::all(glm::lessThan(outer.lo, inner.lo)) &&
            glm::all(glm::lessThan(inner.hi, outer.hi)))
          return true;
      }
    return false;
  };
  std::vector<std::vector<bool>> inside(model.meshes.size());
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    const Mesh& mesh = model.meshes[m];
    const std::vector<std::string_view> meshNames = meshAndNodeNames(model, m, nodeOfMesh[m]);
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      std::vector<std::string_view> names = meshNames;
      const int material = mesh.primitives[p].material;
      if (material >= 0 && size_t(material) < model.materials.size()) names.push_back(model.materials[size_t(material)].name);
      const bool named = std::any_of(meshNames.begin(), meshNames.end(),
                                     [](std::string_view n) { return namesAnEyeball(std::string(n)); }) ||
                         materialNamesAnEyeball(model, material) ||
                         anyNameContains(names, "teeth") || anyNameContains(names, "tooth") || anyNameContains(names, "tongue") ||
                         (anyNameContains(names, "mouth") && (anyNameContains(names, "interior") || anyNameContains(names, "inside") ||
                                                          anyNameContains(names, "bag") || anyNameContains(names, "cavity")));
      inside[m].push_back(named && !mesh.primitives[p].positions.empty() && enclosed(boxes[m][p], m, p));
    }
  }
  return inside;
}

}  // namespace eng
