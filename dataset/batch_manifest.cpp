#include "dataset/batch_manifest.h"

#include <algorithm>
#include <cmath>

#include <nlohmann/json.hpp>

#include "engine/scene/file_bytes.h"

namespace dataset {
namespace {

constexpr size_t kMaxManifestBytes = size_t{256} << 20;

std::string outputOf(const std::vector<std::string>& args) {
  for (size_t i = 0; i + 1 < args.size(); ++i)
    if (args[i] == "--out" || args[i] == "-o") return args[i + 1];
  for (const std::string& arg : args)
    if (arg.rfind("--out=", 0) == 0) return arg.substr(6);
  return "";
}

// The job on one line, or job.error saying why it is none.
void readJob(std::string_view line, std::string_view source, BatchJob& job) {
  const std::string where = std::string(source) + ": line " + std::to_string(job.line) + ": ";
  const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
  if (!j.is_object()) return void(job.error = where + "not a JSON object");
  for (const auto& [key, value] : j.items())
    if (key != "kind" && key != "args" && key != "output") return void(job.error = where + "unknown key '" + key + "' (kind, args, output)");
  if (!j.contains("kind") || !j["kind"].is_string()) return void(job.error = where + "no \"kind\" (render, express, say, play, dataset)");
  job.kind = j["kind"].get<std::string>();
  if (std::find(kBatchKinds.begin(), kBatchKinds.end(), job.kind) == kBatchKinds.end())
    return void(job.error = where + "unknown kind '" + job.kind + "' (render, express, say, play, dataset)");
  if (!j.contains("args") || !j["args"].is_array()) return void(job.error = where + "no \"args\" array (the command line)");
  for (const auto& arg : j["args"]) {
    if (!arg.is_string()) return void(job.error = where + "\"args\" must hold strings only");
    job.args.push_back(arg.get<std::string>());
  }
  if (j.contains("output") && !j["output"].is_string()) return void(job.error = where + "\"output\" must be a string");
  job.output = j.contains("output") ? j["output"].get<std::string>() : outputOf(job.args);
}

}  // namespace

std::vector<BatchJob> parseBatchManifest(std::string_view text, std::string_view source) {
  std::vector<BatchJob> jobs;
  size_t lineNumber = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    start = end + 1;
    ++lineNumber;
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string_view::npos || line[first] == '#') continue;
    BatchJob job{.index = jobs.size(), .line = lineNumber};
    readJob(line, source, job);
    jobs.push_back(std::move(job));
  }
  return jobs;
}

eng::Result<std::vector<BatchJob>> readBatchManifest(const std::filesystem::path& path) {
  auto bytes = eng::readFileBytes(path, kMaxManifestBytes);
  if (!bytes) return bytes.error();
  return parseBatchManifest(std::string_view(reinterpret_cast<const char*>(bytes->data()), bytes->size()), path.string());
}

std::string resultJson(const BatchResult& result) {
  nlohmann::ordered_json j{{"job", result.job}, {"kind", result.kind}, {"ok", result.ok}, {"output", result.output}};
  j["error"] = result.ok ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(result.error);
  j["seconds"] = std::round(result.seconds * 1000.0) / 1000.0;
  return j.dump();
}

}  // namespace dataset
