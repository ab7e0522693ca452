// Rigging a face without targets (issue 33): the built-in head's units and
// the ARKit shapes carried onto a 100k-vertex head (the head's skin after one
// Loop subdivision: 120k skin vertices), landmarks and parts given. The issue
// asks for under 30 s on a 2-core machine; docs/autorig.md has the times.
//   build/bin/facial_bench --benchmark_filter=Autorig
#include <benchmark/benchmark.h>

#include "autorig/builtin_source.h"
#include "autorig/mouth_opening.h"
#include "autorig/target_transfer.h"
#include "engine/scene/gltf_loader.h"
#include "importers/loop_subdivision.h"

namespace {

void BM_AutorigDenseHead(benchmark::State& state) {
  eng::Result<eng::Model> head = eng::loadModel(FACIAL_SOURCE_DIR "/data/head.glb");
  if (!head) return state.SkipWithError(head.error().message.c_str());
  eng::Model face = *head;
  for (eng::Mesh& mesh : face.meshes) {
    mesh.targetNames.clear();
    mesh.defaultWeights.clear();
    for (eng::Primitive& p : mesh.primitives) p.targets.clear();
  }
  if (auto r = importers::loopSubdivide(face.meshes[0].primitives[0], "head skin"); !r)
    return state.SkipWithError(r.error().message.c_str());
  eng::Result<autorig::SourceFace> source = autorig::builtInSource(*head);
  eng::Result<autorig::SourceFace> target = autorig::builtInSource(face);  // its landmarks and parts, as a user's file would give
  if (!source || !target) return state.SkipWithError("built-in head not set up");
  size_t made = 0;
  for (auto _ : state) {
    eng::Result<autorig::TransferResult> rigged =
        autorig::transferTargets(*source, face, target->posed, target->landmarks, target->parts);
    if (!rigged) return state.SkipWithError(rigged.error().message.c_str());
    made = rigged->report.made.size();
    benchmark::DoNotOptimize(rigged->model.meshes.data());
  }
  state.SetLabel(std::to_string(target->posed.vertexCount()) + " vertices, " + std::to_string(made) + " targets made");
}
BENCHMARK(BM_AutorigDenseHead)->Unit(benchmark::kSecond)->Iterations(1);

// The same dense skin as a scan brings it: nothing inside the mouth (the
// head's mouth inside, teeth and tongue dropped). Timed: making the mouth
// ready (autorig/mouth_opening: the head's carried in, hidden behind the
// lips), posing the changed face and finding its parts again, and the transfer.
void BM_AutorigDenseScan(benchmark::State& state) {
  eng::Result<eng::Model> head = eng::loadModel(FACIAL_SOURCE_DIR "/data/head.glb");
  if (!head) return state.SkipWithError(head.error().message.c_str());
  eng::Model scan = *head;
  for (eng::Mesh& mesh : scan.meshes) {
    mesh.targetNames.clear();
    mesh.defaultWeights.clear();
    for (eng::Primitive& p : mesh.primitives) p.targets.clear();
  }
  if (auto r = importers::loopSubdivide(scan.meshes[0].primitives[0], "head skin"); !r)
    return state.SkipWithError(r.error().message.c_str());
  eng::Result<autorig::SourceFace> source = autorig::builtInSource(*head);
  eng::Result<autorig::SourceFace> dense = autorig::builtInSource(scan);  // its landmarks, as a user's file would give
  if (!source || !dense) return state.SkipWithError("built-in head not set up");
  scan.meshes[0].primitives.resize(1);
  size_t added = 0, vertices = 0;
  for (auto _ : state) {
    eng::Model face = scan;
    autorig::PosedFace posed = autorig::poseAtRest(face);
    autorig::FaceParts parts = autorig::findFaceParts(face, posed, dense->landmarks);
    const autorig::MouthOpening opening = autorig::openTheMouth(face, posed, dense->landmarks, parts, *source);
    posed = autorig::poseAtRest(face);
    parts = autorig::findFaceParts(face, posed, dense->landmarks);
    eng::Result<autorig::TransferResult> rigged = autorig::transferTargets(*source, face, posed, dense->landmarks, parts);
    if (!rigged) return state.SkipWithError(rigged.error().message.c_str());
    added = opening.insideVertices;
    vertices = posed.vertexCount();
    benchmark::DoNotOptimize(rigged->model.meshes.data());
  }
  state.SetLabel(std::to_string(vertices) + " vertices, " + std::to_string(added) + " of them carried into the mouth");
}
BENCHMARK(BM_AutorigDenseScan)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
