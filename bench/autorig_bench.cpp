// Rigging a face without targets (issue 33): the built-in head's units and
// the ARKit shapes carried onto a 100k-vertex head (the head's skin after one
// Loop subdivision: 120k skin vertices), landmarks and parts given. The issue
// asks for under 30 s on a 2-core machine; docs/autorig.md has the times.
//   build/bin/facial_bench --benchmark_filter=Autorig
#include <benchmark/benchmark.h>

#include <memory>

#include "autorig/builtin_source.h"
#include "autorig/mouth_opening.h"
#include "autorig/target_transfer.h"
#include "engine/scene/gltf_loader.h"
#include "importers/loop_subdivision.h"

namespace {

// The built-in head (the source) and a dense face made from it: its targets
// stripped, its skin Loop-subdivided once (120k skin vertices), with the
// landmarks and parts builtInSource finds on it (as a user's file would give).
struct DenseHead {
  std::unique_ptr<eng::Model> head;  // the source refers to it
  autorig::SourceFace source;
  eng::Model face;
  autorig::PosedFace posed;  // the dense face's
  autorig::FaceLandmarks landmarks;
  autorig::FaceParts parts;
};

eng::Result<DenseHead> denseHead() {
  DenseHead d;
  d.head = std::make_unique<eng::Model>(ENG_TRY_VALUE(eng::loadModel(FACIAL_SOURCE_DIR "/data/head.glb")));
  d.face = *d.head;
  for (eng::Mesh& mesh : d.face.meshes) {
    mesh.targetNames.clear();
    mesh.defaultWeights.clear();
    for (eng::Primitive& p : mesh.primitives) p.targets.clear();
  }
  ENG_TRY(importers::loopSubdivide(d.face.meshes[0].primitives[0], "head skin"));
  d.source = ENG_TRY_VALUE(autorig::builtInSource(*d.head));
  autorig::SourceFace dense = ENG_TRY_VALUE(autorig::builtInSource(d.face));
  d.posed = std::move(dense.posed);
  d.landmarks = dense.landmarks;
  d.parts = std::move(dense.parts);
  return d;
}

void BM_AutorigDenseHead(benchmark::State& state) {
  eng::Result<DenseHead> d = denseHead();
  if (!d) return state.SkipWithError(d.error().message.c_str());
  size_t made = 0;
  for (auto _ : state) {
    eng::Result<autorig::TransferResult> rigged =
        autorig::transferTargets(d->source, d->face, d->posed, d->landmarks, d->parts);
    if (!rigged) return state.SkipWithError(rigged.error().message.c_str());
    made = rigged->report.made.size();
    benchmark::DoNotOptimize(rigged->model.meshes.data());
  }
  state.SetLabel(std::to_string(d->posed.vertexCount()) + " vertices, " + std::to_string(made) + " targets made");
}
BENCHMARK(BM_AutorigDenseHead)->Unit(benchmark::kSecond)->Iterations(1);

// The same dense skin as a scan brings it: nothing inside the mouth (the
// head's mouth inside, teeth and tongue dropped). Timed: making the mouth
// ready (autorig/mouth_opening: the head's carried in, hidden behind the
// lips), posing the changed face and finding its parts again, and the transfer.
void BM_AutorigDenseScan(benchmark::State& state) {
  eng::Result<DenseHead> d = denseHead();
  if (!d) return state.SkipWithError(d.error().message.c_str());
  eng::Model scan = d->face;
  scan.meshes[0].primitives.resize(1);
  const autorig::FaceLandmarks& landmarks = d->landmarks;
  size_t added = 0, vertices = 0;
  for (auto _ : state) {
    eng::Model face = scan;
    autorig::PosedFace posed = autorig::poseAtRest(face);
    autorig::FaceParts parts = autorig::findFaceParts(face, posed, landmarks);
    const autorig::MouthOpening opening = autorig::openTheMouth(face, posed, landmarks, parts, d->source);
    posed = autorig::poseAtRest(face);
    parts = autorig::findFaceParts(face, posed, landmarks);
    eng::Result<autorig::TransferResult> rigged = autorig::transferTargets(d->source, face, posed, landmarks, parts);
    if (!rigged) return state.SkipWithError(rigged.error().message.c_str());
    added = opening.insideVertices;
    vertices = posed.vertexCount();
    benchmark::DoNotOptimize(rigged->model.meshes.data());
  }
  state.SetLabel(std::to_string(vertices) + " vertices, " + std::to_string(added) + " of them carried into the mouth");
}
BENCHMARK(BM_AutorigDenseScan)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
