#include "tests/autorig/transfer_fixture.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "autorig/builtin_source.h"
#include "autorig/face_frame.h"
#include "autorig/face_parts.h"
#include "engine/scene/gltf_loader.h"
#include "tests/common/test_support.h"

namespace transfer_fixture {

std::optional<eng::Model> loadHead() {
  eng::Result<eng::Model> model = eng::loadModel(testing_support::sourceDir() / "data/head.glb");
  if (!model) {
    ADD_FAILURE() << model.error().message;
    return std::nullopt;
  }
  return std::move(*model);
}

autorig::SourceFace headSource(const eng::Model& head) {
  eng::Result<autorig::SourceFace> source = autorig::builtInSource(head);
  if (!source) {
    ADD_FAILURE() << source.error().message;
    return {};
  }
  return std::move(*source);
}

std::optional<autorig::TransferResult> rigWithFixtureLandmarks(const eng::Model& face, const autorig::PosedFace& posed,
                                                              const char* landmarksFile,
                                                              autorig::FaceLandmarks* landmarks,
                                                              const autorig::TransferOptions& options) {
  static const std::optional<eng::Model> head = loadHead();
  if (!head) return std::nullopt;
  static const autorig::SourceFace source = headSource(*head);
  eng::Result<autorig::FaceLandmarks> points =
      autorig::readLandmarksFile(testing_support::sourceDir() / "tests/autorig/data" / landmarksFile);
  if (!points) {
    ADD_FAILURE() << points.error().message;
    return std::nullopt;
  }
  if (landmarks) *landmarks = *points;
  eng::Result<autorig::TransferResult> rigged =
      autorig::transferTargets(source, face, posed, *points, autorig::findFaceParts(face, posed, *points), options);
  if (!rigged) {
    ADD_FAILURE() << rigged.error().message;
    return std::nullopt;
  }
  return std::move(*rigged);
}

float relativeError(const eng::Model& a, const eng::Model& b, const char* mesh, size_t primitive, const char* targetA,
                    const char* targetB) {
  auto find = [&](const eng::Model& model, const char* target) -> std::pair<const eng::Mesh*, size_t> {
    for (const eng::Mesh& m : model.meshes) {
      if (m.name != mesh) continue;
      auto it = std::find(m.targetNames.begin(), m.targetNames.end(), target);
      if (it != m.targetNames.end()) return {&m, size_t(it - m.targetNames.begin())};
    }
    return {nullptr, 0};
  };
  const auto [ma, ta] = find(a, targetA);
  const auto [mb, tb] = find(b, targetB);
  if (!ma || !mb) {
    ADD_FAILURE() << "no target " << (ma ? targetB : targetA) << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  float size = 0.0f, worst = 0.0f;
  if (primitive >= ma->primitives.size() || primitive >= mb->primitives.size()) {
    ADD_FAILURE() << "no primitive " << primitive << " on mesh " << mesh;
    return std::numeric_limits<float>::infinity();
  }
  const std::vector<glm::vec3>& da = ma->primitives[primitive].targets[ta].positions;
  const std::vector<glm::vec3>& db = mb->primitives[primitive].targets[tb].positions;
  for (size_t v = 0; v < da.size() && v < db.size(); ++v) {
    size = std::max(size, glm::length(da[v]));
    worst = std::max(worst, glm::length(da[v] - db[v]));
  }
  return size > 0.0f ? worst / size : std::numeric_limits<float>::infinity();
}

Comparison compareTargets(const eng::Mesh& made, const char* madeName, const eng::Mesh& truth, const char* trueName) {
  auto index = [](const eng::Mesh& mesh, const char* name) {
    return size_t(std::find(mesh.targetNames.begin(), mesh.targetNames.end(), name) - mesh.targetNames.begin());
  };
  const size_t tm = index(made, madeName), tt = index(truth, trueName);
  if (tm >= made.targetNames.size() || tt >= truth.targetNames.size()) {
    ADD_FAILURE() << "no target " << (tm >= made.targetNames.size() ? madeName : trueName);
    const float inf = std::numeric_limits<float>::infinity();
    return {inf, inf, inf};
  }
  double diff = 0.0, trueEnergy = 0.0, madeEnergy = 0.0, dot = 0.0;
  for (size_t p = 0; p < made.primitives.size() && p < truth.primitives.size(); ++p) {
    const std::vector<glm::vec3>& m = made.primitives[p].targets[tm].positions;
    const std::vector<glm::vec3>& t = truth.primitives[p].targets[tt].positions;
    for (size_t v = 0; v < m.size() && v < t.size(); ++v) {
      diff += double(glm::dot(m[v] - t[v], m[v] - t[v]));
      trueEnergy += double(glm::dot(t[v], t[v]));
      madeEnergy += double(glm::dot(m[v], m[v]));
      dot += double(glm::dot(m[v], t[v]));
    }
  }
  if (!(trueEnergy > 0.0)) return {};
  return {float(std::sqrt(diff / trueEnergy)), float(dot / std::sqrt(std::max(trueEnergy * madeEnergy, 1e-300))),
          float(dot / trueEnergy)};
}

float lidGap(const eng::Model& model, size_t m, const autorig::PosedFace& posed, const autorig::FaceLandmarks& landmarks,
             const char* target, std::span<const size_t> upper, std::span<const size_t> lower) {
  const autorig::PosedPrimitive* p = posed.find(m, 0);
  const eng::Mesh& mesh = model.meshes[m];
  const size_t t = size_t(std::find(mesh.targetNames.begin(), mesh.targetNames.end(), target) - mesh.targetNames.begin());
  if (!p || t >= mesh.targetNames.size()) {
    ADD_FAILURE() << "no " << target;
    return NAN;
  }
  auto at = [&](size_t landmark, float weight) {
    size_t nearest = 0;
    for (size_t v = 0; v < p->positions.size(); ++v)
      if (glm::length(p->positions[v] - landmarks.points[landmark]) <
          glm::length(p->positions[nearest] - landmarks.points[landmark]))
        nearest = v;
    return p->positions[nearest] +
           weight * (glm::inverse(p->worldToLocal[nearest]) * mesh.primitives[0].targets[t].positions[nearest]);
  };
  const glm::vec3 up = autorig::LandmarkFrame(landmarks).up();
  auto side = [&](std::span<const size_t> points, float w) {
    glm::vec3 sum(0.0f);
    for (const size_t l : points) sum += at(l, w);
    return sum / float(points.size());
  };
  auto gap = [&](float w) { return glm::dot(side(upper, w) - side(lower, w), up); };
  return gap(1.0f) / gap(0.0f);
}

}  // namespace transfer_fixture
