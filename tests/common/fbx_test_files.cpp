#include "tests/common/fbx_test_files.h"

#include <cstring>

#include <zlib.h>

#include "tests/common/placed_primitive.h"

namespace testing_support {
namespace {

void put32(std::string& out, uint32_t v) {
  for (int k = 0; k < 4; ++k) out.push_back(char((v >> (8 * k)) & 0xff));
}

template <typename T>
std::string arrayOf(char type, std::span<const T> v, bool zlib) {
  std::string raw(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  std::string out(1, type);
  put32(out, uint32_t(v.size()));
  if (zlib) {
    uLongf size = compressBound(uLong(raw.size()));
    std::string packed(size, '\0');
    compress(reinterpret_cast<Bytef*>(packed.data()), &size, reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()));
    packed.resize(size);
    put32(out, 1);
    put32(out, uint32_t(packed.size()));
    return out + packed;
  }
  put32(out, 0);
  put32(out, uint32_t(raw.size()));
  return out + raw;
}

void put64(std::string& out, uint64_t v) {
  put32(out, uint32_t(v));
  put32(out, uint32_t(v >> 32));
}

// A node record: end offset, value count and value bytes in 32 bits before
// FBX 7.5 (version 7500), in 64 bits from it; children end with a null record.
void writeNode(std::string& out, const FbxTestNode& node, bool wide) {
  const size_t header = wide ? 25 : 13;
  const size_t start = out.size();
  out.append(header, '\0');
  out += node.name;
  size_t valueBytes = 0;
  for (const std::string& v : node.values) {
    out += v;
    valueBytes += v.size();
  }
  if (!node.children.empty()) {
    for (const FbxTestNode& c : node.children) writeNode(out, c, wide);
    out.append(header, '\0');
  }
  std::string fields;
  for (uint64_t field : {uint64_t(out.size()), uint64_t(node.values.size()), uint64_t(valueBytes)}) {
    if (wide) put64(fields, field);
    else put32(fields, uint32_t(field));
  }
  fields.push_back(char(node.name.size()));
  out.replace(start, header, fields);
}

FbxTestNode property(const std::string& name, const std::string& type, std::vector<std::string> values) {
  FbxTestNode p{"P", {fbxString(name), fbxString(type), fbxString(""), fbxString("A")}, {}};
  for (std::string& v : values) p.values.push_back(std::move(v));
  return p;
}

}  // namespace

std::string fbxInt(int32_t v) {
  std::string out(1, 'I');
  put32(out, uint32_t(v));
  return out;
}

std::string fbxLong(int64_t v) {
  std::string out(1, 'L');
  put64(out, uint64_t(v));
  return out;
}

std::string fbxDouble(double v) {
  std::string out(1, 'D');
  char bytes[8];
  std::memcpy(bytes, &v, 8);
  return out + std::string(bytes, 8);
}

std::string fbxString(std::string_view s) {
  std::string out(1, 'S');
  put32(out, uint32_t(s.size()));
  return out + std::string(s);
}

std::string fbxDoubles(std::span<const double> v, bool zlib) { return arrayOf('d', v, zlib); }
std::string fbxInts(std::span<const int32_t> v, bool zlib) { return arrayOf('i', v, zlib); }

std::string fbxName(std::string_view name, std::string_view objectClass) {
  return std::string(name) + std::string("\0\1", 2) + std::string(objectClass);
}

std::string fbxBinary(const std::vector<FbxTestNode>& top, uint32_t version) {
  std::string out("Kaydara FBX Binary  \0\x1a\0", 23);
  put32(out, version);
  const bool wide = version >= 7500;
  for (const FbxTestNode& node : top) writeNode(out, node, wide);
  out.append(wide ? 25 : 13, '\0');
  return out;
}

FbxTestNode fbxVectorProperties(const std::vector<std::pair<std::string, glm::dvec3>>& properties) {
  FbxTestNode block{"Properties70", {}, {}};
  for (const auto& [name, v] : properties)
    block.children.push_back(property(name, name, {fbxDouble(v.x), fbxDouble(v.y), fbxDouble(v.z)}));
  return block;
}

std::string modelAsFbx(const eng::Model& model) {
  FbxTestNode objects{"Objects", {}, {}};
  FbxTestNode connections{"Connections", {}, {}};
  int64_t id = 1000;
  forEachPlacedPrimitive(model, [&](const PlacedPrimitive& placed) {
    const eng::Primitive& p = placed.primitive;
    std::vector<double> vertices, normals, uvs;
    for (const glm::vec3& w : placed.positions) vertices.insert(vertices.end(), {w.x, w.y, w.z});
    for (size_t v = 0; v < p.positions.size(); ++v) {
      const glm::vec2 uv = v < p.texcoords.size() ? p.texcoords[v] : glm::vec2(0.0f);
      uvs.insert(uvs.end(), {uv.x, 1.0 - uv.y});
    }
    std::vector<int32_t> polygons;
    for (size_t t = 0; t + 2 < p.indices.size(); t += 3) {
      polygons.insert(polygons.end(), {int32_t(p.indices[t]), int32_t(p.indices[t + 1]), ~int32_t(p.indices[t + 2])});
      for (int k = 0; k < 3; ++k) {
        const glm::vec3& n = placed.normals[p.indices[t + size_t(k)]];
        normals.insert(normals.end(), {n.x, n.y, n.z});
      }
    }
    const int64_t geometry = id++, node = id++;
    const std::string name = placed.meshName + "_" + std::to_string(node);
    objects.children.push_back(FbxTestNode{
        "Geometry",
        {fbxLong(geometry), fbxString(fbxName(name, "Geometry")), fbxString("Mesh")},
        {{"Vertices", {fbxDoubles(vertices, true)}, {}},
         {"PolygonVertexIndex", {fbxInts(polygons, true)}, {}},
         {"LayerElementNormal",
          {fbxInt(0)},
          {{"MappingInformationType", {fbxString("ByPolygonVertex")}, {}},
           {"ReferenceInformationType", {fbxString("Direct")}, {}},
           {"Normals", {fbxDoubles(normals, true)}, {}}}},
         {"LayerElementUV",
          {fbxInt(0)},
          {{"MappingInformationType", {fbxString("ByVertice")}, {}},
           {"ReferenceInformationType", {fbxString("Direct")}, {}},
           {"UV", {fbxDoubles(uvs, true)}, {}}}}}});
    objects.children.push_back(FbxTestNode{"Model", {fbxLong(node), fbxString(fbxName(name, "Model")), fbxString("Mesh")}, {}});
    connections.children.push_back({"C", {fbxString("OO"), fbxLong(geometry), fbxLong(node)}, {}});
    connections.children.push_back({"C", {fbxString("OO"), fbxLong(node), fbxLong(0)}, {}});
  });
  FbxTestNode settings{"GlobalSettings", {}, {{"Properties70", {}, {property("UnitScaleFactor", "double", {fbxDouble(100.0)})}}}};
  return fbxBinary({settings, objects, connections});
}

}  // namespace testing_support
