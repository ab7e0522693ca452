#pragma once
// The source face's expression detail layers carried onto the target's skin
// (texture cross-blending, eng::DetailLayer). The built-in head's forehead
// furrows, brow knot, nasolabial folds, flush and pallor, each fading in
// with the action unit that makes it, are as much a part of its expressions
// as its shapes: the head stripped and rigged onto itself without them read
// 4 of 7 states to the judge, with them 6. Each layer is baked in the target
// skin material's own UVs through the dense correspondence, as a
// modulation of the colour under it (eng::DetailBlend::Modulate): the share
// by which the layer changes the head's skin tone, so a crease darkens any
// skin, whatever its texture or tone, as much as it darkens the head's.
#include <cstddef>
#include <string>
#include <vector>

#include "autorig/dense_correspondence.h"
#include "autorig/target_transfer.h"
#include "engine/scene/model.h"

namespace autorig {

struct DetailTransferOptions {
  // A carried layer's image, a side: the head's creases are a millimetre
  // wide, and a face's skin may fill only part of its UV square.
  int size = 1024;
};

// What was carried, one line per target material ("material 'Skin': 9 layers
// over 5 images of 1024 px ..."), and why a skin material got none.
struct DetailTransferReport {
  std::vector<std::string> carried;
  std::vector<std::string> warnings;
};

// Adds the carried images and layers to `face`, whose skin meshes already
// hold the made targets. `src` and `tgt` are the surfaces `corr` matched
// (the target's skin vertices are the ones that get layers); `posed` is the
// target at rest. A material that other meshes without the layers' targets
// share, or whose skin has no UVs, is left without them.
DetailTransferReport carryDetailLayers(const SourceFace& source, const FaceSurface& src, const FaceSurface& tgt,
                                       const Correspondence& corr, const PosedFace& posed, eng::Model& face,
                                       const DetailTransferOptions& options = {});

// A layer image painted for the head's dense mesh as a face too coarse to
// fold where it does shows it: narrow highlights (a fold's lit edge) kept
// only as far as they are broad, narrow creases spread (about 1 mm more on
// the head) into the softer shade of a fold, no darker than the crease.
// `tone`: the skin colour the image was painted over (linear); texels
// brighter than it are highlights, the others creases.
eng::Image layerForACoarseMesh(const eng::Image& image, const glm::vec3& tone);

}  // namespace autorig
