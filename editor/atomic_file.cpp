#include "editor/atomic_file.h"

#include <system_error>

namespace editor {

namespace fs = std::filesystem;

fs::path temporarySibling(const fs::path& path) {
  fs::path temp = path;
  temp.replace_filename(path.stem().string() + ".saving" + path.extension().string());
  return temp;
}

eng::Result<void> replaceFileAtomically(const fs::path& path,
                                        const std::function<eng::Result<void>(const fs::path&)>& write) {
  if (path.empty()) return eng::makeError("no file name given");
  if (fs::is_directory(path)) return eng::makeError(path.string() + ": is a folder, not a file");
  const fs::path temp = temporarySibling(path);
  std::error_code ignored;
  auto written = write(temp);
  if (!written) {
    fs::remove(temp, ignored);
    return written.error();
  }
  std::error_code error;
  fs::rename(temp, path, error);
  if (error) {
    fs::remove(temp, ignored);
    return eng::makeError(path.string() + ": cannot replace the file (" + error.message() + ")");
  }
  return {};
}

}  // namespace editor
