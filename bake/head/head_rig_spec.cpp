#include "bake/head/head_rig_spec.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

#include "bake/head/skin_painter.h"
#include "facial/runtime/json/json_node.h"
#include "facial/runtime/rig/action_units.h"

namespace bake {
namespace {

using facial::JsonNode;

// The spec's own value rules on top of JsonNode's: strings are never empty,
// vectors have exactly N numbers.
eng::Result<std::string> nonEmptyString(const JsonNode& v) {
  std::string s = ENG_TRY_VALUE(v.string());
  if (s.empty()) return v.error("empty string");
  return s;
}

eng::Result<std::string> nonEmptyStringAt(const JsonNode& obj, std::string_view key) {
  return nonEmptyString(ENG_TRY_VALUE(obj.at(key)));
}

template <int N>
eng::Result<glm::vec<N, float>> vec(const JsonNode& v) {
  if (!v.isArray() || v.raw().size() != N) return v.error("expected an array of " + std::to_string(N) + " numbers");
  glm::vec<N, float> out;
  for (int i = 0; i < N; ++i) out[i] = ENG_TRY_VALUE(v.element(i).number());
  return out;
}

eng::Result<std::vector<std::string>> strings(const JsonNode& v) {
  const size_t count = ENG_TRY_VALUE(v.size());
  std::vector<std::string> out;
  for (size_t i = 0; i < count; ++i) out.push_back(ENG_TRY_VALUE(nonEmptyString(v.element(i))));
  return out;
}

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Left-side name -> right-side name ("brow_inner_L" -> "brow_inner_R",
// "eye_L.upper_lid" -> "eye_R.upper_lid"); unchanged when not left-sided.
std::string mirrorName(std::string s) {
  if (auto at = s.find("_L."); at != std::string::npos) s[at + 1] = 'R';
  if (endsWith(s, "_L")) s.back() = 'R';
  return s;
}
bool leftSided(const std::string& s) { return mirrorName(s) != s; }

glm::vec3 mirror(const glm::vec3& v) { return glm::vec3(-v.x, v.y, v.z); }

eng::Result<LandmarkDef> parseLandmark(const JsonNode& v, bool& mirrored) {
  ENG_TRY(v.allowOnly({"name", "xy", "feature", "position", "offset", "mirror", "note"}));
  LandmarkDef d;
  d.name = ENG_TRY_VALUE(nonEmptyStringAt(v, "name"));
  const int kinds = int(v.has("xy")) + int(v.has("feature")) + int(v.has("position"));
  if (kinds != 1) return v.error("landmark \"" + d.name + "\" needs exactly one of \"xy\", \"feature\", \"position\"");
  if (auto xy = v.find("xy")) {
    d.kind = LandmarkDef::Kind::Surface;
    d.xy = ENG_TRY_VALUE(vec<2>(*xy));
  } else if (auto feature = v.find("feature")) {
    d.kind = LandmarkDef::Kind::Feature;
    d.feature = ENG_TRY_VALUE(nonEmptyString(*feature));
  } else {
    d.kind = LandmarkDef::Kind::Position;
    d.position = ENG_TRY_VALUE(vec<3>(ENG_TRY_VALUE(v.at("position"))));
  }
  if (auto offset = v.find("offset")) d.offset = ENG_TRY_VALUE(vec<3>(*offset));
  mirrored = ENG_TRY_VALUE(v.booleanOr("mirror", false));
  if (mirrored && !leftSided(d.name))
    return ENG_TRY_VALUE(v.at("mirror"))
        .error("only left-side landmarks (name ending in _L) can be mirrored, \"" + d.name + "\" is not");
  return d;
}

LandmarkDef mirrored(const LandmarkDef& d) {
  LandmarkDef m = d;
  m.name = mirrorName(d.name);
  m.xy.x = -d.xy.x;
  m.feature = mirrorName(d.feature);
  m.position = mirror(d.position);
  m.offset = mirror(d.offset);
  return m;
}

eng::Result<uint8_t> maskParts(const JsonNode& list) {
  const std::vector<std::string> parts = ENG_TRY_VALUE(strings(list));
  uint8_t mask = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    bool found = false;
    for (int p = 0; p < kHeadPartCount; ++p)
      if (parts[i] == headPartName(static_cast<HeadPart>(p))) {
        mask |= uint8_t(1u << p);
        found = true;
      }
    if (!found)
      return list.element(i).error("unknown part \"" + parts[i] +
                                   "\" (expected skin, mouth, teeth_upper, teeth_lower or tongue)");
  }
  return mask;
}

eng::Result<MaskDef> parseMask(const JsonNode& v) {
  ENG_TRY(v.allowOnly({"parts", "jaw", "side", "radius", "feather"}));
  MaskDef m;
  if (auto parts = v.find("parts")) m.parts = ENG_TRY_VALUE(maskParts(*parts));
  if (auto jawNode = v.find("jaw")) {
    const std::string jaw = ENG_TRY_VALUE(nonEmptyString(*jawNode));
    if (jaw == "upper") m.jaw = MaskDef::Jaw::Upper;
    else if (jaw == "lower") m.jaw = MaskDef::Jaw::Lower;
    else if (jaw == "any") m.jaw = MaskDef::Jaw::Any;
    else return jawNode->error("expected \"upper\", \"lower\" or \"any\", found \"" + jaw + "\"");
  }
  if (auto sideNode = v.find("side")) {
    const std::string side = ENG_TRY_VALUE(nonEmptyString(*sideNode));
    if (side == "left") m.side = MaskDef::Side::Left;
    else if (side == "right") m.side = MaskDef::Side::Right;
    else if (side == "both") m.side = MaskDef::Side::Both;
    else return sideNode->error("expected \"left\", \"right\" or \"both\", found \"" + side + "\"");
  }
  m.radius = ENG_TRY_VALUE(v.numberOr("radius", m.radius));
  m.feather = ENG_TRY_VALUE(v.numberOr("feather", m.feather));
  if (!(m.radius > 0.0f)) return JsonNode(v.raw(), facial::childPath(v.pointer(), "radius")).error("must be > 0");
  if (!(m.feather > 0.0f)) return JsonNode(v.raw(), facial::childPath(v.pointer(), "feather")).error("must be > 0");
  return m;
}

// One entry of a part's "move": [x, y, z] or {"by": [x, y, z], "to": landmark}.
eng::Result<DisplacementDef> parseDisplacement(const JsonNode& v, std::string landmark) {
  DisplacementDef d;
  d.landmark = std::move(landmark);
  if (v.isArray()) {
    d.by = ENG_TRY_VALUE(vec<3>(v));
    return d;
  }
  ENG_TRY(v.allowOnly({"by", "to"}));
  if (auto by = v.find("by")) d.by = ENG_TRY_VALUE(vec<3>(*by));
  if (auto to = v.find("to")) d.to = ENG_TRY_VALUE(nonEmptyString(*to));
  if (!v.has("by") && !v.has("to")) return v.error("needs \"by\" and/or \"to\"");
  return d;
}

// A symmetric part: every left-sided move, pin and free landmark gets its right-side twin.
void addMirroredSide(DeformPartDef& part) {
  const size_t n = part.moves.size();
  for (size_t i = 0; i < n; ++i) {
    const DisplacementDef& d = part.moves[i];
    if (!leftSided(d.landmark)) continue;
    part.moves.push_back({mirrorName(d.landmark), mirror(d.by), mirrorName(d.to)});
  }
  for (auto* list : {&part.pins, &part.free}) {
    const size_t m = list->size();
    for (size_t i = 0; i < m; ++i)
      if (leftSided((*list)[i])) list->push_back(mirrorName((*list)[i]));
  }
}

eng::Result<DeformPartDef> parsePart(const JsonNode& v) {
  ENG_TRY(v.allowOnly({"move", "pins", "free", "mask", "symmetric", "note"}));
  DeformPartDef part;
  const JsonNode move = ENG_TRY_VALUE(v.at("move"));
  if (!move.isObject()) return move.error("expected an object, found " + std::string(facial::jsonTypeName(move.raw())));
  if (move.raw().empty()) return move.error("no landmark is moved");
  for (auto it = move.raw().begin(); it != move.raw().end(); ++it)
    part.moves.push_back(ENG_TRY_VALUE(parseDisplacement(ENG_TRY_VALUE(move.at(it.key())), it.key())));
  if (auto pins = v.find("pins")) part.pins = ENG_TRY_VALUE(strings(*pins));
  if (auto free = v.find("free")) part.free = ENG_TRY_VALUE(strings(*free));
  if (auto mask = v.find("mask")) part.mask = ENG_TRY_VALUE(parseMask(*mask));
  if (ENG_TRY_VALUE(v.booleanOr("symmetric", false))) {
    if (part.mask.side != MaskDef::Side::Both)
      return ENG_TRY_VALUE(v.at("symmetric")).error("a symmetric part cannot have a one-sided mask");
    addMirroredSide(part);
  }
  return part;
}

eng::Result<facial::RbfKernel> parseKernel(const JsonNode& k, facial::RbfKernel kernel) {
  ENG_TRY(k.allowOnly({"type", "k", "c"}));
  const JsonNode typeNode = ENG_TRY_VALUE(k.at("type"));
  const std::string type = ENG_TRY_VALUE(nonEmptyString(typeNode));
  if (type == "biharmonic") kernel.type = facial::RbfKernelType::Biharmonic;
  else if (type == "polyharmonic") kernel.type = facial::RbfKernelType::Polyharmonic;
  else if (type == "multiquadric") kernel.type = facial::RbfKernelType::Multiquadric;
  else return typeNode.error("expected biharmonic, polyharmonic or multiquadric, found \"" + type + "\"");
  if (auto order = k.find("k")) kernel.k = static_cast<int>(ENG_TRY_VALUE(order->number()));
  kernel.c = ENG_TRY_VALUE(k.numberOr("c", kernel.c));
  return kernel;
}

// Landmarks (mirrored ones expanded right after their left original); `names` collects every name.
eng::Result<void> parseLandmarks(const JsonNode& list, std::set<std::string>& names, HeadRigSpec& spec) {
  const size_t count = ENG_TRY_VALUE(list.size());
  for (size_t i = 0; i < count; ++i) {
    const JsonNode entry = list.element(i);
    bool mirrorIt = false;
    const LandmarkDef d = ENG_TRY_VALUE(parseLandmark(entry, mirrorIt));
    std::vector<LandmarkDef> defs{d};
    if (mirrorIt) defs.push_back(mirrored(d));
    for (const LandmarkDef& def : defs) {
      if (!names.insert(def.name).second)
        return ENG_TRY_VALUE(entry.at("name")).error("duplicate landmark \"" + def.name + "\"");
      spec.landmarks.push_back(def);
    }
  }
  return {};
}

eng::Result<void> parseAnchors(const JsonNode& list, std::set<std::string>& names, HeadRigSpec& spec) {
  const size_t count = ENG_TRY_VALUE(list.size());
  for (size_t i = 0; i < count; ++i) {
    const JsonNode entry = list.element(i);
    ENG_TRY(entry.allowOnly({"name", "position"}));
    const auto position = ENG_TRY_VALUE(vec<3>(ENG_TRY_VALUE(entry.at("position"))));
    AnchorDef a{ENG_TRY_VALUE(nonEmptyStringAt(entry, "name")), position};  // the string's read last (result.h)
    if (!names.insert(a.name).second) return ENG_TRY_VALUE(entry.at("name")).error("duplicate name \"" + a.name + "\"");
    spec.anchors.push_back(a);
  }
  return {};
}

// Every landmark a part names exists in the spec.
eng::Result<void> checkPartLandmarks(const DeformPartDef& part, const JsonNode& node, const HeadRigSpec& spec) {
  auto require = [&](const std::string& name, const std::string& path) -> eng::Result<void> {
    if (!spec.findLandmark(name)) return JsonNode(node.raw(), path).error("unknown landmark \"" + name + "\"");
    return {};
  };
  const std::string moves = facial::childPath(node.pointer(), "move");
  for (const DisplacementDef& d : part.moves) {
    ENG_TRY(require(d.landmark, facial::childPath(moves, d.landmark)));
    if (!d.to.empty()) ENG_TRY(require(d.to, facial::childPath(facial::childPath(moves, d.landmark), "to")));
  }
  for (const std::string& n : part.pins) ENG_TRY(require(n, facial::childPath(node.pointer(), "pins")));
  for (const std::string& n : part.free) ENG_TRY(require(n, facial::childPath(node.pointer(), "free")));
  return {};
}

eng::Result<ActionUnitDef> parseActionUnit(const JsonNode& v, std::set<std::string>& seen, const HeadRigSpec& spec) {
  ENG_TRY(v.allowOnly({"name", "parts", "note"}));
  ActionUnitDef au;
  const JsonNode nameNode = ENG_TRY_VALUE(v.at("name"));
  au.name = ENG_TRY_VALUE(nonEmptyString(nameNode));
  if (!facial::actionUnitIndex(au.name))
    return nameNode.error("\"" + au.name + "\" is not a channel of facial/runtime/rig/action_units.h");
  if (!seen.insert(au.name).second) return nameNode.error("action unit \"" + au.name + "\" defined twice");
  const JsonNode parts = ENG_TRY_VALUE(v.at("parts"));
  const size_t count = ENG_TRY_VALUE(parts.size());
  if (count == 0) return parts.error("no parts");
  for (size_t p = 0; p < count; ++p) {
    DeformPartDef part = ENG_TRY_VALUE(parsePart(parts.element(p)));
    ENG_TRY(checkPartLandmarks(part, parts.element(p), spec));
    au.parts.push_back(std::move(part));
  }
  return au;
}

// Action units: every canonical channel exactly once.
eng::Result<void> parseActionUnits(const JsonNode& list, HeadRigSpec& spec) {
  const size_t count = ENG_TRY_VALUE(list.size());
  std::set<std::string> seen;
  for (size_t i = 0; i < count; ++i) spec.actionUnits.push_back(ENG_TRY_VALUE(parseActionUnit(list.element(i), seen, spec)));
  for (const facial::ActionUnitInfo& info : facial::actionUnits())
    if (!seen.count(std::string(info.name)))
      return list.error("action unit \"" + std::string(info.name) + "\" is missing");
  return {};
}

eng::Result<DetailLayerDef> parseDetailLayer(const JsonNode& v) {
  ENG_TRY(v.allowOnly({"layer", "target", "strength"}));
  DetailLayerDef d;
  const JsonNode layer = ENG_TRY_VALUE(v.at("layer"));
  const JsonNode target = ENG_TRY_VALUE(v.at("target"));
  d.layer = ENG_TRY_VALUE(nonEmptyString(layer));
  d.target = ENG_TRY_VALUE(nonEmptyString(target));
  d.strength = ENG_TRY_VALUE(v.numberOr("strength", d.strength));
  const auto& known = skinDetailLayerNames();
  if (std::find(known.begin(), known.end(), d.layer) == known.end())
    return layer.error("unknown detail layer \"" + d.layer + "\"");
  if (!facial::actionUnitIndex(d.target)) return target.error("\"" + d.target + "\" is not an action unit channel");
  if (d.strength < 0.0f) return ENG_TRY_VALUE(v.at("strength")).error("must be >= 0");
  return d;
}

eng::Result<HeadRigSpec> readHeadRigSpec(const JsonNode& root) {
  ENG_TRY(root.allowOnly({"format", "version", "about", "units", "kernel", "landmarks", "anchors", "actionUnits",
                          "detailLayers"}));
  const JsonNode format = ENG_TRY_VALUE(root.at("format"));
  if (ENG_TRY_VALUE(nonEmptyString(format)) != "facial-head-landmarks") return format.error("expected \"facial-head-landmarks\"");
  const JsonNode version = ENG_TRY_VALUE(root.at("version"));
  if (ENG_TRY_VALUE(version.number()) != 1.0f) return version.error("only version 1 is supported");

  HeadRigSpec spec;
  if (auto kernel = root.find("kernel")) spec.kernel = ENG_TRY_VALUE(parseKernel(*kernel, spec.kernel));
  std::set<std::string> names;
  ENG_TRY(parseLandmarks(ENG_TRY_VALUE(root.at("landmarks")), names, spec));
  if (auto anchors = root.find("anchors")) ENG_TRY(parseAnchors(*anchors, names, spec));
  ENG_TRY(parseActionUnits(ENG_TRY_VALUE(root.at("actionUnits")), spec));
  if (auto layers = root.find("detailLayers")) {
    const size_t count = ENG_TRY_VALUE(layers->size());
    for (size_t i = 0; i < count; ++i) spec.detailLayers.push_back(ENG_TRY_VALUE(parseDetailLayer(layers->element(i))));
  }
  return spec;
}

}  // namespace

std::string_view headPartName(HeadPart part) {
  switch (part) {
    case HeadPart::Skin: return "skin";
    case HeadPart::Mouth: return "mouth";
    case HeadPart::TeethUpper: return "teeth_upper";
    case HeadPart::TeethLower: return "teeth_lower";
    case HeadPart::Tongue: return "tongue";
  }
  return "?";
}

const LandmarkDef* HeadRigSpec::findLandmark(std::string_view name) const {
  for (const LandmarkDef& l : landmarks)
    if (l.name == name) return &l;
  return nullptr;
}

eng::Result<HeadRigSpec> parseHeadRigSpec(std::string_view text, const std::string& source) {
  auto document = facial::parseJsonText(text, source);
  if (!document) return document.error();
  auto spec = readHeadRigSpec(JsonNode(*document, ""));
  if (!spec) return spec.error().prefixed(source + ": ");
  spec->source = source;
  return spec;
}

eng::Result<HeadRigSpec> loadHeadRigSpec(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot open the landmark file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseHeadRigSpec(text.str(), path.string());
}

}  // namespace bake
