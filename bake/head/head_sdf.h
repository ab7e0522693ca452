#pragma once
// The built-in head's skin as an implicit surface: blended ellipsoids, round
// cones and a few grooves (approximate signed distance, negative inside).
// The skin mesh is made by casting rays from inside the head to this surface;
// eyes, teeth and ears are separate meshes and not part of it.
#include <optional>

#include <glm/glm.hpp>

#include "bake/head/head_proportions.h"

namespace bake {

class HeadSdf {
 public:
  explicit HeadSdf(const HeadProportions& proportions);

  float distance(const glm::vec3& p) const;
  glm::vec3 normal(const glm::vec3& p) const;  // normalised central-difference gradient

  // First inside-to-outside crossing along origin + t * dir for t in (0, maxT].
  // `origin` must be inside; nullopt when no crossing is found.
  std::optional<glm::vec3> castOut(const glm::vec3& origin, const glm::vec3& dir, float maxT = 0.4f) const;

  // Hair coverage in [0, 1] at a point near the skin (1 = scalp under hair);
  // shared with the texture painter so the colour follows the hair volume.
  float hairCoverage(const glm::vec3& p) const;
  // Front-projected distance (metres) to the vermilion border, negative on the lips.
  float lipDistance(const glm::vec3& p) const;
  // Ambient occlusion estimate in [0, 1] (1 = open) at a surface point with normal n.
  float occlusion(const glm::vec3& p, const glm::vec3& n) const;
  // Hair thickness profile (0..1), softer at the hairline than the colour.
  float hairVolume(const glm::vec3& p) const;
  // Elevation angle (radians) of the lip seam cone seen from gridCentre.
  float seamElevation() const { return seamElevation_; }
  // Azimuth (radians, atan2(x, z) around gridCentre) of the left mouth corner
  // on the seam cone; the right corner is its negative.
  float mouthCornerAzimuth() const { return cornerAzimuth_; }

 private:
  float face(const glm::vec3& p) const;    // skull, jaw, cheeks, brow, chin
  float nose(const glm::vec3& p) const;
  // Vermilion outline and how far the lips stand out of the muzzle, by |x|.
  struct LipBand {
    float upperHeight, lowerHeight;           // border above / below the seam
    float upperRaise, lowerRaise, seamRaise;  // at each lip's fullest and at the seam
  };
  LipBand lipBand(float ax) const;
  float lipRaise(const glm::vec3& p) const;
  float seamHeight(const glm::vec3& p) const;  // y of the seam cone at p's distance from the grid centre
  float eyeRegion(float d, const glm::vec3& p) const;  // orbit carve + lid shell, both eyes

  HeadProportions prop_;
  float seamElevation_ = 0.0f;
  float cornerAzimuth_ = 0.3f;
  bool seamGroove_ = true;  // off while the constructor locates the corners
};

}  // namespace bake
