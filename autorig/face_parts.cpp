#include "autorig/face_parts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <numeric>
#include <string_view>

#include <Eigen/Dense>

#include "autorig/closest_point.h"
#include "autorig/face_frame.h"
#include "engine/core/enum_names.h"
#include "engine/scene/inner_face_parts.h"
#include "engine/scene/position_hash.h"

namespace autorig {

namespace {

constexpr eng::EnumName<FacePart> kFacePartNames[] = {
    {FacePart::Skin, "skin"},           {FacePart::EyeballRight, "right eyeball"}, {FacePart::EyeballLeft, "left eyeball"},
    {FacePart::UpperTeeth, "upper teeth"}, {FacePart::LowerTeeth, "lower teeth"}, {FacePart::Tongue, "tongue"},
    {FacePart::Lashes, "lashes"},       {FacePart::Brows, "brows"},             {FacePart::Glasses, "glasses"},
    {FacePart::Hair, "hair"},           {FacePart::SkinLayer, "layer on the skin"}, {FacePart::Other, "other"},
};

struct NamedPart {
  std::string_view needle;  // empty: eng::namesAnEyeball decides
  FacePart part;
};

// Checked in order on each name: "eyeglasses" is glasses and "eyelash"
// lashes before "eye" can mean an eyeball; "Outfit_Top" is clothes before
// "top" could mean the upper teeth; "MouthTeeth" is teeth while the mouth's
// inside is skin (it moves with it).
constexpr std::array<NamedPart, 29> kNamedParts = {{
    {"lash", FacePart::Lashes},     {"brow", FacePart::Brows},       {"tongue", FacePart::Tongue},
    {"beard", FacePart::SkinLayer}, {"moustache", FacePart::SkinLayer}, {"mustache", FacePart::SkinLayer},
    {"stubble", FacePart::SkinLayer}, {"facewear", FacePart::SkinLayer}, {"makeup", FacePart::SkinLayer},
    {"tattoo", FacePart::SkinLayer},
    {"glass", FacePart::Glasses},   {"spectacle", FacePart::Glasses}, {"eyewear", FacePart::Glasses},
    {"", FacePart::EyeballRight},   {"hair", FacePart::Hair},        {"outfit", FacePart::Other},
    {"cloth", FacePart::Other},     {"body", FacePart::Other},       {"shirt", FacePart::Other},
    {"foot", FacePart::Other},      {"shoe", FacePart::Other},       {"hand", FacePart::Other},
    {"teeth", FacePart::UpperTeeth}, {"tooth", FacePart::UpperTeeth}, {"mouth", FacePart::Skin},
    {"head", FacePart::Skin},       {"face", FacePart::Skin},        {"skin", FacePart::Skin},
    {"nose", FacePart::Skin},
}};

// The most particular first: material, mesh, node, then the node's parents
// (an eye node under a "Head" node is an eye).
std::vector<std::string_view> primitiveNames(const eng::Model& model, const PosedPrimitive& p) {
  std::vector<std::string_view> names;
  const int material = model.meshes[p.mesh].primitives[p.primitive].material;
  if (material >= 0 && size_t(material) < model.materials.size()) names.push_back(model.materials[size_t(material)].name);
  for (std::string_view n : eng::meshAndNodeNames(model, p.mesh, p.node)) names.push_back(n);
  return names;
}

std::optional<FacePart> partNamed(std::string_view name) {
  for (const NamedPart& named : kNamedParts) {
    const bool says = named.needle.empty() ? eng::namesAnEyeball(std::string(name))
                                           : eng::anyNameContains({name}, named.needle);
    if (says) return named.part;
  }
  return std::nullopt;
}

// Whether the names say which row of teeth: "TeethLower", "upper_teeth".
std::optional<FacePart> teethRowNamed(const std::vector<std::string_view>& names) {
  if (eng::anyNameContains(names, "lower") || eng::anyNameContains(names, "bottom")) return FacePart::LowerTeeth;
  if (eng::anyNameContains(names, "upper")) return FacePart::UpperTeeth;
  return std::nullopt;
}

}  // namespace

const char* facePartName(FacePart part) { return eng::nameOf(kFacePartNames, part).data(); }

std::optional<FacePart> facePartFromNames(const eng::Model& model, const PosedPrimitive& primitive) {
  if (primitive.mesh >= model.meshes.size() || primitive.primitive >= model.meshes[primitive.mesh].primitives.size())
    return std::nullopt;
  const std::vector<std::string_view> names = primitiveNames(model, primitive);
  for (std::string_view name : names)
    if (const std::optional<FacePart> part = partNamed(name)) {
      if (*part != FacePart::UpperTeeth) return part;
      return teethRowNamed(names).value_or(FacePart::UpperTeeth);
    }
  return std::nullopt;
}

namespace {

// Where the face is and which way it looks, from its landmarks.
// The face's axes and size (LandmarkFrame) and where its features are.
struct FaceFrame {
  glm::vec3 right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, 1};  // right: toward the subject's left (36 -> 45)
  float span = 1.0f;                                         // outer eye corners apart
  std::array<glm::vec3, 2> eyeCentre{};                      // the lid lines' centres (0: right eye)
  std::array<float, 2> eyeWidth{};
  glm::vec3 mouthCentre{0.0f};  // the inner lips' centre: the line the teeth part at
  float mouthWidth = 0.0f;
  std::array<glm::vec3, 2> browCentre{};  // 17-21 (right), 22-26
  glm::vec3 centre{0.0f};
  const FaceLandmarks* landmarks = nullptr;
};

glm::vec3 mean(const FaceLandmarks& l, size_t first, size_t last) {
  glm::vec3 sum(0.0f);
  for (size_t i = first; i <= last; ++i) sum += l.points[i];
  return sum / float(last - first + 1);
}

FaceFrame faceFrame(const FaceLandmarks& l) {
  FaceFrame f;
  const auto& p = l.points;
  const LandmarkFrame axes(l);
  f.span = axes.eyeSpan();
  f.right = axes.side(), f.up = axes.up(), f.forward = axes.forward();
  f.eyeCentre = {mean(l, 36, 41), mean(l, 42, 47)};
  f.eyeWidth = {glm::distance(p[36], p[39]), glm::distance(p[42], p[45])};
  f.mouthCentre = mean(l, 60, 67);
  f.mouthWidth = glm::distance(p[48], p[54]);
  f.browCentre = {mean(l, 17, 21), mean(l, 22, 26)};
  f.centre = mean(l, 0, kLandmarkCount - 1);
  f.landmarks = &l;
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
  // The best sphere through the vertices (least squares, so the front half
  // of an eyeball finds the ball's centre) and how far they stray from it
  // over its radius: ~0 for a sphere.
  glm::vec3 sphereCentre{0.0f};
  float radius = 0.0f;
  float spread = 1.0f;
  glm::vec3 lo{0.0f}, hi{0.0f};
  bool bearsLandmarks = false;  // some landmark of the nose, eyes or mouth lies on it: the face's own skin
};

// |p|^2 = 2 p.c + (r^2 - |c|^2) is linear in c and the last term: solved by
// least squares about the vertex mean.
void fitSphere(const std::vector<glm::vec3>& positions, Component& c) {
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (uint32_t v : c.vertices) {
    const glm::dvec3 p = glm::dvec3(positions[v] - c.centre);
    const Eigen::Vector4d row(2.0 * p.x, 2.0 * p.y, 2.0 * p.z, 1.0);
    normal += row * row.transpose();
    rhs += row * glm::dot(p, p);
  }
  const Eigen::Vector4d x = normal.ldlt().solve(rhs);
  const glm::dvec3 centre(x[0], x[1], x[2]);
  const double r2 = x[3] + glm::dot(centre, centre);
  if (!x.allFinite() || !(r2 > 0.0)) return;
  c.sphereCentre = c.centre + glm::vec3(centre);
  c.radius = float(std::sqrt(r2));
  double sum2 = 0.0;
  for (uint32_t v : c.vertices) {
    const double d = glm::distance(glm::dvec3(positions[v]), glm::dvec3(c.sphereCentre)) - double(c.radius);
    sum2 += d * d;
  }
  c.spread = float(std::sqrt(sum2 / double(c.vertices.size())) / double(c.radius));
}

Component describe(const std::vector<glm::vec3>& positions, std::vector<uint32_t> vertices) {
  Component c;
  c.vertices = std::move(vertices);
  c.lo = c.hi = positions[c.vertices[0]];
  for (uint32_t v : c.vertices) c.centre += positions[v], c.lo = glm::min(c.lo, positions[v]), c.hi = glm::max(c.hi, positions[v]);
  c.centre /= float(c.vertices.size());
  c.sphereCentre = c.centre;
  if (c.vertices.size() >= 4) fitSphere(positions, c);
  return c;
}

// Whether a landmark of the nose, eyes or mouth lies within 5 % of the eye
// corners' distance of a vertex of `c`.
bool bearsLandmarks(const std::vector<glm::vec3>& positions, const Component& c, const FaceFrame& f) {
  const float reach = 0.05f * f.span;
  // Not the jaw line and brows: hair hangs beside the face and over the brows.
  for (size_t i = 27; i < kLandmarkCount; ++i) {
    const glm::vec3& l = f.landmarks->points[i];
    if (glm::any(glm::lessThan(l, c.lo - reach)) || glm::any(glm::greaterThan(l, c.hi + reach))) continue;
    for (uint32_t v : c.vertices)
      if (glm::distance(positions[v], l) < reach) return true;
  }
  return false;
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

// An eyeball's size under an eye's lid line, and round: a near-sphere, or a
// ball's front half with an iris set in it (Ready Player Me's), at least
// 0.4 as deep as it is wide, where lashes are thin strips. A sphere that
// fits it is a ball's only when no wider than the piece: a lens (glasses in
// the one primitive of a Ready Player Me avatar exported with a texture
// atlas) is a shallow cap of a sphere much wider than itself.
int eyeballSide(const Component& c, const FaceFrame& f) {
  const int e = eyeOver(c, f);
  if (e < 0 || c.vertices.size() < 20) return -1;
  const glm::vec3 size = c.hi - c.lo;
  const float longest = std::max({size.x, size.y, size.z}), shortest = std::min({size.x, size.y, size.z});
  const float ratio = longest / f.eyeWidth[size_t(e)];
  const bool ball = c.spread < 0.1f && c.radius < 0.8f * longest;
  return (ball || shortest > 0.4f * longest) && ratio > 0.4f && ratio < 3.0f ? e : -1;
}

bool insideTheMouth(const Component& c, const FaceFrame& f) {
  const glm::vec3 d = c.centre - f.mouthCentre;
  return std::abs(glm::dot(d, f.right)) < 0.5f * f.mouthWidth && std::abs(glm::dot(d, f.up)) < 0.35f * f.span &&
         glm::dot(d, f.forward) < 0.05f * f.span && glm::dot(d, f.forward) > -0.8f * f.span &&
         glm::length(c.hi - c.lo) < 1.5f * f.span;
}

// The extent of a component's box along an axis, from `origin`.
glm::vec2 boxExtent(const Component& c, const glm::vec3& origin, const glm::vec3& axis) {
  glm::vec2 r(INFINITY, -INFINITY);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p(corner & 1 ? c.hi.x : c.lo.x, corner & 2 ? c.hi.y : c.lo.y, corner & 4 ? c.hi.z : c.lo.z);
    const float x = glm::dot(p - origin, axis);
    r = {std::min(r.x, x), std::max(r.y, x)};
  }
  return r;
}

// Reaching across both eyes, its front before them, at their height: a pair
// of glasses (their arms may run back to the ears).
bool spansTheEyes(const Component& c, const FaceFrame& f) {
  const glm::vec3 eyes = (f.eyeCentre[0] + f.eyeCentre[1]) * 0.5f;
  const float half = 0.5f * glm::distance(f.eyeCentre[0], f.eyeCentre[1]);
  const glm::vec2 across = boxExtent(c, eyes, f.right), depth = boxExtent(c, eyes, f.forward);
  const glm::vec2 height = boxExtent(c, eyes, f.up);
  return across.x < -half && across.y > half && depth.y > 0.0f && height.y - height.x < f.span &&
         std::abs(glm::dot(c.centre - eyes, f.up)) < 0.3f * f.span;
}

// Small and over a brow (a brow card), or over an eye's lid line (a lash
// strip); both lie on landmarks, so that cannot tell them from the skin.
std::optional<FacePart> hairOnTheFace(const Component& c, const FaceFrame& f) {
  const glm::vec3 size = c.hi - c.lo;
  if (std::max({size.x, size.y, size.z}) > 0.6f * f.span) return std::nullopt;
  for (size_t side = 0; side < 2; ++side) {
    const float toBrow = glm::distance(c.centre, f.browCentre[side]);
    const float toEye = glm::distance(c.centre, f.eyeCentre[side]);
    if (toBrow < toEye && toBrow < 0.25f * f.span) return FacePart::Brows;
    if (toEye <= toBrow && toEye < 0.6f * f.eyeWidth[side]) return FacePart::Lashes;
  }
  return std::nullopt;
}

// Off the face's own skin, across the head and over its top: hair (or a
// hat), long hair hanging far below the brows too.
bool hairOnTheHead(const Component& c, const FaceFrame& f) {
  const glm::vec3 brows = (f.browCentre[0] + f.browCentre[1]) * 0.5f;
  const glm::vec2 across = boxExtent(c, brows, f.right), height = boxExtent(c, brows, f.up);
  return across.y - across.x > 0.8f * f.span && height.y > 0.5f * f.span;
}

// Off the face's own skin and below the chin: the neck's and body's pieces, clothes.
bool belowTheChin(const Component& c, const FaceFrame& f) {
  return glm::dot(c.centre - f.landmarks->points[8], f.up) < -0.2f * f.span;
}

// What geometry says an unnamed component is.
FacePart partOfShape(const Component& c, const FaceFrame& f) {
  if (glm::distance(c.centre, f.centre) > 2.5f * f.span) return FacePart::Other;
  if (const int e = eyeballSide(c, f); e >= 0) return e == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
  if (insideTheMouth(c, f)) return FacePart::UpperTeeth;  // which row: splitTeethRows
  if (spansTheEyes(c, f)) return FacePart::Glasses;
  if (const std::optional<FacePart> part = hairOnTheFace(c, f)) return *part;
  if (c.bearsLandmarks) return FacePart::Skin;
  if (hairOnTheHead(c, f)) return FacePart::Hair;
  return belowTheChin(c, f) ? FacePart::Other : FacePart::Skin;
}

std::string primitiveLabel(const eng::Model& model, const PosedPrimitive& p) {
  const std::string& mesh = model.meshes[p.mesh].name;
  std::string label = mesh.empty() ? "mesh " + std::to_string(p.mesh) : mesh;
  if (model.meshes[p.mesh].primitives.size() > 1) label += " primitive " + std::to_string(p.primitive);
  return label;
}

// "Wolf3D_Teeth: upper teeth 40, lower teeth 44 (by name)"; nothing for
// plain skin.
void notePrimitive(const eng::Model& model, const PosedPrimitive& p, const std::vector<FacePart>& parts,
                   std::vector<std::string>& notes) {
  std::array<size_t, std::size(kFacePartNames)> counts{};
  for (FacePart v : parts) ++counts[size_t(v)];
  if (counts[size_t(FacePart::Skin)] == parts.size()) return;
  std::string line = primitiveLabel(model, p) + ":";
  const char* sep = " ";
  for (size_t k = 0; k < counts.size(); ++k)
    if (counts[k]) line += sep + std::string(facePartName(FacePart(k))) + " " + std::to_string(counts[k]), sep = ", ";
  notes.push_back(line + (facePartFromNames(model, p) ? " (by name)" : " (by shape)"));
}

// Teeth whose row no name gives: one component each, sorted into rows later.
struct TeethPiece {
  size_t primitive;
  std::vector<uint32_t> vertices;
};

// A ball's depth (along the face's forward) below this share of its width
// is its front only: a shell, as Ready Player Me's eyes are.
constexpr float kShellDepth = 0.75f;

// Keeps the larger ball of each eye (not its iris or cornea): the fitted
// sphere, or the box of a ball that is no sphere. A shell's box centre lies
// in front of the ball's (by half the radius for a half ball), where the lids
// would turn about a point inside them: the centre is a radius behind its front.
void recordEyeball(FaceParts& parts, int side, const Component& c, const FaceFrame& f) {
  const bool sphere = c.spread < 0.1f;
  const glm::vec3 size = c.hi - c.lo;
  const float radius = sphere ? c.radius : 0.5f * std::max({size.x, size.y, size.z});
  if (radius <= parts.eyeRadii[size_t(side)]) return;
  glm::vec3 centre = sphere ? c.sphereCentre : (c.lo + c.hi) * 0.5f;
  const float depth = glm::dot(glm::abs(f.forward), size);
  if (!sphere && depth < kShellDepth * 2.0f * radius) centre += f.forward * (0.5f * depth - radius);
  parts.eyeCentres[size_t(side)] = centre;
  parts.eyeRadii[size_t(side)] = radius;
}

FacePart partOfComponent(std::optional<FacePart> named, const Component& c, bool island, const FaceFrame& f,
                         FaceParts& parts) {
  if (named == FacePart::EyeballRight || named == FacePart::EyeballLeft) {
    const int e = eyeOver(c, f);
    const int side = e >= 0 ? e : (glm::dot(c.centre - f.centre, f.right) > 0.0f ? 1 : 0);
    if (e >= 0) recordEyeball(parts, side, c, f);
    return side == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
  }
  // A mesh called "Head" often holds the eyeballs, and the teeth as islands
  // beside its largest piece (facecap's lower row): those are taken from
  // shape. A primitive that is one piece inside the mouth is its lining.
  if (named && *named != FacePart::Skin) return *named;
  const int eye = eyeballSide(c, f);
  if (eye >= 0) {
    recordEyeball(parts, eye, c, f);
    return eye == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft;
  }
  if (!named) return partOfShape(c, f);
  return island && insideTheMouth(c, f) ? FacePart::UpperTeeth : FacePart::Skin;  // the row: splitTeethRows
}

// Both eyes' balls in one primitive (an OBJ groups faces by material, an
// export may merge the two eye meshes): most of its vertices are eyeballs,
// of either side. Across the eyes as a whole, it is no pair of glasses.
bool bothEyeballs(const std::vector<Component>& pieces, const FaceFrame& f) {
  std::array<size_t, 2> balls{};
  size_t total = 0;
  for (const Component& c : pieces) {
    total += c.vertices.size();
    if (const int e = eyeballSide(c, f); e >= 0) balls[size_t(e)] += c.vertices.size();
  }
  return balls[0] > 0 && balls[1] > 0 && 2 * (balls[0] + balls[1]) > total;
}

// Glasses and hair come in many pieces (rims, lenses, bridge, arms; locks):
// an unnamed primitive that is glasses or hair as a whole is all of it.
std::optional<FacePart> wholePrimitivePart(const std::vector<glm::vec3>& positions, const FaceFrame& f) {
  std::vector<uint32_t> all(positions.size());
  std::iota(all.begin(), all.end(), 0u);
  const Component whole = describe(positions, std::move(all));
  // Glasses rest on the nose, near its landmarks; the skin is too tall to pass.
  if (spansTheEyes(whole, f)) return FacePart::Glasses;
  if (!bearsLandmarks(positions, whole, f) && hairOnTheHead(whole, f)) return FacePart::Hair;
  return std::nullopt;
}

// A primitive's connected pieces, each its vertices (positions closer than
// 1e-5 eye spans joined).
std::vector<std::vector<uint32_t>> piecesOf(const eng::Model& model, const PosedPrimitive& p, const FaceFrame& f) {
  uint32_t count = 0;
  const std::vector<uint32_t> label =
      components(p.positions, model.meshes[p.mesh].primitives[p.primitive].indices, 1e-5f * f.span, count);
  std::vector<std::vector<uint32_t>> members(count);
  for (uint32_t v = 0; v < label.size(); ++v) members[label[v]].push_back(v);
  return members;
}

void classifyPrimitive(const eng::Model& model, size_t index, const PosedPrimitive& p,
                       const std::vector<std::vector<uint32_t>>& members, const FaceFrame& f, FaceParts& parts,
                       std::vector<TeethPiece>& teeth) {
  std::vector<FacePart>& out = parts.vertexParts[index];
  out.assign(p.positions.size(), FacePart::Skin);
  if (p.positions.empty()) return;
  const std::optional<FacePart> named = facePartFromNames(model, p);
  const bool rowNamed = named == FacePart::LowerTeeth || (named == FacePart::UpperTeeth &&
                                                           teethRowNamed(primitiveNames(model, p)).has_value());
  std::vector<Component> pieces;
  pieces.reserve(members.size());
  for (const std::vector<uint32_t>& vertices : members) pieces.push_back(describe(p.positions, vertices));
  if (!named && !bothEyeballs(pieces, f)) {
    if (const std::optional<FacePart> whole = wholePrimitivePart(p.positions, f)) {
      out.assign(p.positions.size(), *whole);
      return;
    }
  }
  size_t largest = 0;
  for (const Component& c : pieces) largest = std::max(largest, c.vertices.size());
  for (Component& c : pieces) {
    const bool island = c.vertices.size() < largest;
    if (!named) c.bearsLandmarks = bearsLandmarks(p.positions, c, f);
    const FacePart part = partOfComponent(named, c, island, f, parts);
    for (uint32_t v : c.vertices) out[v] = part;
    if (part == FacePart::UpperTeeth && !rowNamed) teeth.push_back({index, c.vertices});
  }
}

// Otsu's threshold over weighted values: the cut between two groups that
// makes them most apart (rows in a gap, or where touching rows meet).
float otsuSplit(std::vector<std::pair<float, double>> values) {
  std::sort(values.begin(), values.end());
  double total = 0.0, weight = 0.0;
  for (const auto& [v, w] : values) total += double(v) * w, weight += w;
  double below = 0.0, belowWeight = 0.0, bestScore = -1.0;
  float split = values.empty() ? 0.0f : values.front().first;
  for (size_t k = 1; k < values.size(); ++k) {
    below += double(values[k - 1].first) * values[k - 1].second;
    belowWeight += values[k - 1].second;
    const double d = below / belowWeight - (total - below) / (weight - belowWeight);
    const double score = belowWeight * (weight - belowWeight) * d * d;
    if (score > bestScore) bestScore = score, split = (values[k - 1].first + values[k].first) / 2.0f;
  }
  return split;
}

// Extent of a piece along an axis, from the mouth centre.
glm::vec2 extent(const PosedFace& posed, const TeethPiece& piece, const glm::vec3& origin, const glm::vec3& axis) {
  glm::vec2 r(INFINITY, -INFINITY);
  for (uint32_t v : piece.vertices) {
    const float x = glm::dot(posed.primitives[piece.primitive].positions[v] - origin, axis);
    r = {std::min(r.x, x), std::max(r.y, x)};
  }
  return r;
}

// The inside of the mouth as a piece of its own (a sac behind the lips):
// it holds two or more of the other pieces (teeth, tongue) in its box, as
// no row of teeth does. Skin: it moves with the lips and jaw.
void takeOutLining(const PosedFace& posed, std::vector<TeethPiece>& teeth, const FaceFrame& f, FaceParts& parts) {
  std::vector<glm::vec3> centres;  // in the face's axes
  for (const TeethPiece& piece : teeth) {
    glm::dvec3 sum(0.0);
    for (uint32_t v : piece.vertices) sum += glm::dvec3(posed.primitives[piece.primitive].positions[v]);
    const glm::vec3 c = glm::vec3(sum / double(piece.vertices.size())) - f.mouthCentre;
    centres.emplace_back(glm::dot(c, f.right), glm::dot(c, f.up), glm::dot(c, f.forward));
  }
  for (size_t i = teeth.size(); i-- > 0;) {
    const glm::vec2 x = extent(posed, teeth[i], f.mouthCentre, f.right), y = extent(posed, teeth[i], f.mouthCentre, f.up);
    const glm::vec2 z = extent(posed, teeth[i], f.mouthCentre, f.forward);
    size_t held = 0;
    for (size_t k = 0; k < teeth.size(); ++k)
      held += k != i && centres[k].x > x.x && centres[k].x < x.y && centres[k].y > y.x && centres[k].y < y.y &&
              centres[k].z > z.x && centres[k].z < z.y;
    if (held < 2) continue;
    for (uint32_t v : teeth[i].vertices) parts.vertexParts[teeth[i].primitive][v] = FacePart::Skin;
    teeth.erase(teeth.begin() + std::ptrdiff_t(i));
    centres.erase(centres.begin() + std::ptrdiff_t(i));
  }
}

// A tongue kept with the teeth (Ready Player Me's Wolf3D_Teeth): a piece as
// wide as the arches but short of their front, lying inside them. Taken out
// of `teeth` and marked.
void takeOutTongue(const PosedFace& posed, std::vector<TeethPiece>& teeth, const FaceFrame& f, FaceParts& parts) {
  if (teeth.size() < 2) return;
  glm::vec2 across(INFINITY, -INFINITY);
  std::vector<float> front(teeth.size());
  for (size_t i = 0; i < teeth.size(); ++i) {
    const glm::vec2 x = extent(posed, teeth[i], f.mouthCentre, f.right);
    across = {std::min(across.x, x.x), std::max(across.y, x.y)};
    front[i] = extent(posed, teeth[i], f.mouthCentre, f.forward).y;
  }
  const float frontMost = *std::max_element(front.begin(), front.end());
  const float width = across.y - across.x;
  for (size_t i = teeth.size(); i-- > 0;) {
    const glm::vec2 x = extent(posed, teeth[i], f.mouthCentre, f.right);
    if (x.y - x.x < 0.5f * width || front[i] > frontMost - 0.15f * width) continue;
    for (uint32_t v : teeth[i].vertices) parts.vertexParts[teeth[i].primitive][v] = FacePart::Tongue;
    teeth.erase(teeth.begin() + std::ptrdiff_t(i));
  }
}

// Rows in pieces of their own (teeth apart, or one primitive per row) go
// whole by their mean height; a single piece holding both rows is split per
// vertex. Two rows lie one over the other; when the two sides of the split
// lie more one behind the other (the front teeth of a single tilted arch
// against its back teeth), there is one row, and the mouth line says which.
void splitTeethRows(const PosedFace& posed, const std::vector<TeethPiece>& teeth, const FaceFrame& f, FaceParts& parts) {
  const glm::vec3& mouth = f.mouthCentre;
  auto along = [&](const TeethPiece& piece, uint32_t v, const glm::vec3& axis) {
    return glm::dot(posed.primitives[piece.primitive].positions[v] - mouth, axis);
  };
  auto meanHeight = [&](const TeethPiece& piece) {
    double sum = 0.0;
    for (uint32_t v : piece.vertices) sum += along(piece, v, f.up);
    return float(sum / double(piece.vertices.size()));
  };
  // Teeth in more than one primitive: a row each (facecap's upper row is a
  // mesh, its lower row islands of the head), so an arch's tilt cannot mix
  // them; their heights are the primitives' means.
  std::vector<size_t> primitives;
  for (const TeethPiece& piece : teeth) primitives.push_back(piece.primitive);
  std::sort(primitives.begin(), primitives.end());
  primitives.erase(std::unique(primitives.begin(), primitives.end()), primitives.end());
  std::vector<glm::dvec2> byPrimitive(posed.primitives.size());  // height sum, count
  for (const TeethPiece& piece : teeth)
    byPrimitive[piece.primitive] += glm::dvec2(double(meanHeight(piece)) * double(piece.vertices.size()), double(piece.vertices.size()));
  auto rowHeight = [&](const TeethPiece& piece) {
    const glm::dvec2 h = byPrimitive[piece.primitive];
    return primitives.size() > 1 ? float(h.x / h.y) : meanHeight(piece);
  };
  std::vector<std::pair<float, double>> values;
  if (primitives.size() > 1)
    for (size_t i : primitives) values.emplace_back(float(byPrimitive[i].x / byPrimitive[i].y), byPrimitive[i].y);
  else
    for (const TeethPiece& piece : teeth) {
      if (teeth.size() > 1) values.emplace_back(meanHeight(piece), double(piece.vertices.size()));
      else
        for (uint32_t v : piece.vertices) values.emplace_back(along(piece, v, f.up), 1.0);
    }
  const float split = otsuSplit(values);
  std::array<glm::dvec3, 2> sums{};  // below, above: height, depth, vertex count
  for (const TeethPiece& piece : teeth)
    for (uint32_t v : piece.vertices) {
      const bool above = teeth.size() > 1 ? rowHeight(piece) > split : along(piece, v, f.up) > split;
      sums[above] += glm::dvec3(along(piece, v, f.up), along(piece, v, f.forward), 1.0);
      parts.vertexParts[piece.primitive][v] = above ? FacePart::UpperTeeth : FacePart::LowerTeeth;
    }
  const glm::dvec3 apart = sums[1] / std::max(sums[1].z, 1.0) - sums[0] / std::max(sums[0].z, 1.0);
  const bool twoRows = sums[0].z > 0.0 && sums[1].z > 0.0 && std::abs(apart.x) > std::abs(apart.y);
  const FacePart oneRow = values.empty() || meanHeight(teeth[0]) > 0.0f ? FacePart::UpperTeeth : FacePart::LowerTeeth;
  if (!twoRows)
    for (const TeethPiece& piece : teeth)
      for (uint32_t v : piece.vertices) parts.vertexParts[piece.primitive][v] = oneRow;
  char text[160];
  if (twoRows)
    std::snprintf(text, sizeof text, "teeth: %zu piece%s, upper and lower rows parted %.4g above the mouth line",
                  teeth.size(), teeth.size() > 1 ? "s" : "", double(split));
  else
    std::snprintf(text, sizeof text, "teeth: %zu piece%s, one row, %s the mouth line", teeth.size(),
                  teeth.size() > 1 ? "s" : "", oneRow == FacePart::UpperTeeth ? "above" : "below");
  parts.notes.push_back(text);
}

// Where p lies in the plane of the face, about the eye's lid line centre.
glm::vec2 inFacePlane(const FaceFrame& f, size_t eye, const glm::vec3& p) {
  const glm::vec3 d = p - f.eyeCentre[eye];
  return {glm::dot(d, f.right), glm::dot(d, f.up)};
}

// Whether q lies inside the eye's six lid landmarks (36-41 or 42-47, in the
// face's plane) scaled by `scale` about their centre.
bool insideTheLidLine(const FaceFrame& f, size_t eye, glm::vec2 q, float scale) {
  std::array<glm::vec2, 6> ring{};
  glm::vec2 centre(0.0f);
  for (size_t k = 0; k < 6; ++k) centre += ring[k] = inFacePlane(f, eye, f.landmarks->points[36 + 6 * eye + k]);
  centre /= 6.0f;
  bool inside = false;
  for (size_t k = 0, j = 5; k < 6; j = k++) {
    const glm::vec2 a = centre + (ring[k] - centre) * scale, b = centre + (ring[j] - centre) * scale;
    if ((a.y > q.y) != (b.y > q.y) && q.x < (b.x - a.x) * (q.y - a.y) / (b.y - a.y) + a.x) inside = !inside;
  }
  return inside;
}

// The skin inside the lid line that lies on a ball (a scan's eyes are its
// skin, one surface with the lids): the ball is fitted through the skin well
// inside the lid landmarks (kBallCore of their ring), convex towards the
// viewer and of an eyeball's size; the eyeball is the skin on that ball
// (within kOnBall of its radius) reached along edges from there, out to
// kBallReach of the ring (the six landmarks cut the lids' curves short). The
// units leave it still and the lids close over it.
constexpr float kBallCore = 0.5f, kBallReach = 1.5f, kOnBall = 0.06f;

void findEyesInTheSkin(const eng::Model& model, const PosedFace& posed, const FaceFrame& f, FaceParts& parts) {
  for (size_t e = 0; e < 2; ++e) {
    if (parts.eyeRadii[e] > 0.0f) continue;
    const float width = f.eyeWidth[e];
    // Skin vertices within reach, per primitive (index into `near`, or -1).
    std::vector<std::vector<int>> slot(posed.primitives.size());
    std::vector<std::pair<size_t, uint32_t>> near;
    std::vector<glm::vec3> core;
    for (size_t i = 0; i < posed.primitives.size(); ++i) {
      slot[i].assign(posed.primitives[i].positions.size(), -1);
      for (uint32_t v = 0; v < posed.primitives[i].positions.size(); ++v) {
        const glm::vec3& p = posed.primitives[i].positions[v];
        if (parts.vertexParts[i][v] != FacePart::Skin || std::abs(glm::dot(p - f.eyeCentre[e], f.forward)) > 0.5f * width) continue;
        const glm::vec2 q = inFacePlane(f, e, p);
        if (!insideTheLidLine(f, e, q, kBallReach)) continue;
        slot[i][v] = int(near.size());
        near.emplace_back(i, v);
        if (insideTheLidLine(f, e, q, kBallCore)) core.push_back(p);
      }
    }
    if (core.size() < 8) continue;
    std::vector<uint32_t> all(core.size());
    std::iota(all.begin(), all.end(), 0u);
    const Component ball = describe(core, std::move(all));
    const float coreFront = glm::dot(ball.centre - ball.sphereCentre, f.forward);
    if (ball.spread > kOnBall || ball.radius < 0.25f * width || ball.radius > 0.8f * width || coreFront < 0.5f * ball.radius) continue;
    auto onBall = [&](size_t k) {
      const glm::vec3& p = posed.primitives[near[k].first].positions[near[k].second];
      return std::abs(glm::distance(p, ball.sphereCentre) - ball.radius) <= kOnBall * ball.radius;
    };
    std::vector<char> taken(near.size(), 0);
    std::vector<size_t> stack;
    for (size_t k = 0; k < near.size(); ++k)
      if (onBall(k) && insideTheLidLine(f, e, inFacePlane(f, e, posed.primitives[near[k].first].positions[near[k].second]), kBallCore))
        taken[k] = 1, stack.push_back(k);
    std::vector<std::vector<uint32_t>> neighbours(near.size());
    for (size_t i = 0; i < posed.primitives.size(); ++i) {
      const std::vector<uint32_t>& indices = model.meshes[posed.primitives[i].mesh].primitives[posed.primitives[i].primitive].indices;
      for (size_t t = 0; t + 2 < indices.size(); t += 3)
        for (size_t c = 0; c < 3; ++c) {
          const uint32_t a = indices[t + c], b = indices[t + (c + 1) % 3];
          if (a >= slot[i].size() || b >= slot[i].size() || slot[i][a] < 0 || slot[i][b] < 0) continue;
          neighbours[size_t(slot[i][a])].push_back(uint32_t(slot[i][b]));
          neighbours[size_t(slot[i][b])].push_back(uint32_t(slot[i][a]));
        }
    }
    while (!stack.empty()) {
      const size_t k = stack.back();
      stack.pop_back();
      for (uint32_t n : neighbours[k])
        if (!taken[n] && onBall(n)) taken[n] = 1, stack.push_back(n);
    }
    size_t count = 0;
    for (size_t k = 0; k < near.size(); ++k)
      if (taken[k]) parts.vertexParts[near[k].first][near[k].second] = e == 0 ? FacePart::EyeballRight : FacePart::EyeballLeft, ++count;
    parts.eyeCentres[e] = ball.sphereCentre;
    parts.eyeRadii[e] = ball.radius;
    parts.eyesInTheSkin[e] = true;
    char text[160];
    std::snprintf(text, sizeof text, "%s eyeball: %zu vertices of the skin inside the lids, on a ball of radius %.4g (a scan's eye)",
                  e == 0 ? "right" : "left", count, double(ball.radius));
    parts.notes.push_back(text);
  }
}

// No eyeball mesh: the ball sits behind the lid line (eyeballBehindTheLids).
void estimateEyeballs(FaceParts& parts, const FaceFrame& f) {
  for (size_t e = 0; e < 2; ++e) {
    if (parts.eyeRadii[e] > 0.0f) continue;
    const Eyeball ball = eyeballBehindTheLids(*f.landmarks, e);
    parts.eyeRadii[e] = ball.radius;
    parts.eyeCentres[e] = ball.centre;
    parts.notes.push_back(std::string(e == 0 ? "right" : "left") + " eyeball: no mesh, estimated behind the lids");
  }
}

}  // namespace

Eyeball eyeballBehindTheLids(const FaceLandmarks& landmarks, size_t eye) {
  const FaceFrame f = faceFrame(landmarks);
  Eyeball ball;
  ball.radius = 0.45f * f.eyeWidth[eye];
  ball.centre = f.eyeCentre[eye] - f.forward * (0.8f * ball.radius);
  ball.margins = f.eyeCentre[eye];
  return ball;
}

// Well behind the lips, inside the mouth: where the teeth and tongue lie
// over the mouth's inside (the chin below the lips recedes less).
bool insideTheLips(const glm::vec3& p, const FaceFrame& f) {
  const glm::vec3 d = p - f.mouthCentre;
  return std::abs(glm::dot(d, f.right)) < 0.6f * f.mouthWidth && std::abs(glm::dot(d, f.up)) < 0.25f * f.span &&
         glm::dot(d, f.forward) < -0.1f * f.span;
}

// A piece no name tells, lying just off the face's skin on its outside, is a
// layer on it: a beard or moustache merged into one primitive with the rest
// (a Ready Player Me avatar exported with a texture atlas), whose soul patch
// in the mouth's box was taken for teeth and whose moustache for lips to cut.
// The skin it lies on: the skin pieces at least a quarter the size of the
// largest; lying on it: seven in ten of its vertices within 5% of the eye
// span outside it, on skin facing forward or not deep behind the lips (the
// tongue lies as close over the mouth's floor, the teeth by the lips' inside).
void findLayersOnTheSkin(const eng::Model& model, const PosedFace& posed,
                         const std::vector<std::vector<std::vector<uint32_t>>>& piecesOfPrimitive, const FaceFrame& f,
                         FaceParts& parts, std::vector<TeethPiece>& teeth) {
  struct Piece {
    size_t primitive;
    bool named;  // its primitive's names tell its part
    std::vector<uint32_t> vertices;
  };
  std::vector<Piece> skinPieces, candidates;
  size_t largest = 0;
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    const PosedPrimitive& p = posed.primitives[i];
    const std::vector<FacePart>& part = parts.vertexParts[i];
    if (p.positions.empty()) continue;
    const bool named = facePartFromNames(model, p).has_value();
    for (const std::vector<uint32_t>& piece : piecesOfPrimitive[i]) {
      const FacePart kind = part[piece.front()];
      if (kind == FacePart::Skin) largest = std::max(largest, piece.size());
      if (kind == FacePart::Skin || (!named && (kind == FacePart::UpperTeeth || kind == FacePart::LowerTeeth)))
        (kind == FacePart::Skin ? skinPieces : candidates).push_back({i, named, piece});
    }
  }
  // Small unnamed skin pieces are candidates too; the large ones are the skin.
  std::vector<glm::vec3> positions;
  std::vector<std::array<uint32_t, 3>> triangles;
  for (Piece& piece : skinPieces) {
    if (4 * piece.vertices.size() < largest) {
      if (!piece.named) candidates.push_back(std::move(piece));
      continue;
    }
    const PosedPrimitive& p = posed.primitives[piece.primitive];
    const std::vector<uint32_t>& indices = model.meshes[p.mesh].primitives[p.primitive].indices;
    std::vector<uint32_t> at(p.positions.size(), UINT32_MAX);
    for (uint32_t v : piece.vertices) at[v] = uint32_t(positions.size()), positions.push_back(p.positions[v]);
    for (size_t t = 0; t + 2 < indices.size(); t += 3)
      if (at[indices[t]] != UINT32_MAX && at[indices[t + 1]] != UINT32_MAX && at[indices[t + 2]] != UINT32_MAX)
        triangles.push_back({at[indices[t]], at[indices[t + 1]], at[indices[t + 2]]});
  }
  if (triangles.empty() || candidates.empty()) return;
  const TriangleGrid grid(positions, triangles, {});
  for (const Piece& piece : candidates) {
    const PosedPrimitive& p = posed.primitives[piece.primitive];
    size_t on = 0;
    for (uint32_t v : piece.vertices) {
      const ClosestPoint q = grid.closest(p.positions[v], FaceRegion::None, 0.05f * f.span);
      if (!q.found) continue;
      const auto& t = triangles[q.triangle];
      const glm::vec3 n = glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]);
      const bool facesOut = glm::dot(glm::normalize(n), f.forward) > 0.5f || !insideTheLips(q.position, f);
      on += glm::dot(p.positions[v] - q.position, n) > 0.0f && facesOut;
    }
    if (10 * on < 7 * piece.vertices.size()) continue;
    for (uint32_t v : piece.vertices) parts.vertexParts[piece.primitive][v] = FacePart::SkinLayer;
    std::erase_if(teeth, [&](TeethPiece& t) {
      if (t.primitive != piece.primitive) return false;
      std::erase_if(t.vertices, [&](uint32_t v) { return parts.vertexParts[t.primitive][v] == FacePart::SkinLayer; });
      return t.vertices.empty();
    });
  }
}

FaceParts findFaceParts(const eng::Model& model, const PosedFace& posed, const FaceLandmarks& landmarks) {
  FaceParts parts;
  const FaceFrame frame = faceFrame(landmarks);
  parts.vertexParts.resize(posed.primitives.size());
  std::vector<TeethPiece> teeth;
  std::vector<std::vector<std::vector<uint32_t>>> pieces(posed.primitives.size());
  for (size_t i = 0; i < posed.primitives.size(); ++i) {
    pieces[i] = piecesOf(model, posed.primitives[i], frame);
    classifyPrimitive(model, i, posed.primitives[i], pieces[i], frame, parts, teeth);
  }
  findLayersOnTheSkin(model, posed, pieces, frame, parts, teeth);
  takeOutLining(posed, teeth, frame, parts);
  takeOutTongue(posed, teeth, frame, parts);
  splitTeethRows(posed, teeth, frame, parts);
  findEyesInTheSkin(model, posed, frame, parts);
  for (size_t i = 0; i < posed.primitives.size(); ++i)
    notePrimitive(model, posed.primitives[i], parts.vertexParts[i], parts.notes);
  parts.eyeballsFound = parts.eyeRadii[0] > 0.0f && parts.eyeRadii[1] > 0.0f;
  estimateEyeballs(parts, frame);
  return parts;
}

}  // namespace autorig
