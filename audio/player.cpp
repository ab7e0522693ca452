#include "audio/player.h"

#include <alsa/asoundlib.h>
#include <jack/jack.h>
#include <portaudio.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

namespace audio {
constexpr double kMaxPlaySeconds = 30 * 60;

// Named (not anonymous): Impl, which has external linkage, holds them.
namespace player_parts {

// Where the sound card is: the frame that the callback's buffer starts with
// and the stream time at which that frame reaches the speaker. Written by the
// audio thread, read by the caller's; a sequence count makes the pair consistent.
struct AudioClockMark {
  std::atomic<uint64_t> sequence{0};
  std::atomic<int64_t> bufferFirstFrame{0};
  std::atomic<double> bufferDacTime{0};

  void write(int64_t frame, double dacTime) {
    sequence.fetch_add(1, std::memory_order_acq_rel);
    bufferFirstFrame.store(frame, std::memory_order_relaxed);
    bufferDacTime.store(dacTime, std::memory_order_relaxed);
    sequence.fetch_add(1, std::memory_order_acq_rel);
  }
  std::pair<int64_t, double> read() const {
    for (;;) {
      const uint64_t before = sequence.load(std::memory_order_acquire);
      const int64_t frame = bufferFirstFrame.load(std::memory_order_relaxed);
      const double dac = bufferDacTime.load(std::memory_order_relaxed);
      if (!(before & 1) && sequence.load(std::memory_order_acquire) == before) return {frame, dac};
    }
  }
};

void ignoreAlsaMessage(const char*, int, const char*, int, const char*, ...) {}
void ignoreJackMessage(const char*) {}

// PortAudio probes ALSA and JACK when it starts; both print a dozen lines on
// stderr when there is no card or no server (CI, ssh), which would bury the
// one note the caller prints. Their messages are dropped for the whole
// process: the programs use the sound card only through this player.
void quietenAudioBackends() {
  static std::once_flag once;
  std::call_once(once, [] {
    snd_lib_error_set_handler(&ignoreAlsaMessage);
    jack_set_error_function(&ignoreJackMessage);
    jack_set_info_function(&ignoreJackMessage);
  });
}

struct StreamCloser {
  void operator()(PaStream* stream) const {
    Pa_AbortStream(stream);
    Pa_CloseStream(stream);
  }
};

}  // namespace player_parts
using namespace player_parts;

struct Player::Impl {
  bool portAudioStarted = false;  // Pa_Initialize succeeded: Pa_Terminate in the destructor
  std::string note;
  std::vector<float> clip;
  int sampleRate = 0;
  std::unique_ptr<PaStream, StreamCloser> stream;  // only with sound
  std::atomic<int64_t> framesWritten{0};           // handed to the card so far
  AudioClockMark mark;
  double outputLatency = 0;
  // The silent clock, and a stopped clip's frozen time.
  std::chrono::steady_clock::time_point silentStart;
  bool playing = false;
  double stoppedAt = 0;

  ~Impl() {
    stream.reset();
    if (portAudioStarted) Pa_Terminate();
  }
  double clipSeconds() const { return sampleRate > 0 ? double(clip.size()) / sampleRate : 0.0; }

  static int fill(const void*, void* output, unsigned long frames, const PaStreamCallbackTimeInfo* time,
                  PaStreamCallbackFlags, void* user) {
    auto* self = static_cast<Impl*>(user);
    auto* out = static_cast<float*>(output);
    const int64_t first = self->framesWritten.load(std::memory_order_relaxed);
    self->mark.write(first, time ? time->outputBufferDacTime : 0.0);
    for (unsigned long i = 0; i < frames; ++i) {
      const size_t index = size_t(first) + i;
      out[i] = index < self->clip.size() ? self->clip[index] : 0.0f;  // silence after the end keeps the clock going
    }
    self->framesWritten.store(first + int64_t(frames), std::memory_order_relaxed);
    return paContinue;
  }

  // Time of the sample at the speaker: the last buffer's first frame plus the
  // time since it reached the speaker; hosts that give no DAC time (0) fall
  // back to frames written less the output latency.
  double soundClock() const {
    const auto [frame, dacTime] = mark.read();
    double seconds;
    if (dacTime > 0) seconds = double(frame) / sampleRate + (Pa_GetStreamTime(stream.get()) - dacTime);
    else seconds = double(framesWritten.load(std::memory_order_relaxed)) / sampleRate - outputLatency;
    return seconds;
  }
};

Player::Player(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Player::Player(Player&&) noexcept = default;
Player& Player::operator=(Player&&) noexcept = default;
Player::~Player() = default;

Player Player::open(const PlayerOptions& options) {
  auto impl = std::make_unique<Impl>();
  if (options.silent) {
    impl->note = "sound off: silent player asked for";
    return Player(std::move(impl));
  }
  quietenAudioBackends();
  if (PaError rc = Pa_Initialize(); rc != paNoError) {
    impl->note = std::string("sound off: cannot start PortAudio (") + Pa_GetErrorText(rc) + ")";
    return Player(std::move(impl));
  }
  impl->portAudioStarted = true;
  if (Pa_GetDeviceCount() <= 0 || Pa_GetDefaultOutputDevice() == paNoDevice) {
    impl->note = "sound off: no audio output device";
    return Player(std::move(impl));
  }
  // A device can be listed and still refuse to open (busy, a dead server): try it now.
  PaStream* probe = nullptr;
  if (PaError rc = Pa_OpenDefaultStream(&probe, 0, 1, paFloat32, 48000, paFramesPerBufferUnspecified, nullptr, nullptr);
      rc != paNoError)
    impl->note = std::string("sound off: cannot open the default output (") + Pa_GetErrorText(rc) + ")";
  else
    Pa_CloseStream(probe);
  return Player(std::move(impl));
}

bool Player::hasSound() const { return impl_->note.empty(); }
const std::string& Player::note() const { return impl_->note; }

eng::Result<void> Player::play(std::span<const float> samples, int sampleRate) {
  if (sampleRate < 8000 || sampleRate > 192000)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "player: sample rate " + std::to_string(sampleRate) + " Hz is outside 8000..192000");
  if (samples.empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "player: no samples to play");
  if (double(samples.size()) / sampleRate > kMaxPlaySeconds)
    return eng::makeError(eng::ErrorKind::TooLarge, "player: over " + std::to_string(int(kMaxPlaySeconds / 60)) + " minutes of audio");
  Impl& s = *impl_;
  stop();
  s.clip.assign(samples.begin(), samples.end());
  s.sampleRate = sampleRate;
  s.framesWritten = 0;
  s.mark.write(0, 0.0);
  s.stoppedAt = 0;
  if (hasSound()) {
    PaStream* raw = nullptr;
    if (PaError rc = Pa_OpenDefaultStream(&raw, 0, 1, paFloat32, sampleRate, paFramesPerBufferUnspecified, &Impl::fill, &s);
        rc != paNoError) {
      s.note = "sound off: the default output refuses " + std::to_string(sampleRate) + " Hz (" + Pa_GetErrorText(rc) + ")";
    } else {
      s.stream.reset(raw);
      if (const PaStreamInfo* info = Pa_GetStreamInfo(raw)) s.outputLatency = info->outputLatency;
      if (PaError started = Pa_StartStream(raw); started != paNoError) {
        s.stream.reset();
        s.note = std::string("sound off: cannot start the default output (") + Pa_GetErrorText(started) + ")";
      }
    }
  }
  s.silentStart = std::chrono::steady_clock::now();
  s.playing = true;
  return {};
}

double Player::clockSeconds() const {
  const Impl& s = *impl_;
  if (!s.playing) return s.stoppedAt;
  double seconds;
  if (s.stream) seconds = s.soundClock();
  else seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - s.silentStart).count();
  return std::clamp(seconds, 0.0, s.clipSeconds());
}

bool Player::finished() const { return !impl_->playing || clockSeconds() >= impl_->clipSeconds(); }

void Player::stop() {
  Impl& s = *impl_;
  if (!s.playing) return;
  s.stoppedAt = clockSeconds();
  s.playing = false;
  s.stream.reset();
}

}  // namespace audio
