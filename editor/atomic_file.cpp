#include "editor/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <fstream>
#include <system_error>

namespace editor {

namespace fs = std::filesystem;

namespace {

// Flushes a file (or a folder's entries) to the disk. rename() alone is atomic
// for other processes, but after a power cut the renamed file could be there
// with its data not yet written; syncing the content before the rename and
// the folder after it closes that window.
bool syncToDisk(const fs::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return false;
  const bool synced = ::fsync(fd) == 0;
  ::close(fd);
  return synced;
}

}  // namespace

fs::path temporarySibling(const fs::path& path) {
  fs::path temp = path;
  temp.replace_filename(path.stem().string() + ".saving" + path.extension().string());
  return temp;
}

eng::Result<void> replaceFileAtomically(const fs::path& path,
                                        const std::function<eng::Result<void>(const fs::path&)>& write) {
  if (path.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "no file name given");
  if (fs::is_directory(path)) return eng::makeError(eng::ErrorKind::InvalidArgument, path.string() + ": is a folder, not a file");
  const fs::path temp = temporarySibling(path);
  std::error_code ignored;
  auto written = write(temp);
  if (!written) {
    fs::remove(temp, ignored);
    return written.error();
  }
  if (!syncToDisk(temp)) {
    fs::remove(temp, ignored);
    return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot flush " + temp.string() + " to the disk; the file was left as it was");
  }
  std::error_code error;
  fs::rename(temp, path, error);
  if (error) {
    fs::remove(temp, ignored);
    return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot replace the file (" + error.message() + ")");
  }
  // The new content is in place; a folder that cannot be synced only weakens
  // the guarantee after a power cut, so it is not an error.
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  syncToDisk(folder);
  return {};
}

eng::Result<void> writeJsonAtomically(const facial::Json& json, const fs::path& path) {
  return replaceFileAtomically(path, [&](const fs::path& temp) -> eng::Result<void> {
    std::ofstream out(temp, std::ios::binary);
    if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot write " + temp.string());
    out << json.dump(1) << '\n';
    out.close();
    if (!out) return eng::makeError(eng::ErrorKind::Io, path.string() + ": write failed (disk full?)");
    return {};
  });
}

}  // namespace editor
