#pragma once
// What a node sees while the graph is built: the channels, parameters and
// timelines it may refer to, and where it was declared (a JSON pointer or
// "node 3 (blend)") so its problems name the spot.
#include <span>
#include <string>
#include <string_view>

#include "engine/core/result.h"
#include "facial/runtime/graph/channel_set.h"
#include "facial/runtime/graph/parameters.h"
#include "facial/runtime/graph/timeline.h"

namespace facial {

struct BuildContext {
  const ChannelSet& channels;
  std::span<const ParameterDecl> parameters;
  std::span<const Timeline> timelines;
  std::string origin;

  // A Malformed error (the graph's content does not fit) reading
  // "<origin>/<subpath>: <problem>" (no subpath: "<origin>: <problem>").
  eng::Error problem(std::string_view subpath, std::string_view problem) const;
  // Fails when `input` names a parameter that does not exist or its constant is not finite.
  eng::Result<void> checkInput(const FloatInput& input, std::string_view field) const;
  // Fails unless `parameter` exists and has type `type`.
  eng::Result<void> checkParameter(ParameterIndex parameter, ParameterType type, std::string_view field) const;
};

}  // namespace facial
