#pragma once
// Where on a mesh each detail layer can show (texture cross-blending,
// Material::detailLayers): a layer blends by its texture's alpha, and most
// are painted over a small part of the face (the forehead's furrows, the
// brow knot, the nasolabial folds). The fragment shader samples every layer
// an instance's weights turn on, for every pixel of the draw, and a CPU
// rasteriser pays for each sample everywhere. So a triangle list is
// ordered into runs of triangles that the same layers can reach, and each
// run is drawn with only those layers.
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace eng {

struct Image;

// Texels around a layer's painted (alpha > 0) texels that still count as
// its region: what a mipmapped, filtered read of a smaller view can blur
// out (eight texels: down to the fourth mip level).
inline constexpr int kDetailRegionMargin = 8;

// One triangle list's runs: triangles reordered so that those with the same
// layer mask are consecutive.
struct DetailRuns {
  struct Run {
    uint32_t firstIndex = 0;  // into `indices`
    uint32_t indexCount = 0;
    uint32_t layerMask = 0;   // bit l: layer l (of the first 32) may show on these triangles
  };
  std::vector<uint32_t> indices;
  std::vector<Run> runs;  // in order, covering `indices`
};

// The layers' regions as masks of texels (alpha > 0, grown by the margin), one per layer.
class DetailRegions {
 public:
  // `layers[l]`: layer l's texture; null or undecoded: the layer may show anywhere.
  explicit DetailRegions(std::span<const Image* const> layers);
  // The layers (bit l) whose region a triangle's texture footprint touches.
  uint32_t layersOver(glm::vec2 a, glm::vec2 b, glm::vec2 c) const;
  // `indices` (a triangle list over `texcoords`) in runs by layer mask.
  DetailRuns runsOf(std::span<const uint32_t> indices, std::span<const glm::vec2> texcoords) const;
  size_t layerCount() const { return masks_.size(); }

 private:
  // Square blocks of texels, each kNone, kAll or kSome painted: most
  // footprints are answered from the few blocks they cover.
  static constexpr int kBlock = 8;
  static constexpr uint8_t kNone = 0, kAll = 1, kSome = 2;
  struct Mask {
    int width = 0, height = 0;   // 0: everywhere
    std::vector<uint8_t> texels;  // 1 inside the grown region
    int blocksWide = 0;
    std::vector<uint8_t> blocks;  // by row of blocks
    uint8_t over(int x0, int y0, int x1, int y1) const;
  };
  std::vector<Mask> masks_;
};

}  // namespace eng
