#pragma once
// Where the members of a crowd stand: `facial demo --crowd N` (windowed and
// headless) and `facial bench frames --instances K` place copies of one model
// side by side in a square grid, centred on the origin, in the XY plane.
//
// The rules (the headless demo's and the benchmark's; the window demo used to
// space columns by the box's width and rows by its height): a grid of
// ceil(sqrt(N)) columns, filled row by row from the top left, each cell a
// square whose side is 1.15 x the larger of the box's width and height. One
// square cell keeps a head-shaped box from crowding its neighbours' ears and
// keeps the benchmark's frames (and so its timings) as they were; a box with
// no extent gets a 1 x 1 cell.
//
//   const std::vector<glm::vec3> offsets = app::crowdOffsets(crowd, bounds);
//   const eng::Aabb all = app::crowdBounds(offsets, bounds);
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"
#include "facial/runtime/graph/graph_definition.h"

namespace app {

// Each member's offset from the model's own position, member i at row
// i / columns, column i % columns.
std::vector<glm::vec3> crowdOffsets(uint32_t count, const eng::Aabb& box);

// The box around `box` moved by every offset (what a camera frames to show the crowd).
eng::Aabb crowdBounds(std::span<const glm::vec3> offsets, const eng::Aabb& box);

// Each member runs its own GraphInstance: `count` of them are charged to a
// budget of `maxBytes` before any is made (a graph of a few megabytes can
// hold megabytes per character). The error names the count, the bytes each
// and the limit; the caller puts the graph file in front.
eng::Result<void> checkCrowdBudget(uint32_t count, const facial::GraphDefinition& graph,
                                   size_t maxBytes = eng::kDefaultLoadBudgetBytes);

}  // namespace app
