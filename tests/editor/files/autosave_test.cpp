// Autosave and recovery: edits the editor never saved come back in the next
// editor that opens the document, with a message; saved work is never
// replaced by an older autosave.
#include <chrono>
#include <fstream>
#include <thread>

#include <gtest/gtest.h>

#include "editor/autosave.h"
#include "editor/timeline_document.h"
#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;
using editor::TimelineAutosave;
using editor::TimelineDocument;
using Clock = TimelineAutosave::Clock;

TimelineDocument smallClip() {
  TimelineDocument doc("talk", 2.0f);
  auto track = doc.addTrack("AU26_JawDrop");
  EXPECT_TRUE(track.ok());
  EXPECT_TRUE(doc.setKey(*track, 0.0f, 0.0f).ok());
  EXPECT_TRUE(doc.setKey(*track, 1.0f, 0.6f).ok());
  return doc;
}

// Makes `later` visibly newer than `earlier` to the file system's clock.
void touchAfter(const fs::path& later, const fs::path& earlier) {
  fs::last_write_time(later, fs::last_write_time(earlier) + std::chrono::seconds(2));
}

TEST(Autosave, PathIsAHiddenSiblingOfTheDocument) {
  EXPECT_EQ(editor::autosavePathFor("/work/clips/talk.json"), fs::path("/work/clips/.talk.json.autosave"));
  EXPECT_EQ(editor::autosavePathFor("talk.json"), fs::path(".talk.json.autosave"));
}

TEST(Autosave, WritesUnsavedEditsOncePerIntervalAndNotWhenClean) {
  const fs::path dir = testing_support::freshTempDir("autosave_interval");
  TimelineDocument doc = smallClip();
  ASSERT_TRUE(doc.save(dir / "talk.json").ok());
  TimelineAutosave autosave(editor::autosavePathFor(dir / "talk.json"), std::chrono::milliseconds(1000));
  const auto t0 = Clock::now();

  auto wrote = autosave.update(doc, t0);  // clean: nothing to autosave
  ASSERT_TRUE(wrote.ok());
  EXPECT_FALSE(*wrote);
  EXPECT_FALSE(fs::exists(autosave.file()));

  ASSERT_TRUE(doc.setKey(0, 1.5f, 0.2f).ok());
  wrote = autosave.update(doc, t0);  // the first edit is written at once
  ASSERT_TRUE(wrote.ok()) << wrote.error().message;
  EXPECT_TRUE(*wrote);
  EXPECT_TRUE(fs::exists(autosave.file()));

  ASSERT_TRUE(doc.setKey(0, 1.8f, 0.1f).ok());
  EXPECT_FALSE(*autosave.update(doc, t0 + std::chrono::milliseconds(500)));  // within the interval
  EXPECT_TRUE(*autosave.update(doc, t0 + std::chrono::milliseconds(1500)));
  EXPECT_FALSE(*autosave.update(doc, t0 + std::chrono::milliseconds(3000)));  // nothing new

  // A save makes the autosave pointless: the editor discards it.
  ASSERT_TRUE(doc.save(dir / "talk.json").ok());
  autosave.discard();
  EXPECT_FALSE(fs::exists(autosave.file()));
}

TEST(Autosave, TheNextEditorRecoversTheLastEditsWithAMessage) {
  const fs::path dir = testing_support::freshTempDir("autosave_recover");
  const fs::path path = dir / "talk.json";
  {
    // The first editor: opens, edits, autosaves, then dies without saving.
    TimelineDocument doc = smallClip();
    ASSERT_TRUE(doc.save(path).ok());
    ASSERT_TRUE(doc.setKey(0, 1.5f, 0.9f).ok());
    TimelineAutosave autosave(editor::autosavePathFor(path));
    ASSERT_TRUE(autosave.flush(doc).ok());
    touchAfter(autosave.file(), path);
  }
  auto recovered = editor::recoverAutosave(path);
  ASSERT_TRUE(recovered.ok()) << recovered.error().message;
  ASSERT_TRUE(recovered->has_value());
  const TimelineDocument& doc = (*recovered)->document;
  ASSERT_EQ(doc.tracks().size(), 1u);
  EXPECT_EQ(doc.tracks()[0].keys.size(), 3u);
  EXPECT_FLOAT_EQ(doc.sample(0, 1.5f), 0.9f);
  EXPECT_TRUE(doc.dirty()) << "recovered edits are not saved yet";
  const std::string& message = (*recovered)->message;
  EXPECT_NE(message.find("recovered unsaved edits of " + path.string()), std::string::npos) << message;
  EXPECT_NE(message.find(".talk.json.autosave"), std::string::npos) << message;
  // The document itself is untouched until the user saves.
  auto onDisk = TimelineDocument::load(path);
  ASSERT_TRUE(onDisk.ok());
  EXPECT_EQ(onDisk->tracks()[0].keys.size(), 2u);
}

TEST(Autosave, RecoversANeverSavedDocument) {
  const fs::path dir = testing_support::freshTempDir("autosave_unsaved");
  const fs::path path = dir / "new.json";
  TimelineDocument doc = smallClip();
  TimelineAutosave autosave(editor::autosavePathFor(path));
  ASSERT_TRUE(autosave.flush(doc).ok());
  auto recovered = editor::recoverAutosave(path);
  ASSERT_TRUE(recovered.ok()) << recovered.error().message;
  ASSERT_TRUE(recovered->has_value());
  EXPECT_EQ((*recovered)->document.tracks().size(), 1u);
}

TEST(Autosave, AnAutosaveOlderThanTheDocumentIsStaleAndRemoved) {
  const fs::path dir = testing_support::freshTempDir("autosave_stale");
  const fs::path path = dir / "talk.json";
  TimelineDocument doc = smallClip();
  ASSERT_TRUE(doc.setKey(0, 1.5f, 0.9f).ok());
  TimelineAutosave autosave(editor::autosavePathFor(path));
  ASSERT_TRUE(autosave.flush(doc).ok());
  ASSERT_TRUE(doc.save(path).ok());
  touchAfter(path, autosave.file());
  auto recovered = editor::recoverAutosave(path);
  ASSERT_TRUE(recovered.ok());
  EXPECT_FALSE(recovered->has_value());
  EXPECT_FALSE(fs::exists(autosave.file()));
}

// Validity: a damaged autosave is reported, naming it, and left for the user.
TEST(AutosaveValidity, ABrokenAutosaveIsAnErrorNamingIt) {
  const fs::path dir = testing_support::freshTempDir("autosave_broken");
  const fs::path path = dir / "talk.json";
  testing_support::writeFile(editor::autosavePathFor(path), "{\"version\": 1, \"tracks\": [");
  auto recovered = editor::recoverAutosave(path);
  ASSERT_FALSE(recovered.ok());
  EXPECT_NE(recovered.error().message.find(".talk.json.autosave"), std::string::npos) << recovered.error().message;
  EXPECT_TRUE(fs::exists(editor::autosavePathFor(path)));
}

}  // namespace
