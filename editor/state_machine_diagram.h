#pragma once
// Where the state machine diagram draws things, in canvas pixels: a box per
// state on a ring, "any state" in the middle, an arrow per transition from
// the edge of one box to the edge of the other (a pair of opposite
// transitions drawn side by side, not on top of each other), and what a click
// at a point hits. Plain geometry with no ImGui, so the panel only draws it
// and the layout rules are unit-tested.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "editor/graph_document.h"

namespace editor {

struct DiagramBox {
  std::string state;  // GraphDocument::kAnyState for the any-state box
  glm::vec2 min{0.0f}, max{0.0f};
  glm::vec2 centre() const { return 0.5f * (min + max); }
  bool contains(glm::vec2 p) const { return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y; }
};

struct DiagramArrow {
  size_t transition = 0;  // index into GraphDocument::transitions()
  size_t fromBox = 0, toBox = 0;
  glm::vec2 start{0.0f}, end{0.0f};  // on the boxes' edges
  // The point at `progress` in [0, 1] along the arrow.
  glm::vec2 at(float progress) const { return start + progress * (end - start); }
};

class StateMachineDiagram {
 public:
  static constexpr glm::vec2 kBoxSize{84.0f, 26.0f};
  static constexpr float kPairOffset = 5.0f;  // pixels between an arrow and its opposite

  // Lays out `states` (in order, clockwise from the top) and `transitions` in a canvas of `size` pixels.
  void layout(const std::vector<GraphStateInfo>& states, const std::vector<GraphTransitionInfo>& transitions,
              glm::vec2 size);

  const std::vector<DiagramBox>& boxes() const { return boxes_; }
  const std::vector<DiagramArrow>& arrows() const { return arrows_; }
  std::optional<size_t> findBox(std::string_view state) const;
  // The box under `p`, else the arrow within `tolerance` pixels of it.
  std::optional<size_t> boxAt(glm::vec2 p) const;
  std::optional<size_t> arrowAt(glm::vec2 p, float tolerance = 4.0f) const;

 private:
  std::vector<DiagramBox> boxes_;
  std::vector<DiagramArrow> arrows_;
};

// Where the segment from `inside` towards `outside` leaves the box.
glm::vec2 boxExit(const DiagramBox& box, glm::vec2 towards);

}  // namespace editor
