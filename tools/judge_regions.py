#!/usr/bin/env python3
"""Which part of a face keeps an independent expression classifier
(../shared/judge/fer_judge.py) from naming a state: region swaps against a
face that it does name.

usage: tools/judge_regions.py STATE --reference REF [--model MODEL]
                              [--size 256] [--yaw 0] [--facial build/bin/facial]
                              [--judge ../shared/judge/fer_judge.py]

Renders STATE with `facial express` on MODEL (default: the built-in head) and
on REF, crops both the way the judge does (its face detector, 64x64 grey),
moves REF's crop so that its eyes (OpenCV's eye detector) lie on MODEL's, and for each region of the face (brows, eyes, nose, cheeks, mouth,
chin, jaw, upper and lower half, all but the hair) prints what the judge
says of MODEL with that region taken from REF, and of REF with that region
taken from MODEL. A region whose swap moves the verdict most is where the
faces differ in what the classifier reads: look there, with your own eyes,
for the cause (a crease that reads as a smile, eyes that read as startled).
Needs Debian's python3-opencv and python3-numpy (./bootstrap.sh installs them).
"""
import argparse
import importlib.util
import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np

from tool_paths import add_facial_and_judge

EYE_CASCADE = "/usr/share/opencv4/haarcascades/haarcascade_eye.xml"  # Debian's opencv-data
JUDGE_LABEL = {"anger": "angry"}  # the judge's word for a state, where it differs
# Rows and columns of the judge's 64x64 face crop (the detector's box plus a
# tenth on each side) that hold each part of a face seen from the front.
REGIONS = {
    "brows": (15, 25, 10, 54),
    "eyes": (24, 32, 10, 54),
    "brows+eyes": (15, 32, 10, 54),
    "nose": (32, 44, 24, 40),
    "cheeks": (30, 46, 6, 58),
    "inner cheeks": (30, 46, 14, 50),
    "mouth": (42, 55, 20, 44),
    "chin": (52, 62, 20, 44),
    "jaw": (44, 64, 6, 58),
    "upper half": (0, 32, 0, 64),
    "lower half": (32, 64, 0, 64),
    "all but the hair": (14, 64, 6, 58),
}


def load_judge(path):
    spec = importlib.util.spec_from_file_location("fer_judge", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def face_box(judge, grey):
    """The judge's face: the largest box of its detector, with its settings (None: no face)."""
    faces = judge.cascade.detectMultiScale(grey, 1.1, 5, minSize=(32, 32))
    return max(faces, key=lambda f: f[2] * f[3]) if len(faces) else None


def crop_box(grey, box, scale=1.2):
    """The part of `grey` `scale` times `box`, about its centre, cut at the image's edges.
    1.2 is the judge's own crop (the box and a tenth of it on each side), in its own
    integer arithmetic, so that it gives the judge's verdicts."""
    x, y, w, h = box
    pad = int(round((scale - 1.0) / 2.0, 6) * w)  # at 1.2 exactly the judge's int(0.1 * w)
    return grey[max(0, y - pad):y + h + pad, max(0, x - pad):x + w + pad]


def judge_crop(judge, path):
    """The 64x64 grey crop the judge classifies (its own detector and padding),
    and the eye centres in it (None where two eyes are not found)."""
    grey = cv2.cvtColor(cv2.imread(path), cv2.COLOR_BGR2GRAY)
    box = face_box(judge, grey)
    if box is None:
        sys.exit(f"judge_regions: {path}: the judge's detector finds no face")
    grey = crop_box(grey, box)
    return cv2.resize(grey, (64, 64)).astype(np.float32), eye_centres(grey)


def eye_centres(face):
    """Left and right eye centres in 64x64 crop units, from OpenCV's eye detector."""
    cascade = cv2.CascadeClassifier(EYE_CASCADE)
    if cascade.empty():
        sys.exit(f"judge_regions: {EYE_CASCADE}: no eye detector (Debian's opencv-data installs it)")
    h, w = face.shape
    eyes = [e for e in cascade.detectMultiScale(face[: int(h * 0.6)], 1.05, 3, minSize=(w // 12, w // 12))]
    left = [e for e in eyes if e[0] + e[2] / 2 < w / 2]
    right = [e for e in eyes if e[0] + e[2] / 2 >= w / 2]
    if not left or not right:
        return None
    centre = lambda e: np.array([(e[0] + e[2] / 2) * 64.0 / w, (e[1] + e[3] / 2) * 64.0 / h])
    return [centre(max(side, key=lambda e: e[2] * e[3])) for side in (left, right)]


def aligned(reference, reference_eyes, onto_eyes):
    """`reference` moved, turned and scaled so its eyes lie on `onto_eyes`."""
    if reference_eyes is None or onto_eyes is None:
        return reference, "unaligned (two eyes not found in both crops)"
    r = complex(*(reference_eyes[1] - reference_eyes[0]))
    o = complex(*(onto_eyes[1] - onto_eyes[0]))
    k = o / r  # rotation and scale
    t = complex(*onto_eyes[0]) - k * complex(*reference_eyes[0])
    warp = np.float32([[k.real, -k.imag, t.real], [k.imag, k.real, t.imag]])
    return cv2.warpAffine(reference, warp, (64, 64), borderMode=cv2.BORDER_REPLICATE), "aligned by the eyes"


def region_mask(rows_cols):
    y0, y1, x0, x1 = rows_cols
    mask = np.zeros((64, 64), np.float32)
    mask[y0:y1, x0:x1] = 1.0
    return cv2.GaussianBlur(mask, (5, 5), 1.5)  # a soft seam, not an edge the classifier reads


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("state")
    ap.add_argument("--reference", required=True, help="a face the judge names STATE on")
    ap.add_argument("--model", default="", help="face file (default: the built-in head)")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--yaw", type=float, default=0.0)
    add_facial_and_judge(ap)
    a = ap.parse_args()
    if not os.path.exists(a.judge):
        sys.exit(f"judge_regions: {a.judge}: no judge here (it lives in ../shared/judge)")
    judge = load_judge(a.judge)
    label = JUDGE_LABEL.get(a.state, a.state)
    if label not in judge.LABELS:
        sys.exit(f"judge_regions: the judge has no state '{a.state}' (it knows {', '.join(judge.LABELS)})")

    with tempfile.TemporaryDirectory() as tmp:
        crops = []
        for name, model in (("model", a.model), ("reference", a.reference)):
            out = os.path.join(tmp, name + ".png")
            cmd = [a.facial, "express", a.state, "--size", f"{a.size}x{a.size}", "--yaw", f"{a.yaw:g}", "--out", out]
            if model:
                cmd += ["--model", model]
            run = subprocess.run(cmd, capture_output=True, text=True)
            if run.returncode != 0:
                sys.exit(f"judge_regions: facial express {a.state} on {model or 'the built-in head'}: {run.stderr.strip()}")
            crops.append(judge_crop(judge, out))
    (face, face_eyes), (reference, reference_eyes) = crops
    reference, how = aligned(reference, reference_eyes, face_eyes)

    def verdict(crop):
        p = judge.forward((crop / 255.0 - 0.5) * 2.0)
        top = judge.LABELS[int(np.argmax(p))]
        return f"{label} {p[judge.LABELS.index(label)]:.2f}  (says {top} {p.max():.2f})"

    print(f"'{a.state}' at {a.size} px, yaw {a.yaw:g}; p of {label}, and the judge's verdict")
    print(f"  {'model':34s} {verdict(face)}")
    print(f"  {'reference (' + how + ')':34s} {verdict(reference)}")
    for name, rows_cols in REGIONS.items():
        m = region_mask(rows_cols)
        print(f"  {'model with the reference ' + name:50s} {verdict(face * (1 - m) + reference * m)}")
    for name, rows_cols in REGIONS.items():
        m = region_mask(rows_cols)
        print(f"  {'reference with the model ' + name:50s} {verdict(reference * (1 - m) + face * m)}")


if __name__ == "__main__":
    main()
