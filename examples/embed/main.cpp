// An engine's side of the embedding API: its face mesh has ARKit's blend
// shapes; the character plays the project's tour graph over them, changes
// emotion on cue and looks at a point that moves, and the engine would copy
// the weights onto its mesh and the rotations onto its head and eye joints.
// Here each frame's weights are printed (those above 0.01).
#include <cstdio>
#include <string>
#include <vector>

#include <facial/character.h>

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : FACIAL_DATA_DIR;
  const std::vector<std::string> targets = {
      "browDownLeft",   "browDownRight",  "browInnerUp",     "browOuterUpLeft", "browOuterUpRight", "cheekPuff",
      "cheekSquintLeft", "cheekSquintRight", "eyeBlinkLeft", "eyeBlinkRight",   "eyeLookDownLeft",  "eyeLookDownRight",
      "eyeLookInLeft",  "eyeLookInRight", "eyeLookOutLeft",  "eyeLookOutRight", "eyeLookUpLeft",    "eyeLookUpRight",
      "eyeSquintLeft",  "eyeSquintRight", "eyeWideLeft",     "eyeWideRight",    "jawForward",       "jawLeft",
      "jawOpen",        "jawRight",       "mouthClose",      "mouthDimpleLeft", "mouthDimpleRight", "mouthFrownLeft",
      "mouthFrownRight", "mouthFunnel",   "mouthLeft",       "mouthLowerDownLeft", "mouthLowerDownRight",
      "mouthPressLeft", "mouthPressRight", "mouthPucker",    "mouthRight",      "mouthRollLower",   "mouthRollUpper",
      "mouthShrugLower", "mouthShrugUpper", "mouthSmileLeft", "mouthSmileRight", "mouthStretchLeft",
      "mouthStretchRight", "mouthUpperUpLeft", "mouthUpperUpRight", "noseSneerLeft", "noseSneerRight", "tongueOut"};

  auto character = facial::Character::create(data + "/graphs/tour.json", targets,
                                             {.expressions = data + "/expressions.json", .seed = 1});
  if (!character) {
    std::fprintf(stderr, "embed: %s\n", character.error().message.c_str());
    return 1;
  }
  std::printf("rig: %s, gaze: %s\n", std::string(character->rigScheme()).c_str(), character->gazeOutputs().c_str());
  if (auto r = character->setBool("autoplay", false); !r) {
    std::fprintf(stderr, "embed: %s\n", r.error().message.c_str());
    return 1;
  }
  for (int frame = 0; frame < 200; ++frame) {
    if (frame == 20) (void)character->trigger("happy");
    if (frame == 110) (void)character->trigger("surprise");
    // Something passing in front of the face, half a metre away, left to right.
    (void)character->lookAt(0.4f - 0.004f * float(frame), 0.05f, 0.5f);
    if (auto r = character->update(1.0f / 60.0f); !r) {
      std::fprintf(stderr, "embed: %s\n", r.error().message.c_str());
      return 1;
    }
    const auto head = character->headRotation();
    std::printf("frame %3d head (%.4f %.4f %.4f %.4f):", frame, head[0], head[1], head[2], head[3]);
    for (size_t i = 0; i < targets.size(); ++i)
      if (character->weights()[i] > 0.01f) std::printf(" %s=%.3f", targets[i].c_str(), character->weights()[i]);
    std::printf("\n");
  }
  return 0;
}
