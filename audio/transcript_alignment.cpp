#include "audio/transcript_alignment.h"

#include <pocketsphinx.h>
#include <sphinxbase/cmd_ln.h>
#include <sphinxbase/err.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <utility>

#include "audio/resample.h"

namespace audio {

// Named (not anonymous): declared in the header's namespace scope users never see.
namespace alignment_parts {

constexpr int kModelSampleRate = 16000;
constexpr double kPaddingSeconds = 0.3;  // silence around the recording: the model expects to start and end in silence
constexpr std::string_view kPhoneWordPrefix = "ph_";  // no dictionary word starts so
constexpr std::string_view kSilenceWord = "ph_SIL";

std::mutex alignMutex;

struct DecoderFree {
  void operator()(ps_decoder_t* decoder) const { ps_free(decoder); }
};
struct ConfigFree {
  void operator()(cmd_ln_t* config) const { cmd_ln_free_r(config); }
};
struct SphinxStringFree {
  void operator()(char* text) const { std::free(text); }
};

struct TranscriptWord {
  std::string text;
  std::vector<std::string> phones;  // ARPAbet
};

// Words: runs of letters, apostrophes and non-ASCII bytes (so "café" stays one
// word and is reported whole), lower-cased.
std::vector<std::string> splitWords(std::string_view text) {
  std::vector<std::string> words;
  std::string word;
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (std::isalpha(byte) || c == '\'' || byte >= 0x80 || std::isdigit(byte)) {
      word += char(std::tolower(byte));
    } else if (!word.empty()) {
      words.push_back(std::move(word));
      word.clear();
    }
  }
  if (!word.empty()) words.push_back(std::move(word));
  return words;
}

std::vector<std::string> splitPhones(std::string_view phones) {
  std::vector<std::string> out;
  size_t start = 0;
  while (start < phones.size()) {
    const size_t end = std::min(phones.find(' ', start), phones.size());
    if (end > start) out.emplace_back(phones.substr(start, end - start));
    start = end + 1;
  }
  return out;
}

eng::Result<std::pair<std::unique_ptr<cmd_ln_t, ConfigFree>, std::unique_ptr<ps_decoder_t, DecoderFree>>> openDecoder() {
  const std::filesystem::path model = FACIAL_POCKETSPHINX_MODEL_DIR "/en-us/en-us";
  const std::filesystem::path dictionary = FACIAL_POCKETSPHINX_MODEL_DIR "/en-us/cmudict-en-us.dict";
  std::error_code ec;
  if (!std::filesystem::exists(model, ec) || !std::filesystem::exists(dictionary, ec))
    return eng::makeError(eng::ErrorKind::NotFound, "align: the English model is missing at " + model.parent_path().string() +
                                                        " (install pocketsphinx-en-us)");
  // No voice-activity trimming (it would shift every time); topn 16: with the
  // default 4 Gaussians the search loses some phrases a grammar allows; no
  // filler loops: the grammar has its own silences.
  std::unique_ptr<cmd_ln_t, ConfigFree> config(cmd_ln_init(nullptr, ps_args(), TRUE, "-hmm", model.c_str(), "-dict", dictionary.c_str(),
                                                           "-samprate", "16000", "-remove_silence", "no", "-topn", "16", "-fsgusefiller", "no", "-beam",
                                                           "1e-100", "-pbeam", "1e-100", "-wbeam", "1e-80", nullptr));
  if (!config) return eng::makeError(eng::ErrorKind::Io, "align: cannot configure pocketsphinx");
  std::unique_ptr<ps_decoder_t, DecoderFree> decoder(ps_init(config.get()));
  if (!decoder) return eng::makeError(eng::ErrorKind::Io, "align: cannot load the English model from " + model.string());
  return std::make_pair(std::move(config), std::move(decoder));
}

eng::Result<std::vector<TranscriptWord>> lookUpWords(ps_decoder_t* decoder, std::string_view text) {
  std::vector<TranscriptWord> words;
  for (std::string& word : splitWords(text)) {
    std::unique_ptr<char, SphinxStringFree> phones(ps_lookup_word(decoder, word.c_str()));
    if (!phones)
      return eng::makeError(eng::ErrorKind::NotFound, "align: '" + word + "' is not in the English dictionary" +
                                                          (std::isdigit(static_cast<unsigned char>(word[0])) ? " (write numbers as words)" : ""));
    words.push_back({std::move(word), splitPhones(phones.get())});
  }
  if (words.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "align: the transcript has no words");
  if (words.size() > kMaxAlignWords)
    return eng::makeError(eng::ErrorKind::TooLarge, "align: " + std::to_string(words.size()) + " words, over the limit of " +
                                                        std::to_string(kMaxAlignWords));
  return words;
}

// The grammar: every phone of every word, in order, each a one-phone word,
// with an optional silence between words and at both ends. Explicit
// silences instead of pocketsphinx's filler loops: with those, the search
// sometimes ended off the grammar ("at nine tonight" failed to align).
eng::Result<void> setPhoneGrammar(ps_decoder_t* decoder, const std::vector<TranscriptWord>& words) {
  const std::string silence = "[" + std::string(kSilenceWord) + "]";
  std::string grammar = "#JSGF V1.0;\ngrammar transcript;\npublic <utterance> = " + silence;
  std::vector<std::string> distinct = {"SIL"};
  for (const auto& word : words) {
    for (const auto& phone : word.phones) {
      grammar += " " + std::string(kPhoneWordPrefix) + phone;
      if (std::find(distinct.begin(), distinct.end(), phone) == distinct.end()) distinct.push_back(phone);
    }
    grammar += " " + silence;
  }
  grammar += ";\n";
  for (size_t i = 0; i < distinct.size(); ++i) {
    // The last addition rebuilds the decoder's triphone tables for all of them.
    const std::string phoneWord = std::string(kPhoneWordPrefix) + distinct[i];
    if (ps_add_word(decoder, phoneWord.c_str(), distinct[i].c_str(), i + 1 == distinct.size()) < 0)
      return eng::makeError(eng::ErrorKind::Malformed, "align: the model has no phone " + distinct[i]);
  }
  if (ps_set_jsgf_string(decoder, "transcript", grammar.c_str()) < 0 || ps_set_search(decoder, "transcript") < 0)
    return eng::makeError(eng::ErrorKind::Io, "align: pocketsphinx refused the transcript grammar");
  return {};
}

std::vector<int16_t> paddedModelInput(const std::vector<float>& samples) {
  const size_t padding = size_t(kPaddingSeconds * kModelSampleRate);
  std::vector<int16_t> pcm(padding, 0);
  pcm.reserve(samples.size() + 2 * padding);
  for (float x : samples) pcm.push_back(int16_t(std::lround(std::clamp(std::isfinite(x) ? x : 0.0f, -1.0f, 1.0f) * 32767)));
  pcm.resize(pcm.size() + padding, 0);
  return pcm;
}

// The decoded phone segments (fillers and silences left out), as seconds in the unpadded recording.
TranscriptAlignment collectSegments(ps_decoder_t* decoder, int framesPerSecond, double duration, const std::vector<TranscriptWord>& words) {
  TranscriptAlignment out;
  for (ps_seg_t* seg = ps_seg_iter(decoder); seg; seg = ps_seg_next(seg)) {
    const std::string_view name = ps_seg_word(seg);
    if (name.substr(0, kPhoneWordPrefix.size()) != kPhoneWordPrefix || name == kSilenceWord) continue;
    int first = 0, last = 0;
    ps_seg_frames(seg, &first, &last);
    auto seconds = [&](int frame) { return std::clamp(double(frame) / framesPerSecond - kPaddingSeconds, 0.0, duration); };
    out.phonemes.push_back({std::string(arpabetToIpa(name.substr(kPhoneWordPrefix.size()))), seconds(first), seconds(last + 1)});
  }
  size_t next = 0;
  for (const auto& word : words) {
    if (next + word.phones.size() > out.phonemes.size()) break;
    out.words.push_back({word.text, out.phonemes[next].start, out.phonemes[next + word.phones.size() - 1].end});
    next += word.phones.size();
  }
  return out;
}

}  // namespace alignment_parts

using namespace alignment_parts;

std::string_view arpabetToIpa(std::string_view arpabet) {
  while (!arpabet.empty() && std::isdigit(static_cast<unsigned char>(arpabet.back()))) arpabet.remove_suffix(1);
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 39> table = {{
      {"AA", "ɑ"}, {"AE", "æ"}, {"AH", "ə"}, {"AO", "ɔ"}, {"AW", "aʊ"}, {"AY", "aɪ"}, {"B", "b"},   {"CH", "tʃ"},
      {"D", "d"},  {"DH", "ð"}, {"EH", "ɛ"}, {"ER", "ɝ"}, {"EY", "eɪ"}, {"F", "f"},   {"G", "ɡ"},   {"HH", "h"},
      {"IH", "ɪ"}, {"IY", "i"}, {"JH", "dʒ"}, {"K", "k"}, {"L", "l"},   {"M", "m"},   {"N", "n"},   {"NG", "ŋ"},
      {"OW", "oʊ"}, {"OY", "ɔɪ"}, {"P", "p"}, {"R", "ɹ"}, {"S", "s"},   {"SH", "ʃ"},  {"T", "t"},   {"TH", "θ"},
      {"UH", "ʊ"}, {"UW", "u"}, {"V", "v"},  {"W", "w"},  {"Y", "j"},   {"Z", "z"},   {"ZH", "ʒ"},
  }};
  for (const auto& [code, ipa] : table)
    if (code == arpabet) return ipa;
  return {};
}

eng::Result<TranscriptAlignment> alignTranscript(std::span<const float> samples, int sampleRate, std::string_view text) {
  if (samples.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "align: no samples");
  if (sampleRate < 8000 || sampleRate > 384000)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "align: sample rate " + std::to_string(sampleRate) + " Hz is outside 8000..384000");
  const double duration = double(samples.size()) / sampleRate;
  if (duration > kMaxAlignSeconds)
    return eng::makeError(eng::ErrorKind::TooLarge, "align: " + std::to_string(int(duration)) + " s of audio, over the limit of " +
                                                        std::to_string(int(kMaxAlignSeconds)) + " s");
  const std::vector<float> modelRate = ENG_TRY_VALUE(resampleMono(samples, sampleRate, kModelSampleRate));

  std::lock_guard lock(alignMutex);
  err_set_logfp(nullptr);  // sphinxbase logs every step on stderr otherwise
  auto [config, decoder] = ENG_TRY_VALUE(openDecoder());
  const std::vector<TranscriptWord> words = ENG_TRY_VALUE(lookUpWords(decoder.get(), text));
  ENG_TRY(setPhoneGrammar(decoder.get(), words));
  const std::vector<int16_t> pcm = paddedModelInput(modelRate);
  if (ps_start_utt(decoder.get()) < 0 || ps_process_raw(decoder.get(), pcm.data(), pcm.size(), FALSE, TRUE) < 0 ||
      ps_end_utt(decoder.get()) < 0)
    return eng::makeError(eng::ErrorKind::Io, "align: pocketsphinx failed to decode the recording");
  int32 score = 0;
  if (!ps_get_hyp(decoder.get(), &score))
    return eng::makeError(eng::ErrorKind::Malformed, "align: the recording does not fit the transcript (no alignment found)");
  TranscriptAlignment alignment = collectSegments(decoder.get(), cmd_ln_int32_r(config.get(), "-frate"), duration, words);
  if (alignment.words.size() != words.size())
    return eng::makeError(eng::ErrorKind::Malformed, "align: the recording does not fit the transcript (" +
                                                         std::to_string(alignment.words.size()) + " of " + std::to_string(words.size()) + " words aligned)");
  return alignment;
}

}  // namespace audio
