#include "engine/scene/gltf_file_access.h"

#include <algorithm>

#include "engine/scene/file_bytes.h"

namespace eng {
namespace {

// True when `p` (normalised, absolute) is `dir` or below it.
bool isInside(const std::filesystem::path& p, const std::filesystem::path& dir) {
  auto pi = p.begin();
  for (auto di = dir.begin(); di != dir.end(); ++di, ++pi) {
    if (di->empty()) continue;  // trailing separator of dir
    if (pi == p.end() || *pi != *di) return false;
  }
  return true;
}

}  // namespace

GltfFileAccess::GltfFileAccess(std::filesystem::path baseDir, size_t maxFileBytes, LoadBudget& budget)
    : maxFileBytes_(maxFileBytes), budget_(budget) {
  std::error_code ec;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(std::filesystem::absolute(baseDir), ec);
  baseDir_ = ec ? std::filesystem::absolute(baseDir).lexically_normal() : canonical;
  baseDirString_ = baseDir_.string();
  prefix_ = (!baseDirString_.empty() && baseDirString_.back() == '/') ? baseDirString_ : baseDirString_ + "/";
}

std::string GltfFileAccess::uriOf(const std::string& requested) const {
  return requested.size() > prefix_.size() ? requested.substr(prefix_.size()) : std::string{};
}

tinygltf::FsCallbacks GltfFileAccess::callbacks() {
  tinygltf::FsCallbacks cb;
  cb.FileExists = &GltfFileAccess::fileExists;
  cb.ExpandFilePath = &GltfFileAccess::expandFilePath;
  cb.ReadWholeFile = &GltfFileAccess::readWholeFile;
  cb.WriteWholeFile = &GltfFileAccess::writeWholeFile;
  cb.user_data = this;
  return cb;
}

std::string GltfFileAccess::problemFor(const std::string& uri) const {
  for (const auto& [u, why] : uriProblems_)
    if (u == uri) return why;
  return {};
}

void GltfFileAccess::record(const std::string& uri, const std::string& why, ErrorKind kind) {
  if (!problemFor(uri).empty()) return;
  if (problems_.empty()) firstProblemKind_ = kind;
  uriProblems_.emplace_back(uri, why);
  problems_.push_back(why);
}

bool GltfFileAccess::resolve(const std::string& requested, std::filesystem::path* out, bool recordProblems) {
  // tinygltf joins base_dir and the (url-decoded) uri with '/', then retries
  // with "." (the process's working directory): only the first form is ours.
  if (requested.compare(0, prefix_.size(), prefix_) != 0) return false;
  const std::string uri = uriOf(requested);
  if (uri.empty()) return false;
  if (uri.find('\0') != std::string::npos) {
    if (recordProblems) record(uri, "uri '" + uri + "' contains a NUL byte; refused");
    return false;
  }
  const std::filesystem::path uriPath(uri);
  if (uriPath.is_absolute()) {
    if (recordProblems) record(uri, "uri '" + uri + "' is an absolute path; only files beside the model are read");
    return false;
  }
  const std::filesystem::path lexical = (baseDir_ / uriPath).lexically_normal();
  if (!isInside(lexical, baseDir_)) {
    if (recordProblems) record(uri, "uri '" + uri + "' points outside the model's folder; refused");
    return false;
  }
  // Symlinks inside the folder may still point out of it.
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::weakly_canonical(lexical, ec);
  if (!ec && !isInside(real, baseDir_)) {
    if (recordProblems) record(uri, "uri '" + uri + "' resolves (through a link) outside the model's folder; refused");
    return false;
  }
  *out = lexical;
  return true;
}

bool GltfFileAccess::fileExists(const std::string& path, void* self) {
  auto* access = static_cast<GltfFileAccess*>(self);
  std::filesystem::path resolved;
  if (!access->resolve(path, &resolved, true)) return false;
  std::error_code ec;
  if (std::filesystem::is_regular_file(resolved, ec)) return true;
  const std::string uri = access->uriOf(path);
  access->record(uri, "file '" + uri + "' (uri of a buffer or image) not found beside the model", ErrorKind::NotFound);
  return false;
}

std::string GltfFileAccess::expandFilePath(const std::string& path, void*) {
  // Deliberately the identity: a uri is a file name, never a shell word.
  return path;
}

bool GltfFileAccess::readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                                   void* self) {
  auto* access = static_cast<GltfFileAccess*>(self);
  std::filesystem::path resolved;
  if (!access->resolve(path, &resolved, true)) {
    if (err) *err += "refused to read '" + path + "'";
    return false;
  }
  auto bytes = readFileBytes(resolved, access->maxFileBytes_);
  if (!bytes) {
    access->record(access->uriOf(path), bytes.error().message, bytes.error().kind);
    if (err) *err += bytes.error().message;
    return false;
  }
  // Every image and buffer that names the file holds its own copy.
  if (auto ok = access->budget_.charge(bytes->size(), "file '" + access->uriOf(path) + "'"); !ok) {
    access->record(access->uriOf(path), ok.error().message, ErrorKind::TooLarge);
    if (err) *err += ok.error().message;
    return false;
  }
  *out = std::move(*bytes);
  return true;
}

bool GltfFileAccess::writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing files is disabled while loading";
  return false;
}

}  // namespace eng
