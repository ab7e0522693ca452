#include "audio/resample.h"

extern "C" {
#include <libavutil/channel_layout.h>
#include <libavutil/error.h>
#include <libavutil/mathematics.h>
#include <libswresample/swresample.h>
}

#include <memory>
#include <string>

namespace audio {
namespace {

struct ResamplerFree {
  void operator()(SwrContext* s) const { swr_free(&s); }
};

eng::Error resampleError(int fromRate, int toRate, int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof(text));
  return eng::makeError(eng::ErrorKind::Io, "resampling " + std::to_string(fromRate) + " Hz to " + std::to_string(toRate) + " Hz failed: " + text);
}

}  // namespace

eng::Result<std::vector<float>> resampleMono(std::span<const float> samples, int fromRate, int toRate) {
  if (fromRate < 1000 || fromRate > 384000 || toRate < 1000 || toRate > 384000)
    return eng::makeError(eng::ErrorKind::InvalidArgument, "resampling " + std::to_string(fromRate) + " Hz to " + std::to_string(toRate) +
                                                               " Hz: rates must be within 1000..384000");
  if (fromRate == toRate || samples.empty()) return std::vector<float>(samples.begin(), samples.end());
  AVChannelLayout mono = AV_CHANNEL_LAYOUT_MONO;
  SwrContext* raw = nullptr;
  if (int rc = swr_alloc_set_opts2(&raw, &mono, AV_SAMPLE_FMT_FLT, toRate, &mono, AV_SAMPLE_FMT_FLT, fromRate, 0, nullptr); rc < 0)
    return resampleError(fromRate, toRate, rc);
  std::unique_ptr<SwrContext, ResamplerFree> resampler(raw);
  if (int rc = swr_init(resampler.get()); rc < 0) return resampleError(fromRate, toRate, rc);
  std::vector<float> out(size_t(av_rescale_rnd(int64_t(samples.size()), toRate, fromRate, AV_ROUND_UP)) + 256);
  uint8_t* outPlanes[1] = {reinterpret_cast<uint8_t*>(out.data())};
  const uint8_t* inPlanes[1] = {reinterpret_cast<const uint8_t*>(samples.data())};
  const int converted = swr_convert(resampler.get(), outPlanes, int(out.size()), inPlanes, int(samples.size()));
  if (converted < 0) return resampleError(fromRate, toRate, converted);
  // The filter's delay: what it still holds comes out when flushed.
  uint8_t* tail[1] = {reinterpret_cast<uint8_t*>(out.data() + converted)};
  const int flushed = swr_convert(resampler.get(), tail, int(out.size()) - converted, nullptr, 0);
  if (flushed < 0) return resampleError(fromRate, toRate, flushed);
  out.resize(size_t(converted) + size_t(flushed));
  return out;
}

}  // namespace audio
