#include "bake/head/head_rig_spec.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "engine/core/json_nesting.h"
#include "bake/head/skin_painter.h"
#include "facial/runtime/rig/action_units.h"

namespace bake {
namespace {

using nlohmann::json;

struct SpecError {
  std::string message;
};

// Reads JSON values while tracking their path, so every error can say where.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw SpecError{source_ + ": " + (path.empty() ? "/" : path) + ": " + problem};
  }
  const json& member(const json& obj, const std::string& path, const char* key) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(path, std::string("missing \"") + key + "\"");
    return *it;
  }
  void object(const json& v, const std::string& path) const {
    if (!v.is_object()) fail(path, "expected an object, found " + std::string(v.type_name()));
  }
  void array(const json& v, const std::string& path) const {
    if (!v.is_array()) fail(path, "expected an array, found " + std::string(v.type_name()));
  }
  void allowOnly(const json& obj, const std::string& path, std::initializer_list<const char*> keys) const {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
      bool known = false;
      for (const char* k : keys) known = known || it.key() == k;
      if (!known) fail(path + "/" + it.key(), "unknown key \"" + it.key() + "\"");
    }
  }
  float number(const json& v, const std::string& path) const {
    if (!v.is_number()) fail(path, "expected a number, found " + std::string(v.type_name()));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(path, "number is not finite");
    return static_cast<float>(d);
  }
  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "expected a string, found " + std::string(v.type_name()));
    const std::string s = v.get<std::string>();
    if (s.empty()) fail(path, "empty string");
    return s;
  }
  bool boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "expected true or false, found " + std::string(v.type_name()));
    return v.get<bool>();
  }
  template <int N>
  glm::vec<N, float> vec(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != N) fail(path, "expected an array of " + std::to_string(N) + " numbers");
    glm::vec<N, float> out;
    for (int i = 0; i < N; ++i) out[i] = number(v[i], path + "/" + std::to_string(i));
    return out;
  }
  std::vector<std::string> strings(const json& v, const std::string& path) const {
    array(v, path);
    std::vector<std::string> out;
    for (size_t i = 0; i < v.size(); ++i) out.push_back(string(v[i], path + "/" + std::to_string(i)));
    return out;
  }

 private:
  std::string source_;
};

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

LandmarkDef parseLandmark(const Reader& r, const json& v, const std::string& path, bool& mirrored) {
  r.object(v, path);
  r.allowOnly(v, path, {"name", "xy", "feature", "position", "offset", "mirror", "note"});
  LandmarkDef d;
  d.name = r.string(r.member(v, path, "name"), path + "/name");
  const int kinds = int(v.contains("xy")) + int(v.contains("feature")) + int(v.contains("position"));
  if (kinds != 1) r.fail(path, "landmark \"" + d.name + "\" needs exactly one of \"xy\", \"feature\", \"position\"");
  if (v.contains("xy")) {
    d.kind = LandmarkDef::Kind::Surface;
    d.xy = r.vec<2>(v["xy"], path + "/xy");
  } else if (v.contains("feature")) {
    d.kind = LandmarkDef::Kind::Feature;
    d.feature = r.string(v["feature"], path + "/feature");
  } else {
    d.kind = LandmarkDef::Kind::Position;
    d.position = r.vec<3>(v["position"], path + "/position");
  }
  if (v.contains("offset")) d.offset = r.vec<3>(v["offset"], path + "/offset");
  mirrored = v.contains("mirror") && r.boolean(v["mirror"], path + "/mirror");
  if (mirrored && !leftSided(d.name))
    r.fail(path + "/mirror", "only left-side landmarks (name ending in _L) can be mirrored, \"" + d.name + "\" is not");
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

MaskDef parseMask(const Reader& r, const json& v, const std::string& path) {
  r.object(v, path);
  r.allowOnly(v, path, {"parts", "jaw", "side", "radius", "feather"});
  MaskDef m;
  if (v.contains("parts")) {
    m.parts = 0;
    const std::vector<std::string> parts = r.strings(v["parts"], path + "/parts");
    for (size_t i = 0; i < parts.size(); ++i) {
      bool found = false;
      for (int p = 0; p < kHeadPartCount; ++p)
        if (parts[i] == headPartName(static_cast<HeadPart>(p))) {
          m.parts |= uint8_t(1u << p);
          found = true;
        }
      if (!found)
        r.fail(path + "/parts/" + std::to_string(i),
               "unknown part \"" + parts[i] + "\" (expected skin, mouth, teeth_upper, teeth_lower or tongue)");
    }
  }
  if (v.contains("jaw")) {
    const std::string jaw = r.string(v["jaw"], path + "/jaw");
    if (jaw == "upper") m.jaw = MaskDef::Jaw::Upper;
    else if (jaw == "lower") m.jaw = MaskDef::Jaw::Lower;
    else if (jaw == "any") m.jaw = MaskDef::Jaw::Any;
    else r.fail(path + "/jaw", "expected \"upper\", \"lower\" or \"any\", found \"" + jaw + "\"");
  }
  if (v.contains("side")) {
    const std::string side = r.string(v["side"], path + "/side");
    if (side == "left") m.side = MaskDef::Side::Left;
    else if (side == "right") m.side = MaskDef::Side::Right;
    else if (side == "both") m.side = MaskDef::Side::Both;
    else r.fail(path + "/side", "expected \"left\", \"right\" or \"both\", found \"" + side + "\"");
  }
  if (v.contains("radius")) m.radius = r.number(v["radius"], path + "/radius");
  if (v.contains("feather")) m.feather = r.number(v["feather"], path + "/feather");
  if (!(m.radius > 0.0f)) r.fail(path + "/radius", "must be > 0");
  if (!(m.feather > 0.0f)) r.fail(path + "/feather", "must be > 0");
  return m;
}

DeformPartDef parsePart(const Reader& r, const json& v, const std::string& path) {
  r.object(v, path);
  r.allowOnly(v, path, {"move", "pins", "free", "mask", "symmetric", "note"});
  DeformPartDef part;
  const json& move = r.member(v, path, "move");
  r.object(move, path + "/move");
  if (move.empty()) r.fail(path + "/move", "no landmark is moved");
  for (auto it = move.begin(); it != move.end(); ++it) {
    const std::string p = path + "/move/" + it.key();
    DisplacementDef d;
    d.landmark = it.key();
    if (it->is_array()) {
      d.by = r.vec<3>(*it, p);
    } else {
      r.object(*it, p);
      r.allowOnly(*it, p, {"by", "to"});
      if (it->contains("by")) d.by = r.vec<3>((*it)["by"], p + "/by");
      if (it->contains("to")) d.to = r.string((*it)["to"], p + "/to");
      if (!it->contains("by") && !it->contains("to")) r.fail(p, "needs \"by\" and/or \"to\"");
    }
    part.moves.push_back(d);
  }
  if (v.contains("pins")) part.pins = r.strings(v["pins"], path + "/pins");
  if (v.contains("free")) part.free = r.strings(v["free"], path + "/free");
  if (v.contains("mask")) part.mask = parseMask(r, v["mask"], path + "/mask");
  const bool symmetric = v.contains("symmetric") && r.boolean(v["symmetric"], path + "/symmetric");
  if (symmetric) {
    if (part.mask.side != MaskDef::Side::Both)
      r.fail(path + "/symmetric", "a symmetric part cannot have a one-sided mask");
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
  return part;
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
  const Reader r(source);
  try {
    json root;
    if (auto nesting = eng::checkJsonNesting(text, source); !nesting) return nesting.error();
    try {
      root = json::parse(text);
    } catch (const json::parse_error& e) {
      r.fail("", std::string("not valid JSON (") + e.what() + ")");
    }
    r.object(root, "");
    r.allowOnly(root, "", {"format", "version", "about", "units", "kernel", "landmarks", "anchors", "actionUnits",
                           "detailLayers"});
    if (r.string(r.member(root, "", "format"), "/format") != "facial-head-landmarks")
      r.fail("/format", "expected \"facial-head-landmarks\"");
    if (r.number(r.member(root, "", "version"), "/version") != 1.0f) r.fail("/version", "only version 1 is supported");

    HeadRigSpec spec;
    spec.source = source;
    if (root.contains("kernel")) {
      const json& k = root["kernel"];
      r.object(k, "/kernel");
      r.allowOnly(k, "/kernel", {"type", "k", "c"});
      const std::string type = r.string(r.member(k, "/kernel", "type"), "/kernel/type");
      if (type == "biharmonic") spec.kernel.type = facial::RbfKernelType::Biharmonic;
      else if (type == "polyharmonic") spec.kernel.type = facial::RbfKernelType::Polyharmonic;
      else if (type == "multiquadric") spec.kernel.type = facial::RbfKernelType::Multiquadric;
      else r.fail("/kernel/type", "expected biharmonic, polyharmonic or multiquadric, found \"" + type + "\"");
      if (k.contains("k")) spec.kernel.k = static_cast<int>(r.number(k["k"], "/kernel/k"));
      if (k.contains("c")) spec.kernel.c = r.number(k["c"], "/kernel/c");
    }

    // Landmarks (mirrored ones expanded right after their left original).
    const json& landmarks = r.member(root, "", "landmarks");
    r.array(landmarks, "/landmarks");
    std::set<std::string> names;
    for (size_t i = 0; i < landmarks.size(); ++i) {
      const std::string path = "/landmarks/" + std::to_string(i);
      bool mirrorIt = false;
      LandmarkDef d = parseLandmark(r, landmarks[i], path, mirrorIt);
      std::vector<LandmarkDef> defs{d};
      if (mirrorIt) defs.push_back(mirrored(d));
      for (const LandmarkDef& def : defs) {
        if (!names.insert(def.name).second) r.fail(path + "/name", "duplicate landmark \"" + def.name + "\"");
        spec.landmarks.push_back(def);
      }
    }
    if (root.contains("anchors")) {
      const json& anchors = root["anchors"];
      r.array(anchors, "/anchors");
      for (size_t i = 0; i < anchors.size(); ++i) {
        const std::string path = "/anchors/" + std::to_string(i);
        r.object(anchors[i], path);
        r.allowOnly(anchors[i], path, {"name", "position"});
        AnchorDef a{r.string(r.member(anchors[i], path, "name"), path + "/name"),
                    r.vec<3>(r.member(anchors[i], path, "position"), path + "/position")};
        if (!names.insert(a.name).second) r.fail(path + "/name", "duplicate name \"" + a.name + "\"");
        spec.anchors.push_back(a);
      }
    }

    // Action units: every canonical channel exactly once.
    const json& aus = r.member(root, "", "actionUnits");
    r.array(aus, "/actionUnits");
    std::set<std::string> seen;
    auto requireLandmark = [&](const std::string& name, const std::string& path) {
      if (!spec.findLandmark(name)) r.fail(path, "unknown landmark \"" + name + "\"");
    };
    for (size_t i = 0; i < aus.size(); ++i) {
      const std::string path = "/actionUnits/" + std::to_string(i);
      r.object(aus[i], path);
      r.allowOnly(aus[i], path, {"name", "parts", "note"});
      ActionUnitDef au;
      au.name = r.string(r.member(aus[i], path, "name"), path + "/name");
      if (!facial::actionUnitIndex(au.name))
        r.fail(path + "/name", "\"" + au.name + "\" is not a channel of facial/runtime/rig/action_units.h");
      if (!seen.insert(au.name).second) r.fail(path + "/name", "action unit \"" + au.name + "\" defined twice");
      const json& parts = r.member(aus[i], path, "parts");
      r.array(parts, path + "/parts");
      if (parts.empty()) r.fail(path + "/parts", "no parts");
      for (size_t p = 0; p < parts.size(); ++p) {
        const std::string pp = path + "/parts/" + std::to_string(p);
        DeformPartDef part = parsePart(r, parts[p], pp);
        for (const DisplacementDef& d : part.moves) {
          requireLandmark(d.landmark, pp + "/move/" + d.landmark);
          if (!d.to.empty()) requireLandmark(d.to, pp + "/move/" + d.landmark + "/to");
        }
        for (const std::string& n : part.pins) requireLandmark(n, pp + "/pins");
        for (const std::string& n : part.free) requireLandmark(n, pp + "/free");
        au.parts.push_back(std::move(part));
      }
      spec.actionUnits.push_back(std::move(au));
    }
    for (const facial::ActionUnitInfo& info : facial::actionUnits())
      if (!seen.count(std::string(info.name)))
        r.fail("/actionUnits", "action unit \"" + std::string(info.name) + "\" is missing");

    if (root.contains("detailLayers")) {
      const json& layers = root["detailLayers"];
      r.array(layers, "/detailLayers");
      for (size_t i = 0; i < layers.size(); ++i) {
        const std::string path = "/detailLayers/" + std::to_string(i);
        r.object(layers[i], path);
        r.allowOnly(layers[i], path, {"layer", "target", "strength"});
        DetailLayerDef d;
        d.layer = r.string(r.member(layers[i], path, "layer"), path + "/layer");
        d.target = r.string(r.member(layers[i], path, "target"), path + "/target");
        if (layers[i].contains("strength")) d.strength = r.number(layers[i]["strength"], path + "/strength");
        const auto& known = skinDetailLayerNames();
        if (std::find(known.begin(), known.end(), d.layer) == known.end())
          r.fail(path + "/layer", "unknown detail layer \"" + d.layer + "\"");
        if (!facial::actionUnitIndex(d.target)) r.fail(path + "/target", "\"" + d.target + "\" is not an action unit channel");
        if (d.strength < 0.0f) r.fail(path + "/strength", "must be >= 0");
        spec.detailLayers.push_back(d);
      }
    }
    return spec;
  } catch (const SpecError& e) {
    return eng::makeError(eng::ErrorKind::Malformed, e.message);
  }
}

eng::Result<HeadRigSpec> loadHeadRigSpec(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::Io, path.string() + ": cannot open the landmark file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseHeadRigSpec(text.str(), path.string());
}

}  // namespace bake
