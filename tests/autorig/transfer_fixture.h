#pragma once
// The built-in head as a transfer source and target in tests: its parts told
// apart by material and mesh (the head's own names, so these tests do not
// depend on the parts finder), and 68 landmarks placed by hand on it: an iBUG
// layout in the head's front plane (metres, from data/head_landmarks.json's
// features) snapped onto the skin along -Z, as the landmarks file a user
// writes would be.
#include <optional>

#include "autorig/target_transfer.h"
#include "engine/scene/model.h"

namespace transfer_fixture {

// data/head.glb, or nullopt (with a test failure) when it cannot be read.
std::optional<eng::Model> loadHead();
autorig::FaceParts headParts(const eng::Model& head, const autorig::PosedFace& posed);
autorig::FaceLandmarks headLandmarks(const eng::Model& head, const autorig::PosedFace& posed,
                                     const autorig::FaceParts& parts);
// The head set up as a source (posed, landmarks, parts); `head` must outlive it.
autorig::SourceFace headSource(const eng::Model& head);

// How far target B of b is from target A of a on one primitive of the mesh
// named `mesh` (same vertices): the largest vertex difference over A's
// largest displacement, |a - b|max / |a|max.
float relativeError(const eng::Model& a, const eng::Model& b, const char* mesh, size_t primitive, const char* targetA,
                    const char* targetB);

}  // namespace transfer_fixture
