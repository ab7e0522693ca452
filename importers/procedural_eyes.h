#pragma once
// Eyes for faces whose eyeballs arrive without a texture (facecap, many
// scans, sculpts): a white ball reads as a blank stare, so nobody can tell
// where the face looks or what it feels. Such an eyeball gets a procedural
// eye material -- sclera, iris with radial fibres, pupil, dark limbal ring and
// a catch-light -- mapped along the eye's gaze axis (the face's forward: +Z
// in glTF, turned square to the line between the two eyes where the file
// holds the face turned aside or rolled) by planar texture coordinates
// computed from the rest pose, so the
// iris moves with the eyeball's node and with any morph of its vertices.
// Textured eyes are left alone.
//
// An eyeball is a primitive whose node, parent nodes, mesh or material name
// says "eye" (not brow/lash/lid/socket/...) with no base colour texture and a
// roughly spherical shape (a least-squares sphere fits its vertices).
#include <cstddef>
#include <string>
#include <vector>

#include "engine/scene/inner_face_parts.h"  // eng::namesAnEyeball
#include "engine/scene/model.h"

namespace importers {

struct EyePrimitive {
  int mesh = -1;
  int primitive = -1;
  int node = -1;          // a node that draws the mesh (its world transform gives the gaze axis)
  glm::vec3 centre{0.0f};  // sphere fit, mesh space
  float radius = 0.0f;
  glm::vec3 gazeAxis{0.0f, 0.0f, 1.0f};  // mesh space, unit
};

// Vertex colours off white (a scan's or a sculpt's paint, COLOR_0).
bool paintedPerVertex(const eng::Primitive& primitive);
// An untextured material left at an exporter's default (white, or a neutral
// grey of 0.5 or more), or none, and not painted per vertex: the author gave
// the primitive no colour.
bool unauthoredPlain(const eng::Model& model, const eng::Primitive& primitive);

// The untextured eyeballs of `model`, at rest: the balls named as eyes, else
// (no names to go by) a pair of balls of one size, level, a few radii apart,
// inside the head.
std::vector<EyePrimitive> findUntexturedEyes(const eng::Model& model);

// Dresses every eyeball findUntexturedEyes() finds: adds the eye texture (one
// image shared by all eyes) and one material per distinct source material,
// sets planar texture coordinates on the eye primitives. Returns how many
// primitives were dressed (0: the model is unchanged).
size_t dressUntexturedEyes(eng::Model& model);

// The procedural eye texture (RGBA8, sRGB): for tests and tools.
eng::Image proceduralEyeImage(int size = 256);

}  // namespace importers
