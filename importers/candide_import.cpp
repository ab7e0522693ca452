#include "importers/candide_import.h"

#include <charconv>
#include <cmath>
#include <new>
#include <string>
#include <vector>

#include "importers/candide_eyes.h"
#include "engine/core/text_lines.h"
#include "engine/scene/file_bytes.h"
#include "facial/runtime/rig/candide_units.h"

namespace importers {
namespace {

constexpr size_t kMaxFileBytes = size_t{8} << 20;
// Far above CANDIDE's 113 vertices; keeps a corrupt count from allocating gigabytes.
constexpr size_t kMaxCount = 1'000'000;

// Whitespace-separated tokens of one line.
std::vector<std::string_view> tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool parseFloat(std::string_view token, float& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size() && std::isfinite(value);
}

bool parseIndex(std::string_view token, size_t& value) {
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  return ec == std::errc() && end == token.data() + token.size();
}

// Non-blank lines with their 1-based numbers, for "<source>:<line>:" messages.
class LineReader {
 public:
  LineReader(std::string_view text, std::string_view source, eng::LoadBudget& budget)
      : lines_(text), source_(source), budget_(budget) {}

  // Next non-blank line, trimmed; false at the end of the text.
  bool next(std::string_view& line) { return lines_.nextNonBlank(line); }
  // Looks at the next non-blank line without consuming it.
  bool peek(std::string_view& line) const {
    eng::TextLines ahead = lines_;
    return ahead.nextNonBlank(line);
  }
  eng::Error error(const std::string& problem) const {
    return eng::makeError(eng::ErrorKind::Malformed, std::string(source_) + ":" + std::to_string(lines_.number()) + ": " + problem);
  }
  eng::Error endError(const std::string& what) const {
    return eng::makeError(eng::ErrorKind::Malformed, std::string(source_) + ":" + std::to_string(lines_.number()) + ": file ends before " + what);
  }
  // Charges what the line's numbers make to the load's budget.
  eng::Result<void> charge(size_t count, size_t bytesEach, const std::string& what) {
    auto ok = budget_.charge(count, bytesEach, what);
    if (!ok) return ok.error().prefixed(std::string(source_) + ":" + std::to_string(lines_.number()) + ": ");
    return {};
  }

 private:
  eng::TextLines lines_;
  std::string_view source_;
  eng::LoadBudget& budget_;
};

// "# VERTEX LIST:" -> "VERTEX LIST", "# END OF FILE" -> "END OF FILE"; empty for
// lines that are not section headers (unit names such as "# Jaw drop" are mixed case).
std::string_view headerName(std::string_view line) {
  if (line.empty() || line[0] != '#') return {};
  std::string_view name = eng::trimmed(line.substr(1));
  if (!name.empty() && name.back() == ':') name = eng::trimmed(name.substr(0, name.size() - 1));
  if (name.empty()) return {};
  for (char c : name)
    if (!(c == ' ' || (c >= 'A' && c <= 'Z'))) return {};
  return name;
}

eng::Result<void> expectHeader(LineReader& in, std::string_view name) {
  std::string_view line;
  if (!in.next(line)) return in.endError("the '# " + std::string(name) + ":' section");
  if (headerName(line) != name)
    return in.error("expected '# " + std::string(name) + ":', got '" + std::string(line) + "'");
  return {};
}

eng::Result<size_t> readCount(LineReader& in, const std::string& what) {
  std::string_view line;
  if (!in.next(line)) return in.endError("the " + what);
  const std::vector<std::string_view> t = tokens(line);
  size_t count = 0;
  if (t.size() != 1 || !parseIndex(t[0], count))
    return in.error("expected the " + what + " (one non-negative integer), got '" + std::string(line) + "'");
  if (count > kMaxCount)
    return in.error(what + " " + std::to_string(count) + " exceeds the limit of " + std::to_string(kMaxCount));
  return count;
}

eng::Result<std::vector<glm::vec3>> readVertices(LineReader& in) {
  auto count = readCount(in, "vertex count");
  if (!count) return count.error();
  // Positions and the normals made for them.
  if (auto ok = in.charge(*count, 2 * sizeof(glm::vec3), std::to_string(*count) + " vertices"); !ok) return ok.error();
  std::vector<glm::vec3> positions(*count);
  for (size_t i = 0; i < *count; ++i) {
    std::string_view line;
    const std::string what = "vertex " + std::to_string(i) + " of " + std::to_string(*count);
    if (!in.next(line)) return in.endError(what);
    const std::vector<std::string_view> t = tokens(line);
    if (t.size() != 3 || !parseFloat(t[0], positions[i].x) || !parseFloat(t[1], positions[i].y) ||
        !parseFloat(t[2], positions[i].z))
      return in.error("expected three finite numbers 'x y z' for " + what + ", got '" + std::string(line) + "'");
  }
  return positions;
}

eng::Result<std::vector<uint32_t>> readFaces(LineReader& in, size_t vertexCount) {
  auto count = readCount(in, "triangle count");
  if (!count) return count.error();
  if (auto ok = in.charge(*count, 3 * sizeof(uint32_t), std::to_string(*count) + " triangles"); !ok) return ok.error();
  std::vector<uint32_t> indices;
  indices.reserve(*count * 3);
  for (size_t f = 0; f < *count; ++f) {
    std::string_view line;
    const std::string what = "triangle " + std::to_string(f) + " of " + std::to_string(*count);
    if (!in.next(line)) return in.endError(what);
    const std::vector<std::string_view> t = tokens(line);
    if (t.size() != 3) return in.error("expected three vertex indices for " + what + ", got '" + std::string(line) + "'");
    for (std::string_view token : t) {
      size_t index = 0;
      if (!parseIndex(token, index)) return in.error("'" + std::string(token) + "' is not a vertex index (" + what + ")");
      if (index >= vertexCount)
        return in.error("vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount) +
                        " vertices) in " + what);
      indices.push_back(static_cast<uint32_t>(index));
    }
  }
  return indices;
}

struct Unit {
  std::string name;
  std::vector<glm::vec3> deltas;  // one per vertex
};

eng::Result<std::vector<Unit>> readUnits(LineReader& in, size_t vertexCount, const std::string& kind) {
  auto count = readCount(in, kind + " count");
  if (!count) return count.error();
  std::vector<Unit> units(*count);
  for (size_t u = 0; u < *count; ++u) {
    std::string_view line;
    const std::string which = kind + " " + std::to_string(u) + " of " + std::to_string(*count);
    if (!in.next(line)) return in.endError(which);
    if (line[0] != '#' || !headerName(line).empty() || eng::trimmed(line.substr(1)).empty())
      return in.error("expected the name line '# <name>' of " + which + ", got '" + std::string(line) + "'");
    Unit& unit = units[u];
    unit.name = std::string(eng::trimmed(line.substr(1)));
    // A unit is a delta for every vertex, and becomes a target of position
    // and normal deltas: a few bytes of file each, whatever the vertex count.
    if (auto ok = in.charge(vertexCount, 3 * sizeof(glm::vec3), which + " ('" + unit.name.substr(0, 40) + "', " +
                                                                  std::to_string(vertexCount) + " vertices)");
        !ok)
      return ok.error();
    unit.deltas.assign(vertexCount, glm::vec3(0.0f));
    auto entries = readCount(in, "entry count of " + kind + " '" + unit.name + "'");
    if (!entries) return entries.error();
    for (size_t e = 0; e < *entries; ++e) {
      if (!in.next(line)) return in.endError("entry " + std::to_string(e) + " of '" + unit.name + "'");
      const std::vector<std::string_view> t = tokens(line);
      size_t index = 0;
      glm::vec3 d(0.0f);
      if (t.size() != 4 || !parseIndex(t[0], index) || !parseFloat(t[1], d.x) || !parseFloat(t[2], d.y) ||
          !parseFloat(t[3], d.z))
        return in.error("expected 'vertex dx dy dz' in '" + unit.name + "', got '" + std::string(line) + "'");
      if (index >= vertexCount)
        return in.error("vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertexCount) +
                        " vertices) in '" + unit.name + "'");
      unit.deltas[index] += d;
    }
  }
  return units;
}

// `count` numbers, any number per line, up to the next header.
eng::Result<std::vector<float>> readValues(LineReader& in, size_t count, const std::string& what) {
  std::vector<float> values;
  values.reserve(count);
  std::string_view line;
  while (values.size() < count) {
    if (!in.peek(line) || !headerName(line).empty())
      return in.error(what + " lists " + std::to_string(values.size()) + " values, expected " + std::to_string(count));
    in.next(line);
    for (std::string_view token : tokens(line)) {
      float v = 0.0f;
      if (!parseFloat(token, v)) return in.error("'" + std::string(token) + "' is not a finite number in " + what);
      if (values.size() == count) return in.error(what + " lists more than " + std::to_string(count) + " values");
      values.push_back(v);
    }
  }
  return values;
}

std::vector<glm::vec3> vertexNormals(const std::vector<glm::vec3>& positions, const std::vector<uint32_t>& indices) {
  std::vector<glm::vec3> normals(positions.size(), glm::vec3(0.0f));
  for (size_t i = 0; i + 2 < indices.size(); i += 3) {
    const glm::vec3 &a = positions[indices[i]], &b = positions[indices[i + 1]], &c = positions[indices[i + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);  // area-weighted
    for (size_t k = 0; k < 3; ++k) normals[indices[i + k]] += n;
  }
  for (glm::vec3& n : normals) {
    const float len = glm::length(n);
    n = len > 0.0f ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
  }
  return normals;
}

eng::MorphTarget makeTarget(const eng::Primitive& base, const std::vector<glm::vec3>& deltas) {
  eng::MorphTarget target;
  target.positions = deltas;
  std::vector<glm::vec3> moved = base.positions;
  for (size_t v = 0; v < moved.size(); ++v) moved[v] += deltas[v];
  const std::vector<glm::vec3> normals = vertexNormals(moved, base.indices);
  target.normals.resize(normals.size());
  for (size_t v = 0; v < normals.size(); ++v) target.normals[v] = normals[v] - base.normals[v];
  return target;
}

// The four sections every CANDIDE-3 file has, in their fixed order.
struct CandideSections {
  std::vector<glm::vec3> positions;
  std::vector<uint32_t> indices;
  std::vector<Unit> animationUnits;
  std::vector<Unit> shapeUnits;
};

// Reads the required sections; each must follow its header, in order.
eng::Result<CandideSections> readRequiredSections(LineReader& in) {
  CandideSections sections;
  if (auto r = expectHeader(in, "VERTEX LIST"); !r) return r.error();
  auto positions = readVertices(in);
  if (!positions) return positions.error();
  sections.positions = std::move(*positions);
  const size_t n = sections.positions.size();
  if (auto r = expectHeader(in, "FACE LIST"); !r) return r.error();
  auto indices = readFaces(in, n);
  if (!indices) return indices.error();
  sections.indices = std::move(*indices);
  if (auto r = expectHeader(in, "ANIMATION UNITS LIST"); !r) return r.error();
  auto animationUnits = readUnits(in, n, "animation unit");
  if (!animationUnits) return animationUnits.error();
  sections.animationUnits = std::move(*animationUnits);
  if (auto r = expectHeader(in, "SHAPE UNITS LIST"); !r) return r.error();
  auto shapeUnits = readUnits(in, n, "shape unit");
  if (!shapeUnits) return shapeUnits.error();
  sections.shapeUnits = std::move(*shapeUnits);
  return sections;
}

// What the optional trailing sections give; absent ones leave their defaults
// (all parameters zero, no texture coordinates).
struct CandideOptionalSections {
  std::vector<float> animationParameters;
  std::vector<float> shapeParameters;
  std::vector<glm::vec2> texcoords;
};

// Reads the optional trailing sections, in the file's order, up to END OF FILE.
eng::Result<CandideOptionalSections> readOptionalSections(LineReader& in, const CandideSections& sections) {
  const size_t n = sections.positions.size();
  CandideOptionalSections optional;
  optional.animationParameters.assign(sections.animationUnits.size(), 0.0f);
  optional.shapeParameters.assign(sections.shapeUnits.size(), 0.0f);
  std::string_view line;
  while (in.next(line)) {
    const std::string_view header = headerName(line);
    if (header == "END OF FILE") break;
    if (header == "ANIMATION PARAMETERS" || header == "SHAPE PARAMETERS") {
      const bool animation = header == "ANIMATION PARAMETERS";
      std::vector<float>& parameters = animation ? optional.animationParameters : optional.shapeParameters;
      auto values = readValues(in, parameters.size(), animation ? "ANIMATION PARAMETERS" : "SHAPE PARAMETERS");
      if (!values) return values.error();
      parameters = std::move(*values);
    } else if (header == "TEXTURE") {
      auto values = readValues(in, 2 * n, "TEXTURE (u v per vertex)");
      if (!values) return values.error();
      optional.texcoords.resize(n);
      for (size_t v = 0; v < n; ++v) optional.texcoords[v] = glm::vec2((*values)[2 * v], (*values)[2 * v + 1]);
    } else {
      return in.error("unexpected line '" + std::string(line) +
                      "' (expected ANIMATION PARAMETERS, SHAPE PARAMETERS, TEXTURE or END OF FILE)");
    }
  }
  return optional;
}

// CANDIDE does not fix a winding; glTF wants counter-clockwise front faces.
// The mask faces +z, so the area-weighted normals must sum towards +z.
void windTowardsViewer(eng::Primitive& primitive) {
  float facing = 0.0f;
  for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3) {
    const glm::vec3 &a = primitive.positions[primitive.indices[i]], &b = primitive.positions[primitive.indices[i + 1]],
                    &c = primitive.positions[primitive.indices[i + 2]];
    facing += glm::cross(b - a, c - a).z;
  }
  if (facing < 0.0f)
    for (size_t i = 0; i + 2 < primitive.indices.size(); i += 3) std::swap(primitive.indices[i + 1], primitive.indices[i + 2]);
}

// The eyes: the skin between the lids is cut out (candide_eyes.h). The
// vertices only that skin used stay, unused, so the file's vertex numbers
// (which trackers and papers refer to) keep naming the same points.
std::vector<MaskEyeOpening> cutEyes(eng::Primitive& primitive, const std::vector<Unit>& animationUnits,
                                    std::string_view source, std::vector<std::string>& warnings) {
  std::vector<MaskEyeOpening> eyes;
  for (const Unit& unit : animationUnits)
    if (const facial::CandideAnimationUnit* known = facial::findCandideUnit(unit.name); known && known->facsNumber == 45)
      eyes = cutEyeOpenings(primitive.positions, primitive.indices, unit.deltas);
  if (eyes.size() < 2)
    warnings.push_back(std::string(source) + ": " + std::to_string(eyes.size()) +
                       " of 2 eye openings found (a loop of lid margins moved by 'Eyes closed' and two corners); "
                       "the rest stay skin, with no eyeball");
  return eyes;
}

// One morph target per unit: animation units under their FACS target names
// (unknown ones under their own), then shape units as SU_<name>.
void addUnitTargets(eng::Mesh& mesh, eng::Primitive& primitive, const CandideSections& sections, std::string_view source,
                    std::vector<std::string>& warnings) {
  for (const Unit& unit : sections.animationUnits) {
    const facial::CandideAnimationUnit* known = facial::findCandideUnit(unit.name);
    if (!known)
      warnings.push_back(std::string(source) + ": animation unit '" + unit.name +
                         "' is not one of CANDIDE-3's 14; kept under its own name");
    mesh.targetNames.push_back(known ? facial::candideTargetName(*known) : unit.name);
    primitive.targets.push_back(makeTarget(primitive, unit.deltas));
  }
  for (const Unit& unit : sections.shapeUnits) {
    mesh.targetNames.push_back("SU_" + unit.name);
    primitive.targets.push_back(makeTarget(primitive, unit.deltas));
  }
}

// The eyeballs are primitives of the mask's mesh, so they share its
// targets: an expression leaves them still (the lids move over them), an
// identity shape carries each with its rim and grows it with its opening,
// so a mask reshaped by --shape keeps its eyes filling their openings.
// Their material's name marks them as eyeballs for the dressing
// (importers/procedural_eyes.h).
eng::Result<void> addEyeballs(eng::Model& model, const std::vector<MaskEyeOpening>& eyes, const CandideSections& sections,
                              std::string_view source, eng::LoadBudget& budget) {
  eng::Mesh& face = model.meshes[0];
  if (!eyes.empty()) {
    eng::Material eyeMaterial;
    eyeMaterial.name = "eye";
    model.materials.push_back(eyeMaterial);
  }
  for (const MaskEyeOpening& eye : eyes) {
    eng::Primitive ball = eyeballBehind(face.primitives[0].positions, eye);
    ball.material = int(model.materials.size()) - 1;
    const size_t targets = sections.animationUnits.size() + sections.shapeUnits.size();
    if (auto ok = budget.charge(targets, ball.positions.size() * 2 * sizeof(glm::vec3),
                                "the eyeball's " + std::to_string(targets) + " morph targets");
        !ok)
      return ok.error().prefixed(std::string(source) + ": ");
    eng::MorphTarget still;
    still.positions.assign(ball.positions.size(), glm::vec3(0.0f));
    still.normals = still.positions;
    ball.targets.assign(sections.animationUnits.size(), still);
    for (const Unit& unit : sections.shapeUnits)
      ball.targets.push_back(eyeballFollowing(face.primitives[0].positions, eye, ball, unit.deltas));
    face.primitives.push_back(std::move(ball));
  }
  return {};
}

eng::Result<eng::Model> parseCandide3Charged(std::string_view text, std::string_view source, eng::LoadBudget& budget) {
  if (text.size() > kMaxFileBytes)
    return eng::makeError(eng::ErrorKind::TooLarge, std::string(source) + ": file of " + std::to_string(text.size()) +
                          " bytes exceeds the limit of " + std::to_string(kMaxFileBytes) + " bytes");
  LineReader in(text, source, budget);
  auto sections = readRequiredSections(in);
  if (!sections) return sections.error();
  auto optional = readOptionalSections(in, *sections);
  if (!optional) return optional.error();

  eng::Model model;
  model.sourcePath = std::string(source);
  eng::Primitive primitive;
  primitive.positions = std::move(sections->positions);
  primitive.indices = std::move(sections->indices);
  windTowardsViewer(primitive);
  primitive.texcoords = std::move(optional->texcoords);
  const std::vector<MaskEyeOpening> eyes = cutEyes(primitive, sections->animationUnits, source, model.warnings);
  primitive.normals = vertexNormals(primitive.positions, primitive.indices);

  eng::Mesh mesh;
  mesh.name = "candide3 face";  // "face": shown dressed like other untextured faces (skin tone, occlusion)
  addUnitTargets(mesh, primitive, *sections, source, model.warnings);
  mesh.defaultWeights = optional->animationParameters;
  mesh.defaultWeights.insert(mesh.defaultWeights.end(), optional->shapeParameters.begin(), optional->shapeParameters.end());
  mesh.primitives.push_back(std::move(primitive));
  model.meshes.push_back(std::move(mesh));

  eng::Node node;
  node.name = "candide3";
  node.mesh = 0;
  model.nodes.push_back(node);
  model.roots.push_back(0);
  if (auto ok = addEyeballs(model, eyes, *sections, source, budget); !ok) return ok.error();
  return model;
}

}  // namespace

eng::Result<eng::Model> parseCandide3(std::string_view text, std::string_view source) {
  eng::LoadBudget budget;
  return parseCandide3(text, source, budget);
}

eng::Result<eng::Model> parseCandide3(std::string_view text, std::string_view source, eng::LoadBudget& budget) {
  // The budget should make this unreachable; if memory still runs out, the file is named.
  try {
    return parseCandide3Charged(text, source, budget);
  } catch (const std::bad_alloc&) {
    return eng::makeError(eng::ErrorKind::TooLarge, std::string(source) + ": out of memory while loading");
  }
}

eng::Result<eng::Model> importCandide3(const std::filesystem::path& wfmFile) {
  eng::Result<std::vector<uint8_t>> bytes = eng::readFileBytes(wfmFile, kMaxFileBytes);
  if (!bytes) return bytes.error();
  const std::string_view text(reinterpret_cast<const char*>(bytes->data()), bytes->size());
  return parseCandide3(text, wfmFile.string());
}

}  // namespace importers
