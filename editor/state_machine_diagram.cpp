#include "editor/state_machine_diagram.h"

#include <algorithm>
#include <cmath>

namespace editor {

namespace {

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 ab = b - a;
  const float length2 = glm::dot(ab, ab);
  const float t = length2 > 0.0f ? std::clamp(glm::dot(p - a, ab) / length2, 0.0f, 1.0f) : 0.0f;
  return glm::length(p - (a + t * ab));
}

}  // namespace

glm::vec2 boxExit(const DiagramBox& box, glm::vec2 towards) {
  const glm::vec2 c = box.centre(), d = towards - c, half = 0.5f * (box.max - box.min);
  // The smallest scale that reaches a side of the box.
  const float sx = std::abs(d.x) > 1e-6f ? half.x / std::abs(d.x) : INFINITY;
  const float sy = std::abs(d.y) > 1e-6f ? half.y / std::abs(d.y) : INFINITY;
  const float s = std::min({sx, sy, 1.0f});
  return c + s * d;
}

void StateMachineDiagram::layout(const std::vector<GraphStateInfo>& states,
                                 const std::vector<GraphTransitionInfo>& transitions, glm::vec2 size) {
  boxes_.clear();
  arrows_.clear();
  const glm::vec2 centre = 0.5f * size;
  // The ring as large as the canvas allows with the boxes inside it.
  const glm::vec2 radius = glm::max(0.5f * size - 0.5f * kBoxSize - glm::vec2(6.0f), glm::vec2(kBoxSize.y));
  const size_t n = states.size();
  for (size_t i = 0; i < n; ++i) {
    const float a = 2.0f * float(M_PI) * float(i) / float(std::max<size_t>(n, 1)) - 0.5f * float(M_PI);
    const glm::vec2 at = centre + radius * glm::vec2(std::cos(a), std::sin(a));
    boxes_.push_back({states[i].name, at - 0.5f * kBoxSize, at + 0.5f * kBoxSize});
  }
  const glm::vec2 anySize = {kBoxSize.x * 0.8f, kBoxSize.y};
  boxes_.push_back({std::string(GraphDocument::kAnyState), centre - 0.5f * anySize, centre + 0.5f * anySize});

  for (size_t t = 0; t < transitions.size(); ++t) {
    const auto from = findBox(transitions[t].from), to = findBox(transitions[t].to);
    if (!from || !to || *from == *to) continue;
    const glm::vec2 a = boxes_[*from].centre(), b = boxes_[*to].centre();
    // Offset sideways (to the arrow's right) so A->B and B->A stay apart.
    const glm::vec2 dir = glm::normalize(b - a), side{-dir.y, dir.x};
    const glm::vec2 shift = kPairOffset * side;
    arrows_.push_back({t, *from, *to, boxExit(boxes_[*from], b + shift) + shift, boxExit(boxes_[*to], a + shift) + shift});
  }
}

std::optional<size_t> StateMachineDiagram::findBox(std::string_view state) const {
  for (size_t i = 0; i < boxes_.size(); ++i)
    if (boxes_[i].state == state) return i;
  return std::nullopt;
}

std::optional<size_t> StateMachineDiagram::boxAt(glm::vec2 p) const {
  for (size_t i = 0; i < boxes_.size(); ++i)
    if (boxes_[i].contains(p)) return i;
  return std::nullopt;
}

std::optional<size_t> StateMachineDiagram::arrowAt(glm::vec2 p, float tolerance) const {
  std::optional<size_t> best;
  float bestDistance = tolerance;
  for (size_t i = 0; i < arrows_.size(); ++i)
    if (const float d = distanceToSegment(p, arrows_[i].start, arrows_[i].end); d <= bestDistance) {
      best = i;
      bestDistance = d;
    }
  return best;
}

}  // namespace editor
