// The C API over facial::Character. Every entry point catches everything: a
// C caller (or another language's FFI) cannot unwind a C++ exception.
#include "facial/c_api.h"

#include <cmath>
#include <cstring>
#include <new>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "facial/character.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "facial/runtime/speech/viseme_track.h"

struct facial_character {
  facial::Character character;
};

namespace {

thread_local std::string gLastError;
thread_local facial_error_kind gLastKind = FACIAL_KIND_NONE;

facial_error_kind toKind(eng::ErrorKind kind) {
  switch (kind) {
    case eng::ErrorKind::NotFound: return FACIAL_KIND_NOT_FOUND;
    case eng::ErrorKind::Io: return FACIAL_KIND_IO;
    case eng::ErrorKind::Malformed: return FACIAL_KIND_MALFORMED;
    case eng::ErrorKind::Unsupported: return FACIAL_KIND_UNSUPPORTED;
    case eng::ErrorKind::TooLarge: return FACIAL_KIND_TOO_LARGE;
    case eng::ErrorKind::InvalidArgument: return FACIAL_KIND_INVALID_ARGUMENT;
    case eng::ErrorKind::Device: return FACIAL_KIND_DEVICE;
  }
  return FACIAL_KIND_INTERNAL;
}

facial_status fail(facial_status status, std::string message, facial_error_kind kind) {
  gLastError = std::move(message);
  gLastKind = kind;
  return status;
}

// A failure the C layer finds itself: the status says the kind.
facial_status fail(facial_status status, std::string message) {
  const facial_error_kind kind = status == FACIAL_ERROR_INVALID_ARGUMENT ? FACIAL_KIND_INVALID_ARGUMENT
                                 : status == FACIAL_ERROR_OUT_OF_MEMORY  ? FACIAL_KIND_OUT_OF_MEMORY
                                                                         : FACIAL_KIND_INTERNAL;
  return fail(status, std::move(message), kind);
}

// A failure of the C++ API: a precondition the caller broke is
// FACIAL_ERROR_INVALID_ARGUMENT whatever the step; anything else is `failure`.
facial_status fail(facial_status failure, const eng::Error& error) {
  const facial_status status = error.kind == eng::ErrorKind::InvalidArgument ? FACIAL_ERROR_INVALID_ARGUMENT : failure;
  return fail(status, error.message, toKind(error.kind));
}

// Runs `body` (returning a status), turning any exception into a status and message.
template <class Body>
facial_status guarded(const char* function, Body&& body) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    return fail(FACIAL_ERROR_OUT_OF_MEMORY, std::string(function) + ": out of memory");
  } catch (const std::exception& e) {
    return fail(FACIAL_ERROR_INTERNAL, std::string(function) + ": " + e.what());
  } catch (...) {
    return fail(FACIAL_ERROR_INTERNAL, std::string(function) + ": unknown failure");
  }
}

facial_status check(const eng::Result<void>& result, facial_status failure) {
  return result ? FACIAL_OK : fail(failure, result.error());
}

// Converts the C cues (an error names what is wrong with one), builds the
// track and hands it to the character.
template <class Cue, class CCue, class Convert>
facial_status speakCues(facial_character& character, std::span<const CCue> items, const char* function, Convert convert) {
  std::vector<Cue> cues;
  cues.reserve(items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    eng::Result<Cue> cue = convert(items[i]);
    if (!cue)
      return fail(FACIAL_ERROR_INVALID_ARGUMENT, std::string(function) + ": cue " + std::to_string(i) + ": " + cue.error().message);
    cues.push_back(std::move(*cue));
  }
  auto built = facial::VisemeTrackBuilder{}.build(cues);
  if (!built) return fail(FACIAL_ERROR_INVALID_ARGUMENT, std::string(function) + ": " + built.error().message);
  auto track = std::make_shared<const facial::VisemeTrack>(std::move(built->track));
  return check(character.character.speak(std::move(track)), FACIAL_ERROR_INVALID_ARGUMENT);
}

facial_status writeQuat(const std::array<float, 4>& q, float out[4]) {
  for (int i = 0; i < 4; ++i) out[i] = q[size_t(i)];
  return FACIAL_OK;
}

}  // namespace

extern "C" {

facial_status facial_character_create(const char* graph_file, const char* expressions_file,
                                      const char* const* target_names, uint32_t target_count, uint64_t seed,
                                      facial_character** out) {
  return guarded("facial_character_create", [&] {
    if (!out) return fail(FACIAL_ERROR_INVALID_ARGUMENT, "facial_character_create: out is NULL");
    *out = nullptr;
    if (!graph_file) return fail(FACIAL_ERROR_INVALID_ARGUMENT, "facial_character_create: graph_file is NULL");
    if (target_count > 0 && !target_names)
      return fail(FACIAL_ERROR_INVALID_ARGUMENT, "facial_character_create: target_names is NULL");
    std::vector<std::string> names;
    names.reserve(target_count);
    for (uint32_t i = 0; i < target_count; ++i) {
      if (!target_names[i])
        return fail(FACIAL_ERROR_INVALID_ARGUMENT,
                    "facial_character_create: target_names[" + std::to_string(i) + "] is NULL");
      names.emplace_back(target_names[i]);
    }
    facial::CharacterOptions options;
    if (expressions_file) options.expressions = expressions_file;
    options.seed = seed;
    auto character = facial::Character::create(graph_file, names, options);
    if (!character) return fail(FACIAL_ERROR_LOAD, character.error());
    *out = new facial_character{std::move(*character)};
    return FACIAL_OK;
  });
}

void facial_character_destroy(facial_character* character) { delete character; }

#define FACIAL_REQUIRE(pointer, function)                                                           \
  if (!(pointer)) return fail(FACIAL_ERROR_INVALID_ARGUMENT, std::string(function) + ": " #pointer " is NULL")

facial_status facial_character_set_float(facial_character* character, const char* parameter, float value) {
  return guarded("facial_character_set_float", [&] {
    FACIAL_REQUIRE(character, "facial_character_set_float");
    FACIAL_REQUIRE(parameter, "facial_character_set_float");
    if (!std::isfinite(value))
      return fail(FACIAL_ERROR_INVALID_ARGUMENT, "facial_character_set_float: value is not finite");
    return check(character->character.setFloat(parameter, value), FACIAL_ERROR_UNKNOWN_PARAMETER);
  });
}

facial_status facial_character_set_bool(facial_character* character, const char* parameter, int value) {
  return guarded("facial_character_set_bool", [&] {
    FACIAL_REQUIRE(character, "facial_character_set_bool");
    FACIAL_REQUIRE(parameter, "facial_character_set_bool");
    return check(character->character.setBool(parameter, value != 0), FACIAL_ERROR_UNKNOWN_PARAMETER);
  });
}

facial_status facial_character_trigger(facial_character* character, const char* parameter) {
  return guarded("facial_character_trigger", [&] {
    FACIAL_REQUIRE(character, "facial_character_trigger");
    FACIAL_REQUIRE(parameter, "facial_character_trigger");
    return check(character->character.trigger(parameter), FACIAL_ERROR_UNKNOWN_PARAMETER);
  });
}

facial_status facial_character_look_at(facial_character* character, float x, float y, float z) {
  return guarded("facial_character_look_at", [&] {
    FACIAL_REQUIRE(character, "facial_character_look_at");
    return check(character->character.lookAt(x, y, z), FACIAL_ERROR_INVALID_ARGUMENT);
  });
}

facial_status facial_character_look_ahead(facial_character* character) {
  return guarded("facial_character_look_ahead", [&] {
    FACIAL_REQUIRE(character, "facial_character_look_ahead");
    character->character.lookAhead();
    return FACIAL_OK;
  });
}

facial_status facial_character_update(facial_character* character, float dt) {
  return guarded("facial_character_update", [&] {
    FACIAL_REQUIRE(character, "facial_character_update");
    return check(character->character.update(dt), FACIAL_ERROR_INVALID_ARGUMENT);
  });
}

const float* facial_character_weights(const facial_character* character) {
  return character ? character->character.weights().data() : nullptr;
}

uint32_t facial_character_weight_count(const facial_character* character) {
  return character ? character->character.weightCount() : 0;
}

facial_status facial_character_head_rotation(const facial_character* character, float out_xyzw[4]) {
  return guarded("facial_character_head_rotation", [&] {
    FACIAL_REQUIRE(character, "facial_character_head_rotation");
    FACIAL_REQUIRE(out_xyzw, "facial_character_head_rotation");
    return writeQuat(character->character.headRotation(), out_xyzw);
  });
}

facial_status facial_character_eye_rotation(const facial_character* character, facial_eye eye, float out_xyzw[4]) {
  return guarded("facial_character_eye_rotation", [&] {
    FACIAL_REQUIRE(character, "facial_character_eye_rotation");
    FACIAL_REQUIRE(out_xyzw, "facial_character_eye_rotation");
    // A C caller may pass any integer; in C++ reading it as a facial_eye
    // outside the enum's values is undefined (UBSan: invalid enum load), so
    // it is checked as the integer it is.
    std::underlying_type_t<facial_eye> value = 0;
    std::memcpy(&value, &eye, sizeof value);
    if (value != FACIAL_EYE_LEFT && value != FACIAL_EYE_RIGHT)
      return fail(FACIAL_ERROR_INVALID_ARGUMENT, "facial_character_eye_rotation: eye is neither left nor right");
    return writeQuat(
        character->character.eyeRotation(value == FACIAL_EYE_LEFT ? facial::Eye::Left : facial::Eye::Right), out_xyzw);
  });
}

facial_status facial_character_speak_phonemes(facial_character* character, const facial_timed_phoneme* phonemes,
                                              uint32_t count) {
  return guarded("facial_character_speak_phonemes", [&] {
    FACIAL_REQUIRE(character, "facial_character_speak_phonemes");
    if (count > 0) FACIAL_REQUIRE(phonemes, "facial_character_speak_phonemes");
    return speakCues<facial::TimedPhoneme>(*character, std::span(phonemes, count), "facial_character_speak_phonemes",
                                           [](const facial_timed_phoneme& p) -> eng::Result<facial::TimedPhoneme> {
                                             if (!p.ipa) return eng::makeError(eng::ErrorKind::InvalidArgument, "ipa is NULL");
                                             return facial::TimedPhoneme{p.ipa, p.start, p.end};
                                           });
  });
}

facial_status facial_character_speak_visemes(facial_character* character, const facial_timed_viseme* visemes,
                                             uint32_t count) {
  return guarded("facial_character_speak_visemes", [&] {
    FACIAL_REQUIRE(character, "facial_character_speak_visemes");
    if (count > 0) FACIAL_REQUIRE(visemes, "facial_character_speak_visemes");
    return speakCues<facial::TimedViseme>(*character, std::span(visemes, count), "facial_character_speak_visemes",
                                          [](const facial_timed_viseme& v) -> eng::Result<facial::TimedViseme> {
                                            const auto viseme = v.viseme ? facial::rigVisemeIndex(v.viseme) : std::nullopt;
                                            if (!viseme)
                                              return eng::makeError(eng::ErrorKind::InvalidArgument,
                                                                    "viseme is not one of " + facial::visemeNameList());
                                            return facial::TimedViseme{*viseme, v.start, v.end};
                                          });
  });
}

facial_status facial_character_set_speech_time(facial_character* character, float audio_clock_seconds) {
  return guarded("facial_character_set_speech_time", [&] {
    FACIAL_REQUIRE(character, "facial_character_set_speech_time");
    return check(character->character.setSpeechTime(audio_clock_seconds), FACIAL_ERROR_INVALID_ARGUMENT);
  });
}

facial_status facial_character_stop_speaking(facial_character* character) {
  return guarded("facial_character_stop_speaking", [&] {
    FACIAL_REQUIRE(character, "facial_character_stop_speaking");
    character->character.stopSpeaking();
    return FACIAL_OK;
  });
}

const char* facial_last_error_message(void) { return gLastError.c_str(); }

facial_error_kind facial_last_error_kind(void) { return gLastKind; }

}  // extern "C"
