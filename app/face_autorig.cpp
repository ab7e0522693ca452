#include "app/face_autorig.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <system_error>

#include <unistd.h>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "app/face_landmark_finder.h"
#include "app/face_setup.h"
#include "autorig/builtin_source.h"
#include "autorig/eye_opening.h"
#include "autorig/face_frame.h"
#include "autorig/face_parts.h"
#include "autorig/mouth_opening.h"
#include "autorig/part_primitives.h"
#include "autorig/posed_face.h"
#include "engine/core/fnv1a.h"
#include "engine/core/text_lines.h"
#include "engine/scene/file_bytes.h"
#include "engine/scene/gltf_loader.h"
#include "engine/scene/gltf_writer.h"
#include "engine/scene/mesh_weld.h"
#include "engine/scene/weights.h"
#include "facial/runtime/rig/rig_mapping.h"
#include "importers/face_dressing.h"
#include "facial/runtime/rig/rigmap_file.h"

namespace app {
namespace {

std::string countOf(size_t n, std::string_view what) { return std::to_string(n) + " " + std::string(what); }

std::string reasonOf(const eng::Model& model, const eng::Result<facial::RigCalibration>& rig) {
  std::vector<std::string> names;  // each once, however many meshes carry it
  for (const std::string& name : eng::WeightLayout(model).names())
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  if (names.empty()) return "it has no morph targets";
  if (!rig) {
    std::string sample;
    for (size_t i = 0; i < names.size() && i < 4; ++i) sample += (i ? ", " : "") + names[i];
    return "no scheme recognises its " + countOf(names.size(), "target names") + " (" + sample +
           (names.size() > 4 ? ", ..." : "") + ")";
  }
  const facial::RigMappingReport& report = rig->rig.report();
  if (report.scheme == facial::RigScheme::Visemes) return "its targets are lip-sync visemes only: " + report.detail;
  const facial::EmotionFeatures features = facial::emotionFeatures(rig->rig);
  const char* missing = features.brows        ? "moves no lip corners"
                        : features.lipCorners ? "moves no brows"
                                              : "moves neither brows nor lip corners";
  return "its " + std::string(facial::rigSchemeName(report.scheme)) + " rig " + missing + ": " + report.detail;
}

eng::Result<std::string> readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return eng::makeError(eng::ErrorKind::NotFound, path.string() + ": cannot be read");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The running program's size and time: a rebuilt program (a changed
// landmark finder or transfer) makes its rigs anew instead of trusting ones
// an older build made, without reading the program's bytes each run.
std::string programStamp() {
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return {};
  const auto size = std::filesystem::file_size(exe, ec);
  const auto time = std::filesystem::last_write_time(exe, ec).time_since_epoch().count();
  return ec ? std::string() : std::to_string(size) + ":" + std::to_string(time);
}

std::set<std::string> targetNameSet(const eng::Model& model) {
  std::set<std::string> names;
  for (const eng::Mesh& mesh : model.meshes) names.insert(mesh.targetNames.begin(), mesh.targetNames.end());
  return names;
}

}  // namespace

TargetChanges targetChanges(const eng::Model& face, const eng::Model& rigged) {
  const std::set<std::string> before = targetNameSet(face), after = targetNameSet(rigged);
  TargetChanges changes;
  changes.kept.assign(before.begin(), before.end());
  std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(changes.made));
  return changes;
}

namespace {

// A VRM whose expressions for the emotions bind nothing (its rig maps the
// emotions onto expressions that change nothing): shown as it is, every
// emotion would be the neutral face, without a word.
bool vrmEmotionsMoveNothing(const importers::LoadedFace& face, const eng::Result<facial::RigCalibration>& rig) {
  if (!face.vrm || !rig) return false;
  for (uint32_t e = 0; e < facial::kEmotionCount; ++e) {
    if (facial::Emotion(e) == facial::Emotion::Neutral) continue;
    for (uint32_t expression : rig->rig.targets(facial::emotionInput(facial::Emotion(e))))
      if (face.vrm->moves(expression)) return false;
  }
  return true;
}

}  // namespace

std::string autorigReason(const importers::LoadedFace& face, const eng::Result<facial::RigCalibration>& rig,
                          const std::filesystem::path& rigmapFile) {
  const bool stillVrm = vrmEmotionsMoveNothing(face, rig);
  if (!stillVrm && (!importers::isPlainMesh(face.format) || face.vrm)) return {};
  facial::RigMappingOptions options;
  options.modelName = modelNameOf(face.model.sourcePath);
  options.rigmapDirectory = dataDirectory() / "rigmaps";
  options.rigmapFile = rigmapFile;
  // A rig map given, or one found by the face's name that maps targets, rigs
  // the face its own way. One found by name that only calibrates (the
  // built-in head's data/rigmaps/head.json) was written for another face of
  // that name (a scan called head.stl) and keeps nothing from being rigged.
  if (!rigmapFile.empty()) return {};
  if (const std::filesystem::path found = facial::rigMapFileFor(options); !found.empty()) {
    auto rigmap = facial::loadRigMapFile(found, eng::WeightLayout(face.model).names());
    if (!rigmap || rigmap->mapping) return {};
  }
  if (stillVrm) return "its VRM expressions for the emotions bind nothing: no morph target, material colour or texture transform";
  if (!rig) return rig.error().kind == eng::ErrorKind::Unsupported ? reasonOf(face.model, rig) : std::string();
  return facial::showsEmotions(rig->rig) ? std::string() : reasonOf(face.model, rig);
}

bool emotesInPart(const eng::Result<facial::RigCalibration>& rig) {
  if (!rig) return false;
  const facial::EmotionFeatures features = facial::emotionFeatures(rig->rig);
  return features.brows != features.lipCorners;
}

bool keepsOwnRig(const importers::LoadedFace& face, const eng::Result<facial::RigCalibration>& rig) {
  return emotesInPart(rig) || face.vrm != nullptr;
}

std::string cannotEmoteLine(const std::filesystem::path& model, const std::string& reason,
                            const eng::Result<facial::RigCalibration>& rig) {
  if (!rig) return rig.error().message;
  return model.string() + (emotesInPart(rig) ? ": shows emotions only in part: " : ": cannot show emotions: ") + reason;
}

eng::Result<FaceAutorig> FaceAutorig::load(const std::filesystem::path& head) {
  FaceAutorig rigger;
  rigger.headPath_ = head.empty() ? defaultModelPath() : head;
  auto model = eng::loadModel(rigger.headPath_);
  if (!model) return model.error();
  rigger.head_ = std::make_unique<eng::Model>(std::move(*model));
  auto source = autorig::builtInSource(*rigger.head_);
  if (!source) return source.error().prefixed(rigger.headPath_.string() + ": ");
  rigger.source_ = std::move(*source);
  auto headRig = buildModelRig(*rigger.head_);
  if (!headRig) return headRig.error();
  for (const facial::ActionUnitCalibration& unit : headRig->units) rigger.headScales_.emplace_back(unit.channel, unit.scale);
  return rigger;
}

eng::Result<autorig::FaceLandmarks> faceLandmarks(const importers::LoadedFace& face,
                                                  const std::filesystem::path& landmarksFile) {
  const autorig::PosedFace posed = autorig::poseAtRest(face.model);
  if (landmarksFile.empty()) {
    // Landmarks belong to the shape, not to its shading: a flat-shaded or
    // hard-edged face is shown to the detector smooth (dlib's fit of the jaw
    // line moved by up to a third of the eye span on facecap made flat).
    // Each primitive is tried alone; the model (its images) is copied only
    // when one of them has such copies.
    const eng::Model& display = face.displayModel();
    std::optional<eng::Model> smooth;
    for (size_t m = 0; m < display.meshes.size(); ++m)
      for (size_t p = 0; p < display.meshes[m].primitives.size(); ++p) {
        eng::Primitive welded = display.meshes[m].primitives[p];
        if (eng::weldIdenticalVertices(welded, {.acrossHardEdges = true}) == 0) continue;
        if (!smooth) smooth = display;
        smooth->meshes[m].primitives[p] = std::move(welded);
      }
    return findFaceLandmarks(face.model, posed, {.display = smooth ? &*smooth : &display});
  }
  auto landmarks = autorig::readLandmarksFile(landmarksFile);
  if (!landmarks) return landmarks.error();
  ENG_TRY(autorig::checkLandmarksOnSurface(*landmarks, face.model, posed, landmarksFile.string()));
  return landmarks;
}

eng::Result<AutorigResult> FaceAutorig::rig(const eng::Model& face, const autorig::FaceLandmarks& landmarks,
                                            const std::string& faceName, const autorig::TransferOptions& options) const {
  // Copies of a vertex in every attribute (a triangle soup's corners) made
  // one, so the lips and lids have edges to be labelled and mended along; so
  // are copies split only by their shading (a hard edge, a flat-shaded face),
  // whose shading comes back once the targets are made.
  eng::Model opened = face;
  const size_t welded = eng::weldIdenticalVertices(opened);
  std::vector<std::vector<size_t>> shadingWelded(opened.meshes.size());
  size_t shadingWeldedCount = 0;
  for (size_t m = 0; m < opened.meshes.size(); ++m)
    for (eng::Primitive& primitive : opened.meshes[m].primitives) {
      shadingWelded[m].push_back(eng::weldIdenticalVertices(primitive, {.acrossHardEdges = true}));
      shadingWeldedCount += shadingWelded[m].back();
    }
  autorig::PosedFace posed = autorig::poseAtRest(opened);
  autorig::FaceParts parts = autorig::findFaceParts(opened, posed, landmarks);
  // Welded lips cut, the head's mouth inside where the face has none: then the
  // changed face is posed and its parts found again.
  autorig::MouthOpening opening = autorig::openTheMouth(opened, posed, landmarks, parts, source_);
  if (opening.changed()) {
    posed = autorig::poseAtRest(opened);
    parts = autorig::findFaceParts(opened, posed, landmarks);
  }
  // A scan's eyes in its skin cut free from the lids, the head's eyeballs behind them.
  autorig::EyeOpening eyes = autorig::openTheEyes(opened, posed, landmarks, parts, source_);
  if (eyes.changed()) {
    posed = autorig::poseAtRest(opened);
    parts = autorig::findFaceParts(opened, posed, landmarks);
  }
  auto transferred = autorig::transferTargets(source_, opened, posed, landmarks, parts, options);
  if (!transferred) return transferred.error().prefixed(faceName + ": ");
  AutorigResult result;
  result.model = std::move(transferred->model);
  // Eyeballs, teeth and tongue merged into an untextured skin get primitives
  // of their own, which the display then dresses.
  if (const size_t separated = autorig::separateInnerParts(result.model, posed, parts); separated > 0)
    parts.notes.push_back(std::to_string(separated) + " eyeball, teeth or tongue piece(s) of an untextured primitive drawn apart, to be dressed");
  for (size_t m = 0; m < shadingWelded.size(); ++m)
    for (size_t p = 0; p < shadingWelded[m].size() && p < result.model.meshes[m].primitives.size(); ++p)
      if (shadingWelded[m][p] > 0) eng::restoreHardEdges(result.model.meshes[m].primitives[p], face.meshes[m].primitives[p]);
  result.report = std::move(transferred->report);
  // The units carried from the head move each feature as far as the head's
  // for this face's proportions: they keep the head's strengths. Measured
  // against this face's size instead, Ready Player Me's outer brows were
  // driven x1.37 (the head's x0.93), its brows lowered x0.90 (x0.63) till
  // the skin folded at the nose's root in anger, and its jaw x0.80 (x1.69).
  // The units made from the face's own shapes are measured as its own.
  const auto listed = [](const std::vector<std::string>& names, const std::string& name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  std::vector<std::pair<std::string, float>> calibration;
  for (const auto& [channel, scale] : headScales_)
    if (listed(result.report.made, channel) && !listed(result.report.own, channel)) calibration.emplace_back(channel, scale);
  for (const auto& entry : result.model.calibration)
    if (std::none_of(calibration.begin(), calibration.end(), [&](const auto& c) { return c.first == entry.first; }))
      calibration.push_back(entry);
  result.model.calibration = std::move(calibration);
  result.landmarks = landmarks;
  result.partNotes = std::move(parts.notes);
  if (welded > 0)
    result.partNotes.push_back(std::to_string(welded) + " vertices that copied another in every attribute welded to it (a triangle soup's corners)");
  if (shadingWeldedCount > 0)
    result.partNotes.push_back(std::to_string(shadingWeldedCount) +
                               " vertices split from another only by their shading (hard edges, flat shading) rigged as one surface, their shading kept");
  result.partNotes.insert(result.partNotes.end(), opening.notes.begin(), opening.notes.end());
  result.partNotes.insert(result.partNotes.end(), eyes.notes.begin(), eyes.notes.end());
  return result;
}

std::filesystem::path autorigCacheDirectory() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::filesystem::path(xdg) / "facial" / "autorig";
  if (const char* home = std::getenv("HOME"); home && *home)
    return std::filesystem::path(home) / ".cache" / "facial" / "autorig";
  std::error_code ec;
  return std::filesystem::temp_directory_path(ec) / "facial-autorig";
}

eng::Result<void> saveModelAtomically(const eng::Model& model, const std::filesystem::path& path) {
  return eng::writeFileWhole(path, [&](const std::filesystem::path& partial) { return eng::saveModel(model, partial); });
}

std::filesystem::path landmarksBeside(const std::filesystem::path& modelPath) {
  return modelPath.parent_path() / (modelPath.stem().string() + ".landmarks.json");
}

namespace {

// "a%20b.png" -> "a b.png": a glTF URI as a relative path.
std::string uriPath(std::string_view uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(std::string(uri.substr(i + 1, 2)), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The last word of each line of `text` that starts with `key` (OBJ's mtllib,
// an MTL's texture maps, whose options come before the file).
std::vector<std::string> lastWordsAfter(std::string_view text, std::initializer_list<std::string_view> keys) {
  std::vector<std::string> words;
  eng::TextLines lines(text);
  std::string_view line;
  while (lines.nextNonBlank(line))
    for (std::string_view key : keys) {
      if (!line.starts_with(key) || line.size() <= key.size() || (line[key.size()] != ' ' && line[key.size()] != '\t'))
        continue;
      words.emplace_back(line.substr(line.find_last_of(" \t") + 1));
    }
  return words;
}

}  // namespace

std::vector<std::filesystem::path> filesReadWith(const std::filesystem::path& model, std::string_view bytes) {
  std::vector<std::filesystem::path> files;
  const std::filesystem::path dir = model.parent_path();
  const size_t first = bytes.find_first_not_of(" \t\r\n");
  std::string_view json;
  if (bytes.starts_with("glTF") && bytes.size() >= 20) {  // a GLB: its JSON chunk (its own buffer is inside)
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    json = bytes.substr(20, std::min<size_t>(length, bytes.size() - 20));
  } else if (first != std::string::npos && bytes[first] == '{') {  // a .gltf
    json = bytes;
  }
  if (!json.empty()) {  // its buffers and images outside it
    const nlohmann::json gltf = nlohmann::json::parse(json, nullptr, false);
    if (!gltf.is_object()) return files;
    for (const char* array : {"buffers", "images"}) {
      if (!gltf.contains(array) || !gltf[array].is_array()) continue;
      for (const nlohmann::json& item : gltf[array])
        if (item.is_object() && item.contains("uri") && item["uri"].is_string()) {
          const std::string uri = item["uri"];
          if (!uri.starts_with("data:")) files.push_back(dir / uriPath(uri));
        }
    }
    return files;
  }
  for (const std::string& library : lastWordsAfter(bytes, {"mtllib"})) {  // an OBJ: its materials and their maps
    const std::filesystem::path mtl = dir / library;
    files.push_back(mtl);
    if (auto text = readBytes(mtl))
      for (const std::string& map : lastWordsAfter(*text, {"map_Kd", "map_Ka", "map_d", "map_Bump", "bump", "norm"}))
        files.push_back(dir / map);
  }
  return files;
}

namespace {

// The cache entry of `modelPath` rigged from `head` (and `landmarks`, when
// not empty): named by the hash of everything that decides what is made,
// the files the model reads beside it included (an edited texture is not
// served stale).
eng::Result<std::filesystem::path> cacheEntry(const std::filesystem::path& modelPath, const std::filesystem::path& head,
                                              const std::filesystem::path& landmarks) {
  eng::Fnv1a key;
  key.add(kAutorigVersion);
  key.add(programStamp());
  for (const std::filesystem::path& file : {head, modelPath, landmarks}) {
    if (file.empty()) continue;
    auto bytes = readBytes(file);
    if (!bytes) return bytes.error();
    key.add(file == landmarks ? "landmarks" : "");
    key.add(*bytes);
    if (file != modelPath) continue;
    for (const std::filesystem::path& read : filesReadWith(modelPath, *bytes)) {
      key.add(read.filename().string());
      if (auto more = readBytes(read)) key.add(*more);  // a missing one: the loader warns, the face loads
    }
  }
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.glb", static_cast<unsigned long long>(key.h));
  return autorigCacheDirectory() / name;
}

}  // namespace

eng::Result<CachedAutorig> autorigCached(const std::filesystem::path& modelPath) {
  const std::filesystem::path head = defaultModelPath();
  std::error_code ec;
  const std::filesystem::path landmarksFile =
      std::filesystem::is_regular_file(landmarksBeside(modelPath), ec) ? landmarksBeside(modelPath) : std::filesystem::path();
  auto entry = cacheEntry(modelPath, head, landmarksFile);
  if (!entry) return entry.error();
  CachedAutorig cached;
  cached.path = std::move(*entry);

  auto face = importers::loadFace(modelPath, {.dressForDisplay = true});
  if (!face) return face.error();
  const std::filesystem::path landmarksKept = landmarksBeside(cached.path);
  if (std::filesystem::is_regular_file(cached.path, ec)) {
    auto rigged = eng::loadModel(cached.path);
    auto kept = autorig::readLandmarksFile(landmarksKept);
    if (rigged && kept) {
      cached.reused = true;
      static_cast<TargetChanges&>(cached) = targetChanges(face->model, *rigged);
      cached.landmarks = std::move(*kept);
      return cached;
    }
    // An unreadable cache entry is made again below (and replaced).
  }
  auto landmarks = faceLandmarks(*face, landmarksFile);
  if (!landmarks) return landmarks.error();
  auto rigger = FaceAutorig::load(head);
  if (!rigger) return rigger.error();
  auto rigged = rigger->rig(face->model, *landmarks, modelPath.string());
  if (!rigged) return rigged.error();
  std::filesystem::create_directories(cached.path.parent_path(), ec);
  if (ec)
    return eng::makeError(eng::ErrorKind::Io, cached.path.parent_path().string() + ": cannot make the autorig cache (" +
                          ec.message() + ")");
  // The landmarks first: an entry is whole when its model is there.
  if (auto saved = autorig::writeLandmarksFile(*landmarks, landmarksKept); !saved) return saved.error();
  if (auto saved = saveModelAtomically(rigged->model, cached.path); !saved) return saved.error();
  static_cast<TargetChanges&>(cached) = targetChanges(face->model, rigged->model);
  cached.landmarks = std::move(*landmarks);
  cached.warnings = std::move(rigged->report.warnings);
  return cached;
}

eng::Result<CachedAutorig> loadAutorigged(const std::filesystem::path& modelPath,
                                          const importers::LoadFaceOptions& options, importers::LoadedFace& face) {
  auto cached = autorigCached(modelPath);
  if (!cached) return cached.error();
  // Dressed once stood up: the procedural eyes face the model's front (+Z).
  importers::LoadFaceOptions undressed = options;
  undressed.dressForDisplay = false;
  auto rigged = importers::loadFace(cached->path, undressed);
  if (!rigged) return rigged.error();
  rigged->model.sourcePath = modelPath.string();
  if (const std::optional<StandingUp> up = standingUp(cached->landmarks)) eng::turnAtRoots(rigged->model, up->turn);
  if (options.dressForDisplay) rigged->dressed = importers::dressedForDisplay(rigged->model);
  face = std::move(*rigged);
  return cached;
}

std::optional<StandingUp> standingUp(const autorig::FaceLandmarks& landmarks) {
  const autorig::LandmarkFrame frame(landmarks);
  if (!std::isfinite(frame.forward().x) || !std::isfinite(frame.forward().y) || !std::isfinite(frame.forward().z))
    return std::nullopt;
  // The axes nearest the face's front and top; a top along the front's axis
  // (a face seen from straight above or below) takes the next nearest.
  auto nearestAxis = [](const glm::vec3& v, const glm::vec3& unlike) {
    glm::vec3 best(0.0f);
    for (int a = 0; a < 3; ++a)
      for (float sign : {1.0f, -1.0f}) {
        glm::vec3 axis(0.0f);
        axis[a] = sign;
        if (std::abs(glm::dot(axis, unlike)) > 0.5f) continue;
        if (glm::dot(axis, v) > glm::dot(best, v) || best == glm::vec3(0.0f)) best = axis;
      }
    return best;
  };
  const glm::vec3 front = nearestAxis(frame.forward(), glm::vec3(0.0f));
  const glm::vec3 top = nearestAxis(frame.up(), front);
  const glm::mat3 quarterTurn = standingUpRotation(front, top);
  const glm::mat3 exact = levelRotation(landmarks);
  const float offQuarterTurn = glm::degrees(glm::angle(glm::quat_cast(exact * glm::transpose(quarterTurn))));
  // Points only fitted in the targets' box (no face detected) say too little of the turn.
  if (offQuarterTurn > kQuarterTurnSlackDegrees && !landmarks.source.starts_with(kFittedInTheTargetsBox)) {
    return StandingUp{glm::quat_cast(exact), "looks along " + directionName(frame.forward()) + ", its top along " +
                                                 directionName(frame.up()) + ", turned " +
                                                 std::to_string(int(std::lround(offQuarterTurn))) + "° from glTF's axes"};
  }
  if (front.z == 1.0f && top.y == 1.0f) return std::nullopt;
  return StandingUp{glm::quat_cast(quarterTurn), "looks along " + signedAxisName(front) + ", its top along " + signedAxisName(top)};
}

}  // namespace app
