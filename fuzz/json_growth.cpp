#include "fuzz/json_growth.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t maxSize);

namespace fuzz {
namespace {

using Json = nlohmann::ordered_json;

// Deeper than any real file; keeps the recursive walks below off the stack's end.
constexpr size_t kMaxDepth = 200;

size_t bracketDepth(const uint8_t* data, size_t size) {
  size_t depth = 0, deepest = 0;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '[' || data[i] == '{') deepest = std::max(deepest, ++depth);
    if ((data[i] == ']' || data[i] == '}') && depth > 0) --depth;
  }
  return deepest;
}

void collect(Json& j, std::vector<Json*>& out) {
  if (j.is_array() || j.is_object() || j.is_number()) out.push_back(&j);
  if (j.is_array() || j.is_object())
    for (Json& child : j) collect(child, out);
}

// Makes a copy's names its own: "smile" -> "smile_3", keys of objects too
// (graph timelines are keyed by name).
void suffixStrings(Json& j, const std::string& suffix) {
  if (j.is_string()) {
    j = j.get<std::string>() + suffix;
  } else if (j.is_array()) {
    for (Json& child : j) suffixStrings(child, suffix);
  } else if (j.is_object()) {
    Json renamed = Json::object();
    for (auto& [key, value] : j.items()) {
      suffixStrings(value, suffix);
      renamed[key] = std::move(value);
    }
    j = std::move(renamed);
  }
}

// More of an array: one element copied up to 3x the array's length.
void growArray(Json& array, std::mt19937& rng) {
  if (array.empty()) return;
  const Json element = array[rng() % array.size()];
  const size_t copies = 1 + rng() % (3 * array.size());
  for (size_t k = 0; k < copies; ++k) {
    Json copy = element;
    if (rng() % 4 != 0) suffixStrings(copy, "_" + std::to_string(k));  // sometimes left equal: duplicates
    array.push_back(std::move(copy));
  }
}

// Deeper: a member object replaced by a copy of its parent (a graph node
// becomes its own child), or a name-keyed member copied under new names.
void growObject(Json& object, std::mt19937& rng) {
  std::vector<std::string> objectMembers;
  for (auto& [key, value] : object.items())
    if (value.is_object()) objectMembers.push_back(key);
  if (objectMembers.empty()) return;
  const std::string& key = objectMembers[rng() % objectMembers.size()];
  if (rng() % 2 == 0) {
    const Json parent = object;
    object[key] = parent;
    return;
  }
  const Json value = object[key];
  const size_t copies = 1 + rng() % (3 * object.size());
  for (size_t k = 0; k < copies; ++k) object[key + "_" + std::to_string(k)] = value;
}

// Bigger: counts, indices, durations and times scaled up; an integer
// saturates at int64's bounds (grown again, it overflowed: the mutator's own
// undefined behaviour, which the sanitizer rightly reported).
void growNumber(Json& number, std::mt19937& rng) {
  constexpr double kFactors[] = {2.0, 16.0, 1000.0, 1e6};
  const double factor = kFactors[rng() % std::size(kFactors)];
  if (number.is_number_integer()) {
    const int64_t value = number.get<int64_t>();
    int64_t grown = 0;
    if (__builtin_mul_overflow(value, static_cast<int64_t>(factor), &grown))
      grown = value < 0 ? std::numeric_limits<int64_t>::min() : std::numeric_limits<int64_t>::max();
    number = grown;
  } else {
    number = number.get<double>() * factor;
  }
}

}  // namespace

size_t mutateGrowingJson(uint8_t* data, size_t size, size_t maxSize, unsigned seed) {
  std::mt19937 rng(seed);
  if (rng() % 2 == 0 || bracketDepth(data, size) > kMaxDepth) return LLVMFuzzerMutate(data, size, maxSize);
  Json doc = Json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (doc.is_discarded()) return LLVMFuzzerMutate(data, size, maxSize);
  std::vector<Json*> nodes;
  collect(doc, nodes);
  if (nodes.empty()) return LLVMFuzzerMutate(data, size, maxSize);
  Json& target = *nodes[rng() % nodes.size()];
  if (target.is_array()) growArray(target, rng);
  else if (target.is_object()) growObject(target, rng);
  else growNumber(target, rng);
  const std::string text = doc.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > maxSize) return LLVMFuzzerMutate(data, size, maxSize);
  std::memcpy(data, text.data(), text.size());
  return text.size();
}

}  // namespace fuzz
