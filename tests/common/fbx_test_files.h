#pragma once
// Binary FBX 7.x written by hand for the tests: any node tree (broken ones
// too: a value's bytes are given as they are stored), and any model at rest
// as an FBX of one mesh Model per primitive, as a scan or sculpt exports.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "engine/scene/model.h"

namespace testing_support {

// One stored value: a type code and its bytes.
std::string fbxInt(int32_t v);                    // 'I'
std::string fbxLong(int64_t v);                   // 'L'
std::string fbxDouble(double v);                  // 'D'
std::string fbxString(std::string_view s);        // 'S'
std::string fbxDoubles(std::span<const double> v, bool zlib = false);   // 'd'
std::string fbxInts(std::span<const int32_t> v, bool zlib = false);     // 'i'
// An FBX object's name as binary FBX stores it: "Name\0\1Class".
std::string fbxName(std::string_view name, std::string_view objectClass);

struct FbxTestNode {
  std::string name;
  std::vector<std::string> values;  // fbxInt(...), ...
  std::vector<FbxTestNode> children;
};

// The file: header, the top-level nodes, the closing null record; record
// headers in 64 bits from version 7500 (FBX 2016 and later), as exporters write them.
std::string fbxBinary(const std::vector<FbxTestNode>& top, uint32_t version = 7400);

// Properties70 with one "P" entry per (name, x, y, z) vector property.
FbxTestNode fbxVectorProperties(const std::vector<std::pair<std::string, glm::dvec3>>& properties);

// A model at rest as one FBX: every mesh node's primitives in world space
// (positions, normals by polygon vertex, texture coordinates), a mesh Model
// each, no targets, no materials; Y up, metres (UnitScaleFactor 100).
std::string modelAsFbx(const eng::Model& model);

}  // namespace testing_support
