#pragma once
// Ambient occlusion per vertex, baked from the rest pose: how much of the
// sky above each vertex the model itself hides. Deep places -- the mouth
// bag behind closed lips, nostrils, the lids' rim around an eyeball, the
// ear's folds -- come out dark, so an open mouth reads as an opening and the
// eyes get their lash line even on an untextured scan. Baked at rest, it
// stays right for what is hidden at rest (the mouth's inside stays dark when
// the jaw drops).
//
// How: the model is voxelised into a grid (surface voxels), and from each
// vertex a fixed set of cosine-distributed rays marches the grid; a ray that
// meets a voxel within `reach` is occluded. Cost: O(vertices x rays x steps),
// tens of milliseconds for a head.
#include <vector>

#include "engine/scene/model.h"

namespace importers {

struct OcclusionOptions {
  int resolution = 128;  // voxels along the longest side of the bounds
  int rays = 48;
  float reach = 0.2f;    // how far a ray looks, fraction of the bounds' longest side
};

// Per mesh, per primitive, per vertex: visibility in [0, 1] (1 = open sky),
// for every mesh instance's first drawing node. Meshes no node draws get 1.
std::vector<std::vector<std::vector<float>>> bakeVertexOcclusion(const eng::Model& model,
                                                                 const OcclusionOptions& options = {});

}  // namespace importers
