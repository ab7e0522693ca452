#include "facial/runtime/json/json_document.h"

#include <cstdio>
#include <fstream>
#include <system_error>

#include "engine/core/json_nesting.h"

namespace facial {

eng::Result<Json> readJsonFile(const std::filesystem::path& path, size_t maxBytes) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    return eng::makeError(eng::ErrorKind::NotFound, name + ": " + (std::filesystem::exists(path, ec) ? "not a regular file" : "file not found"));
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return eng::makeError(eng::ErrorKind::Io, name + ": cannot read the file size (" + ec.message() + ")");
  if (size > maxBytes)
    return eng::makeError(eng::ErrorKind::TooLarge, name + ": file is " + std::to_string(size) + " bytes, more than the " +
                          std::to_string(maxBytes) + " accepted for a JSON document");
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::Io, name + ": cannot open the file for reading");
  std::string text(static_cast<size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  if (static_cast<uintmax_t>(in.gcount()) != size) return eng::makeError(eng::ErrorKind::Io, name + ": short read");
  return parseJsonText(text, name);
}

eng::Result<Json> parseJsonText(std::string_view text, std::string_view source) {
  if (auto nesting = eng::checkJsonNesting(text, source); !nesting) return nesting.error();
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::exception& e) {
    // what() reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
    // (out_of_range.406 for numbers like 1e999 that overflow a double)
    std::string detail = e.what();
    if (const size_t at = detail.find("] "); at != std::string::npos) detail = detail.substr(at + 2);
    return eng::makeError(eng::ErrorKind::Malformed, std::string(source) + ": invalid JSON: " + detail);
  }
}

std::string childPath(std::string_view parent, std::string_view key) {
  std::string path(parent);
  path += '/';
  for (char c : key) {
    if (c == '~') path += "~0";
    else if (c == '/') path += "~1";
    else path += c;
  }
  return path;
}

std::string childPath(std::string_view parent, size_t index) { return std::string(parent) + "/" + std::to_string(index); }

eng::Result<void> checkFormatVersion(const Json& version, int supported) {
  if (version.is_number_integer() && version.get<int64_t>() == supported) return {};
  const std::string reads = "(this build reads version " + std::to_string(supported) + ")";
  if (version.is_number_integer() && version.get<int64_t>() > supported)
    return eng::makeError(eng::ErrorKind::Unsupported,
                          "unsupported version " + version.dump() + ": written by a newer release of facial " + reads);
  return eng::makeError(eng::ErrorKind::Unsupported, "unsupported version " + version.dump() + " " + reads);
}

std::string formatNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

std::string_view jsonTypeName(const Json& value) { return value.type_name(); }

}  // namespace facial
