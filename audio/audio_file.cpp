#include "audio/audio_file.h"

#include <sndfile.h>

#include <memory>
#include <string>
#include <system_error>

#include "engine/scene/file_bytes.h"

namespace audio {
namespace {

struct SndfileCloser {
  void operator()(SNDFILE* file) const { sf_close(file); }
};
using SndfileHandle = std::unique_ptr<SNDFILE, SndfileCloser>;

constexpr sf_count_t kReadBlockFrames = 4096;

// Why sf_open failed. libsndfile's own text for a probe that found no format
// is sometimes a stale system error ("File does not exist"), so the common
// cases get words of their own.
std::string openFailure() {
  switch (sf_error(nullptr)) {
    case SF_ERR_UNRECOGNISED_FORMAT: return "not WAV, FLAC, OGG (Vorbis, Opus) or MP3";
    case SF_ERR_MALFORMED_FILE: return "the header is damaged";
    case SF_ERR_UNSUPPORTED_ENCODING: return "its encoding is not supported";
    default: return "not a recognised audio format, or damaged";
  }
}

}  // namespace

eng::Result<AudioClip> readAudioFile(const std::filesystem::path& path) {
  const std::string name = path.string();
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return eng::makeError(eng::ErrorKind::NotFound, name + ": no such audio file");
  if (std::filesystem::is_directory(path, ec)) return eng::makeError(eng::ErrorKind::Io, name + ": is a folder, not an audio file");
  SF_INFO info{};
  SndfileHandle file(sf_open(name.c_str(), SFM_READ, &info));
  if (!file) return eng::makeError(eng::ErrorKind::Malformed, name + ": cannot read as audio: " + openFailure());
  if (info.channels <= 0 || info.samplerate <= 0)
    return eng::makeError(eng::ErrorKind::Malformed, name + ": audio header has " + std::to_string(info.channels) + " channels at " +
                                                         std::to_string(info.samplerate) + " Hz");
  const sf_count_t maxFrames = static_cast<sf_count_t>(kMaxAudioFileSeconds * info.samplerate);
  if (info.frames > maxFrames && info.frames != SF_COUNT_MAX)
    return eng::makeError(eng::ErrorKind::TooLarge, name + ": " + std::to_string(info.frames / info.samplerate) +
                                                        " s of audio, over the limit of " + std::to_string(int(kMaxAudioFileSeconds)) + " s");
  // Integer files scaled to -1..1; clipping on float files that go past it.
  sf_command(file.get(), SFC_SET_NORM_FLOAT, nullptr, SF_TRUE);

  AudioClip clip;
  clip.sampleRate = info.samplerate;
  // Read in blocks: the header's frame count may be wrong (MP3, a truncated WAV).
  std::vector<float> block(static_cast<size_t>(kReadBlockFrames) * info.channels);
  for (;;) {
    const sf_count_t frames = sf_readf_float(file.get(), block.data(), kReadBlockFrames);
    if (frames <= 0) break;
    for (sf_count_t f = 0; f < frames; ++f) {
      float sum = 0;
      for (int c = 0; c < info.channels; ++c) sum += block[static_cast<size_t>(f) * info.channels + c];
      clip.samples.push_back(sum / info.channels);
    }
    if (static_cast<sf_count_t>(clip.samples.size()) > maxFrames)
      return eng::makeError(eng::ErrorKind::TooLarge, name + ": over the limit of " + std::to_string(int(kMaxAudioFileSeconds)) + " s of audio");
  }
  if (sf_error(file.get()) != SF_ERR_NO_ERROR)
    return eng::makeError(eng::ErrorKind::Malformed, name + ": audio data is damaged: " + sf_strerror(file.get()));
  if (clip.samples.empty()) return eng::makeError(eng::ErrorKind::Malformed, name + ": the audio file has no samples");
  return clip;
}

eng::Result<void> writeWavFile(const std::filesystem::path& path, std::span<const float> samples, int sampleRate) {
  const std::string name = path.string();
  if (sampleRate <= 0) return eng::makeError(eng::ErrorKind::InvalidArgument, name + ": sample rate " + std::to_string(sampleRate) + " Hz");
  const std::filesystem::path partial = eng::partialPathFor(path);
  SF_INFO info{.samplerate = sampleRate, .channels = 1, .format = SF_FORMAT_WAV | SF_FORMAT_PCM_16};
  {
    SndfileHandle file(sf_open(partial.c_str(), SFM_WRITE, &info));
    if (!file) return eng::makeError(eng::ErrorKind::Io, name + ": cannot write: " + sf_strerror(nullptr));
    // Floats past -1..1 clip instead of wrapping around.
    sf_command(file.get(), SFC_SET_CLIPPING, nullptr, SF_TRUE);
    const auto count = static_cast<sf_count_t>(samples.size());
    if (sf_writef_float(file.get(), samples.data(), count) != count) {
      const std::string why = sf_strerror(file.get());
      file.reset();
      std::filesystem::remove(partial);
      return eng::makeError(eng::ErrorKind::Io, name + ": cannot write: " + why);
    }
  }
  ENG_TRY(eng::commitPartialFile(partial, path));
  return {};
}

}  // namespace audio
