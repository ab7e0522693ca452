#include "cli/demo/demo_faces.h"

#include <glm/gtc/matrix_transform.hpp>

#include "app/crowd_layout.h"
#include "engine/view/framing_bounds.h"
#include "facial/runtime/graph/graph_definition.h"

namespace cli {

eng::Result<DemoFaces> DemoFaces::create(const app::FaceSetup& setup, const facial::SharedGraphDefinition& graph,
                                         const std::filesystem::path& graphPath, eng::FramingMode framing,
                                         const std::array<bool, kEmotions.size()>& emotions, const DemoOptions& o) {
  DemoFaces faces;
  faces.emotions_ = emotions;
  faces.random_.seed(uint32_t(o.seed));
  const uint32_t count = std::max<uint32_t>(1, o.crowd);
  const eng::FramingMode other = framing == eng::FramingMode::Face ? eng::FramingMode::All : eng::FramingMode::Face;
  const eng::Aabb bounds = eng::framingBounds(setup.model(), framing);
  const eng::Aabb faceBounds = eng::framingBounds(setup.model(), eng::FramingMode::Face);
  const std::vector<glm::vec3> offsets = app::crowdOffsets(count, bounds);
  faces.bounds_[size_t(framing)] = app::crowdBounds(offsets, bounds);
  faces.bounds_[size_t(other)] = app::crowdBounds(offsets, eng::framingBounds(setup.model(), other));

  auto skeleton = app::SkeletonMotion::create(setup.model(), o.clip);
  if (!skeleton) return skeleton.error();
  auto materials = app::FaceMaterials::create(setup);
  if (!materials) return materials.error();
  const std::vector<std::string> names = setup.layout().names();
  const facial::CharacterParts parts{
      .graph = graph, .rig = &setup.graphRig(), .restWeights = setup.baseWeights(), .vrm = setup.vrm()};
  const bool autoplay = graph->findParameter("autoplay").has_value();
  if (auto ok = app::checkCrowdBudget(count, *graph); !ok) return ok.error().prefixed(graphPath.string() + ": ");
  faces.faces_.reserve(count);
  for (uint32_t i = 0; i < count; ++i) {
    const HeadPlacement head(bounds, faceBounds);
    auto character = facial::Character::create(parts, names, head.eyeOptions({.seed = o.seed + i, .idleLife = !o.still}));
    if (!character) return character.error().prefixed(graphPath.string() + ": ");
    if (autoplay) (void)character->setBool("autoplay", false);
    faces.faces_.push_back(Face{std::move(*character), head, glm::translate(glm::mat4(1.0f), offsets[i]),
                                std::uniform_real_distribution<float>(0.5f, 3.0f)(faces.random_), *skeleton, 0.0f,
                                *materials});
  }
  faces.instances_.resize(count);
  for (size_t i = 0; i < count; ++i) {
    faces.instances_[i].transform = faces.faces_[i].placement;
    faces.instances_[i].weights = faces.faces_[i].character.weights();
  }
  return faces;
}

void DemoFaces::bind(const eng::vk::GpuModel& model) {
  for (eng::vk::ModelInstance& instance : instances_) instance.model = &model;
}

void DemoFaces::update(float dt, const glm::vec3& viewer) {
  for (size_t i = 0; i < faces_.size(); ++i) {
    Face& face = faces_[i];
    if (crowd()) triggerRandomEmotion(face, dt);
    // The eyes follow the viewer: the camera in this face's model space.
    const glm::vec3 viewerInModel = glm::vec3(glm::inverse(face.placement) * glm::vec4(viewer, 1.0f));
    const glm::vec3 target = face.head.gazeTarget(viewerInModel);
    // The viewer is always finite (an orbit camera) and dt is the loop's clamped frame time: neither call can fail.
    (void)face.character.lookAt(target.x, target.y, target.z);
    (void)face.character.update(dt);
    // Sizes were fixed at set-up and the weights come clamped from the rig: cannot fail.
    (void)face.materials.update(face.character.expressionWeights());
    instances_[i].materials = face.materials.materials();
    place(i, dt);
  }
}

void DemoFaces::triggerRandomEmotion(Face& face, float dt) {
  face.nextTrigger -= dt;
  if (face.nextTrigger > 0.0f) return;
  const int emotion = std::uniform_int_distribution<int>(0, int(kEmotions.size()) - 1)(random_);
  if (emotions_[size_t(emotion)]) (void)face.character.trigger(kEmotions[size_t(emotion)]);
  face.nextTrigger = std::uniform_real_distribution<float>(2.0f, 5.0f)(random_);
}

// The face's model where the idle life puts it: a skinned avatar turns its
// head joint and the body only breathes; any other model sways as a whole.
void DemoFaces::place(size_t i, float dt) {
  Face& face = faces_[i];
  face.time += dt;
  const std::array<glm::quat, 2> eyeTurns{HeadPlacement::eyeTurn(face.character, facial::Eye::Left),
                                          HeadPlacement::eyeTurn(face.character, facial::Eye::Right)};
  if (face.skeleton.turnsHeadJoint()) {
    face.skeleton.update(face.time, HeadPlacement::headTurn(face.character), eyeTurns);
    instances_[i].transform = face.head.breathing(face.placement, face.character);
  } else {
    face.skeleton.update(face.time, glm::quat(1.0f, 0.0f, 0.0f, 0.0f), eyeTurns);
    instances_[i].transform = face.head.transform(face.placement, face.character);
  }
  instances_[i].nodeWorld = face.skeleton.nodeWorld();
}

}  // namespace cli
