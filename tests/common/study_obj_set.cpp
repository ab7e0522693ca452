#include "tests/common/study_obj_set.h"

#include <cstdio>
#include <fstream>

#include "engine/scene/cpu_morph.h"
#include "engine/scene/weights.h"

namespace testing_support {

void writePosedObj(const eng::Model& model, std::span<const float> weights, const std::filesystem::path& path) {
  const eng::WeightLayout layout(model);
  std::ofstream out(path, std::ios::binary);
  out << "# " << path.filename().string() << ": written by a test (study_obj_set)\n";
  std::string faces;
  uint32_t base = 1;
  char line[96];
  for (int n = 0; n < int(model.nodes.size()); ++n) {
    const int m = model.nodes[n].mesh;
    if (m < 0) continue;
    const glm::mat4 world = model.worldTransform(n);
    for (const eng::Primitive& p : model.meshes[m].primitives) {
      std::vector<glm::vec3> positions(p.vertexCount()), normals;
      eng::morphPrimitiveCpu(p, *layout.meshWeights(weights, m), positions, normals);
      for (const glm::vec3& v : positions) {
        const glm::vec3 w = glm::vec3(world * glm::vec4(v, 1.0f));
        std::snprintf(line, sizeof line, "v %.7g %.7g %.7g\n", w.x, w.y, w.z);
        out << line;
      }
      for (size_t i = 0; i + 2 < p.indices.size(); i += 3) {
        std::snprintf(line, sizeof line, "f %u %u %u\n", base + p.indices[i], base + p.indices[i + 1],
                      base + p.indices[i + 2]);
        faces += line;
      }
      base += uint32_t(p.vertexCount());
    }
  }
  out << faces;
}

void writeStudyObjSet(const eng::Model& model, size_t weightCount, const PresetPose& pose,
                      const std::filesystem::path& folder) {
  std::filesystem::create_directories(folder);
  std::vector<float> weights(weightCount);
  for (const StudySetFile& f : kStudySet) {
    if (!pose(f.preset, weights)) return;
    writePosedObj(model, weights, folder / (std::string(f.file) + ".obj"));
  }
}

std::string studyRigMapJson(float gain) {
  std::string map = "{\"version\": 1, \"model\": \"study set\", \"map\": {";
  for (size_t i = 1; i < std::size(kStudySet); ++i)
    map += std::string(i > 1 ? ", " : "") + "\"" + kStudySet[i].preset + "\": [{\"target\": \"" + kStudySet[i].file +
           "\", \"weight\": " + std::to_string(gain) + "}]";
  return map + "}}\n";
}

}  // namespace testing_support
