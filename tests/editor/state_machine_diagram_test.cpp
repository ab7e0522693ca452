// editor/state_machine_diagram.h: boxes that do not overlap, arrows from edge
// to edge (opposite ones apart), and what a click hits.
#include <gtest/gtest.h>

#include "editor/state_machine_diagram.h"

namespace {

using editor::GraphStateInfo;
using editor::GraphTransitionInfo;
using editor::StateMachineDiagram;

StateMachineDiagram diagram(size_t states) {
  std::vector<GraphStateInfo> s;
  for (size_t i = 0; i < states; ++i) s.push_back({"s" + std::to_string(i), "happy"});
  std::vector<GraphTransitionInfo> t = {{.from = "s0", .to = "s1"}, {.from = "s1", .to = "s0"},
                                        {.from = "any", .to = "s2"}, {.from = "s0", .to = "nowhere"}};
  StateMachineDiagram d;
  d.layout(s, t, {560.0f, 360.0f});
  return d;
}

bool overlap(const editor::DiagramBox& a, const editor::DiagramBox& b) {
  return a.min.x < b.max.x && b.min.x < a.max.x && a.min.y < b.max.y && b.min.y < a.max.y;
}

}  // namespace

TEST(StateMachineDiagram, BoxesStayInsideTheCanvasAndApart) {
  for (size_t n : {1u, 2u, 7u, 8u}) {
    const StateMachineDiagram d = diagram(n);
    ASSERT_EQ(d.boxes().size(), n + 1) << "the states and 'any'";
    for (size_t i = 0; i < d.boxes().size(); ++i) {
      EXPECT_GE(d.boxes()[i].min.x, 0.0f);
      EXPECT_GE(d.boxes()[i].min.y, 0.0f);
      EXPECT_LE(d.boxes()[i].max.x, 560.0f);
      EXPECT_LE(d.boxes()[i].max.y, 360.0f);
      for (size_t j = i + 1; j < d.boxes().size(); ++j)
        EXPECT_FALSE(overlap(d.boxes()[i], d.boxes()[j])) << n << " states: " << i << " and " << j;
    }
  }
}

TEST(StateMachineDiagram, ArrowsRunEdgeToEdgeAndOppositeOnesApart) {
  const StateMachineDiagram d = diagram(7);
  ASSERT_EQ(d.arrows().size(), 3u) << "the transition to an unknown state is not drawn";
  for (const auto& arrow : d.arrows()) {
    EXPECT_FALSE(d.boxes()[arrow.fromBox].contains(arrow.at(0.5f)));
    EXPECT_FALSE(d.boxes()[arrow.toBox].contains(arrow.at(0.5f)));
    const glm::vec2 c = d.boxes()[arrow.fromBox].centre();
    EXPECT_LT(glm::length(arrow.start - c), glm::length(arrow.end - c));
  }
  EXPECT_GT(glm::length(d.arrows()[0].at(0.5f) - d.arrows()[1].at(0.5f)), 2.0f * StateMachineDiagram::kPairOffset - 0.1f);
  EXPECT_EQ(d.boxes()[d.arrows()[2].fromBox].state, "any");
}

TEST(StateMachineDiagram, AClickHitsABoxOrAnArrow) {
  const StateMachineDiagram d = diagram(7);
  EXPECT_EQ(d.boxAt(d.boxes()[3].centre()), 3u);
  const auto& arrow = d.arrows()[2];
  EXPECT_EQ(d.arrowAt(arrow.at(0.5f) + glm::vec2(0.0f, 1.0f)), 2u);
  EXPECT_FALSE(d.boxAt({1.0f, 1.0f}));
  EXPECT_FALSE(d.arrowAt({1.0f, 1.0f}));
}
