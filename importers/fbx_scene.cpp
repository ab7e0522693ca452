#include "importers/fbx_scene.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "engine/core/confined_path.h"
#include "engine/core/load_budget.h"
#include "engine/core/text_lines.h"
#include "engine/core/uv_raster.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/image_io.h"
#include "engine/scene/model_check.h"
#include "engine/scene/normals.h"
#include "importers/fbx_document.h"

namespace importers {
namespace {

using fbx::Node;

// "Name\0\1Class" (binary) or "Class::Name" (ASCII): the name.
std::string objectName(std::string_view raw) {
  if (const size_t k = raw.find(std::string_view("\0\1", 2)); k != std::string_view::npos) return std::string(raw.substr(0, k));
  if (const size_t k = raw.find("::"); k != std::string_view::npos) return std::string(raw.substr(k + 2));
  return std::string(raw);
}

struct Object {
  const Node* node = nullptr;
  std::string name;
  std::string_view subclass;  // "Mesh", "Shape", "LimbNode", "BlendShape", "Cluster", ...
};

struct Link {
  int64_t id = 0;
  std::string_view property;  // an OP connection's property ("DiffuseColor"), empty for OO
};

// A Properties70 entry's values start after name, type, label and flags;
// Properties60 (older 7.x writers) have no label.
const Node* propertyNamed(const Node& object, std::string_view name, size_t& first) {
  for (const char* block : {"Properties70", "Properties60"}) {
    const Node* props = object.child(block);
    if (!props) continue;
    first = block[10] == '7' ? 4 : 3;
    for (const Node& p : props->children)
      if (p.text(0) == name) return &p;
  }
  return nullptr;
}

std::optional<double> numberProperty(const Node& object, std::string_view name) {
  size_t first = 0;
  const Node* p = propertyNamed(object, name, first);
  if (!p) return std::nullopt;
  const auto v = p->number(first);
  if (!v || !std::isfinite(*v)) return std::nullopt;
  return v;
}

std::optional<glm::dvec3> vectorProperty(const Node& object, std::string_view name) {
  size_t first = 0;
  const Node* p = propertyNamed(object, name, first);
  if (!p) return std::nullopt;
  glm::dvec3 v;
  for (int k = 0; k < 3; ++k) {
    const auto c = p->number(first + size_t(k));
    if (!c || !std::isfinite(*c)) return std::nullopt;
    v[k] = *c;
  }
  return v;
}

glm::dmat4 translation(const glm::dvec3& t) { return glm::translate(glm::dmat4(1.0), t); }

// FBX Euler angles in degrees; order 0 (XYZ) turns about X first.
glm::dmat4 eulerRotation(const glm::dvec3& degrees, int order) {
  const glm::dvec3 r = glm::radians(degrees);
  const glm::dmat4 x = glm::rotate(glm::dmat4(1.0), r.x, glm::dvec3(1, 0, 0));
  const glm::dmat4 y = glm::rotate(glm::dmat4(1.0), r.y, glm::dvec3(0, 1, 0));
  const glm::dmat4 z = glm::rotate(glm::dmat4(1.0), r.z, glm::dvec3(0, 0, 1));
  switch (order) {
    case 1: return y * z * x;  // XZY
    case 2: return x * z * y;  // YZX
    case 3: return z * x * y;  // YXZ
    case 4: return y * x * z;  // ZXY
    case 5: return x * y * z;  // ZYX
    default: return z * y * x;  // XYZ, and spheric XYZ
  }
}

// The FBX SDK's local transform,
// T * Roff * Rp * Rpre * R * Rpost^-1 * Rp^-1 * Soff * Sp * S * Sp^-1,
// as the node's translation, rotation and scale: its linear part is the
// rotation Rpre * R * Rpost^-1 times the scale S, so the split is exact
// and the node can be posed like a glTF one.
// As the FBX SDK (and Blender's importer) reads it, pre- and post-rotation
// and the rotation order count only while RotationActive is set.
struct AnimatedTransform {
  std::optional<glm::dvec3> translation, rotation, scale;  // Lcl values at a key, where animated
};

void setLocalTransform(const Node& model, eng::Node& node, const AnimatedTransform& at = {}) {
  const glm::dvec3 zero(0.0);
  const bool rotationActive = numberProperty(model, "RotationActive").value_or(0.0) != 0.0;
  const int order = rotationActive ? int(numberProperty(model, "RotationOrder").value_or(0)) : 0;
  auto activeRotation = [&](std::string_view name) { return rotationActive ? vectorProperty(model, name).value_or(zero) : zero; };
  const glm::dmat4 rp = translation(vectorProperty(model, "RotationPivot").value_or(zero));
  const glm::dmat4 sp = translation(vectorProperty(model, "ScalingPivot").value_or(zero));
  const glm::dvec3 scale = at.scale ? *at.scale : vectorProperty(model, "Lcl Scaling").value_or(glm::dvec3(1.0));
  // Pre- and post-rotation in the node's rotation order too, as Blender and
  // three.js read them; the post-rotation inverted, as the FBX SDK and three.js
  // have it (Blender 3.4 leaves it as it is).
  const glm::dmat4 rotation = eulerRotation(activeRotation("PreRotation"), order) *
                              eulerRotation(at.rotation ? *at.rotation : vectorProperty(model, "Lcl Rotation").value_or(zero), order) *
                              glm::inverse(eulerRotation(activeRotation("PostRotation"), order));
  const glm::dmat4 local = translation(at.translation ? *at.translation : vectorProperty(model, "Lcl Translation").value_or(zero)) *
                           translation(vectorProperty(model, "RotationOffset").value_or(zero)) * rp * rotation * glm::inverse(rp) *
                           translation(vectorProperty(model, "ScalingOffset").value_or(zero)) * sp * glm::scale(glm::dmat4(1.0), scale) *
                           glm::inverse(sp);
  node.translation = glm::vec3(local[3]);
  node.rotation = glm::normalize(glm::quat(glm::quat_cast(glm::dmat3(rotation))));
  node.scale = glm::vec3(scale);
}

// The transform that applies to a Model's own geometry only (its rotation
// in the node's order, as Blender and three.js read it).
glm::dmat4 geometricTransform(const Node& model) {
  const glm::dvec3 zero(0.0);
  const bool rotationActive = numberProperty(model, "RotationActive").value_or(0.0) != 0.0;
  const int order = rotationActive ? int(numberProperty(model, "RotationOrder").value_or(0)) : 0;
  return translation(vectorProperty(model, "GeometricTranslation").value_or(zero)) *
         eulerRotation(vectorProperty(model, "GeometricRotation").value_or(zero), order) *
         glm::scale(glm::dmat4(1.0), vectorProperty(model, "GeometricScaling").value_or(glm::dvec3(1.0)));
}

// A layer element (normals, UVs, colours) as it maps polygon corners to values.
struct LayerElement {
  enum class Mapping { PolygonVertex, Vertex, Polygon, AllSame } mapping = Mapping::PolygonVertex;
  bool indexed = false;
  std::vector<double> values;
  std::vector<int64_t> index;
  size_t width = 3;

  // The element's value number for a corner, -1 when out of range.
  int64_t valueFor(size_t polygon, size_t corner, int64_t controlPoint) const {
    const size_t i = mapping == Mapping::PolygonVertex ? corner
                     : mapping == Mapping::Vertex      ? size_t(controlPoint)
                     : mapping == Mapping::Polygon     ? polygon
                                                       : 0;
    int64_t k = int64_t(i);
    if (indexed) {
      if (i >= index.size()) return -1;
      k = index[i];
    }
    return k >= 0 && size_t(k) < values.size() / width ? k : -1;
  }
};

// The first layer element called `name` with `valuesName` ("Normals") and,
// when indexed, `indexName` ("NormalsIndex"); nullopt (with a warning) when
// it is absent or unusable.
std::optional<LayerElement> layerElement(const Node& geometry, std::string_view name, std::string_view valuesName,
                                         std::string_view indexName, size_t width, const std::string& where,
                                         std::vector<std::string>& warnings) {
  const Node* node = nullptr;
  for (const Node& c : geometry.children)
    if (c.name == name && (!node || c.integer(0).value_or(1) == 0)) node = &c;
  if (!node) return std::nullopt;
  LayerElement e;
  e.width = width;
  const Node* mapping = node->child("MappingInformationType");
  const Node* reference = node->child("ReferenceInformationType");
  const std::string_view m = mapping ? mapping->text(0) : "ByPolygonVertex";
  const std::string_view r = reference ? reference->text(0) : "Direct";
  if (m == "ByPolygonVertex") e.mapping = LayerElement::Mapping::PolygonVertex;
  else if (m == "ByVertex" || m == "ByVertice") e.mapping = LayerElement::Mapping::Vertex;
  else if (m == "ByPolygon") e.mapping = LayerElement::Mapping::Polygon;
  else if (m == "AllSame") e.mapping = LayerElement::Mapping::AllSame;
  else {
    warnings.push_back(where + ": " + std::string(name) + " mapped '" + eng::shownText(m) + "' is not read");
    return std::nullopt;
  }
  e.indexed = r == "IndexToDirect" || r == "Index";
  const Node* values = node->child(valuesName);
  if (values) e.values = values->numbers(0);
  if (e.indexed) {
    const Node* index = node->child(indexName);
    if (!index || !index->integers(0, e.index)) {
      warnings.push_back(where + ": " + std::string(name) + " is indexed but has no " + std::string(indexName) + "; not read");
      return std::nullopt;
    }
  }
  if (e.values.empty() || e.values.size() % width != 0) {
    warnings.push_back(where + ": " + std::string(name) + " holds " + std::to_string(e.values.size()) + " numbers, not a multiple of " +
                       std::to_string(width) + "; not read");
    return std::nullopt;
  }
  return e;
}

// A vertex of a primitive: one control point with one normal, UV and colour.
struct VertexKey {
  int64_t controlPoint;
  float n[3];
  float uv[2];
  float colour[4];
  // Field by field (a memcmp would read the padding after `colour`); exact
  // floats: corners agree only when the file gives them the same values.
  bool operator==(const VertexKey& o) const {
    return controlPoint == o.controlPoint && std::memcmp(n, o.n, sizeof n + sizeof uv + sizeof colour) == 0;
  }
};
struct VertexKeyHash {
  size_t operator()(const VertexKey& k) const {
    size_t h = std::hash<int64_t>()(k.controlPoint);
    uint32_t bits[9];
    std::memcpy(bits, k.n, sizeof(bits));
    for (uint32_t b : bits) h = h * 1000003u ^ b;
    return h;
  }
};

struct PrimitiveBuild {
  eng::Primitive prim;
  std::vector<int64_t> controlPoint;  // per vertex
  int64_t slot = 0;                   // the Model's material slot
  bool fileNormals = true;
  bool anyTexcoords = false;
};

class SceneBuilder {
 public:
  SceneBuilder(const fbx::Document& doc, const std::filesystem::path& path, eng::LoadBudget& budget)
      : doc_(doc), path_(path), name_(path.string()), budget_(budget) {}

  eng::Result<eng::Model> build() {
    ENG_TRY(indexObjects());
    const glm::dmat4 axes = axisConversion();
    eng::Node root;
    root.name = "FBX axes and units";
    root.matrix = glm::mat4(axes);
    root.hasMatrix = true;
    model_.nodes.push_back(root);
    model_.roots = {0};
    ENG_TRY(addModels());
    addAnimations();
    if (model_.meshes.empty())
      return eng::makeError(eng::ErrorKind::Malformed, name_ + ": no mesh to draw" +
                            (firstSkipped_.empty() ? std::string(" (the file has no mesh geometry)") : "; " + firstSkipped_));
    if (glm::determinant(axes) < 0.0)
      for (eng::Mesh& mesh : model_.meshes)
        for (eng::Primitive& prim : mesh.primitives)
          for (size_t t = 0; t + 2 < prim.indices.size(); t += 3) std::swap(prim.indices[t + 1], prim.indices[t + 2]);
    model_.sourcePath = name_;
    if (auto consistent = eng::checkModel(model_); !consistent) return consistent.error().prefixed(name_ + ": ");
    return std::move(model_);
  }

 private:
  void warn(std::string what) { model_.warnings.push_back(std::move(what)); }

  eng::Result<void> indexObjects() {
    const Node* objects = doc_.root.child("Objects");
    if (!objects) return eng::makeError(eng::ErrorKind::Malformed, name_ + ": an FBX file without an Objects section");
    size_t repeated = 0;
    for (const Node& o : objects->children) {
      const auto id = o.integer(0);
      if (!id) continue;  // FBX 7 numbers every object
      repeated += !objects_.try_emplace(*id, Object{&o, objectName(o.text(1)), o.text(2)}).second;
    }
    if (repeated > 0) warn(std::to_string(repeated) + " object(s) reuse an earlier object's id; the earlier one is read");
    // Each Model's matrix at bind time (BindPose entries), for skins.
    for (const Node& o : objects->children) {
      if (o.name != "Pose" || o.text(2) != "BindPose") continue;
      for (const Node& entry : o.children) {
        if (entry.name != "PoseNode") continue;
        const Node* node = entry.child("Node");
        const auto matrix = matrixOf(entry.child("Matrix"));
        if (node && node->integer(0) && matrix) bindPose_.try_emplace(*node->integer(0), *matrix);
      }
    }
    if (const Node* connections = doc_.root.child("Connections"))
      for (const Node& c : connections->children) {
        if (c.name != "C") continue;
        const auto child = c.integer(1), parent = c.integer(2);
        if (!child || !parent) continue;
        const Link down{*child, c.text(3)};
        children_[*parent].push_back(down);
        parents_[*child].push_back(Link{*parent, c.text(3)});
      }
    return {};
  }

  // The file's axes (GlobalSettings) turned to Y up, +Z front, +X right, and
  // its unit (UnitScaleFactor centimetres) to metres.
  glm::dmat4 axisConversion() {
    const Node* settings = doc_.root.child("GlobalSettings");
    auto setting = [&](std::string_view key, double fallback) {
      return settings ? numberProperty(*settings, key).value_or(fallback) : fallback;
    };
    int up = int(setting("UpAxis", 1)), front = int(setting("FrontAxis", 2)), coord = int(setting("CoordAxis", 0));
    double upSign = setting("UpAxisSign", 1) < 0 ? -1 : 1, frontSign = setting("FrontAxisSign", 1) < 0 ? -1 : 1,
           coordSign = setting("CoordAxisSign", 1) < 0 ? -1 : 1;
    const bool valid = up >= 0 && up < 3 && front >= 0 && front < 3 && coord >= 0 && coord < 3 && up != front && up != coord &&
                       front != coord;
    if (!valid) {
      warn("GlobalSettings names the axes up " + std::to_string(up) + ", front " + std::to_string(front) + ", coord " +
           std::to_string(coord) + ": read as Y up, Z front");
      up = 1, front = 2, coord = 0, upSign = frontSign = coordSign = 1;
    }
    double unit = setting("UnitScaleFactor", 1.0);
    if (!(unit > 0.0 && unit < 1e6)) {
      warn("UnitScaleFactor " + std::to_string(unit) + " read as 1 (centimetres)");
      unit = 1.0;
    }
    glm::dmat4 m(0.0);
    m[coord][0] = coordSign;
    m[up][1] = upSign;
    m[front][2] = frontSign;
    m[3][3] = 1.0;
    return glm::scale(glm::dmat4(1.0), glm::dvec3(unit / 100.0)) * m;
  }

  std::vector<int64_t> linked(int64_t parent, std::string_view kind, std::string_view subclass = {}) const {
    std::vector<int64_t> out;
    const auto it = children_.find(parent);
    if (it == children_.end()) return out;
    for (const Link& l : it->second) {
      const auto o = objects_.find(l.id);
      if (o == objects_.end() || o->second.node->name != kind) continue;
      if (!subclass.empty() && o->second.subclass != subclass) continue;
      out.push_back(l.id);
    }
    return out;
  }

  eng::Result<void> addModels() {
    // Nodes in file order, then parents, then meshes (which need the bones' nodes for skins).
    std::vector<int64_t> models;
    for (const Node& o : doc_.root.child("Objects")->children)
      if (o.name == "Model")
        if (const auto id = o.integer(0); id && objects_.at(*id).node == &o) models.push_back(*id);
    for (int64_t id : models) {
      const Object& o = objects_.at(id);
      eng::Node node;
      node.name = o.name;
      setLocalTransform(*o.node, node);
      nodeOf_[id] = int(model_.nodes.size());
      modelOfNode_.resize(model_.nodes.size() + 1, 0);
      modelOfNode_.back() = id;
      model_.nodes.push_back(std::move(node));
    }
    for (int64_t id : models) {
      const int index = nodeOf_.at(id);
      int parent = 0;
      if (const auto it = parents_.find(id); it != parents_.end())
        for (const Link& l : it->second)
          if (const auto p = nodeOf_.find(l.id); p != nodeOf_.end() && p->second != index) {
            parent = p->second;
            break;
          }
      model_.nodes[size_t(index)].parent = parent;
    }
    // A parent chain that comes back to itself would hang every traversal.
    // Each node is walked up once (a chain of 100,000 Models stays linear).
    enum : uint8_t { kUnseen, kOnPath, kDone };
    std::vector<uint8_t> state(model_.nodes.size(), kUnseen);
    std::vector<int> path;
    for (size_t n = 1; n < model_.nodes.size(); ++n) {
      path.clear();
      int at = int(n);
      while (at > 0 && state[size_t(at)] == kUnseen) {
        state[size_t(at)] = kOnPath;
        path.push_back(at);
        at = model_.nodes[size_t(at)].parent;
      }
      if (at > 0 && state[size_t(at)] == kOnPath)
        return eng::makeError(eng::ErrorKind::Malformed, name_ + ": Model '" + eng::shownText(model_.nodes[size_t(at)].name) + "' is its own ancestor");
      for (int p : path) state[size_t(p)] = kDone;
    }
    for (size_t n = 1; n < model_.nodes.size(); ++n) model_.nodes[size_t(model_.nodes[n].parent)].children.push_back(int(n));
    warnOfOtherScaleInheritance(models);
    for (int64_t id : models) {
      const Object& o = objects_.at(id);
      if (o.subclass != "Mesh") continue;
      for (int64_t geometry : linked(id, "Geometry", "Mesh")) {
        auto mesh = buildMesh(id, geometry);
        if (!mesh) {
          warn(mesh.error().message + "; mesh skipped");
          if (firstSkipped_.empty()) firstSkipped_ = mesh.error().message;
          continue;
        }
        eng::Node& node = model_.nodes[size_t(nodeOf_.at(id))];
        if (node.mesh >= 0) {  // a second geometry on one Model: a child node draws it
          eng::Node extra;
          extra.name = node.name + " geometry " + std::to_string(model_.nodes.size());
          extra.parent = nodeOf_.at(id);
          extra.mesh = int(model_.meshes.size());
          extra.skin = mesh->second;
          node.children.push_back(int(model_.nodes.size()));
          model_.nodes.push_back(std::move(extra));
        } else {
          node.mesh = int(model_.meshes.size());
          node.skin = mesh->second;
        }
        model_.meshes.push_back(std::move(mesh->first));
      }
    }
    return {};
  }

  // A node graph multiplies parents' matrices in (FBX's InheritType 1, RSrs,
  // what Maya and Blender write); the other two ways differ only under a
  // non-uniform scale, which is warned of. Parents come before children here
  // only by chance, so whether a node is under a non-uniform scale is found
  // once per node, walking up to the first node already known.
  void warnOfOtherScaleInheritance(const std::vector<int64_t>& models) {
    std::vector<int8_t> unevenAbove(model_.nodes.size(), -1);  // -1 unknown
    unevenAbove[0] = 0;
    std::vector<int> path;
    auto isUnevenAbove = [&](int node) {
      path.clear();
      for (int at = node; unevenAbove[size_t(at)] < 0; at = model_.nodes[size_t(at)].parent) path.push_back(at);
      for (auto it = path.rbegin(); it != path.rend(); ++it) {
        const eng::Node& parent = model_.nodes[size_t(model_.nodes[size_t(*it)].parent)];
        const glm::vec3 s = glm::abs(parent.scale);
        const bool uneven = model_.nodes[size_t(*it)].parent > 0 && std::max({s.x, s.y, s.z}) > 1.0001f * std::min({s.x, s.y, s.z});
        unevenAbove[size_t(*it)] = int8_t(uneven || unevenAbove[size_t(model_.nodes[size_t(*it)].parent)] > 0);
      }
      return unevenAbove[size_t(node)] > 0;
    };
    size_t otherInheritance = 0;
    for (int64_t id : models)
      if (int(numberProperty(*objects_.at(id).node, "InheritType").value_or(1)) != 1) otherInheritance += isUnevenAbove(nodeOf_.at(id));
    if (otherInheritance > 0)
      warn(std::to_string(otherInheritance) + " Model(s) under a non-uniform scale inherit it another way than RSrs (InheritType 0 or 2); "
           "read as RSrs, they may show sheared");
  }

  eng::Result<void> charge(size_t count, size_t each, std::string_view what) {
    if (auto charged = budget_.charge(count, each, what); !charged) return charged.error().prefixed(name_ + ": ");
    return {};
  }

  // A geometry's problem, without the file's name: it becomes a warning (the
  // mesh skipped) or, when nothing is left, part of the file's error.
  eng::Error geometryError(const std::string& where, const std::string& what) const {
    return eng::makeError(eng::ErrorKind::Malformed, where + ": " + what);
  }

  // What a geometry's first layer holds for its polygon corners.
  struct GeometryLayers {
    std::optional<LayerElement> normals, uvs, colours;
    std::vector<int64_t> polygonMaterial;  // a material slot per polygon, or one for all
    bool allSameMaterial = true;
    glm::dmat3 normalMatrix{1.0};  // the geometric transform's, for normals
  };

  GeometryLayers layersOf(const Node& g, const glm::dmat4& geometric, const std::string& where) {
    GeometryLayers layers;
    layers.normalMatrix = glm::transpose(glm::inverse(glm::dmat3(geometric)));
    layers.normals = layerElement(g, "LayerElementNormal", "Normals", "NormalsIndex", 3, where, model_.warnings);
    layers.uvs = layerElement(g, "LayerElementUV", "UV", "UVIndex", 2, where, model_.warnings);
    layers.colours = layerElement(g, "LayerElementColor", "Colors", "ColorIndex", 4, where, model_.warnings);
    if (const Node* c = g.child("LayerElementMaterial")) {
      if (const Node* m = c->child("Materials")) m->integers(0, layers.polygonMaterial);
      const Node* mapping = c->child("MappingInformationType");
      layers.allSameMaterial = !mapping || mapping->text(0) == "AllSame";
    }
    return layers;
  }

  // The geometry's control points through its geometric transform.
  eng::Result<std::vector<glm::vec3>> controlPointsOf(const Node& g, const glm::dmat4& geometric, const std::string& where) {
    const Node* verticesNode = g.child("Vertices");
    if (!verticesNode) return geometryError(where, "no Vertices");
    const std::vector<double> vertices = verticesNode->numbers(0);
    if (vertices.size() % 3 != 0) return geometryError(where, std::to_string(vertices.size()) + " vertex coordinates, not a multiple of 3");
    for (double v : vertices)
      if (!std::isfinite(v)) return geometryError(where, "a vertex coordinate is not a finite number");
    std::vector<glm::vec3> points(vertices.size() / 3);
    for (size_t p = 0; p < points.size(); ++p)
      points[p] = glm::vec3(geometric * glm::dvec4(vertices[3 * p], vertices[3 * p + 1], vertices[3 * p + 2], 1.0));
    return points;
  }

  // What one polygon corner carries; `b` learns whether its normals and UVs are usable.
  static VertexKey cornerKey(const GeometryLayers& layers, size_t polygon, size_t corner, int64_t cp, PrimitiveBuild& b,
                             size_t& badNormals) {
    VertexKey key{};
    key.controlPoint = cp;
    if (layers.normals) {
      const LayerElement& e = *layers.normals;
      const int64_t i = e.valueFor(polygon, corner, cp);
      glm::dvec3 n(0.0);
      if (i >= 0) n = layers.normalMatrix * glm::dvec3(e.values[3 * i], e.values[3 * i + 1], e.values[3 * i + 2]);
      const double len = glm::length(n);
      if (std::isfinite(len) && len > 1e-12) {
        n /= len;
        key.n[0] = float(n.x), key.n[1] = float(n.y), key.n[2] = float(n.z);
      } else {
        b.fileNormals = false;
        ++badNormals;
      }
    }
    if (layers.uvs) {
      const LayerElement& e = *layers.uvs;
      const int64_t i = e.valueFor(polygon, corner, cp);
      if (i >= 0 && std::isfinite(e.values[2 * i]) && std::isfinite(e.values[2 * i + 1])) {
        key.uv[0] = float(e.values[2 * i]);
        key.uv[1] = float(1.0 - e.values[2 * i + 1]);  // FBX's V points up, glTF's down
        b.anyTexcoords = true;
      }
    }
    if (layers.colours) {
      const int64_t i = layers.colours->valueFor(polygon, corner, cp);
      for (int c = 0; c < 4; ++c) {
        const double v = i >= 0 ? layers.colours->values[size_t(4 * i + c)] : 1.0;
        key.colour[c] = std::isfinite(v) ? float(std::clamp(v, 0.0, 1.0)) : 1.0f;
      }
    }
    return key;
  }

  // The polygons fanned into one primitive per material slot, a vertex per
  // control point where its corners agree.
  eng::Result<std::vector<PrimitiveBuild>> buildPrimitives(const std::vector<int64_t>& polygonIndex, const std::vector<glm::vec3>& points,
                                                           const GeometryLayers& layers, size_t slots, const std::string& where) {
    std::map<int64_t, size_t> primitiveOfSlot;
    std::vector<PrimitiveBuild> builds;
    std::vector<std::unordered_map<VertexKey, uint32_t, VertexKeyHash>> vertexOf;
    size_t polygon = 0, start = 0, badNormals = 0;
    std::vector<uint32_t> face;
    for (size_t corner = 0; corner < polygonIndex.size(); ++corner) {
      // A polygon's last corner is stored as ~index.
      if (polygonIndex[corner] >= 0 && corner + 1 < polygonIndex.size()) continue;
      int64_t slot = 0;
      if (!layers.polygonMaterial.empty()) {
        const size_t i = layers.allSameMaterial ? 0 : polygon;
        slot = i < layers.polygonMaterial.size() ? layers.polygonMaterial[i] : 0;
      }
      if (slot < 0 || size_t(slot) >= std::max<size_t>(slots, 1)) slot = 0;
      const auto [it, added] = primitiveOfSlot.try_emplace(slot, builds.size());
      if (added) {
        builds.emplace_back().slot = slot;
        vertexOf.emplace_back();
      }
      PrimitiveBuild& b = builds[it->second];
      auto& map = vertexOf[it->second];
      face.clear();
      for (size_t k = start; k <= corner; ++k) {
        const int64_t cp = polygonIndex[k] < 0 ? ~polygonIndex[k] : polygonIndex[k];
        if (size_t(cp) >= points.size())
          return geometryError(where, "polygon " + std::to_string(polygon) + " names vertex " + std::to_string(cp) + " of " +
                                          std::to_string(points.size()));
        const VertexKey key = cornerKey(layers, polygon, k, cp, b, badNormals);
        const auto [vit, isNew] = map.try_emplace(key, uint32_t(b.prim.positions.size()));
        if (isNew) {
          b.prim.positions.push_back(points[size_t(cp)]);
          b.prim.normals.push_back(glm::vec3(key.n[0], key.n[1], key.n[2]));
          b.prim.texcoords.push_back(glm::vec2(key.uv[0], key.uv[1]));
          if (layers.colours)
            b.prim.colors.push_back(glm::vec4(eng::srgbToLinear(key.colour[0]), eng::srgbToLinear(key.colour[1]),
                                              eng::srgbToLinear(key.colour[2]), key.colour[3]));
          b.controlPoint.push_back(cp);
        }
        face.push_back(vit->second);
      }
      // Fanned; points and edges (fewer than three corners) add nothing.
      for (size_t k = 2; k < face.size(); ++k) b.prim.indices.insert(b.prim.indices.end(), {face[0], face[k - 1], face[k]});
      ++polygon;
      start = corner + 1;
    }
    if (badNormals > 0) warn(where + ": " + std::to_string(badNormals) + " corners without a usable normal; smooth normals made");
    std::erase_if(builds, [](const PrimitiveBuild& b) { return b.prim.indices.empty(); });
    if (builds.empty()) return geometryError(where, "no polygon with three corners or more");
    for (PrimitiveBuild& b : builds) {
      if (!b.anyTexcoords) b.prim.texcoords.clear();
      if (!layers.normals || !b.fileNormals) b.prim.normals = eng::computeSmoothNormals(b.prim.positions, b.prim.indices);
    }
    return builds;
  }

  // The mesh of a Model's Geometry and its skin (-1 when it has none).
  eng::Result<std::pair<eng::Mesh, int>> buildMesh(int64_t modelId, int64_t geometryId) {
    const Object& modelObject = objects_.at(modelId);
    const Object& geometryObject = objects_.at(geometryId);
    const Node& g = *geometryObject.node;
    const std::string where = "geometry '" + eng::shownText(geometryObject.name) + "'";
    const glm::dmat4 geometric = geometricTransform(*modelObject.node);
    const std::vector<glm::vec3> points = ENG_TRY_VALUE(controlPointsOf(g, geometric, where));
    const Node* polygonsNode = g.child("PolygonVertexIndex");
    std::vector<int64_t> polygonIndex;
    if (!polygonsNode || !polygonsNode->integers(0, polygonIndex))
      return geometryError(where, "no PolygonVertexIndex of whole numbers");
    ENG_TRY(charge(polygonIndex.size(), sizeof(eng::Primitive) / 4 + 64, "FBX " + where));
    const std::vector<int64_t> materialIds = linked(modelId, "Material");
    std::vector<PrimitiveBuild> builds =
        ENG_TRY_VALUE(buildPrimitives(polygonIndex, points, layersOf(g, geometric, where), materialIds.size(), where));
    eng::Mesh mesh;
    mesh.name = modelObject.name;
    // The Model's material connections, in order, are its slots.
    for (PrimitiveBuild& b : builds) b.prim.material = size_t(b.slot) < materialIds.size() ? materialFor(materialIds[size_t(b.slot)]) : -1;
    ENG_TRY(addTargets(geometryId, points.size(), glm::dmat3(geometric), builds, mesh, where));
    const int skin = ENG_TRY_VALUE(addSkin(geometryId, modelId, builds, where));
    for (PrimitiveBuild& b : builds) mesh.primitives.push_back(std::move(b.prim));
    return std::make_pair(std::move(mesh), skin);
  }

  // Blend shape channels as morph targets, each from its full shape.
  eng::Result<void> addTargets(int64_t geometryId, size_t controlPoints, const glm::dmat3& linear, std::vector<PrimitiveBuild>& builds,
                               eng::Mesh& mesh, const std::string& where) {
    std::vector<std::vector<glm::vec3>> restNormals(builds.size());
    // Which primitive vertices each control point became, so that a shape
    // costs what it moves (and the primitives it moves, charged to the
    // budget), not the mesh's size times the channels.
    std::vector<uint32_t> firstOfPoint(controlPoints + 1, 0);
    for (const PrimitiveBuild& b : builds)
      for (int64_t cp : b.controlPoint) ++firstOfPoint[size_t(cp) + 1];
    for (size_t p = 0; p < controlPoints; ++p) firstOfPoint[p + 1] += firstOfPoint[p];
    std::vector<std::pair<uint32_t, uint32_t>> vertexOfPoint(firstOfPoint.back());  // (primitive, vertex)
    {
      std::vector<uint32_t> next(firstOfPoint.begin(), firstOfPoint.end() - 1);
      for (uint32_t i = 0; i < builds.size(); ++i)
        for (uint32_t v = 0; v < builds[i].controlPoint.size(); ++v) vertexOfPoint[next[size_t(builds[i].controlPoint[v])]++] = {i, v};
    }
    for (int64_t blendShape : linked(geometryId, "Deformer", "BlendShape")) {
      const std::string& deformerName = objects_.at(blendShape).name;
      for (int64_t channelId : linked(blendShape, "Deformer", "BlendShapeChannel")) {
        const Object& channel = objects_.at(channelId);
        std::string name = channel.name;
        // Maya writes "<deformer>.<channel>"; the channel's own name is the target's.
        if (!deformerName.empty() && name.size() > deformerName.size() + 1 && name.starts_with(deformerName + "."))
          name.erase(0, deformerName.size() + 1);
        const std::string what = where + ": blend shape '" + eng::shownText(name) + "'";
        const std::vector<int64_t> shapes = linked(channelId, "Geometry", "Shape");
        if (shapes.empty()) {
          warn(what + " has no shape; left out");
          continue;
        }
        // The full shape is the one at the largest FullWeights (the last, as written).
        size_t full = shapes.size() - 1;
        if (const Node* weights = channel.node->child("FullWeights"); weights && shapes.size() > 1) {
          const std::vector<double> w = weights->numbers(0);
          if (w.size() == shapes.size()) full = size_t(std::max_element(w.begin(), w.end()) - w.begin());
          warn(what + ": " + std::to_string(shapes.size() - 1) + " in-between shape(s) not read; the full shape is");
        }
        const Node& shape = *objects_.at(shapes[full]).node;
        std::vector<int64_t> indexes;
        const Node* indexesNode = shape.child("Indexes");
        const Node* verticesNode = shape.child("Vertices");
        const std::vector<double> offsets = verticesNode ? verticesNode->numbers(0) : std::vector<double>();
        if (!indexesNode || !indexesNode->integers(0, indexes) || offsets.size() != 3 * indexes.size()) {
          warn(what + ": " + std::to_string(indexes.size()) + " indexes and " + std::to_string(offsets.size()) +
               " offset coordinates do not pair; left out");
          continue;
        }
        bool usable = true;
        std::vector<bool> moves(builds.size(), false);
        for (size_t k = 0; k < indexes.size() && usable; ++k) {
          const glm::dvec3 d(offsets[3 * k], offsets[3 * k + 1], offsets[3 * k + 2]);
          usable = indexes[k] >= 0 && size_t(indexes[k]) < controlPoints && std::isfinite(d.x) && std::isfinite(d.y) && std::isfinite(d.z);
          if (!usable || d == glm::dvec3(0.0)) continue;
          for (uint32_t j = firstOfPoint[size_t(indexes[k])]; j < firstOfPoint[size_t(indexes[k]) + 1]; ++j) moves[vertexOfPoint[j].first] = true;
        }
        if (!usable) {
          warn(what + " names a vertex past " + std::to_string(controlPoints) + " or a non-finite offset; left out");
          continue;
        }
        std::vector<eng::MorphTarget> targets(builds.size());
        for (size_t i = 0; i < builds.size(); ++i)
          if (moves[i]) {
            ENG_TRY(charge(builds[i].prim.positions.size(), 2 * sizeof(glm::vec3), "FBX " + what));
            targets[i].positions.assign(builds[i].prim.positions.size(), glm::vec3(0.0f));
          }
        for (size_t k = 0; k < indexes.size(); ++k) {
          const glm::vec3 d(linear * glm::dvec3(offsets[3 * k], offsets[3 * k + 1], offsets[3 * k + 2]));
          for (uint32_t j = firstOfPoint[size_t(indexes[k])]; j < firstOfPoint[size_t(indexes[k]) + 1]; ++j)
            if (moves[vertexOfPoint[j].first]) targets[vertexOfPoint[j].first].positions[vertexOfPoint[j].second] = d;
        }
        for (size_t i = 0; i < builds.size(); ++i) {
          PrimitiveBuild& b = builds[i];
          eng::MorphTarget& target = targets[i];
          if (moves[i]) {
            // The shape's own normals are left: the change of the smooth normal
            // is exactly zero where nothing moves.
            std::vector<glm::vec3> moved(b.prim.positions);
            for (size_t v = 0; v < moved.size(); ++v) moved[v] += target.positions[v];
            if (restNormals[i].empty()) restNormals[i] = eng::computeSmoothNormals(b.prim.positions, b.prim.indices);
            target.normals = eng::computeSmoothNormals(moved, b.prim.indices);
            for (size_t v = 0; v < moved.size(); ++v) target.normals[v] -= restNormals[i][v];
          }
          b.prim.targets.push_back(std::move(target));
        }
        targetOfChannel_[channelId] = {int(model_.meshes.size()), int(mesh.targetNames.size())};
        mesh.targetNames.push_back(name);
        const Node* percent = channel.node->child("DeformPercent");
        mesh.defaultWeights.push_back(float(std::clamp(percent ? percent->number(0).value_or(0.0) : 0.0, -1000.0, 1000.0) / 100.0));
      }
    }
    return {};
  }

  // The 16 numbers of a cluster's matrix node, column by column as FBX stores them.
  static std::optional<glm::dmat4> matrixOf(const Node* node) {
    if (!node) return std::nullopt;
    const std::vector<double> m = node->numbers(0);
    if (m.size() != 16) return std::nullopt;
    glm::dmat4 out;
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) {
        if (!std::isfinite(m[size_t(4 * c + r)])) return std::nullopt;
        out[c][r] = m[size_t(4 * c + r)];
      }
    return out;
  }

  // The geometry's skin clusters as a skin over the bone Models; -1 without one.
  eng::Result<int> addSkin(int64_t geometryId, int64_t modelId, std::vector<PrimitiveBuild>& builds, const std::string& where) {
    const std::vector<int64_t> skins = linked(geometryId, "Deformer", "Skin");
    if (skins.empty()) return -1;
    size_t controlPoints = 0;
    for (const PrimitiveBuild& b : builds)
      for (int64_t cp : b.controlPoint) controlPoints = std::max(controlPoints, size_t(cp) + 1);
    std::vector<std::vector<std::pair<float, uint16_t>>> influences(controlPoints);
    eng::Skin skin;
    skin.name = objects_.at(skins[0]).name;
    // Where the mesh was when it was bound: its BindPose entry, else where it
    // is now. (Clusters' "Transform" is written differently by different
    // exporters; three.js and the FBX SDK's samples use the bind pose too.)
    glm::dmat4 meshBind = fileSpaceWorld(nodeOf_.at(modelId));
    if (const auto it = bindPose_.find(modelId); it != bindPose_.end()) meshBind = it->second;
    for (int64_t clusterId : linked(skins[0], "Deformer", "Cluster")) {
      const Object& cluster = objects_.at(clusterId);
      const std::vector<int64_t> bones = linked(clusterId, "Model");
      const std::string what = where + ": skin cluster '" + eng::shownText(cluster.name) + "'";
      const auto bind = matrixOf(cluster.node->child("TransformLink"));
      std::vector<int64_t> indexes;
      const Node* indexesNode = cluster.node->child("Indexes");
      const Node* weightsNode = cluster.node->child("Weights");
      const std::vector<double> weights = weightsNode ? weightsNode->numbers(0) : std::vector<double>();
      if (indexesNode && !indexesNode->integers(0, indexes)) indexes.clear();
      if (bones.empty() || !bind || indexes.size() != weights.size()) {
        warn(what + (bones.empty() ? " has no bone" : !bind ? " has no TransformLink matrix" : ": its indexes and weights do not pair") +
             "; left out");
        continue;
      }
      if (skin.joints.size() >= 65535) return geometryError(where, "a skin of more than 65535 bones");
      const auto joint = uint16_t(skin.joints.size());
      skin.joints.push_back(nodeOf_.at(bones[0]));
      skin.inverseBindMatrices.push_back(glm::mat4(glm::inverse(*bind) * meshBind));
      for (size_t k = 0; k < indexes.size(); ++k)
        if (indexes[k] >= 0 && size_t(indexes[k]) < controlPoints && std::isfinite(weights[k]) && weights[k] > 0.0)
          influences[size_t(indexes[k])].emplace_back(float(weights[k]), joint);
    }
    if (skin.joints.empty()) return -1;
    // Control points no cluster moves stay with the mesh's own node (a joint whose bind is the identity).
    int meshJoint = -1;
    size_t most = 1;
    for (auto& list : influences) {
      std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
      most = std::max(most, list.size());
    }
    constexpr size_t kMostSets = 4;  // sixteen influences; the weakest beyond are dropped
    const size_t sets = std::min(kMostSets, (most + 3) / 4);
    for (PrimitiveBuild& b : builds) {
      const size_t n = b.prim.positions.size();
      ENG_TRY(charge(n * sets, sizeof(glm::u16vec4) + sizeof(glm::vec4), "FBX " + where + " skin"));
      b.prim.joints.assign(n * sets, glm::u16vec4(0));
      b.prim.jointWeights.assign(n * sets, glm::vec4(0.0f));
      for (size_t v = 0; v < n; ++v) {
        const auto& list = influences[size_t(b.controlPoint[v])];
        float sum = 0.0f;
        for (size_t k = 0; k < list.size() && k < 4 * sets; ++k) sum += list[k].first;
        if (!(sum > 0.0f)) {
          if (meshJoint < 0) {
            meshJoint = int(skin.joints.size());
            skin.joints.push_back(nodeOf_.at(modelId));
            skin.inverseBindMatrices.push_back(glm::mat4(1.0f));
          }
          b.prim.joints[v * sets] = glm::u16vec4(uint16_t(meshJoint), 0, 0, 0);
          b.prim.jointWeights[v * sets] = glm::vec4(1.0f, 0.0f, 0.0f, 0.0f);
          continue;
        }
        for (size_t k = 0; k < list.size() && k < 4 * sets; ++k) {
          b.prim.joints[v * sets + k / 4][int(k % 4)] = list[k].second;
          b.prim.jointWeights[v * sets + k / 4][int(k % 4)] = list[k].first / sum;
        }
      }
    }
    if (skin.joints.size() > 65535) return geometryError(where, "a skin of more than 65535 bones");
    model_.skins.push_back(std::move(skin));
    return int(model_.skins.size()) - 1;
  }

  // One animation curve: key times in seconds and values.
  struct Curve {
    std::vector<double> times, values;
    double at(double t) const {
      if (t <= times.front()) return values.front();
      if (t >= times.back()) return values.back();
      const size_t k = size_t(std::upper_bound(times.begin(), times.end(), t) - times.begin());
      const double f = (t - times[k - 1]) / (times[k] - times[k - 1]);
      return values[k - 1] + f * (values[k] - values[k - 1]);
    }
  };

  // The curve linked to a curve node as `property` ("d|X"), nullopt (with a
  // warning) when it has none or is unusable.
  std::optional<Curve> curveOf(int64_t curveNode, std::string_view property, const std::string& what) {
    const auto it = children_.find(curveNode);
    if (it == children_.end()) return std::nullopt;
    for (const Link& l : it->second) {
      const auto o = objects_.find(l.id);
      if (o == objects_.end() || o->second.node->name != "AnimationCurve" || l.property != property) continue;
      const Node& c = *o->second.node;
      std::vector<int64_t> ticks;
      const Node* times = c.child("KeyTime");
      const Node* values = c.child("KeyValueFloat");
      Curve curve;
      if (values) curve.values = values->numbers(0);
      if (!times || !times->integers(0, ticks) || ticks.empty() || ticks.size() != curve.values.size()) {
        warn(what + " " + std::string(property) + ": " + std::to_string(ticks.size()) + " key times and " +
             std::to_string(curve.values.size()) + " values; not read");
        return std::nullopt;
      }
      constexpr double kTicksPerSecond = 46186158000.0;  // FBX's KTime unit
      bool usable = true;
      for (size_t k = 0; k < ticks.size(); ++k) {
        curve.times.push_back(double(ticks[k]) / kTicksPerSecond);
        usable &= std::isfinite(curve.values[k]) && (k == 0 || ticks[k] > ticks[k - 1]);
      }
      if (!usable) {
        warn(what + " " + std::string(property) + ": key times that do not increase or values that are not finite; not read");
        return std::nullopt;
      }
      return curve;
    }
    return std::nullopt;
  }

  // Each AnimationStack's first layer as an animation: DeformPercent curves as
  // the meshes' weights, Lcl Translation / Rotation / Scaling curves as node
  // channels through the node's whole FBX transform. Keys are met linearly
  // (exporters bake every frame); each channel is keyed at the union of its
  // curves' key times.
  void addAnimations() {
    const std::vector<int> nodeOfMesh = model_.firstNodeOfEachMesh();
    for (const Node& o : doc_.root.child("Objects")->children) {
      const auto stackId = o.integer(0);
      if (o.name != "AnimationStack" || !stackId || objects_.at(*stackId).node != &o) continue;
      const std::vector<int64_t> layers = linked(*stackId, "AnimationLayer");
      if (layers.empty()) continue;
      const std::string stackName = objects_.at(*stackId).name;
      if (layers.size() > 1) warn("animation '" + eng::shownText(stackName) + "': only its first of " + std::to_string(layers.size()) + " layers is read");
      eng::Animation animation;
      animation.name = stackName;
      std::map<int, std::map<int, Curve>> weightCurves;                 // mesh -> target -> curve (percent)
      std::map<int, std::array<std::array<std::optional<Curve>, 3>, 3>> nodeCurves;  // node -> T/R/S -> x/y/z
      for (int64_t curveNode : linked(layers[0], "AnimationCurveNode")) {
        const auto up = parents_.find(curveNode);
        if (up == parents_.end()) continue;
        for (const Link& l : up->second) {
          const auto target = objects_.find(l.id);
          if (target == objects_.end() || l.property.empty()) continue;
          const std::string what = "animation '" + eng::shownText(stackName) + "': '" + eng::shownText(target->second.name) + "'";
          if (l.property == "DeformPercent") {
            const auto t = targetOfChannel_.find(l.id);
            if (t == targetOfChannel_.end()) continue;
            if (auto curve = curveOf(curveNode, "d|DeformPercent", what)) weightCurves[t->second.first][t->second.second] = std::move(*curve);
            continue;
          }
          const int component = l.property == "Lcl Translation" ? 0 : l.property == "Lcl Rotation" ? 1 : l.property == "Lcl Scaling" ? 2 : -1;
          const auto node = nodeOf_.find(l.id);
          if (component < 0 || node == nodeOf_.end()) continue;
          for (int axis = 0; axis < 3; ++axis)
            nodeCurves[node->second][size_t(component)][size_t(axis)] = curveOf(curveNode, std::array{"d|X", "d|Y", "d|Z"}[size_t(axis)], what);
        }
      }
      for (auto& [mesh, curves] : weightCurves) addWeightsChannel(animation, mesh, curves, nodeOfMesh);
      for (auto& [node, curves] : nodeCurves) addNodeChannels(animation, node, curves);
      if (animation.channels.empty() && animation.nodeChannels.empty()) continue;
      model_.animations.push_back(std::move(animation));
    }
  }

  // The key times of all `curves`, each once, in order (glTF's times are
  // strictly increasing and not negative).
  static std::vector<float> keyTimes(const std::vector<const Curve*>& curves) {
    std::vector<double> all;
    for (const Curve* c : curves) all.insert(all.end(), c->times.begin(), c->times.end());
    std::sort(all.begin(), all.end());
    std::vector<float> out;
    for (double t : all)
      if (out.empty() || float(std::max(t, 0.0)) > out.back()) out.push_back(float(std::max(t, 0.0)));
    return out;
  }

  void addWeightsChannel(eng::Animation& animation, int meshIndex, const std::map<int, Curve>& curves,
                         const std::vector<int>& nodeOfMesh) {
    const eng::Mesh& mesh = model_.meshes[size_t(meshIndex)];
    eng::WeightsChannel channel;
    channel.mesh = meshIndex;
    channel.node = nodeOfMesh[size_t(meshIndex)];
    channel.interpolation = eng::Interpolation::Linear;
    channel.targetCount = mesh.targetNames.size();
    std::vector<const Curve*> used;
    for (const auto& [target, curve] : curves) used.push_back(&curve);
    channel.times = keyTimes(used);
    for (float t : channel.times)
      for (size_t target = 0; target < channel.targetCount; ++target) {
        const auto it = curves.find(int(target));
        channel.values.push_back(it == curves.end() ? mesh.defaultWeights[target] : float(it->second.at(t) / 100.0));
      }
    animation.channels.push_back(std::move(channel));
  }

  void addNodeChannels(eng::Animation& animation, int node, const std::array<std::array<std::optional<Curve>, 3>, 3>& curves) {
    const Node& model = *objects_.at(modelOfNode_[size_t(node)]).node;
    std::vector<const Curve*> used;
    for (const auto& component : curves)
      for (const auto& axis : component)
        if (axis) used.push_back(&*axis);
    const std::vector<float> times = keyTimes(used);
    if (times.empty()) return;
    const glm::dvec3 rest[3] = {vectorProperty(model, "Lcl Translation").value_or(glm::dvec3(0.0)),
                                vectorProperty(model, "Lcl Rotation").value_or(glm::dvec3(0.0)),
                                vectorProperty(model, "Lcl Scaling").value_or(glm::dvec3(1.0))};
    eng::NodeChannel channels[3];
    for (int c = 0; c < 3; ++c) {
      channels[c].node = node;
      channels[c].path = c == 0 ? eng::NodePath::Translation : c == 1 ? eng::NodePath::Rotation : eng::NodePath::Scale;
      channels[c].interpolation = eng::Interpolation::Linear;
      channels[c].times = times;
    }
    glm::quat previous(1.0f, 0.0f, 0.0f, 0.0f);
    for (float t : times) {
      AnimatedTransform at;
      std::optional<glm::dvec3>* slots[3] = {&at.translation, &at.rotation, &at.scale};
      for (int c = 0; c < 3; ++c) {
        glm::dvec3 v = rest[c];
        for (int axis = 0; axis < 3; ++axis)
          if (curves[size_t(c)][size_t(axis)]) v[axis] = curves[size_t(c)][size_t(axis)]->at(t);
        *slots[c] = v;
      }
      eng::Node posed;
      setLocalTransform(model, posed, at);
      // Neighbouring keys on the same side of the quaternion sphere, so linear keys turn the short way.
      if (glm::dot(posed.rotation, previous) < 0.0f) posed.rotation = -posed.rotation;
      previous = posed.rotation;
      channels[0].values.insert(channels[0].values.end(), {posed.translation.x, posed.translation.y, posed.translation.z});
      channels[1].values.insert(channels[1].values.end(), {posed.rotation.x, posed.rotation.y, posed.rotation.z, posed.rotation.w});
      channels[2].values.insert(channels[2].values.end(), {posed.scale.x, posed.scale.y, posed.scale.z});
    }
    for (eng::NodeChannel& c : channels) animation.nodeChannels.push_back(std::move(c));
  }

  // A node's world matrix in the file's own axes and units (the root's conversion left out).
  glm::dmat4 fileSpaceWorld(int node) const {
    glm::dmat4 world(1.0);
    for (int at = node; at > 0; at = model_.nodes[size_t(at)].parent) world = glm::dmat4(model_.nodes[size_t(at)].localTransform()) * world;
    return world;
  }

  int materialFor(int64_t id) {
    if (const auto it = materialOf_.find(id); it != materialOf_.end()) return it->second;
    const Object& o = objects_.at(id);
    eng::Material m;
    m.name = o.name;
    const glm::dvec3 diffuse = glm::clamp(vectorProperty(*o.node, "DiffuseColor").value_or(vectorProperty(*o.node, "Diffuse").value_or(glm::dvec3(0.8))), 0.0, 1.0);
    m.baseColorImage = textureFor(id, {"DiffuseColor", "Diffuse", "Maya|baseColor", "base_color", "baseColor"});
    // A texture stands for the colour (as Blender's and Maya's importers read it), a colour alone is the factor.
    m.baseColorFactor = m.baseColorImage >= 0 ? glm::vec4(1.0f) : glm::vec4(glm::vec3(diffuse), 1.0f);
    // Roughness from the Phong exponent as Blender writes and reads it
    // ((10 (1 - roughness))^2); not below 0.2, where a Maya Phong's 100 would
    // make skin a mirror. ReflectionFactor is Blender's metallic but Maya's
    // reflectivity (0.5 by default): a skin read metallic would be grey, so
    // every material stays a dielectric.
    if (const auto shininess = numberProperty(*o.node, "Shininess"))
      m.roughness = float(std::clamp(1.0 - std::sqrt(std::max(*shininess, 0.0)) / 10.0, 0.2, 1.0));
    const double opacity = numberProperty(*o.node, "Opacity").value_or(1.0);
    if (opacity >= 0.0 && opacity < 1.0) {
      m.baseColorFactor.a = float(opacity);
      m.alphaMode = eng::AlphaMode::Blend;
    }
    if (textureFor(id, {"TransparentColor", "TransparencyFactor"}, false) >= 0) m.alphaMode = eng::AlphaMode::Blend;
    const int index = int(model_.materials.size());
    model_.materials.push_back(std::move(m));
    materialOf_[id] = index;
    return index;
  }

  // The image of the texture linked to the material's first property of
  // `properties` that has one (case-insensitive), -1 when none reads.
  int textureFor(int64_t materialId, std::initializer_list<std::string_view> properties, bool decode = true) {
    const auto it = children_.find(materialId);
    if (it == children_.end()) return -1;
    auto lower = [](std::string_view s) {
      std::string out(s);
      for (char& c : out) c = char(std::tolower(static_cast<unsigned char>(c)));
      return out;
    };
    for (std::string_view property : properties)
      for (const Link& l : it->second) {
        const auto o = objects_.find(l.id);
        if (o == objects_.end() || o->second.node->name != "Texture" || lower(l.property) != lower(property)) continue;
        if (!decode) return 0;
        return imageOf(l.id);
      }
    return -1;
  }

  // A Video's embedded bytes; writers embed a file once, and the other
  // Videos naming the same file share them (as the FBX SDK reads them).
  std::string_view embeddedContent(const Node& video) {
    if (const Node* content = video.child("Content"); content && !content->text(0).empty()) return content->text(0);
    if (contentOfFile_.empty())
      for (const auto& [id, object] : objects_) {
        if (object.node->name != "Video") continue;
        const Node* content = object.node->child("Content");
        if (!content || content->text(0).empty()) continue;
        for (const char* field : {"RelativeFilename", "Filename", "FileName"})
          if (const Node* f = object.node->child(field); f && !f->text(0).empty()) contentOfFile_.try_emplace(std::string(f->text(0)), content->text(0));
      }
    for (const char* field : {"RelativeFilename", "Filename", "FileName"})
      if (const Node* f = video.child(field); f && !f->text(0).empty())
        if (const auto it = contentOfFile_.find(std::string(f->text(0))); it != contentOfFile_.end()) return it->second;
    return {};
  }

  int imageOf(int64_t textureId) {
    if (const auto it = imageOfTexture_.find(textureId); it != imageOfTexture_.end()) return it->second;
    int& index = imageOfTexture_[textureId];
    index = -1;
    const Object& texture = objects_.at(textureId);
    const std::string what = "texture '" + eng::shownText(texture.name) + "'";
    std::vector<std::string> files;
    auto fileNames = [&](const Node& n) {
      for (const char* field : {"RelativeFilename", "FileName", "Filename"})
        if (const Node* f = n.child(field); f && !f->text(0).empty()) files.emplace_back(f->text(0));
    };
    fileNames(*texture.node);
    for (int64_t videoId : linked(textureId, "Video")) {
      const Node& video = *objects_.at(videoId).node;
      fileNames(video);
      const std::string_view bytes = embeddedContent(video);
      if (bytes.empty()) continue;
      auto image = eng::decodeImage(std::span(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()), objects_.at(videoId).name);
      if (!image) {
        warn(what + ": its embedded image: " + image.error().message);
        continue;
      }
      index = int(model_.images.size());
      model_.images.push_back(std::move(*image));
      return index;
    }
    // Named by file: relative to the FBX's folder, else by name alone there
    // or in the `<stem>.fbm` folder the FBX SDK extracts embedded media to.
    const std::filesystem::path folder = path_.parent_path().empty() ? std::filesystem::path(".") : path_.parent_path();
    for (std::string file : files) {
      std::replace(file.begin(), file.end(), '\\', '/');
      const std::string base = std::filesystem::path(file).filename().string();
      for (const std::string& candidate : {file, base, path_.stem().string() + ".fbm/" + base}) {
        if (candidate.empty() || candidate.front() == '/' || (candidate.size() > 1 && candidate[1] == ':')) continue;
        auto resolved = eng::resolveInsideFolder(folder, candidate);
        std::error_code ec;
        if (!resolved || !std::filesystem::is_regular_file(*resolved, ec)) continue;
        auto image = eng::readImage(*resolved);
        if (!image) {
          warn(what + ": " + image.error().message);
          return index;
        }
        image->name = base;
        index = int(model_.images.size());
        model_.images.push_back(std::move(*image));
        return index;
      }
    }
    warn(what + (files.empty() ? std::string(" names no file and embeds none") : ": '" + eng::shownText(files.front(), 80) +
                                                                                    "' is not beside the FBX") +
         "; its material keeps its colour");
    return index;
  }

  const fbx::Document& doc_;
  std::filesystem::path path_;
  std::string name_;
  eng::LoadBudget& budget_;
  eng::Model model_;
  std::unordered_map<int64_t, Object> objects_;
  std::unordered_map<int64_t, std::vector<Link>> children_;
  std::unordered_map<int64_t, std::vector<Link>> parents_;
  std::unordered_map<int64_t, int> nodeOf_;
  std::vector<int64_t> modelOfNode_;  // node index -> its Model's id (0: the root)
  std::unordered_map<int64_t, int> materialOf_;
  std::unordered_map<int64_t, glm::dmat4> bindPose_;
  std::unordered_map<int64_t, std::pair<int, int>> targetOfChannel_;  // blend shape channel -> (mesh, target)
  std::unordered_map<int64_t, int> imageOfTexture_;
  std::unordered_map<std::string, std::string_view> contentOfFile_;
  std::string firstSkipped_;
};

}  // namespace

eng::Result<eng::Model> importFbx(std::span<const uint8_t> bytes, const std::filesystem::path& path) {
  eng::LoadBudget budget;
  auto doc = fbx::readFbxDocument(bytes, path.string(), budget);
  if (!doc) return doc.error();
  return SceneBuilder(*doc, path, budget).build();
}

}  // namespace importers
