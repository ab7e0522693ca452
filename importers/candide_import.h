#pragma once
// CANDIDE-3 (Ahlberg 2001, .wfm text format) -> eng::Model: one node, one mesh:
// the mask (positions, generated normals, texture coordinates, triangles
// wound counter-clockwise seen from the front, +z), less the skin inside its
// eye openings, and an eyeball behind each opening (candide_eyes.h). Animation units become
// morph targets named after the FACS unit they realise plus the file's name
// ("AU9 Nose wrinkler", see candide_units.h); shape units become identity
// targets "SU_<name>" ("SU_Head height"). Morph targets carry position and
// normal deltas. The file's animation / shape parameters become the mesh's
// default weights. Repeated vertex entries inside one unit add up (the
// distributed file lists vertex 3 twice in some brow units).
#include <filesystem>
#include <string_view>

#include "engine/core/load_budget.h"
#include "engine/core/result.h"
#include "engine/scene/model.h"

namespace importers {

eng::Result<eng::Model> importCandide3(const std::filesystem::path& wfmFile);
// `source` names the text in messages ("<source>:<line>: <problem>").
eng::Result<eng::Model> parseCandide3(std::string_view text, std::string_view source);
// The same, charging what the file's counts make (vertices, triangles, every
// unit as a dense delta per vertex, the targets it becomes) to `budget`: a
// caller that subdivides after passes the same budget on.
eng::Result<eng::Model> parseCandide3(std::string_view text, std::string_view source, eng::LoadBudget& budget);

}  // namespace importers
