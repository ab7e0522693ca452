// editor/graph_document.h: the state machine's edits (states, transitions and
// their timing), undo / redo, and the saved file read back by the runtime's
// loader with the same behaviour as the document in memory.
#include <gtest/gtest.h>

#include "editor/graph_document.h"
#include "facial/runtime/graph/graph_instance.h"
#include "facial/runtime/graph/graph_json.h"
#include "facial/runtime/graph/nodes/state_machine_node.h"
#include "facial/runtime/rig/expression_library.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using editor::GraphDocument;

fs::path tourPath() { return testing_support::sourceDir() / "data" / "graphs" / "tour.json"; }

GraphDocument tour() {
  auto doc = GraphDocument::load(tourPath());
  EXPECT_TRUE(doc.ok()) << doc.error().message;
  return std::move(doc).value();
}

const facial::ExpressionLibrary& library() {
  static const facial::ExpressionLibrary presets =
      facial::ExpressionLibrary::load(testing_support::sourceDir() / "data" / "expressions.json").value();
  return presets;
}

std::vector<std::string> names(const GraphDocument& doc) {
  std::vector<std::string> out;
  for (const auto& s : doc.states()) out.push_back(s.name);
  return out;
}

// The state names a graph visits and its weights, frame by frame, while `trigger` fires at frame 10.
struct Played {
  std::vector<std::string> states;
  std::vector<float> weights;
};
Played play(const facial::SharedGraphDefinition& graph, std::string_view trigger) {
  auto face = facial::GraphInstance::create(graph, 3).value();
  const facial::NodeIndex machine = *graph->findNode("emotions");
  const auto* node = graph->nodeAs<facial::StateMachineNode>(machine);
  Played run;
  for (int frame = 0; frame < 120; ++frame) {
    if (frame == 10) {
      EXPECT_TRUE(face.setTrigger(*graph->findParameter(trigger)));
    }
    face.update(1.0f / 30.0f);
    run.states.push_back(node->states[face.stateMachineStatus(machine)->current].name);
    run.weights.insert(run.weights.end(), face.weights().begin(), face.weights().end());
  }
  return run;
}

}  // namespace

TEST(GraphDocument, ReadsTheTourStatesAndTransitions) {
  const GraphDocument doc = tour();
  EXPECT_EQ(names(doc), (std::vector<std::string>{"neutral", "happy", "sad", "anger", "fear", "surprise", "disgust"}));
  EXPECT_EQ(doc.states()[1].expression, "happy");
  EXPECT_EQ(doc.defaultState(), "neutral");
  const auto t = doc.findTransition("neutral", "happy");
  ASSERT_TRUE(t);
  EXPECT_FLOAT_EQ(t->duration, 0.8f);
  EXPECT_EQ(t->easing, "cosine");
  EXPECT_FLOAT_EQ(*t->exitTime, 2.4f);
  EXPECT_EQ(t->trigger, "autoplay");
  const auto any = doc.findTransition(GraphDocument::kAnyState, "sad");
  ASSERT_TRUE(any);
  EXPECT_EQ(any->trigger, "sad");
  EXPECT_FALSE(doc.dirty());
}

TEST(GraphDocument, RefusesAGraphWithoutAStateMachine) {
  auto doc = GraphDocument::fromJson(facial::Json::parse(R"({"version": 1, "root": {"type": "pose", "preset": "happy"}})"),
                                     "plain.json");
  ASSERT_FALSE(doc.ok());
  EXPECT_EQ(doc.error().message, "plain.json: the graph has no state machine to edit");
}

TEST(GraphDocument, AddsRemovesAndRenamesStatesWithTheirTransitions) {
  GraphDocument doc = tour();
  ASSERT_TRUE(doc.addState("smirk", "happily_disgusted").ok());
  EXPECT_FALSE(doc.addState("smirk", "happy").ok());
  EXPECT_FALSE(doc.addState("any", "happy").ok());
  ASSERT_TRUE(doc.addTransition("happy", "smirk", "smirk", 0.4f, "smoothstep").ok());
  ASSERT_TRUE(doc.renameState("smirk", "grin").ok());
  auto t = doc.findTransition("happy", "grin");
  ASSERT_TRUE(t);
  EXPECT_EQ(t->trigger, "smirk");
  EXPECT_EQ(t->easing, "smoothstep");
  ASSERT_TRUE(doc.renameState("neutral", "rest").ok());
  EXPECT_EQ(doc.defaultState(), "rest");
  EXPECT_TRUE(doc.findTransition("disgust", "rest"));
  EXPECT_TRUE(doc.findTransition(GraphDocument::kAnyState, "rest"));

  ASSERT_TRUE(doc.removeState("sad").ok());
  EXPECT_FALSE(doc.hasState("sad"));
  for (const auto& tr : doc.transitions()) EXPECT_NE(tr.to, "sad") << tr.from;
  EXPECT_FALSE(doc.removeState("sad").ok());
  EXPECT_TRUE(doc.dirty());
}

TEST(GraphDocument, EditsATransitionsTimingAndRefusesBadValues) {
  GraphDocument doc = tour();
  ASSERT_TRUE(doc.editTransition("neutral", "happy", 1.5f, "linear", std::nullopt, false).ok());
  auto t = doc.findTransition("neutral", "happy");
  EXPECT_FLOAT_EQ(t->duration, 1.5f);
  EXPECT_EQ(t->easing, "linear");
  EXPECT_FALSE(t->exitTime);
  EXPECT_FALSE(t->interruptible);
  ASSERT_TRUE(doc.editTransition("neutral", "happy", 0.5f, "cosine", 1.0f, true).ok());
  EXPECT_FLOAT_EQ(*doc.findTransition("neutral", "happy")->exitTime, 1.0f);
  const uint64_t revision = doc.revision();
  EXPECT_EQ(doc.editTransition("neutral", "happy", 0.0f, "cosine", {}, true).error().message,
            "a transition's duration must be a finite number > 0 (got 0)");
  EXPECT_EQ(doc.editTransition("neutral", "happy", 1.0f, "wobbly", {}, true).error().message,
            "unknown easing 'wobbly' (linear, cosine, smoothstep)");
  EXPECT_FALSE(doc.editTransition("neutral", "happy", 1.0f, "cosine", -1.0f, true).ok());
  EXPECT_EQ(doc.editTransition("happy", "neutral", 1.0f, "cosine", {}, true).error().message, "no transition happy -> neutral");
  EXPECT_EQ(doc.revision(), revision);
  EXPECT_FALSE(doc.addTransition("happy", "nobody", "x", 1.0f, "cosine").ok());
  EXPECT_FALSE(doc.addTransition("happy", "sad", "autoplay", 1.0f, "cosine").ok()) << "exists already";
  EXPECT_EQ(doc.addTransition("sad", "happy", "intensity", 1.0f, "cosine").error().message,
            "parameter 'intensity' is a float, not a trigger");
  EXPECT_EQ(doc.revision(), revision);
}

TEST(GraphDocument, UndoAndRedoEveryEdit) {
  GraphDocument doc = tour();
  const facial::Json original = doc.json();
  ASSERT_TRUE(doc.addState("smirk", "happy").ok());
  ASSERT_TRUE(doc.addTransition("smirk", "neutral", "-", 0.3f, "linear").ok());
  const facial::Json edited = doc.json();
  EXPECT_TRUE(doc.undo());
  EXPECT_TRUE(doc.undo());
  EXPECT_FALSE(doc.undo());
  EXPECT_EQ(doc.json(), original);
  EXPECT_FALSE(doc.dirty());
  EXPECT_TRUE(doc.redo());
  EXPECT_TRUE(doc.redo());
  EXPECT_EQ(doc.json(), edited);
  doc.discardLast();
  EXPECT_FALSE(doc.canRedo());
  EXPECT_TRUE(doc.hasState("smirk"));
  EXPECT_FALSE(doc.findTransition("smirk", "neutral"));
}

TEST(GraphDocument, SavedGraphLoadsInTheRuntimeAndBehavesAsTheDocument) {
  GraphDocument doc = tour();
  ASSERT_TRUE(doc.addState("smirk", "happily_disgusted").ok());
  ASSERT_TRUE(doc.addTransition("neutral", "smirk", "smirk", 0.5f, "smoothstep").ok());
  ASSERT_TRUE(doc.editTransition("neutral", "smirk", 0.7f, "cosine", std::nullopt, false).ok());
  const fs::path dir = testing_support::freshTempDir("graph_document_save");
  ASSERT_TRUE(doc.save(dir / "edited.json").ok());
  EXPECT_FALSE(doc.dirty());
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);

  const facial::GraphLoadOptions options{.presets = facial::presetLookup(library())};
  auto saved = facial::loadGraph(dir / "edited.json", options);
  ASSERT_TRUE(saved.ok()) << saved.error().message;
  auto inMemory = facial::parseGraph(doc.json(), tourPath(), options);
  ASSERT_TRUE(inMemory.ok()) << inMemory.error().message;
  const auto* machine = (*saved)->nodeAs<facial::StateMachineNode>(*(*saved)->findNode("emotions"));
  const auto smirk = machine->findState("smirk");
  ASSERT_TRUE(smirk);
  const facial::Transition& t = machine->states[0].transitions.back();
  EXPECT_EQ(t.to, "smirk");
  EXPECT_FLOAT_EQ(t.duration, 0.7f);
  EXPECT_EQ(t.curve.type(), facial::EasingType::Cosine);
  EXPECT_FALSE(t.interruptible);

  const Played fromFile = play(*saved, "smirk"), fromDocument = play(*inMemory, "smirk");
  EXPECT_EQ(fromFile.states.back(), "smirk");
  EXPECT_EQ(fromFile.states, fromDocument.states);
  EXPECT_EQ(fromFile.weights, fromDocument.weights);
}

TEST(GraphDocument, UneditedSaveBehavesAsTheOriginalFile) {
  GraphDocument doc = tour();
  const fs::path dir = testing_support::freshTempDir("graph_document_unedited");
  ASSERT_TRUE(doc.save(dir / "tour.json").ok());
  const facial::GraphLoadOptions options{.presets = facial::presetLookup(library())};
  const Played original = play(facial::loadGraph(tourPath(), options).value(), "fear");
  const Played saved = play(facial::loadGraph(dir / "tour.json", options).value(), "fear");
  EXPECT_EQ(saved.states, original.states);
  EXPECT_EQ(saved.weights, original.weights);
}

TEST(GraphDocument, AFailedSaveKeepsTheOldFile) {
  GraphDocument doc = tour();
  const fs::path dir = testing_support::freshTempDir("graph_document_blocked");
  fs::create_directories(dir / "taken.json");  // a folder where the file should go
  EXPECT_FALSE(doc.save(dir / "taken.json").ok());
  EXPECT_TRUE(fs::is_directory(dir / "taken.json"));
  EXPECT_EQ(testing_support::partialFilesIn(dir), 0u);
}
