/* The embedding API for C and for engines bound through a C FFI (C#/Unity,
 * Godot GDExtension, Python ctypes/cffi). One opaque handle per character;
 * every function returns a status code and never lets a C++ exception out.
 * The message of the last failure on the calling thread is
 * facial_last_error_message() (valid until that thread's next failing call),
 * its kind (missing file, broken file, misuse...) facial_last_error_kind().
 *
 *   facial_character* c = NULL;
 *   if (facial_character_create("tour.json", "expressions.json", names, count, 1, &c) != FACIAL_OK)
 *     fprintf(stderr, "%s\n", facial_last_error_message());
 *   facial_character_trigger(c, "happy");
 *   facial_character_update(c, 1.0f / 60.0f);
 *   const float* w = facial_character_weights(c);   // one per target name
 *   facial_character_destroy(c);
 *
 * Head space (lookAt, rotations): +X the face's left, +Y up, +Z out of the
 * face, origin between the eyes, metres. Quaternions are {x, y, z, w}. */
#ifndef FACIAL_C_API_H
#define FACIAL_C_API_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef enum facial_status {
  FACIAL_OK = 0,
  FACIAL_ERROR_INVALID_ARGUMENT = 1,   /* null pointer, bad count, non-finite number, bad dt, empty or repeated target name */
  FACIAL_ERROR_LOAD = 2,               /* graph, presets or rig map file missing or broken; no rig for the names */
  FACIAL_ERROR_UNKNOWN_PARAMETER = 3,  /* no graph parameter of that name and type */
  FACIAL_ERROR_OUT_OF_MEMORY = 4,
  FACIAL_ERROR_INTERNAL = 5            /* anything else; the message says what */
} facial_status;

/* What kind of failure the last failing call on this thread met (its status
 * says which step failed; the kind says why, e.g. a missing file versus a
 * broken one). Mirrors eng::ErrorKind (engine/core/result.h). */
typedef enum facial_error_kind {
  FACIAL_KIND_NONE = 0,              /* no failure yet on this thread */
  FACIAL_KIND_NOT_FOUND = 1,         /* a file, or a parameter / target / preset name, does not exist */
  FACIAL_KIND_IO = 2,                /* the file exists but cannot be read */
  FACIAL_KIND_MALFORMED = 3,         /* the file's content breaks its format */
  FACIAL_KIND_UNSUPPORTED = 4,       /* well-formed, but a feature, version or rig this build does not handle */
  FACIAL_KIND_TOO_LARGE = 5,         /* over a size, count or nesting limit */
  FACIAL_KIND_INVALID_ARGUMENT = 6,  /* the caller broke a precondition */
  FACIAL_KIND_DEVICE = 7,            /* GPU / driver failure (not produced by the runtime itself) */
  FACIAL_KIND_OUT_OF_MEMORY = 8,
  FACIAL_KIND_INTERNAL = 9           /* an unexpected failure; the message says what */
} facial_error_kind;

typedef enum facial_eye { FACIAL_EYE_LEFT = 0, FACIAL_EYE_RIGHT = 1 } facial_eye;

typedef struct facial_character facial_character;

/* A character playing `graph_file` over the engine's morph targets
 * `target_names[0..target_count)`. `expressions_file`: the presets the graph
 * names (data/expressions.json), or NULL for graphs over raw target names.
 * `seed` picks the blink / saccade streams. On success *out is the handle. */
facial_status facial_character_create(const char* graph_file, const char* expressions_file,
                                      const char* const* target_names, uint32_t target_count, uint64_t seed,
                                      facial_character** out);
/* Frees the character; NULL is allowed. */
void facial_character_destroy(facial_character* character);

facial_status facial_character_set_float(facial_character* character, const char* parameter, float value);
facial_status facial_character_set_bool(facial_character* character, const char* parameter, int value);
facial_status facial_character_trigger(facial_character* character, const char* parameter);
/* The eyes aim at (x, y, z) in head space; facial_character_look_ahead() lets them rest. */
facial_status facial_character_look_at(facial_character* character, float x, float y, float z);
facial_status facial_character_look_ahead(facial_character* character);

/* Advances by dt seconds (>= 0, finite) and refreshes the weights and rotations. */
facial_status facial_character_update(facial_character* character, float dt);

/* One weight per target name, in create()'s order; valid until the next update or destroy. NULL for NULL. */
const float* facial_character_weights(const facial_character* character);
uint32_t facial_character_weight_count(const facial_character* character);
/* The head joint's idle rotation and an eye's gaze rotation, quaternions {x, y, z, w}. */
facial_status facial_character_head_rotation(const facial_character* character, float out_xyzw[4]);
facial_status facial_character_eye_rotation(const facial_character* character, facial_eye eye, float out_xyzw[4]);

/* Lip sync. Timed phonemes (IPA as espeak-ng --ipa or an aligner writes it,
 * "h", "ˈaɪ", ...) or timed visemes (the Oculus set "sil PP FF TH DD kk CH SS
 * nn RR aa E I O U"), seconds from the audio's start, sorted and not
 * overlapping; `ipa` / `viseme` must not be NULL. The track is built in the
 * call (it allocates); playback then follows facial_character_set_speech_time
 * (the host's audio clock, seconds; 0 until set) with no allocation per
 * frame. The emotion keeps the brows, eyes, cheeks and head while speech
 * owns the mouth. FACIAL_ERROR_INVALID_ARGUMENT: a NULL pointer, bad cue
 * times or names, a rig that nothing on the mouth can move (the message
 * says which targets were looked for). */
typedef struct facial_timed_phoneme {
  const char* ipa;
  float start;
  float end;
} facial_timed_phoneme;
typedef struct facial_timed_viseme {
  const char* viseme;
  float start;
  float end;
} facial_timed_viseme;
facial_status facial_character_speak_phonemes(facial_character* character, const facial_timed_phoneme* phonemes,
                                              uint32_t count);
facial_status facial_character_speak_visemes(facial_character* character, const facial_timed_viseme* visemes,
                                             uint32_t count);
facial_status facial_character_set_speech_time(facial_character* character, float audio_clock_seconds);
facial_status facial_character_stop_speaking(facial_character* character);

/* The last failure's message on this thread ("" when none). */
const char* facial_last_error_message(void);
/* The last failure's kind on this thread (FACIAL_KIND_NONE when none). */
facial_error_kind facial_last_error_kind(void);

#ifdef __cplusplus
}
#endif

#endif /* FACIAL_C_API_H */
