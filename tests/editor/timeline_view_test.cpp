// TimelineView: the timeline panel's canvas geometry without ImGui: time and
// value to pixels and back, which row and key a click lands on, the ruler.
#include <array>

#include <gtest/gtest.h>

#include "editor/timeline_document.h"
#include "editor/timeline_view.h"

namespace {

using editor::TimelineArea;
using editor::TimelineView;

// A 2 s clip over [0, 1] in a 1000 x 400 area at (10, 20): the keys get
// 1000 - 170 - 8 = 822 px (411 px/s); two rows share 380 px, so each is capped at 44.
constexpr TimelineArea kArea{.left = 10.0f, .top = 20.0f, .width = 1000.0f, .height = 400.0f};

TEST(TimelineView, MapsTimeAcrossTheCanvasRightOfTheNames) {
  const TimelineView view = TimelineView::fit(kArea, 2, 2.0f, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(view.canvasLeft(), 180.0f);
  EXPECT_FLOAT_EQ(view.canvasWidth(), 822.0f);
  EXPECT_FLOAT_EQ(view.xAt(0.0f), 180.0f);
  EXPECT_FLOAT_EQ(view.xAt(2.0f), view.canvasRight());
  EXPECT_FLOAT_EQ(view.xAt(1.0f), 180.0f + 411.0f);
  EXPECT_FLOAT_EQ(view.timeAt(view.xAt(0.75f)), 0.75f);
  EXPECT_FLOAT_EQ(view.secondsFor(411.0f), 1.0f);
}

TEST(TimelineView, RowsShareTheHeightUnderTheRulerWithinLimits) {
  EXPECT_FLOAT_EQ(TimelineView::fit(kArea, 2, 2.0f, 0.0f, 1.0f).rowHeight(), TimelineView::kMaxRowHeight);
  EXPECT_FLOAT_EQ(TimelineView::fit(kArea, 50, 2.0f, 0.0f, 1.0f).rowHeight(), TimelineView::kMinRowHeight);
  const TimelineView ten = TimelineView::fit(kArea, 10, 2.0f, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(ten.rowHeight(), 38.0f);  // (400 - 20) / 10
  EXPECT_FLOAT_EQ(ten.rowsTop(), 40.0f);
  EXPECT_FLOAT_EQ(ten.rowTop(3), 40.0f + 3.0f * 38.0f);
  EXPECT_FLOAT_EQ(ten.canvasHeight(), 400.0f);
  // Without tracks the canvas still holds the ruler and one (empty) row.
  const TimelineView empty = TimelineView::fit(kArea, 0, 2.0f, 0.0f, 1.0f);
  EXPECT_FLOAT_EQ(empty.canvasHeight(), 20.0f + TimelineView::kMaxRowHeight);
  EXPECT_FALSE(empty.rowAt(50.0f).has_value());
  // A narrow area keeps 50 px of keys.
  EXPECT_FLOAT_EQ(TimelineView::fit({.width = 100.0f, .height = 100.0f}, 1, 1.0f, 0.0f, 1.0f).canvasWidth(), 50.0f);
}

TEST(TimelineView, ValuesRiseInsideTheirRowAndDragsGoBack) {
  const TimelineView view = TimelineView::fit(kArea, 2, 2.0f, 0.0f, 1.0f);
  // Row 1 spans 84..128; values keep 3 px inside it, 1 at the top.
  EXPECT_FLOAT_EQ(view.yAt(1, 0.0f), 128.0f - 3.0f);
  EXPECT_FLOAT_EQ(view.yAt(1, 1.0f), 84.0f + 3.0f);
  EXPECT_FLOAT_EQ(view.yAt(1, 0.5f), 106.0f);
  // Dragging up by the row's value range raises the value by 1.
  EXPECT_FLOAT_EQ(view.valueFor(-(44.0f - 6.0f)), 1.0f);
  const TimelineView wide = TimelineView::fit(kArea, 2, 2.0f, -1.0f, 1.0f);
  EXPECT_FLOAT_EQ(wide.yAt(0, 0.0f), 40.0f + 22.0f);
}

TEST(TimelineView, AClickTakesTheNearestKeyOfTheRowUnderIt) {
  editor::TimelineDocument doc("hit", 2.0f);
  ASSERT_TRUE(doc.addTrack("jawOpen"));
  ASSERT_TRUE(doc.addTrack("browInnerUp"));
  const auto early = doc.setKey(1, 0.5f, 1.0f);
  const auto late = doc.setKey(1, 0.52f, 0.0f);  // close in time, far in value
  const auto other = doc.setKey(0, 0.5f, 1.0f);
  ASSERT_TRUE(early && late && other);
  const TimelineView view = TimelineView::fit(kArea, doc);

  const glm::vec2 onEarly{view.xAt(0.5f) + 2.0f, view.yAt(1, 1.0f) + 2.0f};
  const auto hit = view.hitAt(doc.tracks(), onEarly);
  ASSERT_TRUE(hit.has_value());
  EXPECT_EQ(hit->row, 1u);
  EXPECT_EQ(hit->key, *early);
  EXPECT_EQ(view.hitAt(doc.tracks(), {view.xAt(0.52f), view.yAt(1, 0.0f)})->key, *late);

  // In the row but beyond 7 px of any key: the row, no key (the click scrubs).
  const auto miss = view.hitAt(doc.tracks(), {view.xAt(1.5f), view.yAt(1, 1.0f)});
  ASSERT_TRUE(miss.has_value());
  EXPECT_EQ(miss->row, 1u);
  EXPECT_FALSE(miss->key.has_value());
  EXPECT_FALSE(view.hitAt(doc.tracks(), {view.xAt(0.5f) + 7.5f, view.yAt(1, 1.0f)})->key.has_value());
  // On the ruler or below the rows: nothing.
  EXPECT_FALSE(view.hitAt(doc.tracks(), {view.xAt(0.5f), 30.0f}).has_value());
  EXPECT_FALSE(view.hitAt(doc.tracks(), {view.xAt(0.5f), view.rowsBottom() + 1.0f}).has_value());
}

TEST(TimelineView, RulerLabelsGetSparserOnLongerClips) {
  EXPECT_FLOAT_EQ(TimelineView::rulerLabelStep(2.0f), 0.5f);
  EXPECT_FLOAT_EQ(TimelineView::rulerLabelStep(3.0f), 0.5f);
  EXPECT_FLOAT_EQ(TimelineView::rulerLabelStep(10.0f), 1.0f);
  EXPECT_FLOAT_EQ(TimelineView::rulerLabelStep(30.0f), 5.0f);
}

}  // namespace

// ---- Groups, rows and the time window (issue 34) ----

namespace groups {

using editor::TrackGroup;

TEST(TimelineViewGroups, ChannelsJoinTheGroupTheirNameSays) {
  EXPECT_EQ(editor::trackGroupOf("AU1_InnerBrowRaiser"), TrackGroup::Brows);
  EXPECT_EQ(editor::trackGroupOf("browInnerUp"), TrackGroup::Brows);
  EXPECT_EQ(editor::trackGroupOf("eyeBlinkLeft"), TrackGroup::Eyes);
  EXPECT_EQ(editor::trackGroupOf("AU45_Blink_L"), TrackGroup::Eyes);
  EXPECT_EQ(editor::trackGroupOf("AU6_CheekRaiser"), TrackGroup::Cheeks);
  EXPECT_EQ(editor::trackGroupOf("noseSneerLeft"), TrackGroup::Cheeks);
  EXPECT_EQ(editor::trackGroupOf("AU12_LipCornerPuller_L"), TrackGroup::Mouth);
  EXPECT_EQ(editor::trackGroupOf("mouthSmileLeft"), TrackGroup::Mouth);
  EXPECT_EQ(editor::trackGroupOf("AU26_JawDrop"), TrackGroup::Jaw);
  EXPECT_EQ(editor::trackGroupOf("happy"), TrackGroup::Emotions);
  EXPECT_EQ(editor::trackGroupOf("viseme_PP"), TrackGroup::Visemes);
  EXPECT_EQ(editor::trackGroupOf("Fcl_HA_Hide"), TrackGroup::Targets);
  EXPECT_EQ(editor::trackGroupName(TrackGroup::Targets), "targets");
}

TEST(TimelineViewGroups, RowsPutAHeaderOverEachGroupAndFoldCollapsedOnes) {
  editor::TimelineDocument doc("rows", 2.0f);
  for (const char* channel : {"happy", "AU26_JawDrop", "browInnerUp", "sad", "custom"}) ASSERT_TRUE(doc.addTrack(channel));
  const auto rows = editor::layoutTrackRows(doc.tracks(), {});
  // brows: header + browInnerUp; jaw: header + jaw; emotions: header + happy + sad; targets: header + custom.
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_FALSE(rows[0].track.has_value());
  EXPECT_EQ(rows[0].group, TrackGroup::Brows);
  EXPECT_EQ(rows[1].track, 2u);
  EXPECT_EQ(rows[5].track, 0u);
  EXPECT_EQ(rows[6].track, 3u);
  std::array<bool, editor::kTrackGroupCount> collapsed{};
  collapsed[size_t(TrackGroup::Emotions)] = true;
  const auto folded = editor::layoutTrackRows(doc.tracks(), collapsed);
  ASSERT_EQ(folded.size(), 7u);  // the emotions' header stays
  EXPECT_EQ(folded[4].group, TrackGroup::Emotions);
  EXPECT_FALSE(folded[4].track.has_value());
  // A click on a row maps to its track; a header row has no key.
  TimelineView view = TimelineView::fit(kArea, rows.size(), 2.0f, 0.0f, 1.0f);
  ASSERT_TRUE(doc.setKey(2, 1.0f, 1.0f));
  const auto hit = view.hitAt(doc.tracks(), rows, {view.xAt(1.0f), view.yAt(1, 1.0f)});
  ASSERT_TRUE(hit && hit->key);
  EXPECT_FALSE(view.hitAt(doc.tracks(), rows, {view.xAt(1.0f), view.yAt(0, 1.0f)})->key.has_value());
}

TEST(TimelineViewGroups, TheTimeWindowZoomsAboutTheMouseAndPans) {
  editor::TimeWindow window{0.0f, 2.0f};
  window.zoom(0.5f, 2.0f);  // closer, keeping 0.5 s in place
  EXPECT_FLOAT_EQ(window.start, 0.25f);
  EXPECT_FLOAT_EQ(window.end, 1.25f);
  window.pan(0.5f);
  EXPECT_FLOAT_EQ(window.start, 0.75f);
  window.zoom(1.0f, 1000.0f);
  EXPECT_FLOAT_EQ(window.span(), editor::TimeWindow::kMinSpan);
  window.frame(1.0f, 2.0f);
  EXPECT_FLOAT_EQ(window.start, 0.95f);
  EXPECT_FLOAT_EQ(window.end, 2.05f);
  window = {-50.0f, 100.0f};
  window.clampTo(2.0f);  // at most twice the clip, not far off it
  EXPECT_FLOAT_EQ(window.span(), 4.0f);
  EXPECT_GE(window.start, -2.0f);
  // The view shows the window across the canvas.
  TimelineView view = TimelineView::fit(kArea, 1, 2.0f, 0.0f, 1.0f);
  view.showTime({0.5f, 1.5f});
  EXPECT_FLOAT_EQ(view.xAt(0.5f), view.canvasLeft());
  EXPECT_FLOAT_EQ(view.xAt(1.5f), view.canvasRight());
  EXPECT_FLOAT_EQ(view.timeAt(view.xAt(1.2f)), 1.2f);
}

}  // namespace groups
