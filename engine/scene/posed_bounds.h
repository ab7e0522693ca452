#pragma once
// Where a posed model is, for camera framing: the world-space bounds of the
// mesh in a skeleton pose (morphed, then skinned, then placed by its node),
// the bounds of the part of it one joint moves (the head), and which joint
// is the head.
//
//   const eng::Pose pose = eng::restPose(model);
//   eng::Aabb all = eng::posedBounds(model, pose);
//   if (int head = eng::findHeadJoint(model); head >= 0)
//     eng::Aabb face = eng::posedJointRegionBounds(model, pose, head);
#include <span>

#include "engine/scene/model.h"
#include "engine/scene/skeleton_pose.h"

namespace eng {

// World-space bounds of every mesh instance of the default scene in `pose`
// (pose.nodeCount() == model.nodes.size()). weights: the model's flat morph
// weight vector (eng::WeightLayout order); empty = no morphing. Skinned
// primitives are skinned by their node's skin; for an unskinned model and the
// rest pose this equals Model::bounds().
Aabb posedBounds(const Model& model, const Pose& pose, std::span<const float> weights = {});

// World-space bounds of the posed vertices that `joint` (a node index) and
// the joints under it move with a total skin weight >= minWeight, plus every
// unskinned mesh hung under them: for the head joint, the head (with hair,
// eyes, teeth skinned to it or parented to it) without the body. Invalid
// (Aabb::valid() false) when no vertex qualifies.
Aabb posedJointRegionBounds(const Model& model, const Pose& pose, int joint, float minWeight = 0.5f,
                            std::span<const float> weights = {});

// World-space bounds of the posed vertices that some morph target moves by a
// tenth or more of that target's largest displacement (and by more than a
// thousandth of the primitive's size: quantised exports move everything a
// little): the features a face's targets carry, in `pose`. Invalid when no
// target moves anything.
Aabb posedMorphedBounds(const Model& model, const Pose& pose);

// The node index of the head joint of a skinned model, -1 when it has no
// skin. In order: the VRM humanoid `head` bone (Model::humanoidHead); a skin
// joint named like a head, case-insensitively and after any "prefix:" or
// "prefix_" (Head, head, mixamorig:Head, J_Bip_C_Head, Bip01 Head,
// CC_Base_Head; not HeadTop_End / head_end / HeadEnd); else, for a skeleton
// without such names (CesiumMan, an export that lost them), the highest joint
// (world +Y, rest pose) that carries some vertex, or the joint above it when
// that one carries more vertices around it (an eye's joint is not the head).
int findHeadJoint(const Model& model);

}  // namespace eng
