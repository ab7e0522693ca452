#include "autorig/target_transfer.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string_view>

#include <glm/gtx/compatibility.hpp>

#include "autorig/arkit_from_units.h"
#include "autorig/dense_correspondence.h"
#include "autorig/face_frame.h"
#include "autorig/jaw_hinge.h"
#include "engine/scene/normals.h"
#include "facial/runtime/rig/arkit_names.h"

namespace autorig {
namespace {

// Landmarks farther than this from the face's skin (eye spans) are off it;
// more than kMaxOffSurface of them and the landmarks are not this face's.
constexpr float kOffSurface = 0.2f;
constexpr size_t kMaxOffSurface = 10;
// A matched target vertex takes the whole displacement up to kFullGap from
// the warped source and none beyond the correspondence's maxGap (eye spans):
// lashes a little off the skin follow, a shoulder does not.
constexpr float kFullGap = 0.05f;
// The lid constraint: within kLidInner eyeball radii of the centre a vertex
// keeps its distance to it; it fades out by kLidOuter.
constexpr float kLidInner = 1.25f, kLidOuter = 1.7f;
// Units that open the jaw: the lower teeth and tongue turn with them.
constexpr std::array<std::string_view, 2> kJawUnits{"AU26_JawDrop", "AU27_MouthStretch"};
// Finite-difference step of the warp's Jacobian, in source eye spans (about
// a millimetre: smooth over the biharmonic kernel's kinks at control points).
constexpr float kJacobianStep = 0.01f;

bool sameName(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) == std::tolower(static_cast<unsigned char>(y));
         });
}

std::string describeLandmarks(const char* whose) { return std::string(whose) + " landmarks: "; }

eng::Result<void> checkLandmarks(const FaceLandmarks& landmarks, const char* whose) {
  glm::dvec3 mean(0.0);
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const glm::vec3& p = landmarks.points[i];
    if (!std::isfinite(p.x + p.y + p.z))
      return eng::makeError(eng::ErrorKind::InvalidArgument,
                            describeLandmarks(whose) + "point " + std::to_string(i) + " of 68 is not finite");
    mean += glm::dvec3(p);
  }
  mean /= double(kLandmarkCount);
  double spread = 0.0;
  for (const glm::vec3& p : landmarks.points) spread = std::max(spread, glm::length(glm::dvec3(p) - mean));
  const float eyeSpan = glm::length(landmarks.points[45] - landmarks.points[36]);
  if (!(spread > 1e-6) || !(eyeSpan > 1e-3f * float(spread)))
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          describeLandmarks(whose) + "collapsed: the 68 points lie within " + std::to_string(spread) +
                              " of their centre, the eye corners 36 and 45 " + std::to_string(eyeSpan) + " apart");
  return {};
}

std::vector<std::string> sourceUnits(const eng::Model& model) {
  std::vector<std::string> units;
  for (const eng::Mesh& mesh : model.meshes)
    for (const std::string& name : mesh.targetNames)
      if (name.size() > 2 && name.starts_with("AU") && std::isdigit(static_cast<unsigned char>(name[2])) &&
          std::find(units.begin(), units.end(), name) == units.end())
        units.push_back(name);
  return units;
}

// Each unit's world displacement of every source vertex.
std::vector<std::vector<glm::vec3>> sourceDeltas(const SourceFace& source, const FaceSurface& surface,
                                                 const std::vector<std::string>& units) {
  std::vector<std::vector<glm::vec3>> deltas(units.size(), std::vector<glm::vec3>(surface.positions.size(), glm::vec3(0.0f)));
  for (size_t i = 0; i < surface.vertices.size(); ++i) {
    const PosedPrimitive& posed = source.posed.primitives[surface.vertices[i].primitive];
    const eng::Mesh& mesh = source.model->meshes[posed.mesh];
    const eng::Primitive& primitive = mesh.primitives[posed.primitive];
    const uint32_t v = surface.vertices[i].vertex;
    const glm::mat3 toWorld = glm::inverse(posed.worldToLocal[v]);
    for (size_t u = 0; u < units.size(); ++u) {
      auto it = std::find(mesh.targetNames.begin(), mesh.targetNames.end(), units[u]);
      const size_t t = size_t(it - mesh.targetNames.begin());
      if (it == mesh.targetNames.end() || t >= primitive.targets.size()) continue;
      const std::vector<glm::vec3>& local = primitive.targets[t].positions;
      if (v < local.size()) deltas[u][i] = toWorld * local[v];
    }
  }
  return deltas;
}

glm::vec3 atMatch(const std::vector<glm::vec3>& perVertex, const FaceSurface& surface, const ClosestPoint& match) {
  const auto& t = surface.triangles[match.triangle];
  return match.barycentric.x * perVertex[t[0]] + match.barycentric.y * perVertex[t[1]] + match.barycentric.z * perVertex[t[2]];
}

// Too many landmarks away from the face's skin: they were found on another
// face, on hair or glasses, or typed wrong.
eng::Result<void> checkOnSurface(const FaceSurface& target, const FaceLandmarks& landmarks, const LandmarkFrame& frame) {
  const TriangleGrid grid(target.positions, target.triangles, {});
  size_t off = 0, worst = 0;
  float worstGap = 0.0f;
  for (size_t i = 0; i < kLandmarkCount; ++i) {
    const ClosestPoint hit = grid.closest(landmarks.points[i], FaceRegion::None, kOffSurface * frame.eyeSpan());
    if (hit.found) continue;
    ++off;
    worst = i;
    worstGap = kOffSurface;
  }
  if (off > kMaxOffSurface)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          std::to_string(off) + " of 68 landmarks are off the face's skin (farther than " +
                              std::to_string(worstGap) + " eye spans; the last is point " + std::to_string(worst) +
                              "): they do not belong to this face");
  return {};
}

// The target seen the other way round from the source (a face from the
// back, or left and right swapped): its forward turns against the source's.
eng::Result<void> checkFacing(const SourceFace& source, const FaceLandmarks& landmarks) {
  const Similarity fit = ENG_TRY_VALUE(fitSimilarity(source.landmarks.points, landmarks.points));
  const glm::vec3 carried = fit.rotation * LandmarkFrame(source.landmarks).forward();
  if (glm::dot(carried, LandmarkFrame(landmarks).forward()) < 0.0f)
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "landmarks: the face's 68 points are mirrored (left and right swapped, or seen from the back)");
  return {};
}

struct Moved {
  std::vector<FaceSurface::VertexRef> vertices;  // skin-following vertices, then lower teeth and tongue
  std::vector<glm::vec3> positions;
  std::vector<NamedDeltas> units;
};

// Lids slide over the eyeball: a vertex near an eye keeps its distance to
// the eye's centre, so a blink closes along the ball instead of through it.
glm::vec3 alongEyeball(const glm::vec3& p, const glm::vec3& delta, const FaceParts& parts) {
  glm::vec3 result = delta;
  for (size_t e = 0; e < 2; ++e) {
    const float r = parts.eyeRadii[e];
    if (!(r > 0.0f)) continue;
    const glm::vec3 c = parts.eyeCentres[e];
    const float d = glm::length(p - c);
    if (d >= kLidOuter * r || d < 1e-6f) continue;
    const glm::vec3 moved = p + delta - c;
    const float length = glm::length(moved);
    if (length < 1e-6f) continue;
    const glm::vec3 onSphere = c + moved * (d / length) - p;
    result = glm::mix(delta, onSphere, 1.0f - glm::smoothstep(kLidInner * r, kLidOuter * r, d));
  }
  return result;
}

}  // namespace

namespace {

Moved carryUnits(const SourceFace& source, const FaceSurface& src, const FaceSurface& tgt, const FaceSurface& jaw,
                 const Correspondence& corr, const std::vector<std::string>& units, const FaceLandmarks& landmarks,
                 const FaceParts& parts) {
  const LandmarkFrame sourceFrame(source.landmarks), targetFrame(landmarks);
  const std::vector<std::vector<glm::vec3>> raw = sourceDeltas(source, src, units);
  std::vector<glm::mat3> jacobians(src.positions.size());
  for (size_t i = 0; i < src.positions.size(); ++i)
    jacobians[i] = corr.warp.jacobian(src.positions[i], kJacobianStep * sourceFrame.eyeSpan());

  Moved moved;
  moved.vertices = tgt.vertices;
  moved.positions = tgt.positions;
  moved.vertices.insert(moved.vertices.end(), jaw.vertices.begin(), jaw.vertices.end());
  moved.positions.insert(moved.positions.end(), jaw.positions.begin(), jaw.positions.end());
  const float maxGap = CorrespondenceOptions{}.maxGap * targetFrame.eyeSpan();
  const float fullGap = kFullGap * targetFrame.eyeSpan();

  // The source's chin and its jaw hinge give each jaw unit's angle.
  const TriangleGrid sourceGrid(src.positions, src.triangles, {});
  const ClosestPoint chin = sourceGrid.closest(source.landmarks.points[8], FaceRegion::None, maxGap);
  const JawHinge sourceHinge = estimateJawHinge(source.landmarks), targetHinge = estimateJawHinge(landmarks);

  std::vector<glm::vec3> carried(src.positions.size());
  for (size_t u = 0; u < units.size(); ++u) {
    for (size_t i = 0; i < carried.size(); ++i) carried[i] = jacobians[i] * raw[u][i];
    NamedDeltas unit{units[u], std::vector<glm::vec3>(moved.positions.size(), glm::vec3(0.0f))};
    for (size_t v = 0; v < tgt.positions.size(); ++v) {
      const ClosestPoint& match = corr.matches[v];
      if (!match.found) continue;
      const float weight = 1.0f - glm::smoothstep(fullGap, maxGap, match.distance);
      unit.deltas[v] = alongEyeball(tgt.positions[v], weight * atMatch(carried, src, match), parts);
    }
    const bool jawUnit = std::find(kJawUnits.begin(), kJawUnits.end(), units[u]) != kJawUnits.end();
    if (jawUnit && chin.found) {
      const float angle = hingeAngle(sourceHinge, chin.position, atMatch(raw[u], src, chin));
      for (size_t j = 0; j < jaw.positions.size(); ++j)
        unit.deltas[tgt.positions.size() + j] = turnAboutHinge(targetHinge, angle, jaw.positions[j]);
    }
    moved.units.push_back(std::move(unit));
  }
  return moved;
}

bool faceHas(const eng::Model& face, std::string_view name, bool arkit) {
  const std::optional<uint32_t> shape = arkit ? facial::arkitIndex(name) : std::nullopt;
  for (const eng::Mesh& mesh : face.meshes)
    for (const std::string& existing : mesh.targetNames) {
      if (sameName(existing, name)) return true;
      if (shape && facial::arkitIndex(existing) == shape) return true;
    }
  return false;
}

// A new last target on mesh `mesh`: every weights channel animating it gets
// a zero weight for it in each key (in each of a cubic spline's triples).
void widenWeightChannels(eng::Model& model, size_t mesh) {
  for (eng::Animation& animation : model.animations)
    for (eng::WeightsChannel& channel : animation.channels) {
      if (channel.mesh != int(mesh) || channel.targetCount == 0) continue;
      const size_t n = channel.targetCount;
      std::vector<float> widened;
      widened.reserve(channel.values.size() / n * (n + 1));
      for (size_t i = 0; i + n <= channel.values.size(); i += n) {
        widened.insert(widened.end(), channel.values.begin() + long(i), channel.values.begin() + long(i + n));
        widened.push_back(0.0f);
      }
      channel.values = std::move(widened);
      channel.targetCount = n + 1;
    }
}

// Appends `target` to every mesh it moves: displacements into each vertex's
// mesh space, normal displacements from the smooth normals before and after.
void writeTarget(eng::Model& model, const PosedFace& posed, const Moved& moved, const NamedDeltas& target) {
  constexpr float kStill = 1e-7f;
  std::vector<std::vector<size_t>> byMesh(model.meshes.size());
  for (size_t k = 0; k < moved.vertices.size(); ++k)
    if (glm::length(target.deltas[k]) > kStill)
      byMesh[posed.primitives[moved.vertices[k].primitive].mesh].push_back(k);
  for (size_t m = 0; m < model.meshes.size(); ++m) {
    if (byMesh[m].empty()) continue;
    eng::Mesh& mesh = model.meshes[m];
    std::vector<eng::MorphTarget> added(mesh.primitives.size());
    for (size_t p = 0; p < mesh.primitives.size(); ++p) added[p].positions.assign(mesh.primitives[p].vertexCount(), glm::vec3(0.0f));
    for (size_t k : byMesh[m]) {
      const PosedPrimitive& pp = posed.primitives[moved.vertices[k].primitive];
      added[pp.primitive].positions[moved.vertices[k].vertex] = pp.toLocal(moved.vertices[k].vertex, target.deltas[k]);
    }
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      eng::Primitive& primitive = mesh.primitives[p];
      if (primitive.normals.size() != primitive.vertexCount()) continue;
      std::vector<glm::vec3> after(primitive.positions);
      bool any = false;
      for (size_t v = 0; v < after.size(); ++v) after[v] += added[p].positions[v], any = any || added[p].positions[v] != glm::vec3(0.0f);
      if (!any) continue;
      const std::vector<glm::vec3> before = eng::computeSmoothNormals(primitive.positions, primitive.indices);
      const std::vector<glm::vec3> turned = eng::computeSmoothNormals(after, primitive.indices);
      added[p].normals.resize(after.size());
      for (size_t v = 0; v < after.size(); ++v) added[p].normals[v] = turned[v] - before[v];
    }
    for (size_t p = 0; p < mesh.primitives.size(); ++p) mesh.primitives[p].targets.push_back(std::move(added[p]));
    mesh.targetNames.push_back(target.name);
    mesh.defaultWeights.push_back(0.0f);
    widenWeightChannels(model, m);
  }
}

}  // namespace

eng::Result<TransferResult> transferTargets(const SourceFace& source, const eng::Model& face, const PosedFace& posed,
                                            const FaceLandmarks& landmarks, const FaceParts& parts,
                                            const TransferOptions& options) {
  if (!source.model) return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: no source face");
  ENG_TRY(checkLandmarks(source.landmarks, "source"));
  ENG_TRY(checkLandmarks(landmarks, "face"));
  const std::vector<std::string> units = sourceUnits(*source.model);
  if (units.empty()) {
    size_t targets = 0;
    for (const eng::Mesh& mesh : source.model->meshes) targets += mesh.targetNames.size();
    return eng::makeError(eng::ErrorKind::InvalidArgument,
                          "target transfer: the source has no action units (AU... targets) among its " +
                              std::to_string(targets) + " targets on " + std::to_string(source.model->meshes.size()) + " meshes");
  }
  const FaceSurface src = gatherSurface(*source.model, source.posed, source.parts, {FacePart::Skin});
  const FaceSurface tgt = gatherSurface(face, posed, parts, {FacePart::Skin, FacePart::Lashes, FacePart::Brows});
  if (src.triangles.empty())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: the source has no skin triangles (" +
                                                               std::to_string(src.positions.size()) + " skin vertices)");
  if (tgt.triangles.empty())
    return eng::makeError(eng::ErrorKind::InvalidArgument, "target transfer: the face has no skin triangles (" +
                                                               std::to_string(tgt.positions.size()) + " skin vertices of " +
                                                               std::to_string(posed.vertexCount()) + ")");
  const LandmarkFrame frame(landmarks);
  ENG_TRY(checkOnSurface(tgt, landmarks, frame));
  ENG_TRY(checkFacing(source, landmarks));
  const Correspondence corr = ENG_TRY_VALUE(correspond(src, source.landmarks, tgt, landmarks));
  const FaceSurface jaw = gatherSurface(face, posed, parts, {FacePart::LowerTeeth, FacePart::Tongue});
  const Moved moved = carryUnits(source, src, tgt, jaw, corr, units, landmarks, parts);

  TransferResult result{.model = face, .report = {}};
  TransferReport& report = result.report;
  std::vector<NamedDeltas> made;
  if (options.actionUnits)
    for (const NamedDeltas& unit : moved.units) made.push_back(unit);
  if (options.arkit) {
    std::vector<std::string> unmade;
    for (NamedDeltas& shape : arkitFromUnits(moved.units, moved.positions, frame, unmade)) made.push_back(std::move(shape));
    if (!unmade.empty()) {
      std::string line = std::to_string(unmade.size()) + " ARKit shapes have no action unit to be made from:";
      for (const std::string& name : unmade) line += " " + name;
      report.warnings.push_back(line);
    }
  }
  for (const NamedDeltas& target : made) {
    if (faceHas(face, target.name, !target.name.starts_with("AU"))) {
      report.kept.push_back(target.name);
      continue;
    }
    writeTarget(result.model, posed, moved, target);
    report.made.push_back(target.name);
  }
  if (jaw.positions.empty()) report.warnings.push_back("no lower teeth or tongue found: the jaw units move the skin only");
  if (!(parts.eyeRadii[0] > 0.0f) || !(parts.eyeRadii[1] > 0.0f))
    report.warnings.push_back("no eyeball size known: the lids follow the source's without sliding over the eyes");
  return result;
}

}  // namespace autorig
