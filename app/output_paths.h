#pragma once
// What a command writes: never a file it reads, and a frame folder written
// whole. Every command that writes checks its files here before any work:
//
//   if (auto safe = app::checkOutputs({.inputs = {{"model", o.model}},
//                                      .outputs = {{"--out", o.out}}}); !safe)
//     return fail(safe.error().message);
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "engine/core/result.h"

namespace app {

// A path given on the command line and the option (or argument) that gave it.
struct NamedPath {
  std::string_view option;  // "--out", "model"; empty: the path alone names it
  std::string_view path;    // empty: not given, skipped
};

struct CommandFiles {
  std::vector<NamedPath> inputs;        // files or folders read
  std::vector<NamedPath> outputs;       // files written
  std::vector<NamedPath> frameFolders;  // folders whose frame_NNNN.png are replaced
};

// Refuses an output that is one of the inputs (the same file after `..`,
// symbolic and hard links), an output named twice, and a frame folder that is
// an input or holds one.
eng::Result<void> checkOutputs(const CommandFiles& files);

// The frames of one run, written whole: into DIR/.partial-frames, then, once
// every frame is there, moved into DIR in place of the frame_NNNN.png of an
// earlier run (a shorter run leaves none of the longer one's behind; a failed
// run leaves the old frames as they were). Other files in DIR stay.
class FrameFolder {
 public:
  static eng::Result<FrameFolder> create(const std::filesystem::path& dir);
  FrameFolder(FrameFolder&& other) noexcept;
  FrameFolder& operator=(FrameFolder&&) = delete;
  ~FrameFolder();  // an uncommitted run's staged frames are removed

  // Where frame `index` is written until commit().
  std::filesystem::path framePath(uint32_t index) const;
  eng::Result<void> commit();

 private:
  FrameFolder(std::filesystem::path dir, std::filesystem::path staging);
  std::filesystem::path dir_;
  std::filesystem::path staging_;  // empty once committed or moved from
};

// "frame_0012.png" for 12; the names FrameFolder writes and replaces.
std::string frameFileName(uint32_t index);
bool isFrameFileName(std::string_view name);

}  // namespace app
