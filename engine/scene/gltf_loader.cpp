#include "engine/scene/gltf_loader.h"

// The loader's entry: read the bytes (capped) or take them, tell GLB from JSON, refuse
// hostile nesting, decode the compressed views, let tinygltf parse with our
// file access, then build the Model (gltf_model_builder.h).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <new>
#include <optional>
#include <sstream>

#include <tiny_gltf.h>

#include "engine/core/json_nesting.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/glb_container.h"
#include "engine/scene/gltf_draco.h"
#include "engine/scene/gltf_extensions.h"
#include "engine/scene/gltf_file_access.h"
#include "engine/scene/gltf_json_prepass.h"
#include "engine/scene/gltf_meshopt.h"
#include "engine/scene/gltf_model_builder.h"

namespace eng {
namespace {

// tinygltf's error text as one readable line: newlines joined, the JSON
// library's exception tag replaced, embedded data: URIs shortened.
std::string oneLine(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      out += "; ";
    } else if (c == '[' && text.compare(i, 16, "[json.exception.") == 0 && text.find("] ", i) != std::string::npos) {
      out += "invalid JSON: ";
      i = text.find("] ", i) + 1;
    } else if (c == 'd' && text.compare(i, 5, "data:") == 0) {
      size_t end = i;
      while (end < text.size() && text[end] != ' ' && text[end] != '\n') ++end;
      out += end - i > 40 ? text.substr(i, 40) + "..." : text.substr(i, end - i);
      i = end - 1;
    } else if (c != '\r') {
      out += c;
    }
  }
  return out;
}

// glTF versions are "<major>.<minor>": a 2.x asset loads (minor versions stay
// compatible) unless its minVersion asks for more than 2.0; another major
// version is a different format. Both are refused by name, never misread.
std::optional<Error> assetVersionProblem(const tinygltf::Asset& asset) {
  const auto parse = [](const std::string& text, int& major, int& minor) {
    return std::sscanf(text.c_str(), "%d.%d", &major, &minor) == 2;
  };
  int major = 0, minor = 0;
  if (!parse(asset.version, major, minor))
    return makeError(ErrorKind::Malformed, "asset.version '" + asset.version + "' is not a glTF version (expected 2.0)");
  if (major != 2)
    return makeError(ErrorKind::Unsupported, "glTF version " + asset.version + " is not supported (this loader reads glTF 2.x)");
  if (!asset.minVersion.empty()) {
    if (!parse(asset.minVersion, major, minor))
      return makeError(ErrorKind::Malformed, "asset.minVersion '" + asset.minVersion + "' is not a glTF version");
    if (major != 2 || minor > 0)
      return makeError(ErrorKind::Unsupported, "the file needs glTF " + asset.minVersion +
                                                   " (asset.minVersion), newer than the 2.0 this loader reads");
  }
  return std::nullopt;
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(line);
  return lines;
}

// tinygltf's image hook: keep the encoded bytes and decode later with our own
// limits, so one broken image becomes a warning instead of a failed load.
// It also checks what tinygltf does not: that an image's bufferView fits its buffer.
struct ImageHookContext {
  const tinygltf::Model* gltf = nullptr;
  LoadBudget* budget = nullptr;
  std::optional<Error> overBudget;  // said instead of tinygltf's summary
};

bool keepEncodedImage(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                      const unsigned char* bytes, int size, void* user) {
  auto* ctx = static_cast<ImageHookContext*>(user);
  if (image->bufferView >= 0) {
    const tinygltf::Model& gltf = *ctx->gltf;
    const auto& bv = gltf.bufferViews[static_cast<size_t>(image->bufferView)];
    const size_t bufferSize = gltf.buffers[static_cast<size_t>(bv.buffer)].data.size();
    if (bv.byteOffset > bufferSize || bv.byteLength > bufferSize - bv.byteOffset) {
      if (err)
        *err += "image " + std::to_string(index) + ": bufferView " + std::to_string(image->bufferView) + " (bytes " +
                std::to_string(bv.byteOffset) + ".." + std::to_string(bv.byteOffset + bv.byteLength) +
                ") is out of range of buffer " + std::to_string(bv.buffer) + " (" + std::to_string(bufferSize) +
                " bytes)\n";
      return false;
    }
  }
  if (size < 0) return false;
  // Each image holds its own copy, even of a bufferView other images name too.
  if (auto ok = ctx->budget->charge(static_cast<size_t>(size), "the encoded bytes of image " + std::to_string(index));
      !ok) {
    if (!ctx->overBudget) ctx->overBudget = ok.error();
    if (err) *err += ok.error().message + "\n";
    return false;
  }
  image->image.assign(bytes, bytes + size);
  image->width = image->height = image->component = -1;  // still encoded
  return true;
}


enum class Container { Json, Glb };

// Meshopt views and Draco primitives become plain buffer data before the
// model is built, so everything after reads ordinary accessors.
Result<void> decodeCompressedGeometry(tinygltf::Model& gltf, const std::vector<MeshoptPlaceholder>& placeholders,
                                      LoadBudget& budget, ExtensionOutcomes& outcomes) {
  auto meshopt = decodeMeshoptViews(gltf, placeholders, budget);
  if (!meshopt) return meshopt.error();
  const std::string views = "decoded: " + std::to_string(meshopt->views) + " buffer view(s) (meshoptimizer)";
  if (meshopt->usedExt) outcomes[kExtMeshopt] = views;
  if (meshopt->usedKhr) outcomes[kKhrMeshopt] = views;
  auto draco = decodeDracoPrimitives(gltf, budget);
  if (!draco) return draco.error();
  if (*draco > 0) outcomes[kKhrDraco] = "decoded: " + std::to_string(*draco) + " primitive(s) (Draco)";
  return {};
}

Result<Container> detectContainer(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  if (hasGlbMagic(bytes)) return Container::Glb;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".glb") {
    auto glb = parseGlb(bytes);  // names the wrong magic or the truncation
    return glb.error();
  }
  size_t i = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) i = 3;  // UTF-8 BOM
  while (i < bytes.size() && std::isspace(bytes[i])) ++i;
  if (i < bytes.size() && bytes[i] == '{') return Container::Json;
  if (bytes.empty()) return makeError(ErrorKind::Malformed, "file is empty");
  return makeError(ErrorKind::Malformed, "neither glTF JSON nor a GLB (no '{' and no 'glTF' magic at the start)");
}

}  // namespace

Result<Model> loadModel(const std::filesystem::path& path) { return loadModel(path, GltfLoadLimits{}); }

Result<Model> loadModel(const std::filesystem::path& path, const GltfLoadLimits& limits) {
  try {
    auto bytes = readFileBytes(path, limits.maxFileBytes);
    if (!bytes) return bytes.error();
    return loadModelFromBytes(*bytes, path, limits);
  } catch (const std::bad_alloc&) {
    return makeError(ErrorKind::TooLarge, path.string() + ": out of memory while loading");
  }
}

Result<Model> loadModelFromBytes(std::span<const uint8_t> fileBytes, const std::filesystem::path& path,
                                 const GltfLoadLimits& limits, size_t* charged) {
  const std::string file = path.string();
  if (fileBytes.size() > limits.maxFileBytes)
    return makeError(ErrorKind::TooLarge, file + ": file of " + std::to_string(fileBytes.size()) + " bytes exceeds the limit of " +
                     std::to_string(limits.maxFileBytes) + " bytes");
  try {
    std::span<const uint8_t> bytes = fileBytes;
    auto container = detectContainer(bytes, path);
    if (!container) return container.error().prefixed(file + ": ");
    // The pre-pass (nlohmann) and tinygltf parse recursively: a hostile nesting depth is refused before either.
    std::span<const uint8_t> jsonText = bytes;
    if (*container == Container::Glb) {
      auto glb = parseGlb(bytes);
      if (!glb) return glb.error().prefixed(file + ": ");
      jsonText = glb->json;
    }
    const std::string_view json(reinterpret_cast<const char*>(jsonText.data()), jsonText.size());
    if (auto nesting = checkJsonNesting(json, file); !nesting) return nesting.error();
    LoadBudget budget(limits.maxDecodedBytes);
    struct Report {  // what was charged, however the load ends
      const LoadBudget& budget;
      size_t* out;
      ~Report() {
        if (out) *out = budget.charged();
      }
    } report{budget, charged};
    if (auto ok = chargeGltfObjects(json, budget); !ok) return ok.error().prefixed(file + ": ");
    // Compressed files hold what tinygltf refuses (buffers without data, indices without a bufferView).
    std::vector<uint8_t> stubbed;
    auto placeholders = prepareCompressedGltf(bytes, *container == Container::Glb, stubbed);
    if (!placeholders) return placeholders.error().prefixed(file + ": ");
    if (!stubbed.empty()) bytes = stubbed;

    std::error_code ec;
    const std::filesystem::path baseDir = std::filesystem::absolute(path, ec).parent_path();
    GltfFileAccess files(baseDir, limits.maxFileBytes, budget);
    tinygltf::Model gltf;
    ImageHookContext imageHook{&gltf, &budget, std::nullopt};
    tinygltf::TinyGLTF parser;
    parser.SetFsCallbacks(files.callbacks());
    parser.SetImageLoader(&keepEncodedImage, &imageHook);

    std::string err, warn;
    bool parsed = false;
    if (*container == Container::Glb) {
      auto glb = parseGlb(bytes);
      if (!glb) return glb.error().prefixed(file + ": ");
      parsed = parser.LoadBinaryFromMemory(&gltf, &err, &warn, bytes.data(), static_cast<unsigned>(bytes.size()),
                                           files.baseDirString());
    } else {
      parsed = parser.LoadASCIIFromString(&gltf, &err, &warn, reinterpret_cast<const char*>(bytes.data()),
                                          static_cast<unsigned>(bytes.size()), files.baseDirString());
    }
    if (!parsed) {
      if (imageHook.overBudget) return imageHook.overBudget->prefixed(file + ": ");
      // What our file access refused or could not find says more than tinygltf's summary.
      if (!files.problems().empty()) return files.firstProblem().prefixed(file + ": ");
      return makeError(ErrorKind::Malformed, file + ": " + (err.empty() ? std::string("glTF parse failed") : oneLine(err)));
    }
    if (auto problem = assetVersionProblem(gltf.asset)) return problem->prefixed(file + ": ");
    ExtensionOutcomes outcomes;
    if (auto ok = decodeCompressedGeometry(gltf, *placeholders, budget, outcomes); !ok)
      return ok.error().prefixed(file + ": ");
    GltfModelBuilder builder(file, gltf, limits, budget, files, outcomes);
    auto model = builder.build();
    if (!model) return model;
    model->extensions = describeExtensions(gltf, outcomes);
    for (std::string& line : splitLines(warn))
      if (line.find("Failed to load external") == std::string::npos && line.find("File not found") == std::string::npos)
        model->warnings.push_back("tinygltf: " + line);
    return model;
  } catch (const std::bad_alloc&) {
    return makeError(ErrorKind::TooLarge, file + ": out of memory while loading");
  } catch (const std::exception& e) {
    return makeError(ErrorKind::Malformed, file + ": " + e.what());
  }
}

}  // namespace eng
