#pragma once
// The window demo's faces: one facial::Character each (the graph, its rig,
// idle life and gaze), N of them in the crowd grid (app/crowd_layout.h), with
// the idle head motion placed on the model (head_placement.h), the --clip and
// the head turn of skinned avatars (app/skeleton_motion.h) and the VRM
// material binds following the drawn expressions (app/face_materials.h).
// A crowd's members trigger emotions of their own at random moments; the
// single face is the one the panel drives. update() refreshes one
// eng::vk::ModelInstance per face and does not allocate.
#include <array>
#include <cstdint>
#include <memory>
#include <random>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "app/face_materials.h"
#include "app/face_setup.h"
#include "app/skeleton_motion.h"
#include "cli/demo/demo_options.h"
#include "cli/demo/head_placement.h"
#include "engine/vk/draw/scene_renderer.h"
#include "facial/character.h"

namespace cli {

class DemoFaces {
 public:
  // max(1, options.crowd) faces over `graph` (its "autoplay" switched off);
  // face i is seeded options.seed + i. emotions: which of kEmotions the graph
  // has as triggers (a crowd picks among them). Errors name the graph file
  // for the graph's own problems.
  static eng::Result<DemoFaces> create(const app::FaceSetup& setup, const facial::SharedGraphDefinition& graph,
                                       const std::filesystem::path& graphPath, eng::FramingMode framing,
                                       const std::array<bool, kEmotions.size()>& emotions, const DemoOptions& options);

  size_t size() const { return faces_.size(); }
  bool crowd() const { return faces_.size() > 1; }
  // The first face: the one the panel triggers and poses when there is no crowd.
  facial::Character& single() { return faces_[0].character; }
  const facial::Character& single() const { return faces_[0].character; }
  // The crowd's box by eng::FramingMode: the heads, or the whole models.
  const std::array<eng::Aabb, 2>& bounds() const { return bounds_; }

  // Every face drawn with `model` from now on.
  void bind(const eng::vk::GpuModel& model);
  // Advances every face by dt; their eyes follow the camera at `viewer` (world space).
  void update(float dt, const glm::vec3& viewer);
  std::span<const eng::vk::ModelInstance> instances() const { return instances_; }

 private:
  struct Face {
    facial::Character character;
    HeadPlacement head;
    glm::mat4 placement{1.0f};
    float nextTrigger = 0.0f;      // crowd: seconds until it picks a new emotion
    app::SkeletonMotion skeleton;  // the --clip and, on skinned avatars, the idle head turn
    float time = 0.0f;
    app::FaceMaterials materials;  // VRM material binds following the drawn expression weights
  };
  DemoFaces() = default;
  void triggerRandomEmotion(Face& face, float dt);
  void place(size_t i, float dt);

  std::vector<Face> faces_;
  std::vector<eng::vk::ModelInstance> instances_;
  std::array<eng::Aabb, 2> bounds_;
  std::array<bool, kEmotions.size()> emotions_{};
  std::mt19937 random_;
};

}  // namespace cli
