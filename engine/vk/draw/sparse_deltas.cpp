#include "engine/vk/draw/sparse_deltas.h"

#include <algorithm>

#include "engine/core/work_counter.h"
#include "engine/scene/crease_shading.h"

namespace eng::vk {

SparseDeltas compactDeltas(const Primitive& prim) {
  SparseDeltas out;
  const std::vector<std::vector<float>> darkening = bakeCreaseDarkening(prim);
  out.hasCreases = hasCreases(darkening);
  const size_t n = prim.vertexCount();
  // The targets with something to add: a file listing thousands of empty
  // targets over many vertices made every vertex x target pair a visit
  // (60 KB took over a minute).
  std::vector<uint32_t> carrying;
  for (size_t t = 0; t < prim.targets.size(); ++t) {
    const MorphTarget& target = prim.targets[t];
    out.hasNormals |= !target.normals.empty();
    out.hasTangents |= !target.tangents.empty();
    const bool darkens = t < darkening.size() && !darkening[t].empty();
    if (!target.positions.empty() || !target.normals.empty() || !target.tangents.empty() || darkens)
      carrying.push_back(static_cast<uint32_t>(t));
  }
  const size_t planes = out.hasTangents ? 3 : 2;
  auto at = [](const std::vector<glm::vec3>& deltas, size_t v) { return v < deltas.size() ? deltas[v] : glm::vec3(0.0f); };
  // One vertex's entries, planes in order.
  std::vector<glm::vec4> vertexEntries[kMorphSliceLanes];
  const size_t slices = (n + kMorphSliceLanes - 1) / kMorphSliceLanes;
  out.offsets.reserve(slices + 1);
  uint32_t rows = 0;
  for (size_t slice = 0; slice < slices; ++slice) {
    out.offsets.push_back(rows);
    size_t sliceRows = 0;
    for (uint32_t lane = 0; lane < kMorphSliceLanes; ++lane) {
      std::vector<glm::vec4>& list = vertexEntries[lane];
      list.clear();
      const size_t v = slice * kMorphSliceLanes + lane;
      if (v >= n) continue;
      countWork(carrying.size());
      for (const uint32_t t : carrying) {
        const MorphTarget& target = prim.targets[t];
        const glm::vec3 position = at(target.positions, v), normal = at(target.normals, v);
        const glm::vec3 tangent = at(target.tangents, v);
        const float crease = t < darkening.size() && !darkening[t].empty() ? darkening[t][v] : 0.0f;
        if (position == glm::vec3(0.0f) && normal == glm::vec3(0.0f) && tangent == glm::vec3(0.0f) && crease == 0.0f)
          continue;  // adds exactly nothing
        // The index as a float value, not its bits (small integers' bits are
        // denormals, which a GPU's texel fetch may flush); exact below 2^24.
        list.emplace_back(position, static_cast<float>(t));
        list.emplace_back(normal, crease);
        if (out.hasTangents) list.emplace_back(tangent, 0.0f);
      }
      sliceRows = std::max(sliceRows, list.size() / planes);
    }
    // Padding: zero deltas naming target 0, which add nothing whatever its weight.
    const size_t first = out.entries.size();
    out.entries.resize(first + sliceRows * planes * kMorphSliceLanes, glm::vec4(0.0f));
    for (uint32_t lane = 0; lane < kMorphSliceLanes; ++lane)
      for (size_t e = 0; e < vertexEntries[lane].size(); ++e) {
        const size_t row = e / planes, plane = e % planes;
        out.entries[first + (row * planes + plane) * kMorphSliceLanes + lane] = vertexEntries[lane][e];
      }
    rows += static_cast<uint32_t>(sliceRows);
  }
  out.offsets.push_back(rows);  // no row at all: no target moves anything, entries stay empty
  return out;
}

}  // namespace eng::vk
