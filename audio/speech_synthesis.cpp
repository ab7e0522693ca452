#include "audio/speech_synthesis.h"

#include <espeak-ng/speak_lib.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <cmath>
#include <mutex>
#include <optional>

namespace audio {
namespace {

// espeak-ng's global synthesiser: initialised once, on first use, under the mutex.
std::mutex espeakMutex;
int espeakSampleRate = 0;  // 0 until initialised; -1 when initialisation failed

struct SynthesisEvent {
  espeak_EVENT_TYPE type;
  int sample;          // position in the output, in samples
  int textPosition;    // 1-based character index (words)
  int textLength;      // characters (words)
  std::string phoneme; // IPA, empty for the pause markers espeak interleaves
};

struct SynthesisCollector {
  std::vector<int16_t> samples;
  std::vector<SynthesisEvent> events;
  size_t maxSamples = 0;
  bool overLimit = false;
};

int collectSynthesis(short* wav, int count, espeak_EVENT* events) {
  auto* collector = static_cast<SynthesisCollector*>(events->user_data);
  if (wav && count > 0) collector->samples.insert(collector->samples.end(), wav, wav + count);
  for (espeak_EVENT* event = events; event->type != espeakEVENT_LIST_TERMINATED; ++event) {
    if (event->type != espeakEVENT_WORD && event->type != espeakEVENT_PHONEME) continue;
    SynthesisEvent kept{event->type, event->sample, event->text_position, event->length, {}};
    if (event->type == espeakEVENT_PHONEME)
      kept.phoneme.assign(event->id.string, strnlen(event->id.string, sizeof(event->id.string)));
    collector->events.push_back(std::move(kept));
  }
  if (collector->samples.size() > collector->maxSamples) {
    collector->overLimit = true;
    return 1;  // stops the synthesis
  }
  return 0;
}

// Caller holds espeakMutex.
eng::Result<int> ensureEspeakInitialised() {
  if (espeakSampleRate == 0) {
    // DONT_EXIT: a missing data folder must come back as an error, not end the program.
    const int options = espeakINITIALIZE_PHONEME_EVENTS | espeakINITIALIZE_PHONEME_IPA | espeakINITIALIZE_DONT_EXIT;
    const int rate = espeak_Initialize(AUDIO_OUTPUT_SYNCHRONOUS, 0, nullptr, options);
    espeakSampleRate = rate > 0 ? rate : -1;
    if (rate > 0) espeak_SetSynthCallback(collectSynthesis);
  }
  if (espeakSampleRate < 0)
    return eng::makeError(eng::ErrorKind::NotFound, "espeak-ng: cannot initialise (is espeak-ng-data installed?)");
  return espeakSampleRate;
}

// Caller holds espeakMutex.
std::vector<std::string> listLanguagesLocked() {
  std::vector<std::string> languages;
  const espeak_VOICE** voices = espeak_ListVoices(nullptr);
  for (size_t i = 0; voices && voices[i]; ++i) {
    // `languages` is a list of (priority byte, zero-terminated name), ended by a zero byte.
    for (const char* entry = voices[i]->languages; entry && *entry; entry += 1 + std::strlen(entry + 1) + 1)
      languages.emplace_back(entry + 1);
  }
  std::sort(languages.begin(), languages.end());
  languages.erase(std::unique(languages.begin(), languages.end()), languages.end());
  return languages;
}

std::string unknownLanguageMessage(const std::string& language, const std::vector<std::string>& known) {
  std::string examples;
  for (const char* common : {"en", "en-us", "fr", "de", "es", "it", "vi", "zh", "ja"}) {
    if (!std::binary_search(known.begin(), known.end(), std::string(common))) continue;
    examples += (examples.empty() ? "" : ", ") + std::string(common);
  }
  return "speech: unknown language '" + language + "' (espeak-ng knows " + std::to_string(known.size()) + ", e.g. " +
         examples + ")";
}

// Byte offset of each code point of UTF-8 `text`, plus the end.
std::vector<size_t> codePointOffsets(std::string_view text) {
  std::vector<size_t> offsets;
  for (size_t i = 0; i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) offsets.push_back(i);
  offsets.push_back(text.size());
  return offsets;
}

eng::Result<void> checkSpeechRequest(std::string_view text, const SpeechOptions& options) {
  const size_t characters = codePointOffsets(text).size() - 1;
  if (characters == 0 || std::all_of(text.begin(), text.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); }))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "speech: the text is empty");
  if (characters > kMaxSpeechCharacters)
    return eng::makeError(eng::ErrorKind::TooLarge, "speech: the text has " + std::to_string(characters) +
                                                        " characters, over the limit of " + std::to_string(kMaxSpeechCharacters));
  if (!(options.ratePercent >= 50 && options.ratePercent <= 250))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "speech: rate " + std::to_string(options.ratePercent) + "% is outside 50..250%");
  if (!(options.pitchPercent >= 0 && options.pitchPercent <= 200))
    return eng::makeError(eng::ErrorKind::InvalidArgument, "speech: pitch " + std::to_string(options.pitchPercent) + "% is outside 0..200%");
  return {};
}

// Phonemes end where the next event (phoneme or pause marker) starts; words
// span their phonemes.
void timeEvents(std::string_view text, const SynthesisCollector& collected, int sampleRate, Speech& speech) {
  const double secondsPerSample = 1.0 / sampleRate;
  const int totalSamples = static_cast<int>(collected.samples.size());
  std::vector<const SynthesisEvent*> phonemeEvents;
  for (const auto& event : collected.events)
    if (event.type == espeakEVENT_PHONEME) phonemeEvents.push_back(&event);
  for (size_t i = 0; i < phonemeEvents.size(); ++i) {
    if (phonemeEvents[i]->phoneme.empty()) continue;
    const int end = i + 1 < phonemeEvents.size() ? phonemeEvents[i + 1]->sample : totalSamples;
    speech.phonemes.push_back({phonemeEvents[i]->phoneme, phonemeEvents[i]->sample * secondsPerSample,
                               std::max(phonemeEvents[i]->sample, end) * secondsPerSample});
  }
  const std::vector<size_t> offsets = codePointOffsets(text);
  std::vector<const SynthesisEvent*> wordEvents;
  for (const auto& event : collected.events)
    if (event.type == espeakEVENT_WORD) wordEvents.push_back(&event);
  for (size_t w = 0; w < wordEvents.size(); ++w) {
    const double from = wordEvents[w]->sample * secondsPerSample;
    const double to = w + 1 < wordEvents.size() ? wordEvents[w + 1]->sample * secondsPerSample : totalSamples * secondsPerSample + 1;
    TimedWord word;
    bool hasPhoneme = false;
    for (const auto& phoneme : speech.phonemes) {
      if (phoneme.start < from || phoneme.start >= to) continue;
      if (!hasPhoneme) word.start = phoneme.start;
      word.end = phoneme.end;
      hasPhoneme = true;
    }
    if (!hasPhoneme) continue;  // a word espeak spoke as silence (punctuation read as a pause)
    const size_t first = std::clamp<size_t>(wordEvents[w]->textPosition - 1, 0, offsets.size() - 1);
    const size_t last = std::clamp<size_t>(first + std::max(0, wordEvents[w]->textLength), first, offsets.size() - 1);
    word.text = std::string(text.substr(offsets[first], offsets[last] - offsets[first]));
    speech.words.push_back(std::move(word));
  }
}

}  // namespace

eng::Result<std::vector<std::string>> speechLanguages() {
  std::lock_guard lock(espeakMutex);
  ENG_TRY(ensureEspeakInitialised());
  return listLanguagesLocked();
}

eng::Result<Speech> synthesize(std::string_view text, const SpeechOptions& options) {
  ENG_TRY(checkSpeechRequest(text, options));
  std::lock_guard lock(espeakMutex);
  const int sampleRate = ENG_TRY_VALUE(ensureEspeakInitialised());
  if (options.language.empty() || espeak_SetVoiceByName(options.language.c_str()) != EE_OK)
    return eng::makeError(eng::ErrorKind::NotFound, unknownLanguageMessage(options.language, listLanguagesLocked()));
  // Set after the voice: selecting a voice resets them.
  espeak_SetParameter(espeakRATE, static_cast<int>(std::lround(espeakRATE_NORMAL * options.ratePercent / 100.0f)), 0);
  espeak_SetParameter(espeakPITCH, static_cast<int>(std::lround(50.0f * options.pitchPercent / 100.0f)), 0);

  SynthesisCollector collector;
  collector.maxSamples = static_cast<size_t>(kMaxSpeechSeconds * sampleRate);
  const std::string zeroTerminated(text);
  const espeak_ERROR status = espeak_Synth(zeroTerminated.c_str(), zeroTerminated.size() + 1, 0, POS_CHARACTER, 0,
                                           espeakCHARS_UTF8, nullptr, &collector);
  if (collector.overLimit)
    return eng::makeError(eng::ErrorKind::TooLarge, "speech: over " + std::to_string(int(kMaxSpeechSeconds / 60)) +
                                                        " minutes of audio; split the text");
  if (status != EE_OK)
    return eng::makeError(eng::ErrorKind::Io, "speech: espeak-ng failed to synthesise (error " + std::to_string(status) + ")");
  Speech speech;
  speech.sampleRate = sampleRate;
  timeEvents(text, collector, sampleRate, speech);
  speech.samples = std::move(collector.samples);
  return speech;
}

}  // namespace audio
