#include "autorig/face_parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string_view>

#include "engine/scene/position_hash.h"

#include "engine/core/enum_names.h"
#include "engine/scene/inner_face_parts.h"

namespace autorig {

namespace {

constexpr eng::EnumName<FacePart> kFacePartNames[] = {
    {FacePart::Skin, "skin"},           {FacePart::EyeballRight, "right eyeball"}, {FacePart::EyeballLeft, "left eyeball"},
    {FacePart::UpperTeeth, "upper teeth"}, {FacePart::LowerTeeth, "lower teeth"}, {FacePart::Tongue, "tongue"},
    {FacePart::Lashes, "lashes"},       {FacePart::Brows, "brows"},             {FacePart::Glasses, "glasses"},
    {FacePart::Hair, "hair"},           {FacePart::Other, "other"},
};

struct NamedPart {
  std::string_view needle;
  FacePart part;
};

// Checked in order: "Outfit_Top" is clothes before "top" could mean the
// upper teeth, "eyelash" is lashes before "eye" could mean an eyeball, and
// "MouthTeeth" is teeth while the mouth's inside is skin (it moves with it).
constexpr std::array<NamedPart, 21> kNamedParts = {{
    {"lash", FacePart::Lashes},     {"brow", FacePart::Brows},      {"tongue", FacePart::Tongue},
    {"glass", FacePart::Glasses},   {"spectacle", FacePart::Glasses}, {"eyewear", FacePart::Glasses},
    {"hair", FacePart::Hair},       {"outfit", FacePart::Other},    {"cloth", FacePart::Other},
    {"body", FacePart::Other},      {"shirt", FacePart::Other},     {"foot", FacePart::Other},
    {"shoe", FacePart::Other},      {"hand", FacePart::Other},      {"teeth", FacePart::UpperTeeth},
    {"tooth", FacePart::UpperTeeth}, {"mouth", FacePart::Skin},     {"head", FacePart::Skin},
    {"face", FacePart::Skin},       {"skin", FacePart::Skin},       {"nose", FacePart::Skin},
}};

std::vector<std::string_view> primitiveNames(const eng::Model& model, const PosedPrimitive& p) {
  std::vector<std::string_view> names = eng::meshAndNodeNames(model, p.mesh, p.node);
  const int material = model.meshes[p.mesh].primitives[p.primitive].material;
  if (material >= 0 && size_t(material) < model.materials.size()) names.push_back(model.materials[size_t(material)].name);
  return names;
}

}  // namespace

const char* facePartName(FacePart part) { return eng::nameOf(kFacePartNames, part).data(); }

std::optional<FacePart> facePartFromNames(const eng::Model& model, const PosedPrimitive& primitive) {
  if (primitive.mesh >= model.meshes.size() || primitive.primitive >= model.meshes[primitive.mesh].primitives.size())
    return std::nullopt;
  const std::vector<std::string_view> names = primitiveNames(model, primitive);
  for (const NamedPart& named : kNamedParts)
    if (eng::anyNameContains(names, named.needle)) {
      if (named.part != FacePart::UpperTeeth) return named.part;
      const bool lower = eng::anyNameContains(names, "lower") || eng::anyNameContains(names, "bottom");
      return lower ? FacePart::LowerTeeth : FacePart::UpperTeeth;
    }
  for (std::string_view name : names)
    if (eng::namesAnEyeball(std::string(name))) return FacePart::EyeballRight;
  return std::nullopt;
}

namespace {

// Where the face is and which way it looks, from its landmarks.
struct FaceFrame {
  glm::vec3 right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, 1};  // right: toward the subject's left (36 -> 45)
  float span = 1.0f;                                         // outer eye corners apart
  std::array<glm::vec3, 2> eyeCentre{};                      // the lid lines' centres (0: right eye)
  std::array<float, 2> eyeWidth{};
  glm::vec3 mouthCentre{0.0f};  // the inner lips' centre: the line the teeth part at
  float mouthWidth = 0.0f;
  glm::vec3 centre{0.0f};
};

glm::vec3 mean(const FaceLandmarks& l, size_t first, size_t last) {
  glm::vec3 sum(0.0f);
  for (size_t i = first; i <= last; ++i) sum += l.points[i];
  return sum / float(last - first + 1);
}

FaceFrame faceFrame(const FaceLandmarks& l) {
  FaceFrame f;
  const auto& p = l.points;
  f.span = std::max(glm::distance(p[36], p[45]), 1e-6f);
  f.right = (p[45] - p[36]) / f.span;
  const glm::vec3 rise = p[27] - p[8];
  const glm::vec3 up = rise - f.right * glm::dot(rise, f.right);
  if (glm::length(up) > 1e-9f) f.up = glm::normalize(up);
  f.forward = glm::cross(f.right, f.up);
  f.eyeCentre = {mean(l, 36, 41), mean(l, 42, 47)};
  f.eyeWidth = {glm::distance(p[36], p[39]), glm::distance(p[42], p[45])};
  f.mouthCentre = mean(l, 60, 67);
  f.mouthWidth = glm::distance(p[48], p[54]);
  f.centre = mean(l, 0, kLandmarkCount - 1);
  return f;
}

// Connected components of a primitive's triangles, vertices at one position
// joined (texture seams split a surface's vertices, not the surface).
std::vector<uint32_t> components(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices,
                                 float weld, uint32_t& count) {
  std::vector<uint32_t> parent(positions.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  auto join = [&](uint32_t a, uint32_t b) { parent[root(a)] = root(b); };
  for (size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= positions.size() || indices[t + 1] >= positions.size() || indices[t + 2] >= positions.size())
      continue;
    join(indices[t], indices[t + 1]);
    join(indices[t], indices[t + 2]);
  }
  const eng::PositionHash hash(positions, weld);
  for (uint32_t v = 0; v < positions.size(); ++v)
    for (uint32_t other : hash.near(positions[v], weld)) join(v, other);
  std::vector<uint32_t> label(positions.size(), UINT32_MAX), byRoot(positions.size(), UINT32_MAX);
  count = 0;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    uint32_t& l = byRoot[root(v)];
    if (l == UINT32_MAX) l = count++;
    label[v] = l;
  }
  return label;
}

struct Component {
  std::vector<uint32_t> vertices;
  glm::vec3 centre{0.0f};  // vertex mean
  float radius = 0.0f;     // mean distance from it
  float spread = 1.0f;     // the distances' deviation over the radius: ~0 for a sphere
  glm::vec3 lo{0.0f}, hi{0.0f};
};

Component describe(const std::vector<glm::vec3>& positions, std::vector<uint32_t> vertices) {
  Component c;
  c.vertices = std::move(vertices);
  c.lo = c.hi = positions[c.vertices[0]];
  for (uint32_t v : c.vertices) c.centre += positions[v], c.lo = glm::min(c.lo, positions[v]), c.hi = glm::max(c.hi, positions[v]);
  c.centre /= float(c.vertices.size());
  double sum = 0.0, sum2 = 0.0;
  for (uint32_t v : c.vertices) {
    const double d = glm::distance(positions[v], c.centre);
    sum += d, sum2 += d * d;
  }
  const double n = double(c.vertices.size());
  c.radius = float(sum / n);
  c.spread = c.radius > 0.0f ? float(std::sqrt(std::max(0.0, sum2 / n - (sum / n) * (sum / n))) / (sum / n)) : 1.0f;
  return c;
}

// The eye (0 right, 1 left) whose lid line lies over `c`, or -1.
int eyeOver(const Component& c, const FaceFrame& f) {
  for (int e = 0; e < 2; ++e) {
    const glm::vec3 d = c.centre - f.eyeCentre[size_t(e)];
    const float across = glm::length(d - f.forward * glm::dot(d, f.forward));
    if (across < 0.5f * f.eyeWidth[size_t(e)] && glm::dot(d, f.forward) < 0.25f * f.span) return e;
  }
  return -1;
}

// A closed near-sphere of an eyeball's size behind an eye's lid line.
int eyeballSide(const Component& c, const FaceFrame& f) {
  const int e = eyeOver(c, f);
  if (e < 0 || c.spread > 0.15f || c.vertices.size() < 20) return -1;
  const float ratio = c.radius / f.eyeWidth[size_t(e)];
  return ratio > 0.2f && ratio < 0.9f ? e : -1;
}

bool insideTheMouth(const Component& c, const FaceFrame& f) {
  const glm::vec3 d = c.centre - f.mouthCentre;
  return std::abs(glm::dot(d, f.right)) < 0.5f * f.mouthWidth && std::abs(glm::dot(d, f.up)) < 0.35f * f.span &&
         glm::dot(d, f.forward) < 0.05f * f.span && glm::dot(d, f.forward) > -0.8f * f.span &&
         glm::length(c.hi - c.lo) < 1.5f * f.span;
}

// In front of both eyes and reaching across them: a pair of glasses.
bool spansTheEyes(const Component& c, const FaceFrame& f) {
  float lo = INFINITY, hi = -INFINITY;
  for (const glm::vec3& corner : {c.lo, c.hi}) {
    const float x = glm::dot(corner - f.centre, f.right);
    lo = std::min(lo, x), hi = std::max(hi, x);
  }
  const float eyes = glm::dot(f.eyeCentre[1] - f.centre, f.right);
  const glm::vec3 d = c.centre - (f.eyeCentre[0] + f.eyeCentre[1]) * 0.5f;
  return lo < -eyes && hi > eyes && glm::dot(d, f.forward) > 0.0f && std::abs(glm::dot(d, f.up)) < 0.3f * f.span;
}

FacePart teethSide(const glm::vec3& p, const FaceFrame& f) {
  return glm::dot(p - f.mouthCentre, f.up) >= 0.0f ? FacePart::UpperTeeth : FacePart::LowerTeeth;
}

// A row of teeth lies mostly on one side of the mouth line (its edge may
// cross it); nullopt for a set of both rows in one piece, split per vertex.
std::optional<FacePart> teethRow(const std::vector<glm::vec3>& positions, const Component& c, const FaceFrame& f) {
  size_t upper = 0;
  for (uint32_t v : c.vertices) upper += teethSide(positions[v], f) == FacePart::UpperTeeth;
  if (upper >= c.vertices.size() * 8 / 10) return FacePart::UpperTeeth;
  if (upper <= c.vertices.size() * 2 / 10) return FacePart::LowerTeeth;
  return std::nullopt;
}

// What geometry says an unnamed component is.
FacePart partOfShape(const Component& c, const FaceFrame& f) {
  if (glm::distance(c.centre, f.centre) > 2.5f * f.span) return FacePart::Other;
  if (const int e = eyeballSide(c, f); e >= 0) return e == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
  if (insideTheMouth(c, f)) return FacePart::UpperTeeth;  // which row: per vertex, teethSide
  if (spansTheEyes(c, f)) return FacePart::Glasses;
  return FacePart::Skin;
}

struct PartCounts {
  std::array<size_t, 11> vertices{};
};

std::string primitiveLabel(const eng::Model& model, const PosedPrimitive& p) {
  const std::string& mesh = model.meshes[p.mesh].name;
  std::string label = mesh.empty() ? "mesh " + std::to_string(p.mesh) : mesh;
  if (model.meshes[p.mesh].primitives.size() > 1) label += " primitive " + std::to_string(p.primitive);
  return label;
}

// "Wolf3D_Teeth: upper teeth 40, lower teeth 44 (by name, split at the mouth line)".
std::string note(const std::string& label, const PartCounts& counts, bool named) {
  std::string line = label + ":";
  const char* sep = " ";
  for (size_t k = 0; k < counts.vertices.size(); ++k)
    if (counts.vertices[k]) {
      line += sep + std::string(facePartName(FacePart(k))) + " " + std::to_string(counts.vertices[k]);
      sep = ", ";
    }
  return line + (named ? " (by name)" : " (by shape)");
}

// Keeps the larger sphere of each eye (the ball, not its iris or cornea).
void recordEyeball(FaceParts& parts, int side, const Component& c) {
  if (c.radius > parts.eyeRadii[size_t(side)]) parts.eyeCentres[size_t(side)] = c.centre, parts.eyeRadii[size_t(side)] = c.radius;
}

FacePart partOfComponent(std::optional<FacePart> named, const Component& c, const FaceFrame& f, FaceParts& parts) {
  if (named == FacePart::EyeballRight || named == FacePart::EyeballLeft) {
    const int e = eyeOver(c, f);
    const int side = e >= 0 ? e : (glm::dot(c.centre - f.centre, f.right) > 0.0f ? 1 : 0);
    if (e >= 0) recordEyeball(parts, side, c);
    return side == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
  }
  if (named) return *named;
  const FacePart part = partOfShape(c, f);
  if (part == FacePart::EyeballRight || part == FacePart::EyeballLeft) recordEyeball(parts, part == FacePart::EyeballLeft, c);
  return part;
}

void classifyPrimitive(const eng::Model& model, const PosedPrimitive& p, const FaceFrame& f, FaceParts& parts,
                       std::vector<FacePart>& out) {
  out.assign(p.positions.size(), FacePart::Skin);
  if (p.positions.empty()) return;
  const std::optional<FacePart> named = facePartFromNames(model, p);
  uint32_t count = 0;
  const std::vector<uint32_t> label =
      components(p.positions, model.meshes[p.mesh].primitives[p.primitive].indices, 1e-5f * f.span, count);
  std::vector<std::vector<uint32_t>> members(count);
  for (uint32_t v = 0; v < label.size(); ++v) members[label[v]].push_back(v);
  PartCounts counts;
  for (std::vector<uint32_t>& vertices : members) {
    const Component c = describe(p.positions, std::move(vertices));
    const FacePart part = partOfComponent(named, c, f, parts);
    const bool teeth = part == FacePart::UpperTeeth && named != FacePart::LowerTeeth;
    const std::optional<FacePart> row = teeth ? teethRow(p.positions, c, f) : std::optional<FacePart>(part);
    for (uint32_t v : c.vertices) {
      out[v] = row ? *row : teethSide(p.positions[v], f);
      ++counts.vertices[size_t(out[v])];
    }
  }
  if (named != FacePart::Skin || counts.vertices[size_t(FacePart::Skin)] != p.positions.size())
    parts.notes.push_back(note(primitiveLabel(model, p), counts, named.has_value()));
}

// No eyeball mesh: the ball sits behind the lid line, its radius about 0.45
// of the eye's width (a 24 mm ball behind a 28 mm opening).
void estimateEyeballs(FaceParts& parts, const FaceFrame& f) {
  for (size_t e = 0; e < 2; ++e) {
    if (parts.eyeRadii[e] > 0.0f) continue;
    parts.eyeRadii[e] = 0.45f * f.eyeWidth[e];
    parts.eyeCentres[e] = f.eyeCentre[e] - f.forward * (0.8f * parts.eyeRadii[e]);
    parts.notes.push_back(std::string(e == 0 ? "right" : "left") + " eyeball: no mesh, estimated behind the lids");
  }
}

}  // namespace

FaceParts findFaceParts(const eng::Model& model, const PosedFace& posed, const FaceLandmarks& landmarks) {
  FaceParts parts;
  const FaceFrame frame = faceFrame(landmarks);
  parts.vertexParts.resize(posed.primitives.size());
  for (size_t i = 0; i < posed.primitives.size(); ++i)
    classifyPrimitive(model, posed.primitives[i], frame, parts, parts.vertexParts[i]);
  parts.eyeballsFound = parts.eyeRadii[0] > 0.0f && parts.eyeRadii[1] > 0.0f;
  estimateEyeballs(parts, frame);
  return parts;
}

}  // namespace autorig
