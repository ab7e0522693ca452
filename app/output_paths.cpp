#include "app/output_paths.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "engine/core/confined_path.h"

namespace app {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kStagingFolder = ".partial-frames";

std::string described(const NamedPath& p) {
  const std::string quoted = "'" + std::string(p.path) + "'";
  return p.option.empty() ? quoted : std::string(p.option) + " " + quoted;
}

// The same file: hard links and links between existing files, or the same path
// once `..` and links are resolved (an output not written yet).
bool sameFile(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  return eng::resolvedPath(a) == eng::resolvedPath(b);
}

// A file FrameFolder would replace or clear: a frame directly in `dir`, or anything in its staging folder.
bool replacedByFrames(const fs::path& file, const fs::path& dir) {
  const fs::path path = eng::resolvedPath(file);
  if (eng::isInsideFolder(path, dir / kStagingFolder)) return true;
  return path.parent_path() == dir && isFrameFileName(path.filename().string());
}

eng::Error refused(const NamedPath& output, const std::string& why) {
  return eng::makeError(eng::ErrorKind::InvalidArgument, described(output) + " " + why + "; nothing was written");
}

}  // namespace

eng::Result<void> checkOutputs(const CommandFiles& files) {
  for (size_t i = 0; i < files.outputs.size(); ++i) {
    const NamedPath& out = files.outputs[i];
    if (out.path.empty()) continue;
    for (const NamedPath& in : files.inputs)
      if (!in.path.empty() && sameFile(out.path, in.path))
        return refused(out, "is the input " + described(in) + ": writing it would replace what is read");
    for (size_t j = 0; j < i; ++j)
      if (!files.outputs[j].path.empty() && sameFile(out.path, files.outputs[j].path))
        return refused(out, "is also " + described(files.outputs[j]) + ": one would overwrite the other");
  }
  for (const NamedPath& folder : files.frameFolders) {
    if (folder.path.empty()) continue;
    const fs::path dir = eng::resolvedPath(folder.path);
    for (const NamedPath& in : files.inputs)
      if (!in.path.empty() && replacedByFrames(in.path, dir))
        return refused(folder, "holds the input " + described(in) + " where frames are written");
  }
  return {};
}

std::string frameFileName(uint32_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04u.png", index);
  return name;
}

bool isFrameFileName(std::string_view name) {
  constexpr std::string_view prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 4 + suffix.size() || !name.starts_with(prefix) || !name.ends_with(suffix))
    return false;
  const std::string_view digits = name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  return std::all_of(digits.begin(), digits.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
}

FrameFolder::FrameFolder(fs::path dir, fs::path staging) : dir_(std::move(dir)), staging_(std::move(staging)) {}

FrameFolder::FrameFolder(FrameFolder&& other) noexcept
    : dir_(std::move(other.dir_)), staging_(std::exchange(other.staging_, {})) {}

FrameFolder::~FrameFolder() {
  if (staging_.empty()) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
}

eng::Result<FrameFolder> FrameFolder::create(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return eng::makeError(eng::ErrorKind::Io, dir.string() + ": cannot create folder: " + ec.message());
  const fs::path staging = dir / kStagingFolder;
  fs::remove_all(staging, ec);  // what a killed run left
  if (!ec) fs::create_directory(staging, ec);
  if (ec) return eng::makeError(eng::ErrorKind::Io, staging.string() + ": cannot create folder: " + ec.message());
  return FrameFolder(dir, staging);
}

fs::path FrameFolder::framePath(uint32_t index) const { return staging_ / frameFileName(index); }

eng::Result<void> FrameFolder::commit() {
  // Each new frame replaces its namesake at once; then the old run's extra frames go.
  std::set<std::string> written;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(staging_, ec)) written.insert(entry.path().filename().string());
  if (ec) return eng::makeError(eng::ErrorKind::Io, staging_.string() + ": cannot list the frames: " + ec.message());
  for (const std::string& name : written) {
    fs::rename(staging_ / name, dir_ / name, ec);
    if (ec) return eng::makeError(eng::ErrorKind::Io, (dir_ / name).string() + ": cannot move the frame in: " + ec.message());
  }
  std::vector<fs::path> stale;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    if (isFrameFileName(name) && !written.contains(name)) stale.push_back(entry.path());
  }
  if (ec) return eng::makeError(eng::ErrorKind::Io, dir_.string() + ": cannot list the folder: " + ec.message());
  for (const fs::path& path : stale) {
    fs::remove(path, ec);
    if (ec) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot remove an earlier run's frame: " + ec.message());
  }
  fs::remove_all(staging_, ec);
  staging_.clear();
  return {};
}

}  // namespace app
