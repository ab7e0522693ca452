#include "engine/scene/file_bytes.h"

#include <fstream>
#include <string>

#include <unistd.h>

namespace eng {

Result<std::vector<uint8_t>> readFileBytes(const std::filesystem::path& path, size_t maxBytes) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status)) return makeError(ErrorKind::NotFound, path.string() + ": file not found");
  if (!std::filesystem::is_regular_file(status)) return makeError(ErrorKind::Io, path.string() + ": not a regular file");
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return makeError(ErrorKind::Io, path.string() + ": cannot get file size (" + ec.message() + ")");
  if (size > maxBytes)
    return makeError(ErrorKind::TooLarge, path.string() + ": file of " + std::to_string(size) + " bytes exceeds the limit of " +
                     std::to_string(maxBytes) + " bytes");
  std::ifstream in(path, std::ios::binary);
  if (!in) return makeError(ErrorKind::Io, path.string() + ": cannot open for reading");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  if (size > 0) in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (!in) return makeError(ErrorKind::Io, path.string() + ": read failed");
  return bytes;
}

Result<std::string> readFileText(const std::filesystem::path& path, size_t maxBytes) {
  auto bytes = readFileBytes(path, maxBytes);
  if (!bytes) return bytes.error();
  return std::string(bytes->begin(), bytes->end());
}

Result<void> writeFileBytes(const std::filesystem::path& path, const void* data, size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return makeError(ErrorKind::Io, path.string() + ": cannot open for writing");
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  out.close();
  if (!out) return makeError(ErrorKind::Io, path.string() + ": write failed");
  return {};
}

std::filesystem::path partialPathFor(const std::filesystem::path& path) {
  std::filesystem::path partial = path;
  partial.replace_filename(path.stem().string() + "." + std::to_string(getpid()) + ".partial" + path.extension().string());
  return partial;
}

Result<void> commitPartialFile(const std::filesystem::path& partial, const std::filesystem::path& path) {
  std::error_code ec;
  std::filesystem::rename(partial, path, ec);
  if (!ec) return {};
  std::error_code ignored;
  std::filesystem::remove(partial, ignored);
  return makeError(ErrorKind::Io, path.string() + ": cannot move the finished file into place (" + ec.message() + ")");
}

Result<void> writeFileWhole(const std::filesystem::path& path,
                            const std::function<Result<void>(const std::filesystem::path& partial)>& write) {
  const std::filesystem::path partial = partialPathFor(path);
  if (auto written = write(partial); !written) {
    std::error_code ignored;
    std::filesystem::remove(partial, ignored);
    return written;
  }
  return commitPartialFile(partial, path);
}

}  // namespace eng
