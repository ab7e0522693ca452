#include "editor/app/project_actions.h"

#include <functional>

#include "app/sequence_renderers.h"
#include "app/sequence_recorder.h"
#include "audio/video_writer.h"
#include "editor/glb_export.h"
#include "importers/face_dressing.h"
#include "engine/scene/gltf_loader.h"

namespace editor {

namespace fs = std::filesystem;

namespace {

// Two ways of naming one file ("" = the default one) compare as the same file.
bool sameFile(const fs::path& a, const fs::path& b, const fs::path& fallback) {
  const fs::path x = a.empty() ? fallback : a, y = b.empty() ? fallback : b;
  if (x.empty() || y.empty()) return x.empty() && y.empty();
  std::error_code error;
  return fs::weakly_canonical(x, error) == fs::weakly_canonical(y, error);
}

}  // namespace

ProjectActions::ProjectActions(ProjectPanels panels, fs::path model, fs::path rigmap, fs::path graph, RecentProjects recent)
    : panels_(panels), model_(std::move(model)), rigmap_(std::move(rigmap)), graph_(std::move(graph)), recent_(std::move(recent)) {
  if (auto loaded = recent_.load(); !loaded) message_.report(loaded.error().message, true);
  rememberSaved();
}

Project ProjectActions::current(const fs::path& projectFile) const {
  Project p{.model = model_, .rigmap = rigmap_, .graph = graph_};
  const TimelineDocument& clip = panels_.timeline->document();
  if (!clip.tracks().empty()) p.clips.push_back({clip.name(), projectClipPath(projectFile, clip.name()), clip.settings()});
  p.clips.insert(p.clips.end(), otherClips_.begin(), otherClips_.end());
  for (const auto& [name, weight] : panels_.sculpt->bakedTargets()) p.sculptTargets.push_back({name, weight});
  if (!p.sculptTargets.empty()) p.sculptModel = projectSculptPath(projectFile);
  p.view = panels_.view->viewSettings();
  // A graph edited in the diagram (or the project's own one, saved under another name) goes beside the project.
  const fs::path ownGraph = projectGraphPath(projectFile);
  const bool projectOwnsGraph = !path_.empty() && (sameFile(graph_, projectGraphPath(path_), {}) || sameFile(graph_, projectGraphAutosavePath(path_), {}));
  if (graphEdited() || (projectOwnsGraph && !sameFile(graph_, ownGraph, {}))) p.graph = ownGraph;
  return p;
}

bool ProjectActions::saveAs(const fs::path& path) {
  if (path.empty()) return fail("Save As: no file name given");
  const Project project = current(path);
  std::error_code error;
  if (!panels_.timeline->document().tracks().empty()) {
    const fs::path clip = project.clips.front().file;
    fs::create_directories(clip.parent_path(), error);
    if (error) return fail(clip.parent_path().string() + ": cannot create the clips folder (" + error.message() + ")");
    if (!panels_.timeline->save(clip.string())) return fail(path.string() + ": not saved: the clip could not be written (see above)");
  }
  if (!project.sculptModel.empty())
    if (auto saved = panels_.sculpt->saveModel(project.sculptModel.string()); !saved) return fail(saved.error().message);
  if ((graphEdited() || project.graph != graph_) && !panels_.machine->saveGraph(project.graph.string()))
    return fail(path.string() + ": not saved: the edited graph could not be written (see the state machine panel)");
  if (auto saved = saveProject(project, path); !saved) return fail(saved.error().message);
  graph_ = project.graph;
  path_ = path;
  rememberSaved();
  discardProjectAutosave(path);
  if (auto listed = recent_.add(path); !listed) message_.report(listed.error().message, true);
  message_.report("saved project " + path.string(), false);
  return true;
}

bool ProjectActions::save() {
  if (path_.empty()) return fail("Save: the project has no file yet (use Save As)");
  return saveAs(path_);
}

bool ProjectActions::open(const fs::path& path) {
  auto recovered = recoverProjectAutosave(path);
  if (!recovered) message_.report(recovered.error().message, true);  // the file itself still opens
  std::optional<RecoveredProject> recovery = recovered ? std::move(*recovered) : std::nullopt;
  auto loaded = recovery ? eng::Result<Project>(std::move(recovery->project)) : loadProject(path);
  if (!loaded) return fail(loaded.error().message);
  if (!apply(*loaded, path)) return false;
  recoveredUnsaved_ = recovery.has_value();
  if (auto listed = recent_.add(path); !listed) message_.report(listed.error().message, true);
  message_.report(recovery ? recovery->message : "opened project " + path.string(), false);
  return true;
}

bool ProjectActions::madeOnAnotherFace(const fs::path& path) const {
  auto project = loadProject(path);  // an unreadable one is open()'s to report
  return project && (!sameFile(project->model, model_, app::defaultModelPath()) || !sameFile(project->rigmap, rigmap_, {}));
}

bool ProjectActions::apply(const Project& project, const fs::path& path) {
  const std::string where = path.string() + ": ";
  if (!sameFile(project.model, model_, app::defaultModelPath()) || !sameFile(project.rigmap, rigmap_, {}))
    return fail(where + "made on " + (project.model.empty() ? "the built-in head" : project.model.string()) +
                ", not on the face this editor has open; start it with facial-editor --project " + path.string());
  std::optional<eng::Model> sculpted;
  if (!project.sculptTargets.empty()) {
    auto model = eng::loadModel(project.sculptModel);
    if (!model) return fail(where + "sculpted expressions: " + model.error().message);
    sculpted.emplace(std::move(*model));
  }
  std::vector<std::pair<std::string, float>> bakes;
  for (const ProjectSculptTarget& t : project.sculptTargets) bakes.emplace_back(t.name, t.weight);
  if (auto restored = panels_.sculpt->restore(sculpted ? &*sculpted : nullptr, bakes); !restored)
    return fail(where + "sculpted expressions: " + restored.error().message);
  if (!sameFile(project.graph, graph_, {}) || graphEdited()) {
    const fs::path graph = project.graph.empty() ? app::dataDirectory() / "graphs" / "tour.json" : project.graph;
    if (auto machine = panels_.machine->load(*panels_.face, graph.string()); !machine) return fail(where + machine.error().message);
    graph_ = project.graph;
  }
  if (project.clips.empty()) {
    panels_.timeline->openEmpty(projectClipPath(path, "untitled").string());
  } else if (!panels_.timeline->open(project.clips.front().file.string())) {
    return fail(where + "clip '" + project.clips.front().name + "' did not open (see above)");
  } else {
    panels_.timeline->document().restoreSettings(project.clips.front().settings);
  }
  otherClips_.assign(project.clips.empty() ? project.clips.end() : project.clips.begin() + 1, project.clips.end());
  panels_.view->applyViewSettings(project.view);
  path_ = path;
  rememberSaved();
  return true;
}

bool ProjectActions::newProject() {
  if (auto restored = panels_.sculpt->restore(nullptr, {}); !restored) return fail(restored.error().message);
  panels_.timeline->openEmpty("timeline.json");
  otherClips_.clear();
  path_.clear();
  recoveredUnsaved_ = false;
  rememberSaved();
  message_.report("new project (untitled)", false);
  return true;
}

bool ProjectActions::exportGlb(const fs::path& path) {
  std::vector<TimelineDocument> others;
  for (const ProjectClip& clip : otherClips_) {
    auto loaded = TimelineDocument::load(clip.file);
    if (!loaded) return fail(path.string() + ": not exported: " + loaded.error().message);
    others.push_back(std::move(*loaded));
  }
  std::vector<const TimelineDocument*> clips;
  if (!panels_.timeline->document().tracks().empty()) clips.push_back(&panels_.timeline->document());
  for (const TimelineDocument& clip : others) clips.push_back(&clip);
  TimelinePose pose(panels_.face->rig(), panels_.face->baseWeights(), &panels_.face->expressions());
  auto exported = editor::exportGlb(panels_.sculpt->workingModel(), clips, pose, panels_.face->layout(), path,
                                    kGlbExportSampleRate, panels_.sculpt->bakedTargets());
  if (!exported) return fail(exported.error().message);
  message_.report("exported " + path.string() + ": the face with " + std::to_string(panels_.sculpt->bakedTargets().size()) +
                      " sculpted target(s) and " + std::to_string(exported->animations) + " clip(s) as weights animations" +
                      (exported->droppedTargets ? " (" + std::to_string(exported->droppedTargets) +
                                                      " moving target(s) on other meshes left out: glTF animates one mesh per clip here)"
                                                : std::string()),
                  false);
  return true;
}

eng::Result<const TimelineDocument*> ProjectActions::clipToExport(const std::string& clipName, std::optional<TimelineDocument>& other) const {
  const TimelineDocument& editing = panels_.timeline->document();
  if (!clipName.empty() && clipName != editing.name()) {
    const auto it = std::find_if(otherClips_.begin(), otherClips_.end(), [&](const ProjectClip& c) { return c.name == clipName; });
    if (it == otherClips_.end()) return eng::makeError(eng::ErrorKind::NotFound, "the project has no clip '" + clipName + "'");
    other.emplace(ENG_TRY_VALUE(TimelineDocument::load(it->file)));
  }
  const TimelineDocument& clip = other ? *other : editing;
  if (clip.tracks().empty()) return eng::makeError(eng::ErrorKind::InvalidArgument, "the clip has no tracks");
  return &clip;
}

eng::Result<app::SequenceSummary> ProjectActions::recordClip(const TimelineDocument& clip, app::SequenceOptions sequence,
                                                             const app::FrameSink& sink) const {
  // Drawn as the window draws the face: dressed, with the baked targets, from the view on screen.
  const eng::Model& model = panels_.sculpt->workingModel();
  const std::optional<eng::Model> dressed = importers::dressedForDisplay(model);
  const ProjectView view = panels_.view->viewSettings();
  auto renderers = ENG_TRY_VALUE(app::SequenceRenderers::create(
      dressed ? *dressed : model, {.width = kClipExportSize, .height = kClipExportSize, .yawDegrees = view.yawDegrees,
                                   .pitchDegrees = view.pitchDegrees, .zoom = view.zoom,
                                   .framing = view.wholeModel ? eng::FramingMode::All : eng::FramingMode::Face,
                                   .framesInFlight = app::kSequenceFramesInFlight}));
  TimelinePose pose(panels_.face->rig(), panels_.face->baseWeights(), &panels_.face->expressions());
  std::vector<float> faceWeights(panels_.face->layout().total()), weights;
  eng::vk::ModelInstance instance{&renderers.gpuModel(0), glm::mat4(1.0f), {}};
  sequence.seconds = clip.duration();
  auto recorded = ENG_TRY_VALUE(app::recordSequence(
      renderers.lanes(), sequence,
      [&](const app::FrameContext& frame) -> eng::Result<std::span<const eng::vk::ModelInstance>> {
        instance.model = &renderers.gpuModel(frame.lane);
        if (auto posed = pose.pose(clip, frame.time, faceWeights); !posed) return posed.error();
        panels_.sculpt->bakedWeights(faceWeights, weights);
        instance.weights = weights;
        return std::span<const eng::vk::ModelInstance>(&instance, 1);
      },
      sink));
  ENG_TRY(renderers.checkValidation());
  return recorded;
}

bool ProjectActions::exportGif(const fs::path& path, const std::string& clipName) {
  std::optional<TimelineDocument> other;
  auto clip = clipToExport(clipName, other);
  if (!clip) return fail(path.string() + ": not exported: " + clip.error().message);
  auto recorded = recordClip(**clip, {.framesPerSecond = kGifExportFps, .gifPath = path, .progressLabel = "export gif"}, {});
  if (!recorded) return fail(path.string() + ": not exported: " + recorded.error().message);
  message_.report("exported " + path.string() + ": clip '" + (*clip)->name() + "', " + std::to_string(recorded->frames) + " frames", false);
  return true;
}

bool ProjectActions::exportVideo(const fs::path& path, const std::string& clipName) {
  std::optional<TimelineDocument> other;
  auto clip = clipToExport(clipName, other);
  if (!clip) return fail(path.string() + ": not exported: " + clip.error().message);
  // The writer fills "<path>.partial" and renames it when finished: a failed export leaves no file.
  auto writer = audio::VideoWriter::create(path, {.width = int(kClipExportSize), .height = int(kClipExportSize), .framesPerSecond = kVideoExportFps});
  if (!writer) return fail(path.string() + ": not exported: " + writer.error().message);
  eng::Result<void> written;  // the sink cannot fail the recording: the next frame's step does
  auto recorded = recordClip(**clip, {.framesPerSecond = kVideoExportFps, .progressLabel = "export video"},
                             [&](const app::FrameContext&, const eng::Image& image) {
                               if (written) written = writer->addFrame(image.rgba8);
                             });
  if (recorded && !written) recorded = written.error();
  if (recorded)
    if (auto finished = writer->finish(); !finished) recorded = finished.error();
  if (!recorded) return fail(path.string() + ": not exported: " + recorded.error().message);
  message_.report("exported " + path.string() + ": clip '" + (*clip)->name() + "', " + std::to_string(recorded->frames) +
                      " frames at " + std::to_string(int(kVideoExportFps)) + " fps, no sound",
                  false);
  return true;
}

bool ProjectActions::dirty() const {
  const auto bakes = panels_.sculpt->bakedTargets();
  return recoveredUnsaved_ || panels_.timeline->document().dirty() || !std::equal(bakes.begin(), bakes.end(), savedBakes_.begin(), savedBakes_.end()) ||
         graph_ != savedGraph_ || graphEdited();
}

bool ProjectActions::graphEdited() const {
  const std::optional<GraphDocument>& graph = panels_.machine->document();
  return graph && graph->dirty();
}

std::string ProjectActions::windowTitle() const {
  return (path_.empty() ? std::string("untitled") : path_.filename().string()) + (dirty() ? "*" : "") + " - facial editor - " +
         panels_.face->name();
}

uint64_t ProjectActions::revision() const {
  uint64_t h = panels_.timeline->document().revision() * 1000003u ^ std::hash<std::string>()(graph_.string());
  if (panels_.machine->document()) h = h * 31u + panels_.machine->document()->revision();
  for (const auto& [name, weight] : panels_.sculpt->bakedTargets()) h = h * 31u + std::hash<std::string>()(name) + std::hash<float>()(weight);
  return h;
}

void ProjectActions::rememberSaved() {
  const auto bakes = panels_.sculpt->bakedTargets();
  savedBakes_.assign(bakes.begin(), bakes.end());
  savedGraph_ = graph_;
  recoveredUnsaved_ = false;
  autosavedBakeNames_.clear();
  autosave_.reset();
}

void ProjectActions::update(std::chrono::steady_clock::time_point now) {
  if (path_.empty() || !autosave_.due(dirty(), revision(), now)) return;
  autosave_.written(UINT64_MAX, now);  // a failed write waits for the interval too
  if (writeAutosave()) autosave_.written(revision(), now);
}

bool ProjectActions::writeAutosave() {
  Project project = current(path_);
  project.graph = graph_;  // the graph file as it is, unless the diagram changed it since
  if (graphEdited()) {
    project.graph = projectGraphAutosavePath(path_);
    if (auto saved = panels_.machine->document()->writeCopy(project.graph); !saved) return reportAutosave(saved.error().message);
  }
  const auto bakes = panels_.sculpt->bakedTargets();
  if (!project.sculptTargets.empty()) {
    project.sculptModel = projectSculptAutosavePath(path_);
    std::vector<std::string> names;
    for (const auto& bake : bakes) names.push_back(bake.first);
    if (names != autosavedBakeNames_) {  // a glb only when the bakes changed, not their weights
      if (auto saved = panels_.sculpt->saveModel(project.sculptModel.string()); !saved) return reportAutosave(saved.error().message);
      autosavedBakeNames_ = std::move(names);
    }
  }
  if (auto saved = saveProject(project, projectAutosavePath(path_)); !saved) return reportAutosave(saved.error().message);
  autosaveError_.clear();
  return true;
}

bool ProjectActions::reportAutosave(const std::string& problem) {
  if (problem != autosaveError_) message_.report("project not autosaved: " + problem, true);
  autosaveError_ = problem;
  return false;
}

void ProjectActions::keepUnsaved() {
  if (!path_.empty() && dirty()) writeAutosave();
}

void ProjectActions::discardUnsaved() {
  if (!path_.empty()) discardProjectAutosave(path_);
  panels_.timeline->discardUnsavedEdits();
}

}  // namespace editor
