#!/usr/bin/env python3
"""Seed corpora for the fuzzers, assembled at run time into OUT (never into the tree).

Sources per fuzzer: fuzz/seeds/<name>/ (small hand-made inputs in the tree), the
project's data/ and, when it is there, ../shared (third-party assets, read-only).
A .gltf whose buffers or images are separate files is rewritten with them inlined as
data: URIs (the fuzzers write each input alone into a scratch folder); images over
64 KiB become a 1x1 PNG so the seeds stay small. Inputs over 1 MiB are left out:
libFuzzer would spend the whole run on a few of them.

usage: make_corpus.py OUT
"""
import base64
import json
import os
import pathlib
import shutil
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHARED = (ROOT / '..' / 'shared').resolve()
MAX_SEED = 1 << 20
MAX_INLINE_IMAGE = 64 << 10
TINY_PNG = ('data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8/5+hHgAHggJ/PchI7wAAAABJRU5ErkJggg==')


def inline_gltf(path):
    doc = json.loads(path.read_text())
    for buffer in doc.get('buffers', []):
        uri = buffer.get('uri')
        if uri and not uri.startswith('data:'):
            data = (path.parent / uri).read_bytes()
            buffer['uri'] = 'data:application/octet-stream;base64,' + base64.b64encode(data).decode()
    for image in doc.get('images', []):
        uri = image.get('uri')
        if uri and not uri.startswith('data:'):
            file = path.parent / uri
            if file.stat().st_size <= MAX_INLINE_IMAGE:
                mime = 'image/jpeg' if file.suffix.lower() in ('.jpg', '.jpeg') else 'image/png'
                image['uri'] = 'data:%s;base64,' % mime + base64.b64encode(file.read_bytes()).decode()
            else:
                image['uri'] = TINY_PNG
    return json.dumps(doc, separators=(',', ':')).encode()


def sources(name):
    seeds = sorted((ROOT / 'fuzz' / 'seeds' / name).glob('*'))
    data = ROOT / 'data'
    shared = SHARED if SHARED.is_dir() else None
    if name == 'gltf':
        seeds += [data / 'head.glb']
        if shared:
            seeds += sorted(shared.glob('assets/**/*.gltf')) + sorted(shared.glob('assets/**/*.glb'))
            seeds += sorted(shared.glob('assets/vrm/*.vrm')) + sorted(shared.glob('compressed/**/*.gl*'))
    if name == 'vrm' and shared:
        seeds += sorted(shared.glob('assets/vrm/*.vrm'))
    if name == 'candide' and shared:
        seeds += sorted(shared.glob('candide3/*.wfm'))
    if name == 'image' and shared:
        seeds += sorted(shared.glob('assets/**/*.png')) + sorted(shared.glob('assets/**/*.jpg'))
    if name == 'fbx':
        seeds += sorted((ROOT / 'tests' / 'importers' / 'fbx').glob('*.fbx'))
    if name == 'expressions':
        seeds += [data / 'expressions.json']
    if name == 'rigmap':
        seeds += sorted(data.glob('rigmaps/*.json'))
    if name == 'graph':
        seeds += sorted(data.glob('graphs/*.json'))
    if name in ('timeline', 'editor_timeline'):
        seeds += sorted(data.glob('timelines/*.json'))
    return seeds


def graph_with_inline_timelines(path):
    doc = json.loads(path.read_text())
    for key, value in list(doc.get('timelines', {}).items()):
        if isinstance(value, str):
            doc['timelines'][key] = json.loads((path.parent / value).read_text())
    return json.dumps(doc).encode()


def grown(name):
    """Seeds of the shapes that once cost far more than their size (issue 37),
    generated so the fuzzers start from them: (file name, bytes) pairs, the
    glTF ones under run.sh's max_len for gltf (32 KiB)."""
    seeds = []
    if name == 'gltf':
        base = json.loads((ROOT / 'fuzz' / 'seeds' / 'gltf' / 'skinned_sparse_morph.gltf').read_text())
        chain = json.loads(json.dumps(base))  # a deep hierarchy, every node drawing the mesh
        chain.pop('skins')
        chain.pop('animations')
        count = 600
        chain['nodes'] = [dict({'mesh': 0}, **({'children': [i + 1]} if i + 1 < count else {})) for i in range(count)]
        chain['scenes'] = [{'nodes': [0]}]
        seeds.append(('grown_node_chain.gltf', chain))
        empty = json.loads(json.dumps(base))  # many targets that hold nothing
        mesh = empty['meshes'][0]
        mesh['primitives'][0]['targets'] += [{}] * 2500
        mesh['weights'] += [0] * 2500
        mesh.pop('extras')
        seeds.append(('grown_empty_targets.gltf', empty))
    if name == 'graph':
        n = 400
        states = [{'name': 's%d' % i, 'node': {'type': 'timeline', 'name': 'n%d' % i, 'timeline': 't%d' % i},
                   'transitions': [{'to': 's%d' % ((i + 1) % n), 'duration': 0.5,
                                    'conditions': [{'parameter': 'p%d' % i, 'op': '>', 'value': 0.5}]}]}
                  for i in range(n)]
        seeds.append(('grown_names.json', {
            'version': 1, 'channels': 'actionUnits',
            'parameters': [{'name': 'p%d' % i, 'type': 'float'} for i in range(n)],
            'timelines': {'t%d' % i: {'tracks': [{'channel': 'AU1_InnerBrowRaiser', 'keys': [[0, 0], [1, 1]]}]} for i in range(n)},
            'root': {'type': 'stateMachine', 'name': 'machine', 'states': states}}))
    if name in ('timeline', 'editor_timeline'):
        seeds.append(('grown_tracks.json', {
            'version': 1, 'tracks': [{'channel': 'c%d' % i, 'keys': [[0, 0], [1, 1]]} for i in range(3000)]}))
    return [(file, json.dumps(doc, separators=(',', ':')).encode()) for file, doc in seeds]


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = pathlib.Path(sys.argv[1])
    # One folder per fuzzer (fuzz/fuzz_NAME.cpp), also for those with no
    # hand-made seeds in the tree (git keeps no empty fuzz/seeds/NAME folder):
    # libFuzzer refuses a seed folder that does not exist.
    names = sorted(p.stem[len('fuzz_'):] for p in (ROOT / 'fuzz').glob('fuzz_*.cpp')
                   if 'LLVMFuzzerTestOneInput' in p.read_text())
    for name in names:
        folder = out / name
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir(parents=True)
        kept = 0
        for seed in sources(name):
            if not seed.is_file():
                continue
            if seed.suffix == '.gltf':
                content = inline_gltf(seed)
            elif name == 'graph':
                content = graph_with_inline_timelines(seed)
            else:
                content = seed.read_bytes()
            if len(content) > MAX_SEED:
                print('make_corpus: %s: %s left out (%d bytes, over %d)' % (name, seed, len(content), MAX_SEED))
                continue
            (folder / ('%02d_%s' % (kept, seed.name))).write_bytes(content)
            kept += 1
        for file, content in grown(name):
            (folder / ('%02d_%s' % (kept, file))).write_bytes(content)
            kept += 1
        print('make_corpus: %s: %d seeds' % (name, kept))


if __name__ == '__main__':
    main()
