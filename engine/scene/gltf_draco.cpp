#include "engine/scene/gltf_draco.h"

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include <draco/compression/decode.h>
#include <draco/core/decoder_buffer.h>
#include <nlohmann/json.hpp>

#include "engine/scene/gltf_accessor_reader.h"

namespace eng {
namespace {

// Appends `count` values of the accessor's component type, converted by Draco.
template <class T>
bool appendConverted(const draco::PointAttribute& attr, uint32_t points, int components, std::vector<uint8_t>& out) {
  const size_t start = out.size();
  out.resize(start + static_cast<size_t>(points) * components * sizeof(T));
  T value[4] = {};
  for (uint32_t p = 0; p < points; ++p) {
    const draco::AttributeValueIndex index = attr.mapped_index(draco::PointIndex(p));
    if (index.value() >= attr.size() || !attr.ConvertValue<T>(index, static_cast<int8_t>(components), value))
      return false;
    std::memcpy(out.data() + start + (static_cast<size_t>(p) * components) * sizeof(T), value, components * sizeof(T));
  }
  return true;
}

bool appendAttribute(const draco::PointAttribute& attr, uint32_t points, int components, int componentType,
                     std::vector<uint8_t>& out) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return appendConverted<float>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_BYTE: return appendConverted<int8_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return appendConverted<uint8_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return appendConverted<int16_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return appendConverted<uint16_t>(attr, points, components, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return appendConverted<uint32_t>(attr, points, components, out);
    default: return false;
  }
}

void alignTo4(std::vector<uint8_t>& bytes) { bytes.resize((bytes.size() + 3) / 4 * 4, 0); }

// Points `accessor` at bytes [offset, end of `data`) of the new buffer through a new view.
void retarget(tinygltf::Model& gltf, int accessor, int buffer, size_t offset, size_t length, size_t count) {
  tinygltf::BufferView view;
  view.buffer = buffer;
  view.byteOffset = offset;
  view.byteLength = length;
  view.dracoDecoded = true;
  gltf.bufferViews.push_back(std::move(view));
  tinygltf::Accessor& acc = gltf.accessors[static_cast<size_t>(accessor)];
  acc.bufferView = static_cast<int>(gltf.bufferViews.size() - 1);
  acc.byteOffset = 0;
  acc.count = count;
  acc.sparse.isSparse = false;  // the decoded data is the whole accessor
}

// The primitive's Draco stream, decoded.
Result<std::unique_ptr<draco::Mesh>> decodeDracoMesh(const tinygltf::Model& gltf, const tinygltf::Value& ext,
                                                     const std::string& where) {
  if (!ext.Has("bufferView") || !ext.Get("bufferView").IsNumber() || !ext.Has("attributes") ||
      !ext.Get("attributes").IsObject())
    return makeError(ErrorKind::Malformed, where + ": " + kKhrDraco + " needs an integer 'bufferView' and an 'attributes' object");
  const int viewIndex = ext.Get("bufferView").GetNumberAsInt();
  if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= gltf.bufferViews.size())
    return makeError(ErrorKind::Malformed, where + ": Draco bufferView " + std::to_string(viewIndex) + " does not exist");
  const tinygltf::BufferView& view = gltf.bufferViews[static_cast<size_t>(viewIndex)];
  if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= gltf.buffers.size())
    return makeError(ErrorKind::Malformed, where + ": Draco bufferView " + std::to_string(viewIndex) + " has no valid buffer");
  const std::vector<unsigned char>& src = gltf.buffers[static_cast<size_t>(view.buffer)].data;
  if (view.byteOffset > src.size() || view.byteLength > src.size() - view.byteOffset)
    return makeError(ErrorKind::Malformed, where + ": Draco bufferView " + std::to_string(viewIndex) + " is out of range of its buffer");

  draco::DecoderBuffer input;
  input.Init(reinterpret_cast<const char*>(src.data() + view.byteOffset), view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&input);
  if (!decoded.ok())
    return makeError(ErrorKind::Malformed, where + ": the Draco stream (" + std::to_string(view.byteLength) + " bytes) is corrupt or truncated (" +
                     decoded.status().error_msg_string() + ")");
  return std::move(decoded).value();
}

// The decoded accessors' bytes, and where each accessor's data lies in them.
struct DecodedData {
  struct Pending {
    int accessor;
    size_t offset, length, count;
  };
  std::vector<uint8_t> data;
  std::vector<Pending> pending;
};

// The faces as the primitive's indices accessor declares them (its component type).
Result<void> appendIndices(const tinygltf::Model& gltf, const tinygltf::Primitive& prim, const draco::Mesh& mesh,
                           const std::string& where, size_t budget, DecodedData& out) {
  if (static_cast<size_t>(prim.indices) >= gltf.accessors.size())
    return makeError(ErrorKind::Malformed, where + ": indices accessor " + std::to_string(prim.indices) + " does not exist");
  const int type = gltf.accessors[static_cast<size_t>(prim.indices)].componentType;
  const size_t size = type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 1
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 2
                      : type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT   ? 4
                                                                       : 0;
  if (size == 0) return makeError(ErrorKind::Malformed, where + ": Draco indices accessor has componentType " + std::to_string(type));
  const uint32_t faces = mesh.num_faces();
  const size_t count = static_cast<size_t>(faces) * 3;
  if (count * size > budget) return makeError(ErrorKind::TooLarge, where + ": decoded Draco indices (" + std::to_string(count * size) + " bytes) pass the load budget of " + std::to_string(budget) + " bytes left");
  std::vector<uint8_t>& data = out.data;
  const size_t offset = data.size();
  data.resize(offset + count * size);
  for (uint32_t f = 0; f < faces; ++f)
    for (int c = 0; c < 3; ++c) {
      const uint32_t index = mesh.face(draco::FaceIndex(f))[c].value();
      if (size < 4 && index >> (8 * size) != 0)
        return makeError(ErrorKind::Malformed, where + ": Draco index " + std::to_string(index) + " does not fit the indices accessor's type");
      std::memcpy(data.data() + offset + (static_cast<size_t>(f) * 3 + c) * size, &index, size);  // little-endian
    }
  out.pending.push_back({prim.indices, offset, count * size, count});
  alignTo4(data);
  return {};
}

// Every attribute the extension maps that the primitive reads, converted to its accessor's type.
Result<void> appendAttributes(const tinygltf::Model& gltf, const tinygltf::Primitive& prim, const tinygltf::Value& ext,
                              const draco::Mesh& mesh, const std::string& where, size_t budget, DecodedData& out) {
  // The decoded point count is used as is: Draco may split seam vertices
  // into more points than the accessors declare (CesiumMan: 3572 for 3273),
  // as other Draco loaders do. Uncompressed morph targets of such a primitive
  // no longer match and are refused by the loader's count check.
  const uint32_t points = mesh.num_points();
  const tinygltf::Value& attributes = ext.Get("attributes");
  for (const std::string& semantic : attributes.Keys()) {
    const tinygltf::Value& id = attributes.Get(semantic);
    auto accessorIt = prim.attributes.find(semantic);
    if (accessorIt == prim.attributes.end()) continue;  // nothing reads it
    if (!id.IsNumber() || id.GetNumberAsInt() < 0)
      return makeError(ErrorKind::Malformed, where + ": Draco attribute id of " + semantic + " is not a non-negative integer");
    const draco::PointAttribute* attr = mesh.GetAttributeByUniqueId(static_cast<uint32_t>(id.GetNumberAsInt()));
    if (!attr)
      return makeError(ErrorKind::Malformed, where + ": the Draco stream has no attribute " + std::to_string(id.GetNumberAsInt()) + " (" +
                       semantic + ")");
    const int accessor = accessorIt->second;
    if (accessor < 0 || static_cast<size_t>(accessor) >= gltf.accessors.size())
      return makeError(ErrorKind::Malformed, where + ": " + semantic + " accessor " + std::to_string(accessor) + " does not exist");
    const tinygltf::Accessor& acc = gltf.accessors[static_cast<size_t>(accessor)];
    const int components = gltfComponentCount(acc.type);
    const size_t compSize = gltfComponentSize(acc.componentType);
    if (components == 0 || compSize == 0)
      return makeError(ErrorKind::Malformed, where + ": " + semantic + " accessor " + std::to_string(accessor) +
                       " has a type Draco data cannot be written as");
    const size_t length = static_cast<size_t>(points) * components * compSize;
    if (length > budget - std::min(budget, out.data.size()))
      return makeError(ErrorKind::TooLarge, where + ": decoded Draco " + semantic + " (" + std::to_string(length) + " bytes) passes the load budget of " + std::to_string(budget) + " bytes left");
    const size_t offset = out.data.size();
    if (!appendAttribute(*attr, points, components, acc.componentType, out.data))
      return makeError(ErrorKind::Malformed, where + ": Draco attribute " + semantic + " could not be converted to the accessor's type");
    out.pending.push_back({accessor, offset, length, points});
    alignTo4(out.data);
  }
  return {};
}

// Decodes the primitive's Draco stream into a new buffer and points its
// accessors at it; what it took is charged to `loadBudget`.
Result<void> decodePrimitive(tinygltf::Model& gltf, tinygltf::Primitive& prim, const std::string& where,
                             LoadBudget& loadBudget) {
  const size_t budget = loadBudget.left();
  const tinygltf::Value& ext = prim.extensions.at(kKhrDraco);
  auto mesh = decodeDracoMesh(gltf, ext, where);
  if (!mesh) return mesh.error();
  DecodedData decoded;
  if (prim.indices >= 0)
    if (auto ok = appendIndices(gltf, prim, **mesh, where, budget, decoded); !ok) return ok;
  if (auto ok = appendAttributes(gltf, prim, ext, **mesh, where, budget, decoded); !ok) return ok;
  if (auto ok = loadBudget.charge(decoded.data.size(), where + " decoded Draco data"); !ok) return ok;

  tinygltf::Buffer buffer;
  buffer.name = "decoded Draco data";
  buffer.data = std::move(decoded.data);
  gltf.buffers.push_back(std::move(buffer));
  const int bufferIndex = static_cast<int>(gltf.buffers.size() - 1);
  for (const DecodedData::Pending& p : decoded.pending) retarget(gltf, p.accessor, bufferIndex, p.offset, p.length, p.count);
  return {};
}

}  // namespace

bool stubDracoIndices(nlohmann::json& doc) {
  auto meshes = doc.find("meshes");
  auto accessors = doc.find("accessors");
  if (meshes == doc.end() || !meshes->is_array() || accessors == doc.end() || !accessors->is_array()) return false;
  bool changed = false;
  for (const nlohmann::json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (const nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("indices") || !prim["indices"].is_number_unsigned()) continue;
      const nlohmann::json* draco = nullptr;
      if (auto ext = prim.find("extensions"); ext != prim.end() && ext->is_object())
        if (auto it = ext->find(kKhrDraco); it != ext->end() && it->is_object()) draco = &*it;
      if (!draco || !draco->contains("bufferView") || !(*draco)["bufferView"].is_number_unsigned()) continue;
      const size_t index = prim["indices"].get<size_t>();
      if (index >= accessors->size() || !(*accessors)[index].is_object() || (*accessors)[index].contains("bufferView"))
        continue;
      (*accessors)[index]["bufferView"] = (*draco)["bufferView"];
      changed = true;
    }
  }
  return changed;
}

Result<size_t> decodeDracoPrimitives(tinygltf::Model& gltf, LoadBudget& budget) {
  size_t decoded = 0;
  for (size_t m = 0; m < gltf.meshes.size(); ++m)
    for (size_t p = 0; p < gltf.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = gltf.meshes[m].primitives[p];
      if (!prim.extensions.count(kKhrDraco)) continue;
      const std::string where = "mesh " + std::to_string(m) + " primitive " + std::to_string(p);
      if (auto ok = decodePrimitive(gltf, prim, where, budget); !ok) return ok.error();
      ++decoded;
    }
  return decoded;
}

}  // namespace eng
