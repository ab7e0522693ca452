// facial-editor --script under xvfb-run: the sculpt panel (a pick by window
// pixel, moving the point, the live preview, bake, Save .glb) and timeline
// editing (key all, move, delete, undo / redo, save, a save that cannot
// write) through the same handlers as the UI, checked from the outside: the
// log, the screenshots, and the files the editor saved.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>

#include "editor/timeline_document.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/image_io.h"
#include "facial/runtime/graph/timeline_json.h"
#include "tests/common/test_support.h"
#include "tests/editor/editor_run.h"

namespace {

namespace fs = std::filesystem;
using editor_test::meanDifference;
using editor_test::runEditor;

eng::Image readShot(const fs::path& path) {
  auto image = eng::readImage(path);
  if (!image) {
    ADD_FAILURE() << image.error().message;
    return {};
  }
  if (image->width != 1280 || image->height != 800) ADD_FAILURE() << path << " is " << image->width << "x" << image->height;
  return std::move(*image);
}

// Lines of the log matching `pattern`, each as its submatches.
std::vector<std::smatch> logMatches(const std::string& log, const std::string& pattern) {
  std::vector<std::smatch> found;
  const std::regex re(pattern);
  for (std::sregex_iterator it(log.begin(), log.end(), re), end; it != end; ++it) found.push_back(*it);
  return found;
}

// ---------------------------------------------------------------------------
// Sculpt

// At 1280x800 the face fills the viewport (x 320..960, y 0..560): the nose
// tip is about here.
constexpr int kNoseX = 640, kNoseY = 294;

TEST(EditorScript, SculptPickMovePreviewBakeAndSave) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_sculpt");
  // Zero-displacement points around the nose (landmarks of the built-in
  // head) keep the bend local, as a sculptor pins what must not move; then
  // the nose tip, picked by its pixel.
  std::string anchors;
  for (const char* name : {"nose_root", "ala_L", "ala_R", "philtrum", "infraorbital_L", "infraorbital_R", "cheek_L",
                           "cheek_R", "chin", "forehead_centre"})
    anchors += std::string("0.2 sculpt-landmark ") + name + "\n";
  testing_support::writeFile(dir / "sculpt.txt",
                             anchors +
                             "0.3 sculpt-pick " + std::to_string(kNoseX) + " " + std::to_string(kNoseY) + "  # the nose tip\n"
                             "0.4 screenshot unsculpted.png\n"
                             "0.5 sculpt-move 0 0 0.006   # out of the face (the XYZ drags)\n"
                             "0.5 sculpt-drag 15 0        # to screen right (Shift+drag in the view)\n"
                             "0.6 screenshot sculpted.png\n"
                             "0.7 sculpt-kernel multiquadric 0.02\n"
                             "0.8 screenshot multiquadric.png\n"
                             "0.9 sculpt-kernel biharmonic\n"
                             "1.0 sculpt-bake crooked_nose\n"
                             "1.1 screenshot baked.png\n"
                             "1.2 sculpt-save crooked.glb\n"
                             "1.3 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script sculpt.txt", 20.0f);
  ASSERT_TRUE(editor_test::ranCleanly(run));

  // The pixel pick landed on the nose tip, the front-most point of the face.
  const auto picks = logMatches(run.log, R"(control point '([^']+)' at \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))");
  ASSERT_EQ(picks.size(), 11u) << run.log;
  const std::smatch& nosePick = picks.back();
  const glm::vec3 picked{std::stof(nosePick[2]), std::stof(nosePick[3]), std::stof(nosePick[4])};
  auto original = eng::loadModel(testing_support::sourceDir() / "data" / "head.glb");
  ASSERT_TRUE(original) << original.error().message;
  const eng::Aabb bounds = original->bounds();
  EXPECT_NEAR(picked.x, 0.0f, 0.002f) << run.log;
  EXPECT_GT(picked.z, bounds.max.z - 0.004f) << "the nose tip, not somewhere behind it:\n" << run.log;
  // The XYZ move, then the screen-plane drag: from the front, screen right is +x.
  const auto moves = logMatches(run.log, R"(sculpt: 'point 11' displaced by \(([-0-9.]+), ([-0-9.]+), ([-0-9.]+)\))");
  ASSERT_EQ(moves.size(), 2u) << run.log;
  const glm::vec3 xyzMove{std::stof(moves[0][1]), std::stof(moves[0][2]), std::stof(moves[0][3])};
  const glm::vec3 kMove{std::stof(moves[1][1]), std::stof(moves[1][2]), std::stof(moves[1][3])};
  EXPECT_EQ(xyzMove, glm::vec3(0.0f, 0.0f, 0.006f));
  EXPECT_GT(kMove.x, 0.004f) << "15 pixels to the right on a head about 450 pixels tall";
  EXPECT_LT(kMove.x, 0.012f);
  EXPECT_NEAR(kMove.y, 0.0f, 1e-5f);
  EXPECT_NEAR(kMove.z, 0.006f, 1e-5f);

  // The preview bends the nose and leaves the face away from it alone.
  const eng::Image before = readShot(dir / "unsculpted.png"), after = readShot(dir / "sculpted.png");
  const eng::Image multiquadric = readShot(dir / "multiquadric.png"), baked = readShot(dir / "baked.png");
  for (const eng::Image* shot : {&before, &after, &multiquadric, &baked}) ASSERT_EQ(shot->width, 1280);
  // Pixels that changed clearly (the texture under a sub-pixel shift changes a little everywhere).
  const auto changed = [](const eng::Image& a, const eng::Image& b, int x0, int y0, int x1, int y1) {
    size_t count = 0, total = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x, ++total)
        if (editor_test::colourDistance(editor_test::pixel(a, x, y), editor_test::pixel(b, x, y)) > 48) ++count;
    return double(count) / double(total);
  };
  const int nx0 = kNoseX - 40, ny0 = kNoseY - 50, nx1 = kNoseX + 40, ny1 = kNoseY + 30;
  const double nose = changed(before, after, nx0, ny0, nx1, ny1);
  const double forehead = changed(before, after, 580, 70, 700, 150);
  const double otherCheek = changed(before, after, 550, 280, 590, 370);
  const double noseMean = meanDifference(before, after, nx0, ny0, nx1, ny1);
  const double bakedMean = meanDifference(before, baked, nx0, ny0, nx1, ny1);
  const double kernels = meanDifference(after, multiquadric, nx0, ny0, nx1, ny1);
  std::printf("preview vs unsculpted, pixels changed: nose %.3f, forehead %.3f, other cheek %.3f; mean colour change at "
              "the nose: preview %.2f, baked %.2f, multiquadric vs biharmonic %.2f\n",
              nose, forehead, otherCheek, noseMean, bakedMean, kernels);
  EXPECT_GT(nose, 0.04) << "the preview shows the moved nose";
  EXPECT_GT(noseMean, 6.0) << "the preview shows the moved nose";
  EXPECT_LT(forehead, 0.2 * nose) << "the forehead stays";
  EXPECT_LT(otherCheek, 0.2 * nose) << "the cheek away from the move stays";
  EXPECT_GT(kernels, 0.5) << "another kernel bends the face differently";
  // The bake keeps the look: the new target at weight 1, the points back at
  // rest (shading differs a little: the preview moves positions only, the
  // baked target has normal deltas too).
  EXPECT_GT(bakedMean, 0.6 * noseMean) << "the baked nose is still bent";


  // The saved model: the head's targets plus the baked one, largest at the
  // picked point, where it is the moved displacement.
  ASSERT_NE(run.log.find("saved crooked.glb"), std::string::npos) << run.log;
  auto saved = eng::loadModel(dir / "crooked.glb");
  ASSERT_TRUE(saved) << saved.error().message;
  int node = -1;
  for (size_t n = 0; n < saved->nodes.size(); ++n)
    if (saved->nodes[n].mesh == 0) node = int(n);
  ASSERT_GE(node, 0);
  const eng::Mesh& head = saved->meshes[0];
  ASSERT_EQ(head.targetNames.size(), original->meshes[0].targetNames.size() + 1);
  ASSERT_EQ(head.targetNames.back(), "crooked_nose");
  const glm::mat4 world = saved->worldTransform(node);
  float largest = 0.0f, nearest = 1e9f;
  glm::vec3 largestAt{0.0f}, deltaNearest{0.0f};
  for (const eng::Primitive& primitive : head.primitives) {
    const eng::MorphTarget& target = primitive.targets.back();
    ASSERT_EQ(target.positions.size(), primitive.vertexCount());
    for (size_t v = 0; v < primitive.vertexCount(); ++v) {
      const glm::vec3 at = glm::vec3(world * glm::vec4(primitive.positions[v], 1.0f));
      const glm::vec3 delta = glm::mat3(world) * target.positions[v];
      if (glm::length(delta) > largest) {
        largest = glm::length(delta);
        largestAt = at;
      }
      if (glm::length(at - picked) < nearest) {
        nearest = glm::length(at - picked);
        deltaNearest = delta;
      }
    }
  }
  std::printf("baked: largest delta %.5f at %.4f from the pick; nearest vertex (%.4f away) moved (%.5f %.5f %.5f)\n", largest,
              glm::length(largestAt - picked), nearest, deltaNearest.x, deltaNearest.y, deltaNearest.z);
  EXPECT_LT(glm::length(largestAt - picked), 0.006f) << "the largest delta is at the picked point";
  EXPECT_NEAR(largest, glm::length(kMove), 0.1f * glm::length(kMove));
  EXPECT_LT(glm::length(deltaNearest - kMove), 0.1f * glm::length(kMove)) << "the picked point moved by the scripted move";

  // `facial render` poses the saved target by name.
  const fs::path facial = fs::path(FACIAL_BINARY_DIR) / "bin" / "facial";
  const auto render = [&](const std::string& weight, const fs::path& out) {
    const std::string command = "'" + facial.string() + "' render '" + (dir / "crooked.glb").string() + "' --size 320x320 " +
                                weight + " --out '" + out.string() + "' >>'" + (dir / "render.log").string() + "' 2>&1";
    return std::system(command.c_str());
  };
  ASSERT_EQ(render("--weight crooked_nose=1", dir / "crooked.png"), 0) << editor_test::readText(dir / "render.log");
  ASSERT_EQ(render("", dir / "straight.png"), 0) << editor_test::readText(dir / "render.log");
  auto crooked = eng::readImage(dir / "crooked.png"), straight = eng::readImage(dir / "straight.png");
  ASSERT_TRUE(crooked && straight);
  const double rendered = meanDifference(*crooked, *straight, 0, 0, 320, 320);
  const double renderedCorner = meanDifference(*crooked, *straight, 0, 0, 60, 60);
  std::printf("facial render crooked_nose=1 vs 0: %.3f over the image, %.3f in the corner\n", rendered, renderedCorner);
  EXPECT_GT(rendered, 0.2) << "the render shows the baked target";
  EXPECT_LT(renderedCorner, 0.05);
}

// ---------------------------------------------------------------------------
// Timeline

// The keys of a timeline file as (channel, time, value), loaded by the runtime's own reader.
struct SavedKey {
  std::string channel;
  float time, value;
};
std::vector<SavedKey> savedKeys(const fs::path& path) {
  auto timeline = facial::loadTimeline(path);
  if (!timeline) {
    ADD_FAILURE() << timeline.error().message;
    return {};
  }
  std::vector<SavedKey> keys;
  for (size_t t = 0; t < timeline->tracks.size(); ++t)
    for (const facial::Keyframe& k : timeline->trackKeys(t)) keys.push_back({timeline->tracks[t].channel, k.time, k.value});
  return keys;
}

TEST(EditorScript, TimelineKeyMoveDeleteUndoRedoAndSave) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_timeline");
  const fs::path source = testing_support::sourceDir() / "data" / "timelines" / "talk.json";
  fs::copy_file(source, dir / "talk.json");
  // A save that cannot complete: the temporary sibling it writes first is a
  // folder in the way, so the write fails and the old file must survive.
  testing_support::writeFile(dir / "blocked.json", "old content\n");
  fs::create_directory(dir / "blocked.saving.json");
  testing_support::writeFile(dir / "timeline.txt",
                             "0.1 trigger happy\n"
                             "0.2 timeline-open talk.json\n"
                             "0.2 pad 0 1                 # the control map's surprise pole drives the face\n"
                             "0.9 timeline-key AU26_JawDrop  # its jaw keyed at the playhead (0 s, over the key there)\n"
                             "1.0 timeline-seek 0.5\n"
                             "1.1 timeline-key-all\n"
                             "1.2 timeline-move-selected 0.1 0.2\n"
                             "1.3 screenshot keyed.png\n"
                             "1.4 timeline-delete\n"
                             "1.5 undo\n"
                             "1.6 redo\n"
                             "1.7 timeline-save after_redo.json\n"
                             "1.8 undo\n"
                             "1.9 timeline-save edited.json\n"
                             "2.0 timeline-save no_such_folder/edited.json\n"
                             "2.1 timeline-save blocked.json\n"
                             "2.2 quit\n");
  const editor_test::EditorRun run = runEditor(dir, "--script timeline.txt", 20.0f);
  // Two saves were meant to fail: reported, the script went on, exit status 1.
  EXPECT_EQ(run.exitCode, 1) << run.log;
  ASSERT_TRUE(editor_test::validationSilent(run));
  EXPECT_NE(run.log.find("2 scripted action(s) failed (timeline.txt)"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("error: timeline.txt:15: timeline-save no_such_folder/edited.json: failed"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("error: timeline.txt:16: timeline-save blocked.json: failed"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("no_such_folder/edited.json"), std::string::npos) << run.log;
  EXPECT_FALSE(fs::exists(dir / "no_such_folder")) << "a failed save creates nothing";
  EXPECT_EQ(editor_test::readText(dir / "blocked.json"), "old content\n") << "a failed save keeps the old file";
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename().string().find(".saving"), std::string::npos) << "left behind: " << entry.path();
  EXPECT_EQ(editor_test::readText(source), editor_test::readText(dir / "talk.json")) << "the opened file was not saved over";

  // After every timeline action the editor logs the document; the key count follows the edits.
  std::vector<int> counts;
  for (const std::smatch& m : logMatches(run.log, R"(timeline: 3 tracks, (\d+) keys)")) counts.push_back(std::stoi(m[1]));
  // open, key (over the key at 0 s), seek, key all, move, delete, undo, redo, save, undo, save, save (fails), save (fails)
  EXPECT_EQ(counts, (std::vector<int>{27, 27, 27, 30, 30, 27, 30, 27, 27, 30, 30, 30, 30})) << run.log;
  EXPECT_NE(run.log.find("state happy"), std::string::npos) << "the trigger button's path:\n" << run.log;

  // The keys: the original 27, plus one per track keyed at 0.5 s with the
  // value on screen (the timeline's own curve there), moved to 0.6 s and up by 0.2.
  auto original = editor::TimelineDocument::load(source);
  ASSERT_TRUE(original) << original.error().message;
  const std::vector<SavedKey> before = savedKeys(source), afterRedo = savedKeys(dir / "after_redo.json"),
                              edited = savedKeys(dir / "edited.json");
  ASSERT_EQ(before.size(), 27u);
  ASSERT_EQ(afterRedo.size(), 27u) << "redo deleted the new keys again";
  // The jaw key at 0 s holds the control map's surprise (its jaw drops); the rest are as loaded.
  ASSERT_EQ(afterRedo[0].channel, "AU26_JawDrop");
  EXPECT_EQ(afterRedo[0].time, 0.0f);
  EXPECT_GT(afterRedo[0].value, 0.1f) << "keyed from the face on screen (the control map's surprise)";
  for (size_t i = 1; i < before.size(); ++i) {
    EXPECT_EQ(afterRedo[i].channel, before[i].channel);
    EXPECT_NEAR(afterRedo[i].time, before[i].time, 1e-5f);
    EXPECT_NEAR(afterRedo[i].value, before[i].value, 1e-5f);
  }
  ASSERT_EQ(edited.size(), 30u);
  for (size_t track = 0; track < original->tracks().size(); ++track) {
    const std::string& channel = original->tracks()[track].channel;
    const float expected = std::clamp(original->sample(track, 0.5f) + 0.2f, 0.0f, 1.0f);
    int found = 0;
    for (const SavedKey& k : edited) {
      if (k.channel != channel) continue;
      EXPECT_GT(std::abs(k.time - 0.5f), 1e-4f) << channel << ": the key moved away from 0.5 s";
      if (std::abs(k.time - 0.6f) < 1e-4f) {
        ++found;
        EXPECT_NEAR(k.value, expected, 1e-4f) << channel;
      }
    }
    EXPECT_EQ(found, 1) << channel << " has its moved key at 0.6 s";
  }
}

TEST(EditorScript, ABrokenScriptIsRefusedNamingFileAndLine) {
  // Parsed before the window opens: no display needed.
  const fs::path dir = testing_support::freshTempDir("editor_script_broken");
  const auto refusal = [&](const std::string& script) { return editor_test::scriptRefusal(dir, "bad.txt", script); };
  EXPECT_NE(refusal("0.5 sculpt-pick 10 10\n1.0 sculpt-wiggle 3\n").find("bad.txt:2: unknown action 'sculpt-wiggle'"),
            std::string::npos);
  EXPECT_NE(refusal("1 sculpt-move 0 1\n").find("bad.txt:1: 'sculpt-move' takes 3 argument(s), got 2"), std::string::npos);
  EXPECT_NE(refusal("1 sculpt-kernel gaussian\n").find("bad.txt:1: unknown kernel 'gaussian'"), std::string::npos);
  EXPECT_NE(refusal("1 timeline-seek nan\n").find("bad.txt:1: 'nan' is not a finite number"), std::string::npos);
  EXPECT_NE(refusal("2 undo\n1 redo\n").find("bad.txt:2: time 1 s comes before the previous action's"), std::string::npos);
  EXPECT_NE(refusal("1 trigger giggle\n").find("bad.txt:1: trigger giggle: no trigger parameter 'giggle'"), std::string::npos);
  EXPECT_NE(refusal("1 sculpt-landmark mouth_corner_L\n").find("'mouth_corner_L' is not one of the sculpt panel's landmarks"),
            std::string::npos);
  EXPECT_NE(refusal("1 say\n").find("bad.txt:1: 'say' takes 1 argument(s), got 0"), std::string::npos);
  // A save over a file the editor reads (issue 37), before the window opens.
  for (const char* save : {"timeline-save", "sculpt-save", "screenshot"})
    EXPECT_NE(refusal(std::string("1 ") + save + " ./sub/../bad.txt\n")
                  .find("bad.txt:1: " + std::string(save) + " ./sub/../bad.txt: './sub/../bad.txt' is the input --script 'bad.txt'"),
              std::string::npos)
        << save;
}

// ---------------------------------------------------------------------------
// Speech

// Viewport pixels (x 320..960, y 0..560 at 1280x800, less the status line
// on top, whose frame time changes) whose colour moved by more than 30
// between two shots: a small, sharp change such as the mouth's.
size_t changedViewportPixels(const eng::Image& a, const eng::Image& b) {
  size_t changed = 0;
  for (int y = 30; y < 530; ++y)
    for (int x = 320; x < 960; ++x)
      if (editor_test::colourDistance(editor_test::pixel(a, x, y), editor_test::pixel(b, x, y)) > 30) ++changed;
  return changed;
}

// The Speak box through the script (--mute: silent, as with no sound card):
// the happy face says a line and its mouth moves, then rests; Vietnamese
// speaks; the state machine keeps the face while it speaks.
TEST(EditorScript, SayMovesTheMouthUnderTheEmotionAndRestsAfter) {
  REQUIRE_XVFB();
  const fs::path dir = testing_support::freshTempDir("editor_script_say");
  testing_support::writeFile(dir / "say.txt",
                             "0.3 trigger happy\n"
                             "1.5 screenshot rest.png\n"
                             "1.6 say Papa, how are you? Ah, hello, hello, a long and happy day!\n"
                             "1.9 screenshot s1.png\n2.2 screenshot s2.png\n2.5 screenshot s3.png\n2.8 screenshot s4.png\n"
                             "3.0 say-lang vi\n3.1 say Xin chào, đây là bản tin tối nay.\n"
                             "3.4 screenshot s5.png\n3.7 screenshot s6.png\n"
                             "9.0 screenshot after.png\n");
  // One view scale for every shot: the rest and after shots are compared
  // pixel by pixel, and a view still for a second is drawn at full resolution.
  setenv("FACIAL_RENDER_SCALE", "0.65", 1);
  const editor_test::EditorRun run = runEditor(dir, "--mute --script say.txt", 9.5f);
  unsetenv("FACIAL_RENDER_SCALE");
  ASSERT_TRUE(editor_test::ranCleanly(run));
  EXPECT_NE(run.log.find("facial-editor: speech: \"Papa, how are you? Ah, hello, hello, a long and happy day!\" (en, "),
            std::string::npos)
      << run.log;
  EXPECT_NE(run.log.find("facial-editor: speech: \"Xin chào, đây là bản tin tối nay.\" (vi, "), std::string::npos)
      << run.log;
  EXPECT_NE(run.log.find("facial-editor: note: sound off: silent player asked for"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("facial-editor: speech: done"), std::string::npos) << run.log;
  EXPECT_NE(run.log.find("state happy"), std::string::npos) << "the emotion stays while the face speaks:\n" << run.log;
  const eng::Image rest = readShot(dir / "rest.png");
  size_t widest = 0;
  for (int i = 1; i <= 6; ++i)
    widest = std::max(widest, changedViewportPixels(rest, readShot(dir / ("s" + std::to_string(i) + ".png"))));
  const size_t after = changedViewportPixels(rest, readShot(dir / "after.png"));
  std::printf("viewport pixels changed while speaking: up to %zu; after the line: %zu\n", widest, after);
  EXPECT_GT(widest, 400u) << "the mouth moves while the face speaks";
  EXPECT_LT(after, widest / 4) << "the mouth rests after the line";
}

}  // namespace
