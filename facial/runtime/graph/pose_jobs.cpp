#include "facial/runtime/graph/pose_jobs.h"

#include <algorithm>
#include <cmath>

namespace facial {
namespace {

eng::Error invalid(std::string message) { return eng::makeError(eng::ErrorKind::InvalidArgument, std::move(message)); }

eng::Result<void> sizeMismatch(const char* job, const char* name, size_t size, size_t expected) {
  if (size == expected) return {};
  return invalid(std::string(job) + ": " + name + " has " + std::to_string(size) + " entries, out has " +
                 std::to_string(expected));
}

}  // namespace

eng::Result<void> LerpPoseJob::Validate() const {
  if (auto p = sizeMismatch("LerpPoseJob", "a", a.size(), out.size()); !p) return p;
  if (auto p = sizeMismatch("LerpPoseJob", "b", b.size(), out.size()); !p) return p;
  if (!std::isfinite(t)) return invalid("LerpPoseJob: t is not finite");
  return {};
}

bool LerpPoseJob::Run() const {
  if (!Validate().ok()) return false;  // allocates only to describe a failure
  const float s = 1.0f - t;
  for (size_t i = 0; i < out.size(); ++i) out[i] = s * a[i] + t * b[i];
  return true;
}

eng::Result<void> AccumulatePoseJob::Validate() const {
  if (auto p = sizeMismatch("AccumulatePoseJob", "input", input.size(), out.size()); !p) return p;
  if (!std::isfinite(weight)) return invalid("AccumulatePoseJob: weight is not finite");
  return {};
}

bool AccumulatePoseJob::Run() const {
  if (!Validate().ok()) return false;
  for (size_t i = 0; i < out.size(); ++i) out[i] += weight * input[i];
  return true;
}

eng::Result<void> BilinearPoseJob::Validate() const {
  if (auto p = sizeMismatch("BilinearPoseJob", "q11", q11.size(), out.size()); !p) return p;
  if (auto p = sizeMismatch("BilinearPoseJob", "q12", q12.size(), out.size()); !p) return p;
  if (auto p = sizeMismatch("BilinearPoseJob", "q21", q21.size(), out.size()); !p) return p;
  if (auto p = sizeMismatch("BilinearPoseJob", "q22", q22.size(), out.size()); !p) return p;
  if (!std::isfinite(s2) || !std::isfinite(t2)) return invalid("BilinearPoseJob: s2 or t2 is not finite");
  return {};
}

bool BilinearPoseJob::Run() const {
  if (!Validate().ok()) return false;
  const float s1 = 1.0f - s2, t1 = 1.0f - t2;
  for (size_t i = 0; i < out.size(); ++i)
    out[i] = s1 * (t1 * q11[i] + t2 * q12[i]) + s2 * (t1 * q21[i] + t2 * q22[i]);
  return true;
}

eng::Result<void> AdditivePoseJob::Validate() const {
  if (auto p = sizeMismatch("AdditivePoseJob", "base", base.size(), out.size()); !p) return p;
  if (auto p = sizeMismatch("AdditivePoseJob", "layer", layer.size(), out.size()); !p) return p;
  if (mask.size() > out.size())
    return invalid("AdditivePoseJob: mask has " + std::to_string(mask.size()) + " entries, more than out's " +
                   std::to_string(out.size()));
  if (!std::isfinite(weight)) return invalid("AdditivePoseJob: weight is not finite");
  return {};
}

bool AdditivePoseJob::Run() const {
  if (!Validate().ok()) return false;
  for (size_t i = 0; i < mask.size(); ++i)
    out[i] = std::clamp(base[i] + weight * mask[i] * layer[i], 0.0f, 1.0f);
  for (size_t i = mask.size(); i < out.size(); ++i) out[i] = base[i];
  return true;
}

}  // namespace facial
