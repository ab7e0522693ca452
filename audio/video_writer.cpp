#include "audio/video_writer.h"

#include "audio/resample.h"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/channel_layout.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "engine/scene/file_bytes.h"

namespace audio {
namespace {

std::string avErrorText(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return text;
}

}  // namespace

// Named (not anonymous): Impl, which has external linkage, holds them.
namespace video_handles {
struct CodecContextFree {
  void operator()(AVCodecContext* c) const { avcodec_free_context(&c); }
};
struct FrameFree {
  void operator()(AVFrame* f) const { av_frame_free(&f); }
};
struct PacketFree {
  void operator()(AVPacket* p) const { av_packet_free(&p); }
};
struct SwsFree {
  void operator()(SwsContext* s) const { sws_freeContext(s); }
};
struct OutputFree {
  void operator()(AVFormatContext* f) const {
    if (f->pb) avio_closep(&f->pb);
    avformat_free_context(f);
  }
};
}  // namespace video_handles
using namespace video_handles;

namespace {

struct ContainerChoice {
  const char* muxer;
  std::vector<const char*> videoEncoders, audioEncoders;  // first one found wins
};

// By extension: .mp4 H.264 + AAC, .webm VP9 (or VP8) + Opus (or Vorbis).
const ContainerChoice* containerFor(const std::filesystem::path& path) {
  static const ContainerChoice mp4{"mp4", {"libx264"}, {"aac"}};
  static const ContainerChoice webm{"webm", {"libvpx-vp9", "libvpx"}, {"libopus", "libvorbis"}};
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".mp4") return &mp4;
  if (ext == ".webm") return &webm;
  return nullptr;
}

const AVCodec* findEncoder(const std::vector<const char*>& names) {
  for (const char* name : names)
    if (const AVCodec* codec = avcodec_find_encoder_by_name(name)) return codec;
  return nullptr;
}

eng::Result<void> checkSettings(const std::string& name, const VideoSettings& s) {
  auto invalid = [&](std::string what) { return eng::makeError(eng::ErrorKind::InvalidArgument, name + ": " + what); };
  if (s.width < 16 || s.height < 16 || s.width > 8192 || s.height > 8192 || s.width % 2 || s.height % 2)
    return invalid("video size " + std::to_string(s.width) + "x" + std::to_string(s.height) + " must be even and within 16..8192");
  if (!(s.framesPerSecond >= 1 && s.framesPerSecond <= 240))
    return invalid(std::to_string(s.framesPerSecond) + " frames a second is outside 1..240");
  if (!s.audioSamples.empty() && (s.audioSampleRate < 8000 || s.audioSampleRate > 192000))
    return invalid("audio sample rate " + std::to_string(s.audioSampleRate) + " Hz is outside 8000..192000");
  if (!s.audioSamples.empty() && double(s.audioSamples.size()) / s.audioSampleRate > kMaxSoundtrackSeconds)
    return eng::makeError(eng::ErrorKind::TooLarge, name + ": over " + std::to_string(int(kMaxSoundtrackSeconds / 60)) + " minutes of audio");
  return {};
}

// The encoder's preferred rate: the source's when it takes it, else 48 kHz (Opus takes only that).
int encoderSampleRate(const AVCodec* codec, int sourceRate) {
  if (!codec->supported_samplerates) return sourceRate;
  for (const int* rate = codec->supported_samplerates; *rate; ++rate)
    if (*rate == sourceRate) return sourceRate;
  return 48000;
}

// Float or 16-bit, packed or planar (one channel: the same layout), the first one the encoder lists.
AVSampleFormat encoderSampleFormat(const AVCodec* codec) {
  for (const AVSampleFormat* f = codec->sample_fmts; f && *f != AV_SAMPLE_FMT_NONE; ++f)
    if (*f == AV_SAMPLE_FMT_FLT || *f == AV_SAMPLE_FMT_FLTP || *f == AV_SAMPLE_FMT_S16 || *f == AV_SAMPLE_FMT_S16P) return *f;
  return AV_SAMPLE_FMT_NONE;
}

// libx264 and the AAC encoder report their settings and statistics at the
// default (info) level on stderr; a program's own log says what it wrote.
// Errors still print. A level someone chose (not the default) is kept.
void quietenEncoderLogs() {
  static std::once_flag once;
  std::call_once(once, [] {
    if (av_log_get_level() == AV_LOG_INFO) av_log_set_level(AV_LOG_ERROR);
  });
}

}  // namespace

struct VideoWriter::Impl {
  std::filesystem::path path, partialPath;
  std::string name;
  VideoSettings settings;
  std::unique_ptr<AVFormatContext, OutputFree> output;
  std::unique_ptr<AVCodecContext, CodecContextFree> video, sound;
  AVStream* videoStream = nullptr;
  AVStream* soundStream = nullptr;
  std::unique_ptr<SwsContext, SwsFree> scaler;
  std::unique_ptr<AVFrame, FrameFree> picture, soundFrame;
  std::unique_ptr<AVPacket, PacketFree> packet;
  std::vector<float> soundtrack;  // mono, at the sound encoder's rate
  size_t soundWritten = 0;        // samples of `soundtrack` sent to the encoder
  int64_t framesWritten = 0;
  bool open = false;              // header written, trailer not yet

  // The encoder thread: addFrame() copies each frame into a free slot and
  // returns, so the caller renders the next frame while this one is converted,
  // encoded and muxed. The slots are allocated once; a full queue blocks addFrame().
  std::array<std::vector<uint8_t>, 3> slots;
  size_t firstQueued = 0, queued = 0;  // the queued slots, in order, wrapping
  bool closing = false;                // no more frames: the thread ends once the queue is empty
  eng::Result<void> encoded;           // the encoder thread's first error (later frames are dropped)
  std::mutex mutex;
  std::condition_variable changed;
  std::thread encoder;

  ~Impl() {
    (void)stopEncoder(/*dropQueued=*/true);  // abandoned: the partial file goes below, its error with it
    if (!output) return;
    output.reset();
    std::error_code ignored;
    std::filesystem::remove(partialPath, ignored);
  }

  eng::Error fail(const AVCodecContext* codec, const std::string& what, int code) const {
    const std::string codecName = codec ? std::string(" (") + codec->codec->name + ")" : "";
    return eng::makeError(eng::ErrorKind::Io, name + ": " + what + codecName + ": " + avErrorText(code));
  }
  eng::Result<void> openVideo(const ContainerChoice& choice);
  eng::Result<void> openSound(const ContainerChoice& choice);
  eng::Result<void> resampleSoundtrack();
  eng::Result<void> drain(AVCodecContext* codec, AVStream* stream);
  eng::Result<void> sendSound(int64_t untilSample);
  eng::Result<void> encodeFrame(const std::vector<uint8_t>& rgba8);
  void encodeQueued();
  eng::Result<void> stopEncoder(bool dropQueued);
  eng::Result<void> queueFrame(std::span<const uint8_t> rgba8);
};

eng::Result<void> VideoWriter::Impl::openVideo(const ContainerChoice& choice) {
  const AVCodec* codec = findEncoder(choice.videoEncoders);
  if (!codec)
    return eng::makeError(eng::ErrorKind::Unsupported, name + ": this libavcodec has no " + choice.videoEncoders.front() + " encoder");
  video.reset(avcodec_alloc_context3(codec));
  const AVRational frameRate = av_d2q(settings.framesPerSecond, 100000);
  video->width = settings.width;
  video->height = settings.height;
  video->pix_fmt = AV_PIX_FMT_YUV420P;  // what players everywhere decode
  video->time_base = av_inv_q(frameRate);
  video->framerate = frameRate;
  video->gop_size = std::max(1, int(std::lround(settings.framesPerSecond * 2)));
  if (output->oformat->flags & AVFMT_GLOBALHEADER) video->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (codec->id == AV_CODEC_ID_H264) {
    av_opt_set(video->priv_data, "crf", "20", 0);  // visually clean faces at modest size
    av_opt_set(video->priv_data, "preset", "veryfast", 0);
  } else {
    av_opt_set(video->priv_data, "crf", "32", 0);  // libvpx: constant quality needs bit_rate 0
    av_opt_set(video->priv_data, "deadline", "realtime", 0);
    av_opt_set(video->priv_data, "cpu-used", "8", 0);
    video->bit_rate = 0;
  }
  if (int rc = avcodec_open2(video.get(), codec, nullptr); rc < 0) return fail(video.get(), "cannot open the video encoder", rc);
  videoStream = avformat_new_stream(output.get(), nullptr);
  if (!videoStream) return fail(video.get(), "cannot add the video stream", AVERROR(ENOMEM));
  videoStream->time_base = video->time_base;
  videoStream->avg_frame_rate = frameRate;
  if (int rc = avcodec_parameters_from_context(videoStream->codecpar, video.get()); rc < 0)
    return fail(video.get(), "cannot describe the video stream", rc);
  picture.reset(av_frame_alloc());
  picture->format = video->pix_fmt;
  picture->width = video->width;
  picture->height = video->height;
  if (int rc = av_frame_get_buffer(picture.get(), 0); rc < 0) return fail(video.get(), "cannot allocate a frame", rc);
  scaler.reset(sws_getContext(settings.width, settings.height, AV_PIX_FMT_RGBA, settings.width, settings.height,
                              AV_PIX_FMT_YUV420P, SWS_BILINEAR, nullptr, nullptr, nullptr));
  if (!scaler) return fail(video.get(), "cannot set up RGBA to YUV conversion", AVERROR(EINVAL));
  return {};
}

eng::Result<void> VideoWriter::Impl::openSound(const ContainerChoice& choice) {
  const AVCodec* codec = findEncoder(choice.audioEncoders);
  if (!codec)
    return eng::makeError(eng::ErrorKind::Unsupported, name + ": this libavcodec has no " + choice.audioEncoders.front() + " encoder");
  sound.reset(avcodec_alloc_context3(codec));
  sound->sample_fmt = encoderSampleFormat(codec);
  if (sound->sample_fmt == AV_SAMPLE_FMT_NONE)
    return eng::makeError(eng::ErrorKind::Unsupported, name + ": the " + codec->name + " encoder takes no float or 16-bit samples");
  sound->sample_rate = encoderSampleRate(codec, settings.audioSampleRate);
  av_channel_layout_default(&sound->ch_layout, 1);
  sound->bit_rate = 96000;  // speech, mono
  sound->time_base = AVRational{1, sound->sample_rate};
  if (output->oformat->flags & AVFMT_GLOBALHEADER) sound->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
  if (int rc = avcodec_open2(sound.get(), codec, nullptr); rc < 0) return fail(sound.get(), "cannot open the audio encoder", rc);
  soundStream = avformat_new_stream(output.get(), nullptr);
  if (!soundStream) return fail(sound.get(), "cannot add the audio stream", AVERROR(ENOMEM));
  soundStream->time_base = sound->time_base;
  if (int rc = avcodec_parameters_from_context(soundStream->codecpar, sound.get()); rc < 0)
    return fail(sound.get(), "cannot describe the audio stream", rc);
  soundFrame.reset(av_frame_alloc());
  soundFrame->format = sound->sample_fmt;
  soundFrame->sample_rate = sound->sample_rate;
  av_channel_layout_copy(&soundFrame->ch_layout, &sound->ch_layout);
  // Variable-frame-size encoders (none of ours, but allowed) get 20 ms.
  soundFrame->nb_samples = sound->frame_size > 0 ? sound->frame_size : sound->sample_rate / 50;
  if (int rc = av_frame_get_buffer(soundFrame.get(), 0); rc < 0) return fail(sound.get(), "cannot allocate an audio frame", rc);
  return resampleSoundtrack();
}

eng::Result<void> VideoWriter::Impl::resampleSoundtrack() {
  auto resampled = resampleMono(settings.audioSamples, settings.audioSampleRate, sound->sample_rate);
  if (!resampled) return resampled.error().prefixed(name + ": ");
  soundtrack = std::move(resampled).value();
  return {};
}

// Writes every packet the encoder has ready.
eng::Result<void> VideoWriter::Impl::drain(AVCodecContext* codec, AVStream* stream) {
  for (;;) {
    const int rc = avcodec_receive_packet(codec, packet.get());
    if (rc == AVERROR(EAGAIN) || rc == AVERROR_EOF) return {};
    if (rc < 0) return fail(codec, "encoding failed", rc);
    av_packet_rescale_ts(packet.get(), codec->time_base, stream->time_base);
    packet->stream_index = stream->index;
    if (int wrc = av_interleaved_write_frame(output.get(), packet.get()); wrc < 0) return fail(codec, "writing failed", wrc);
  }
}

// Encodes the soundtrack up to `untilSample` (whole encoder frames; the last one padded with silence).
eng::Result<void> VideoWriter::Impl::sendSound(int64_t untilSample) {
  if (!sound) return {};
  const size_t until = size_t(std::clamp<int64_t>(untilSample, 0, int64_t(soundtrack.size())));
  while (soundWritten < until) {
    if (int rc = av_frame_make_writable(soundFrame.get()); rc < 0) return fail(sound.get(), "cannot reuse the audio frame", rc);
    const size_t count = std::min(size_t(soundFrame->nb_samples), soundtrack.size() - soundWritten);
    const bool isFloat = sound->sample_fmt == AV_SAMPLE_FMT_FLT || sound->sample_fmt == AV_SAMPLE_FMT_FLTP;
    for (int i = 0; i < soundFrame->nb_samples; ++i) {
      const float x = size_t(i) < count ? std::clamp(soundtrack[soundWritten + i], -1.0f, 1.0f) : 0.0f;
      if (isFloat) reinterpret_cast<float*>(soundFrame->data[0])[i] = x;
      else reinterpret_cast<int16_t*>(soundFrame->data[0])[i] = int16_t(std::lround(x * 32767));
    }
    soundFrame->pts = int64_t(soundWritten);
    soundWritten += count;
    if (int rc = avcodec_send_frame(sound.get(), soundFrame.get()); rc < 0) return fail(sound.get(), "encoding audio failed", rc);
    ENG_TRY(drain(sound.get(), soundStream));
  }
  return {};
}

VideoWriter::VideoWriter(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
VideoWriter::VideoWriter(VideoWriter&&) noexcept = default;
VideoWriter& VideoWriter::operator=(VideoWriter&&) noexcept = default;
VideoWriter::~VideoWriter() = default;

eng::Result<VideoWriter> VideoWriter::create(const std::filesystem::path& path, const VideoSettings& settings) {
  quietenEncoderLogs();
  const std::string name = path.string();
  const ContainerChoice* choice = containerFor(path);
  if (!choice) return eng::makeError(eng::ErrorKind::Unsupported, name + ": video files end in .mp4 or .webm");
  ENG_TRY(checkSettings(name, settings));
  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->name = name;
  impl->partialPath = name + ".partial";
  impl->settings = settings;
  impl->packet.reset(av_packet_alloc());
  AVFormatContext* raw = nullptr;
  const std::string partial = impl->partialPath.string();
  if (int rc = avformat_alloc_output_context2(&raw, nullptr, choice->muxer, partial.c_str()); rc < 0 || !raw)
    return impl->fail(nullptr, std::string("cannot set up the ") + choice->muxer + " container", rc);
  impl->output.reset(raw);
  ENG_TRY(impl->openVideo(*choice));
  if (!settings.audioSamples.empty()) ENG_TRY(impl->openSound(*choice));
  impl->settings.audioSamples = {};  // copied into `soundtrack`; the caller's span may go
  if (int rc = avio_open(&impl->output->pb, partial.c_str(), AVIO_FLAG_WRITE); rc < 0)
    return impl->fail(nullptr, "cannot create the file", rc);
  if (int rc = avformat_write_header(impl->output.get(), nullptr); rc < 0)
    return impl->fail(nullptr, std::string("cannot write the ") + choice->muxer + " header", rc);
  impl->open = true;
  for (std::vector<uint8_t>& slot : impl->slots) slot.resize(size_t(settings.width) * settings.height * 4);
  Impl* encoding = impl.get();  // stable: the writer moves the pointer, not the Impl
  impl->encoder = std::thread([encoding] { encoding->encodeQueued(); });
  return VideoWriter(std::move(impl));
}

// Converts, encodes and muxes one frame, with the sound up to its end (on the encoder thread).
eng::Result<void> VideoWriter::Impl::encodeFrame(const std::vector<uint8_t>& rgba8) {
  if (int rc = av_frame_make_writable(picture.get()); rc < 0) return fail(video.get(), "cannot reuse the frame", rc);
  const uint8_t* source[1] = {rgba8.data()};
  const int sourceStride[1] = {settings.width * 4};
  sws_scale(scaler.get(), source, sourceStride, 0, settings.height, picture->data, picture->linesize);
  picture->pts = framesWritten++;
  if (int rc = avcodec_send_frame(video.get(), picture.get()); rc < 0) return fail(video.get(), "encoding video failed", rc);
  ENG_TRY(drain(video.get(), videoStream));
  // Sound up to the end of this frame, so the muxer interleaves as it goes.
  if (sound) ENG_TRY(sendSound(av_rescale_q(framesWritten, video->time_base, sound->time_base)));
  return {};
}

// The encoder thread's loop: the queue's frames in order until closing; after an error it only empties the queue.
void VideoWriter::Impl::encodeQueued() {
  std::unique_lock lock(mutex);
  for (;;) {
    changed.wait(lock, [&] { return queued > 0 || closing; });
    if (queued == 0) return;
    const size_t slot = firstQueued;
    const bool healthy = bool(encoded);
    lock.unlock();
    eng::Result<void> done = healthy ? encodeFrame(slots[slot]) : eng::Result<void>{};
    lock.lock();
    if (!done && encoded) encoded = std::move(done);
    firstQueued = (firstQueued + 1) % slots.size();
    --queued;
    changed.notify_all();
  }
}

// Ends the encoder thread: after the queued frames, or at once dropping them (a writer given up).
eng::Result<void> VideoWriter::Impl::stopEncoder(bool dropQueued) {
  if (!encoder.joinable()) return encoded;
  {
    std::lock_guard lock(mutex);
    closing = true;
    if (dropQueued && encoded) encoded = eng::makeError(eng::ErrorKind::Io, name + ": video abandoned");
  }
  changed.notify_all();
  encoder.join();
  return encoded;
}

eng::Result<void> VideoWriter::Impl::queueFrame(std::span<const uint8_t> rgba8) {
  std::unique_lock lock(mutex);
  changed.wait(lock, [&] { return queued < slots.size() || !encoded; });
  if (!encoded) return encoded;
  // The slot after the queued ones: the encoder thread does not touch it until it is queued.
  const size_t slot = (firstQueued + queued) % slots.size();
  lock.unlock();
  std::memcpy(slots[slot].data(), rgba8.data(), rgba8.size());
  lock.lock();
  ++queued;
  changed.notify_all();
  return {};
}

eng::Result<void> VideoWriter::addFrame(std::span<const uint8_t> rgba8) {
  Impl& s = *impl_;
  if (!s.open) return eng::makeError(eng::ErrorKind::InvalidArgument, s.name + ": video already finished");
  const size_t expected = size_t(s.settings.width) * s.settings.height * 4;
  if (rgba8.size() != expected)
    return eng::makeError(eng::ErrorKind::InvalidArgument, s.name + ": video frame has " + std::to_string(rgba8.size()) +
                                                               " bytes, expected " + std::to_string(expected));
  return s.queueFrame(rgba8);
}

eng::Result<void> VideoWriter::finish() {
  Impl& s = *impl_;
  if (!s.open) return {};
  s.open = false;
  ENG_TRY(s.stopEncoder(/*dropQueued=*/false));
  if (s.sound) {
    ENG_TRY(s.sendSound(int64_t(s.soundtrack.size())));
    if (int rc = avcodec_send_frame(s.sound.get(), nullptr); rc < 0) return s.fail(s.sound.get(), "flushing audio failed", rc);
    ENG_TRY(s.drain(s.sound.get(), s.soundStream));
  }
  if (int rc = avcodec_send_frame(s.video.get(), nullptr); rc < 0) return s.fail(s.video.get(), "flushing video failed", rc);
  ENG_TRY(s.drain(s.video.get(), s.videoStream));
  if (int rc = av_write_trailer(s.output.get()); rc < 0) return s.fail(nullptr, "cannot finish the file", rc);
  if (int rc = avio_closep(&s.output->pb); rc < 0) return s.fail(nullptr, "cannot close the file", rc);
  s.output.reset();
  return eng::commitPartialFile(s.partialPath, s.path);
}

}  // namespace audio
