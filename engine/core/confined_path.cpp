#include "engine/core/confined_path.h"

#include <string>

namespace eng {

bool isInsideFolder(const std::filesystem::path& path, const std::filesystem::path& folder) {
  auto p = path.begin();
  for (auto f = folder.begin(); f != folder.end(); ++f) {
    if (f->empty()) continue;  // the trailing "" of "dir/"
    if (p == path.end() || *p != *f) return false;
    ++p;
  }
  return true;
}

std::filesystem::path resolvedPath(const std::filesystem::path& path) {
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  if (ec) return path.lexically_normal();
  const std::filesystem::path real = std::filesystem::weakly_canonical(absolute, ec);
  return ec ? absolute.lexically_normal() : real;
}

Result<std::filesystem::path> resolveInsideFolder(const std::filesystem::path& folder, std::string_view name) {
  const std::string quoted = "'" + std::string(name) + "'";
  if (name.empty()) return makeError(ErrorKind::Malformed, "empty file name");
  if (name.find('\0') != std::string_view::npos) return makeError(ErrorKind::Malformed, quoted + " contains a NUL byte");
  const std::filesystem::path relative(name);
  if (relative.is_absolute() || relative.has_root_name())
    return makeError(ErrorKind::InvalidArgument, quoted + " is an absolute path; only files in the same folder are read");
  const std::filesystem::path base = resolvedPath(folder.empty() ? std::filesystem::path(".") : folder);
  const std::filesystem::path lexical = (base / relative).lexically_normal();
  if (!isInsideFolder(lexical, base))
    return makeError(ErrorKind::InvalidArgument, quoted + " points outside the folder of the file naming it; refused");
  std::error_code ec;
  const std::filesystem::path real = std::filesystem::weakly_canonical(lexical, ec);
  if (!ec && !isInsideFolder(real, base))
    return makeError(ErrorKind::InvalidArgument, quoted + " resolves (through a link) outside the folder of the file naming it; refused");
  return lexical;
}

}  // namespace eng
