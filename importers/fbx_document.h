#pragma once
// An FBX file's node tree as it is stored, before any meaning is given to it
// (importers/fbx_scene.h does that): binary FBX 7.x, as Maya, 3ds Max,
// Blender, Mixamo and most character tools write it, and ASCII FBX 7.x.
// Every node is a name, a list of property values and child nodes.
//
// Read by hand: Debian has no FBX library but Assimp, whose 5.2.5 crashed
// under our fuzzer within a minute on another format. Every length is
// checked against the bytes left before it is read, every array is charged
// to the load budget before it is inflated (zlib) or allocated, and nesting
// is bounded.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"

namespace importers::fbx {

// One property value. Binary FBX's scalar types (bool, int16/32/64) are
// integers, float and double are numbers, strings and raw bytes are text;
// arrays keep their kind. ASCII arrays of whole numbers are integers.
using Value = std::variant<int64_t, double, std::string, std::vector<int64_t>, std::vector<double>>;

struct Node {
  std::string name;
  std::vector<Value> values;
  std::vector<Node> children;

  // The first child called `childName`, nullptr when there is none.
  const Node* child(std::string_view childName) const;
  // Values read leniently: an integer where a number is asked is converted,
  // and the reverse when the number is whole. nullopt / empty when absent
  // or of another kind.
  std::optional<double> number(size_t i) const;
  std::optional<int64_t> integer(size_t i) const;
  std::string_view text(size_t i) const;
  std::vector<double> numbers(size_t i) const;
  // Whole numbers only (indices): false when a value is not one.
  bool integers(size_t i, std::vector<int64_t>& out) const;
};

struct Document {
  uint32_t version = 0;  // 7400 for FBX 7.4
  Node root;             // its children are the file's top-level nodes
};

// Whether `bytes` start as an FBX file does: the binary magic, or an ASCII
// file's "; FBX" comment.
bool looksLikeFbx(std::span<const uint8_t> bytes);

// `name` names the file in messages. FBX 6 and older (their connections name
// objects instead of numbering them) are refused as unsupported.
eng::Result<Document> readFbxDocument(std::span<const uint8_t> bytes, const std::string& name, eng::LoadBudget& budget);

}  // namespace importers::fbx
