#!/usr/bin/env python3
"""How steadily an independent expression classifier (../shared/judge/fer_judge.py)
names a face's seven basic states across nearby views.

usage: tools/judge_views.py [--model MODEL] [--facial build/bin/facial]
                            [--judge ../shared/judge/fer_judge.py]
                            [--sizes 224,256,320,384] [--yaws -4,0,4]
                            [--crop-scales 0.9,1.05,1.2]

Renders every state with `facial express` at each size (px, square) and yaw
(degrees), runs the judge once over all of them, and prints, per size, the
states named of 7 at each yaw, then each state's hits over all views and the
mean number named per view. One view alone overstates a face: this classifier
flips a state between renders a few pixels or degrees apart, and the 12-view
table in docs/expressions.md is this tool's output.

--crop-scales asks the same of other crops around the judge's face box: at
scale k the classifier sees a square k times the detector's box (1.2 is the
judge's own crop, the box and a tenth of it on each side). Whether a face
reads only on a tighter or a looser crop than the judge's says that the
expressions carry, and that what the judge misses is the face at the scale
of its input, not the mix (see docs/expressions.md, "How expressions are judged").
Needs Debian's python3-opencv and python3-numpy (./bootstrap.sh installs them).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np

from judge_regions import JUDGE_LABEL, crop_box, face_box, load_judge

from tool_paths import add_facial_and_judge

STATES = ["neutral", "happy", "sad", "surprise", "fear", "anger", "disgust"]


def numbers(text, kind):
    return [kind(v) for v in text.split(",") if v.strip()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", default="", help="face file (default: the built-in head)")
    add_facial_and_judge(ap)
    ap.add_argument("--sizes", default="224,256,320,384")
    ap.add_argument("--yaws", default="-4,0,4")
    ap.add_argument("--crop-scales", default="", help="also judge crops k times the detector's box (1.2 = the judge's)")
    a = ap.parse_args()
    if not os.path.exists(a.judge):
        sys.exit(f"judge_views: {a.judge}: no judge here (it lives in ../shared/judge)")
    sizes, yaws = numbers(a.sizes, int), numbers(a.yaws, float)
    if not sizes or not yaws:
        sys.exit("judge_views: --sizes and --yaws each need at least one value")
    crop_scales = numbers(a.crop_scales, float)
    if any(not 0.3 <= k <= 3.0 for k in crop_scales):
        sys.exit("judge_views: each --crop-scales value must lie in [0.3, 3]")

    with tempfile.TemporaryDirectory() as tmp:
        views = []  # (size, yaw, state, path)
        for size in sizes:
            for yaw in yaws:
                for state in STATES:
                    path = os.path.join(tmp, f"{state}_{size}_{yaw:g}.png")
                    cmd = [a.facial, "express", state, "--size", f"{size}x{size}", "--yaw", f"{yaw:g}", "--out", path]
                    if a.model:
                        cmd += ["--model", a.model]
                    run = subprocess.run(cmd, capture_output=True, text=True)
                    if run.returncode != 0:
                        sys.exit(f"judge_views: facial express {state} at {size} px, yaw {yaw:g}: {run.stderr.strip()}")
                    views.append((size, yaw, state, path))
        judged = subprocess.run([sys.executable, a.judge] + [f"{p}:{s}" for _, _, s, p in views],
                                capture_output=True, text=True)
        if judged.returncode != 0:
            sys.exit(f"judge_views: {a.judge}: {judged.stderr.strip()}")
        named = {}  # the judge names each image by its file name, unique per view here
        for line in judged.stdout.splitlines():
            name, _, rest = line.partition(": ")
            if name.endswith(".png"):
                named[os.path.join(tmp, os.path.basename(name))] = rest.rstrip().endswith(" OK")
        missing = [p for _, _, _, p in views if p not in named]
        if missing:
            sys.exit(f"judge_views: {a.judge} gave no verdict for {len(missing)} image(s), e.g. {missing[0]}")
        rescaled = judge_rescaled(load_judge(a.judge), views, crop_scales) if crop_scales else {}

    report(f"{a.model or 'built-in head'}: states named of 7 (letters: the states named)", views, named, sizes, yaws)
    for k, named_at_k in rescaled.items():
        report(f"crop {k:g} x the detector's box:", views, named_at_k, sizes, yaws)


def judge_rescaled(judge, views, scales):
    """{scale: {path: named}}: the judge's network on crops `scale` times its
    detector's face box, centred on the box (cut at the image's edges)."""
    out = {k: {} for k in scales}
    for _, _, state, path in views:
        grey = cv2.cvtColor(cv2.imread(path), cv2.COLOR_BGR2GRAY)
        box = face_box(judge, grey)
        if box is None:
            sys.exit(f"judge_views: {path}: the judge's detector finds no face")
        for k in scales:
            crop = crop_box(grey, box, k)
            p = judge.forward((cv2.resize(crop, (64, 64)).astype(np.float32) / 255.0 - 0.5) * 2.0)
            out[k][path] = judge.LABELS[int(np.argmax(p))] == JUDGE_LABEL.get(state, state)
    return out


def report(title, views, named, sizes, yaws):
    print(title)
    for size in sizes:
        cells = []
        for yaw in yaws:
            hits = [s for sz, y, s, p in views if sz == size and y == yaw and named[p]]
            letters = "".join(s[0] if s in hits else "." for s in STATES)
            cells.append(f"yaw {yaw:+g}: {len(hits)} {letters}")
        print(f"  {size} px   " + "   ".join(cells))
    count = len(sizes) * len(yaws)
    per_state = {s: sum(named[p] for _, _, st, p in views if st == s) for s in STATES}
    print("  over all views: " + ", ".join(f"{s} {per_state[s]}/{count}" for s in STATES))
    print(f"  mean named per view: {sum(per_state.values()) / count:.2f} of 7")


if __name__ == "__main__":
    main()
