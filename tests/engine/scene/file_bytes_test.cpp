#include "engine/scene/file_bytes.h"

#include <gtest/gtest.h>

#include <string>

#include "tests/common/test_support.h"

namespace {

namespace fs = std::filesystem;

// Nothing but the finished file is left in the folder.
size_t filesIn(const fs::path& dir) {
  size_t count = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) count += entry.is_regular_file() ? 1 : 0;
  return count;
}

TEST(WriteFileWhole, AFinishedWriteIsMovedIntoPlaceUnderItsOwnExtension) {
  const fs::path dir = testing_support::freshTempDir("file_whole_ok");
  const fs::path path = dir / "face.glb";
  fs::path seen;
  auto written = eng::writeFileWhole(path, [&](const fs::path& partial) {
    seen = partial;
    return eng::writeFileBytes(partial, "glTF", 4);
  });
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_EQ(seen.extension(), ".glb") << "writers that choose a format by extension still see it";
  EXPECT_NE(seen.filename().string().find(".partial"), std::string::npos) << seen;
  EXPECT_EQ(fs::file_size(path), 4u);
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(WriteFileWhole, AFailedWriteLeavesTheOldFileAndNoPartialFile) {
  const fs::path dir = testing_support::freshTempDir("file_whole_failed");
  const fs::path path = dir / "cues.json";
  ASSERT_TRUE(eng::writeFileBytes(path, "old", 3));
  auto written = eng::writeFileWhole(path, [&](const fs::path& partial) -> eng::Result<void> {
    EXPECT_TRUE(eng::writeFileBytes(partial, "half", 4));
    return eng::makeError(eng::ErrorKind::Io, "disk full");
  });
  ASSERT_FALSE(written);
  EXPECT_EQ(written.error().message, "disk full");
  EXPECT_EQ(fs::file_size(path), 3u);
  EXPECT_EQ(filesIn(dir), 1u);
}

TEST(WriteFileWhole, APlaceThatCannotTakeTheFileIsNamedAndThePartialFileRemoved) {
  const fs::path dir = testing_support::freshTempDir("file_whole_blocked");
  const fs::path path = dir / "taken";
  fs::create_directories(path / "inside");  // a non-empty folder where the file should go
  auto written = eng::writeFileWhole(path, [&](const fs::path& partial) { return eng::writeFileBytes(partial, "x", 1); });
  ASSERT_FALSE(written);
  EXPECT_NE(written.error().message.find(path.string()), std::string::npos) << written.error().message;
  EXPECT_EQ(filesIn(dir), 0u);
}

}  // namespace
