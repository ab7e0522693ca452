#include "engine/scene/gltf_sampler.h"

namespace eng {
namespace {

constexpr int kNearest = 9728, kLinear = 9729;
constexpr int kNearestMipmapNearest = 9984, kLinearMipmapNearest = 9985;
constexpr int kNearestMipmapLinear = 9986, kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071, kMirroredRepeat = 33648, kRepeat = 10497;

void note(std::string& problem, const std::string& what) { problem += (problem.empty() ? "" : ", ") + what; }

void wrapFromGltf(int code, const char* field, TextureWrap& out, std::string& problem) {
  switch (code) {
    case kRepeat: out = TextureWrap::Repeat; break;
    case kClampToEdge: out = TextureWrap::ClampToEdge; break;
    case kMirroredRepeat: out = TextureWrap::MirroredRepeat; break;
    default: note(problem, std::string(field) + " " + std::to_string(code));
  }
}

int wrapCode(TextureWrap wrap) {
  return wrap == TextureWrap::ClampToEdge ? kClampToEdge : wrap == TextureWrap::MirroredRepeat ? kMirroredRepeat : kRepeat;
}

}  // namespace

TextureSampling samplingFromGltf(const GltfSamplerCodes& codes, std::string& problem) {
  TextureSampling s;
  wrapFromGltf(codes.wrapS, "wrapS", s.wrapS, problem);
  wrapFromGltf(codes.wrapT, "wrapT", s.wrapT, problem);
  if (codes.magFilter == kNearest)
    s.magFilter = TextureFilter::Nearest;
  else if (codes.magFilter != kLinear && codes.magFilter != -1)
    note(problem, "magFilter " + std::to_string(codes.magFilter));
  const auto filter = [](bool nearest) { return nearest ? TextureFilter::Nearest : TextureFilter::Linear; };
  switch (codes.minFilter) {
    case -1: break;  // not given: trilinear, as three.js and most engines read it
    case kNearest:
    case kLinear:
      s.minFilter = filter(codes.minFilter == kNearest);
      s.mipmaps = false;
      break;
    case kNearestMipmapNearest:
    case kLinearMipmapNearest:
    case kNearestMipmapLinear:
    case kLinearMipmapLinear:
      s.minFilter = filter(codes.minFilter == kNearestMipmapNearest || codes.minFilter == kNearestMipmapLinear);
      s.mipFilter = filter(codes.minFilter == kNearestMipmapNearest || codes.minFilter == kLinearMipmapNearest);
      break;
    default: note(problem, "minFilter " + std::to_string(codes.minFilter));
  }
  return s;
}

GltfSamplerCodes gltfCodesOf(const TextureSampling& s) {
  GltfSamplerCodes c;
  c.magFilter = s.magFilter == TextureFilter::Nearest ? kNearest : kLinear;
  const bool nearestIn = s.minFilter == TextureFilter::Nearest, nearestBetween = s.mipFilter == TextureFilter::Nearest;
  if (!s.mipmaps)
    c.minFilter = nearestIn ? kNearest : kLinear;
  else if (nearestIn)
    c.minFilter = nearestBetween ? kNearestMipmapNearest : kNearestMipmapLinear;
  else
    c.minFilter = nearestBetween ? kLinearMipmapNearest : kLinearMipmapLinear;
  c.wrapS = wrapCode(s.wrapS);
  c.wrapT = wrapCode(s.wrapT);
  return c;
}

}  // namespace eng
