/* The C API: a character over a FACS-named rig (an engine whose face has one
 * blend shape per action unit, plus eye-turn shapes AU61-64), driven for 200
 * frames; each frame prints the weights above 0.01 and the left eye's rotation. */
#include <stdio.h>
#include <string.h>

#include <facial/c_api.h>

static const char* const kTargets[] = {"AU1",  "AU2",  "AU4",  "AU5",  "AU6",  "AU7",  "AU9",  "AU10", "AU12",
                                       "AU15", "AU17", "AU20", "AU23", "AU25", "AU26", "AU45_L", "AU45_R",
                                       "AU61", "AU62", "AU63", "AU64"};
enum { kTargetCount = sizeof kTargets / sizeof kTargets[0] };

static int report(facial_status status, const char* what) {
  if (status == FACIAL_OK) return 0;
  fprintf(stderr, "embed_c: %s failed (%d): %s\n", what, (int)status, facial_last_error_message());
  return 1;
}

int main(int argc, char** argv) {
  const char* data = argc > 1 ? argv[1] : FACIAL_DATA_DIR;
  char graph[1024], expressions[1024];
  snprintf(graph, sizeof graph, "%s/graphs/tour.json", data);
  snprintf(expressions, sizeof expressions, "%s/expressions.json", data);

  facial_character* character = NULL;
  if (report(facial_character_create(graph, expressions, kTargets, kTargetCount, 7, &character), "create")) return 1;
  /* A parameter the graph lacks: an error code and a message, nothing thrown. */
  if (facial_character_trigger(character, "no such trigger") != FACIAL_ERROR_UNKNOWN_PARAMETER) {
    fprintf(stderr, "embed_c: an unknown trigger was not refused\n");
    return 1;
  }
  if (report(facial_character_set_bool(character, "autoplay", 0), "set_bool")) return 1;
  for (int frame = 0; frame < 200; ++frame) {
    if (frame == 20 && report(facial_character_trigger(character, "anger"), "trigger")) return 1;
    if (frame == 120 && report(facial_character_trigger(character, "sad"), "trigger")) return 1;
    if (report(facial_character_look_at(character, -0.3f, -0.1f, 0.6f), "look_at")) return 1;
    if (report(facial_character_update(character, 1.0f / 60.0f), "update")) return 1;
    const float* weights = facial_character_weights(character);
    float eye[4];
    if (report(facial_character_eye_rotation(character, FACIAL_EYE_LEFT, eye), "eye_rotation")) return 1;
    printf("frame %3d eye (%.3f %.3f %.3f %.3f):", frame, eye[0], eye[1], eye[2], eye[3]);
    for (uint32_t i = 0; i < facial_character_weight_count(character); ++i)
      if (weights[i] > 0.01f) printf(" %s=%.3f", kTargets[i], weights[i]);
    printf("\n");
  }
  facial_character_destroy(character);
  return 0;
}
