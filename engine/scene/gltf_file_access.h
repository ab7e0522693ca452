#pragma once
// tinygltf file-system callbacks that never expand a path (tinygltf's default
// ExpandFilePath has used wordexp on Linux, which runs `$(...)` and backticks)
// and only read regular files inside the model's own folder, up to a size
// limit, each charged to the load's budget. What was refused is remembered
// so the loader can say why.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"

namespace eng {

class GltfFileAccess {
 public:
  // baseDir: the model's folder, absolute. Every path tinygltf asks for must
  // be baseDir + "/" + uri and resolve (symlinks included) inside baseDir.
  GltfFileAccess(std::filesystem::path baseDir, size_t maxFileBytes, LoadBudget& budget);
  GltfFileAccess(const GltfFileAccess&) = delete;
  GltfFileAccess& operator=(const GltfFileAccess&) = delete;

  // The string to hand tinygltf as base_dir.
  const std::string& baseDirString() const { return baseDirString_; }
  // Callbacks bound to this object; it must outlive the tinygltf load.
  tinygltf::FsCallbacks callbacks();

  // One line per refused or unreadable uri ("uri '../x' leaves the model's folder"), in request order.
  const std::vector<std::string>& problems() const { return problems_; }
  // The first problem as an error: NotFound for a missing file, the read's
  // kind for an unreadable one (TooLarge, Io), Malformed for a refused uri.
  // Only when problems() is not empty.
  Error firstProblem() const { return makeError(firstProblemKind_, problems_.front()); }
  // The problem recorded for a uri, or empty.
  std::string problemFor(const std::string& uri) const;

 private:
  // Maps a tinygltf path back to the uri and the confined absolute path;
  // false (recording why) when the path is refused.
  bool resolve(const std::string& requested, std::filesystem::path* out, bool record);
  void record(const std::string& uri, const std::string& why, ErrorKind kind = ErrorKind::Malformed);
  std::string uriOf(const std::string& requested) const;

  static bool fileExists(const std::string& path, void* self);
  static std::string expandFilePath(const std::string& path, void* self);
  static bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* self);
  static bool writeWholeFile(std::string* err, const std::string& path, const std::vector<unsigned char>& contents,
                             void* self);

  std::filesystem::path baseDir_;
  std::string baseDirString_;
  std::string prefix_;  // baseDirString_ with one trailing separator
  size_t maxFileBytes_;
  LoadBudget& budget_;
  std::vector<std::pair<std::string, std::string>> uriProblems_;
  std::vector<std::string> problems_;
  ErrorKind firstProblemKind_ = ErrorKind::Malformed;
};

}  // namespace eng
