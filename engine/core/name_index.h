#pragma once
// Names to indices in one hashed look-up, for whatever resolves names read
// from a file (tracks, parameters, states, channels, materials): a linear
// search per name made n names cost n^2, and 5-13 MB files took minutes
// (issue 37). Each name comparison the table makes counts as work
// (work_counter.h).
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>

#include "engine/core/work_counter.h"

namespace eng {

class NameIndex {
 public:
  // Adds name -> index unless the name is there already (the first stays);
  // returns whether it was added.
  bool add(std::string_view name, uint32_t index) { return map_.try_emplace(std::string(name), index).second; }
  std::optional<uint32_t> find(std::string_view name) const {
    auto it = map_.find(name);
    if (it == map_.end()) return std::nullopt;
    return it->second;
  }
  size_t size() const { return map_.size(); }
  void reserve(size_t count) { map_.reserve(count); }

 private:
  struct Hash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const noexcept { return std::hash<std::string_view>{}(s); }
  };
  struct Equal {
    using is_transparent = void;
    bool operator()(std::string_view a, std::string_view b) const noexcept {
      countWork();
      return a == b;
    }
  };
  std::unordered_map<std::string, uint32_t, Hash, Equal> map_;
};

}  // namespace eng
