#include "app/crowd_layout.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "facial/runtime/graph/graph_instance.h"

namespace app {

std::vector<glm::vec3> crowdOffsets(uint32_t count, const eng::Aabb& box) {
  std::vector<glm::vec3> offsets(count);
  if (count == 0) return offsets;
  const uint32_t columns = static_cast<uint32_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  const uint32_t rows = (count + columns - 1) / columns;
  const float spacing = box.valid() ? std::max(box.size().x, box.size().y) * 1.15f : 1.0f;
  for (uint32_t i = 0; i < count; ++i) {
    const uint32_t row = i / columns, column = i % columns;
    offsets[i] = glm::vec3((float(column) - 0.5f * float(columns - 1)) * spacing,
                           (0.5f * float(rows - 1) - float(row)) * spacing, 0.0f);
  }
  return offsets;
}

eng::Aabb crowdBounds(std::span<const glm::vec3> offsets, const eng::Aabb& box) {
  eng::Aabb all;
  if (!box.valid()) return all;
  for (const glm::vec3& offset : offsets) all.extend(eng::Aabb{box.min + offset, box.max + offset});
  return all;
}

eng::Result<void> checkCrowdBudget(uint32_t count, const facial::GraphDefinition& graph, size_t maxBytes) {
  const size_t each = facial::GraphInstance::bytesFor(graph);
  eng::LoadBudget budget(maxBytes);
  return budget.charge(count, each,
                       "a crowd of " + std::to_string(count) + " characters (" + std::to_string(each) + " bytes of graph state each)");
}

}  // namespace app
