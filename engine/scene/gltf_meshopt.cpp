#include "engine/scene/gltf_meshopt.h"

#include <cmath>
#include <cstring>
#include <string_view>

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>


namespace eng {
namespace {

// Three zero bytes: the smallest data: URI tinygltf accepts (it refuses empty ones).
constexpr const char* kStandInUri = "data:application/octet-stream;base64,AAAA";
constexpr size_t kStandInBytes = 3;

const nlohmann::json* meshoptExtensionOf(const nlohmann::json& object) {
  if (!object.is_object()) return nullptr;
  auto ext = object.find("extensions");
  if (ext == object.end() || !ext->is_object()) return nullptr;
  for (const char* name : {kKhrMeshopt, kExtMeshopt})
    if (auto it = ext->find(name); it != ext->end() && it->is_object()) return &*it;
  return nullptr;
}

// A glTF integer property as size_t; false when absent, negative, fractional or absurd.
bool sizeProperty(const tinygltf::Value& object, const char* name, size_t& out) {
  if (!object.Has(name)) return false;
  const tinygltf::Value& v = object.Get(name);
  if (!v.IsNumber()) return false;
  const double d = v.GetNumberAsDouble();
  if (!(d >= 0.0) || d != std::floor(d) || d > 9.0e15) return false;
  out = static_cast<size_t>(d);
  return true;
}

std::string stringProperty(const tinygltf::Value& object, const char* name, const std::string& fallback) {
  if (!object.Has(name) || !object.Get(name).IsString()) return fallback;
  return object.Get(name).Get<std::string>();
}

std::string meshoptVersion() {  // MESHOPTIMIZER_VERSION 180 = 0.18
  return std::to_string(MESHOPTIMIZER_VERSION / 1000) + "." + std::to_string(MESHOPTIMIZER_VERSION % 1000 / 10);
}

struct CompressedView {
  int source = -1;  // buffer holding the encoded bytes
  size_t byteOffset = 0, byteLength = 0, byteStride = 0, count = 0;
  std::string mode, filter;
};

Result<CompressedView> parseCompressedView(const tinygltf::Value& ext, const std::string& where) {
  CompressedView cv;
  size_t buffer = 0;
  if (!sizeProperty(ext, "buffer", buffer) || buffer > static_cast<size_t>(INT32_MAX))
    return makeError(ErrorKind::Malformed, where + " has no valid 'buffer'");
  cv.source = static_cast<int>(buffer);
  if (ext.Has("byteOffset") && !sizeProperty(ext, "byteOffset", cv.byteOffset))
    return makeError(ErrorKind::Malformed, where + " has an invalid 'byteOffset'");
  if (!sizeProperty(ext, "byteLength", cv.byteLength)) return makeError(ErrorKind::Malformed, where + " has no valid 'byteLength'");
  if (!sizeProperty(ext, "byteStride", cv.byteStride)) return makeError(ErrorKind::Malformed, where + " has no valid 'byteStride'");
  if (!sizeProperty(ext, "count", cv.count)) return makeError(ErrorKind::Malformed, where + " has no valid 'count'");
  cv.mode = stringProperty(ext, "mode", "");
  cv.filter = stringProperty(ext, "filter", "NONE");
  return cv;
}

// The constraints the specification lists for the extension object; the
// decoders assert on several of them, so they are checked before any call.
Result<void> checkLayout(const CompressedView& cv, const std::string& where) {
  if (cv.mode == "ATTRIBUTES") {
    if (cv.byteStride < 4 || cv.byteStride > 256 || cv.byteStride % 4 != 0)
      return makeError(ErrorKind::Malformed, where + ": ATTRIBUTES byteStride " + std::to_string(cv.byteStride) +
                       " must be a multiple of 4 in 4..256");
    if (cv.filter == "OCTAHEDRAL" && cv.byteStride != 4 && cv.byteStride != 8)
      return makeError(ErrorKind::Malformed, where + ": OCTAHEDRAL filter needs byteStride 4 or 8, has " + std::to_string(cv.byteStride));
    if (cv.filter == "QUATERNION" && cv.byteStride != 8)
      return makeError(ErrorKind::Malformed, where + ": QUATERNION filter needs byteStride 8, has " + std::to_string(cv.byteStride));
    if (cv.filter == "COLOR")
      return makeError(ErrorKind::Unsupported, where + ": filter COLOR (KHR_meshopt_compression) needs a newer meshoptimizer than this build's " +
                       meshoptVersion());
    if (cv.filter != "NONE" && cv.filter != "OCTAHEDRAL" && cv.filter != "QUATERNION" && cv.filter != "EXPONENTIAL")
      return makeError(ErrorKind::Malformed, where + ": unknown filter '" + cv.filter + "'");
  } else if (cv.mode == "TRIANGLES" || cv.mode == "INDICES") {
    if (cv.byteStride != 2 && cv.byteStride != 4)
      return makeError(ErrorKind::Malformed, where + ": " + cv.mode + " byteStride must be 2 or 4, has " + std::to_string(cv.byteStride));
    if (cv.mode == "TRIANGLES" && cv.count % 3 != 0)
      return makeError(ErrorKind::Malformed, where + ": TRIANGLES count " + std::to_string(cv.count) + " is not a multiple of 3");
    if (cv.filter != "NONE") return makeError(ErrorKind::Malformed, where + ": " + cv.mode + " takes no filter, has '" + cv.filter + "'");
  } else {
    return makeError(ErrorKind::Malformed, where + ": unknown mode '" + cv.mode + "' (expected ATTRIBUTES, TRIANGLES or INDICES)");
  }
  return {};
}

Result<void> decodeInto(uint8_t* dst, const CompressedView& cv, const uint8_t* src, const std::string& where) {
  int rc = 0;
  if (cv.mode == "ATTRIBUTES") {
    // 0xa0 | version: meshoptimizer 0.18 decodes version 0 only.
    if (cv.byteLength > 0 && (src[0] & 0xf0) == 0xa0 && (src[0] & 0x0f) > 0)
      return makeError(ErrorKind::Unsupported, where + ": attribute stream version " + std::to_string(src[0] & 0x0f) +
                       " (KHR_meshopt_compression) needs a newer meshoptimizer than this build's " + meshoptVersion() +
                       ", which decodes version 0");
    rc = meshopt_decodeVertexBuffer(dst, cv.count, cv.byteStride, src, cv.byteLength);
  } else if (cv.mode == "TRIANGLES") {
    rc = meshopt_decodeIndexBuffer(dst, cv.count, cv.byteStride, src, cv.byteLength);
  } else {
    rc = meshopt_decodeIndexSequence(dst, cv.count, cv.byteStride, src, cv.byteLength);
  }
  if (rc != 0)
    return makeError(ErrorKind::Malformed, where + ": the " + cv.mode + " stream (" + std::to_string(cv.byteLength) +
                     " bytes) is corrupt or truncated (meshopt error " + std::to_string(rc) + ")");
  if (cv.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(dst, cv.count, cv.byteStride);
  else if (cv.filter == "QUATERNION") meshopt_decodeFilterQuat(dst, cv.count, cv.byteStride);
  else if (cv.filter == "EXPONENTIAL") meshopt_decodeFilterExp(dst, cv.count, cv.byteStride);
  return {};
}

}  // namespace

Result<std::vector<MeshoptPlaceholder>> stubMeshoptPlaceholders(nlohmann::json& doc, bool glbHasBin) {
  std::vector<MeshoptPlaceholder> placeholders;
  auto buffers = doc.find("buffers");
  if (buffers == doc.end() || !buffers->is_array()) return placeholders;
  for (size_t i = 0; i < buffers->size(); ++i) {
    nlohmann::json& buffer = (*buffers)[i];
    if (!meshoptExtensionOf(buffer) || buffer.contains("uri")) continue;
    if (i == 0 && glbHasBin) continue;  // the BIN chunk holds real data
    auto length = buffer.find("byteLength");
    if (length == buffer.end() || !length->is_number_unsigned())
      return makeError(ErrorKind::Malformed, "meshopt fallback buffer " + std::to_string(i) + " has no valid byteLength");
    placeholders.push_back({static_cast<int>(i), length->get<size_t>()});
    buffer["uri"] = kStandInUri;
    buffer["byteLength"] = kStandInBytes;
  }
  return placeholders;
}

Result<MeshoptDecodeStats> decodeMeshoptViews(tinygltf::Model& gltf, const std::vector<MeshoptPlaceholder>& placeholders,
                                              LoadBudget& budget) {
  for (const MeshoptPlaceholder& p : placeholders) {
    if (auto ok = budget.charge(p.byteLength, "meshopt fallback buffer " + std::to_string(p.buffer)); !ok) return ok.error();
    tinygltf::Buffer& buffer = gltf.buffers[static_cast<size_t>(p.buffer)];
    buffer.uri.clear();
    buffer.data.assign(p.byteLength, 0);
  }

  MeshoptDecodeStats stats;
  std::vector<uint8_t> scratch;
  for (size_t v = 0; v < gltf.bufferViews.size(); ++v) {
    tinygltf::BufferView& view = gltf.bufferViews[v];
    const char* name = nullptr;
    for (const char* candidate : {kKhrMeshopt, kExtMeshopt})
      if (view.extensions.count(candidate)) name = candidate;
    if (!name) continue;
    const std::string where = "bufferView " + std::to_string(v) + " " + name;
    auto cv = parseCompressedView(view.extensions.at(name), where);
    if (!cv) return cv.error();
    if (auto ok = checkLayout(*cv, where); !ok) return ok.error();
    if (cv->source < 0 || static_cast<size_t>(cv->source) >= gltf.buffers.size())
      return makeError(ErrorKind::Malformed, where + " refers to buffer " + std::to_string(cv->source) + ", the file has " +
                       std::to_string(gltf.buffers.size()));
    const std::vector<unsigned char>& source = gltf.buffers[static_cast<size_t>(cv->source)].data;
    if (cv->byteOffset > source.size() || cv->byteLength > source.size() - cv->byteOffset)
      return makeError(ErrorKind::Malformed, where + ": compressed bytes " + std::to_string(cv->byteOffset) + ".." +
                       std::to_string(cv->byteOffset + cv->byteLength) + " are out of range of buffer " +
                       std::to_string(cv->source) + " (" + std::to_string(source.size()) + " bytes)");
    if (cv->count > SIZE_MAX / cv->byteStride || cv->count * cv->byteStride != view.byteLength)
      return makeError(ErrorKind::Malformed, where + ": count " + std::to_string(cv->count) + " x byteStride " +
                       std::to_string(cv->byteStride) + " does not match the view's byteLength " +
                       std::to_string(view.byteLength));
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= gltf.buffers.size())
      return makeError(ErrorKind::Malformed, where + ": the view's buffer " + std::to_string(view.buffer) + " does not exist");
    std::vector<unsigned char>& target = gltf.buffers[static_cast<size_t>(view.buffer)].data;
    if (view.byteOffset > target.size() || view.byteLength > target.size() - view.byteOffset)
      return makeError(ErrorKind::Malformed, where + ": decoded bytes " + std::to_string(view.byteOffset) + ".." +
                       std::to_string(view.byteOffset + view.byteLength) + " are out of range of buffer " +
                       std::to_string(view.buffer) + " (" + std::to_string(target.size()) + " bytes)");
    // Decoded apart, then copied: the source and the target may be the same buffer.
    if (view.byteLength > scratch.capacity())
      if (auto ok = budget.charge(view.byteLength - scratch.capacity(), where + " decode scratch"); !ok) return ok.error();
    scratch.assign(view.byteLength, 0);
    if (auto ok = decodeInto(scratch.data(), *cv, source.data() + cv->byteOffset, where); !ok) return ok.error();
    if (!scratch.empty()) std::memcpy(target.data() + view.byteOffset, scratch.data(), scratch.size());
    ++stats.views;
    (name == std::string_view(kKhrMeshopt) ? stats.usedKhr : stats.usedExt) = true;
  }
  return stats;
}

}  // namespace eng
