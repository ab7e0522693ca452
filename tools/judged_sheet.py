#!/usr/bin/env python3
"""The seven basic states of a face, each tile captioned with what an
independent expression classifier (../shared/judge/fer_judge.py) calls it.

usage: tools/judged_sheet.py OUT.png [--model MODEL] [--facial build/bin/facial]
                             [--judge ../shared/judge/fer_judge.py] [--size 256]

Renders every state with `facial express` at --size px (the size the judge
test uses), runs the judge once over all of them, and writes one row of tiles
with 'state: judge says X (p of the state)' under each, green where the judge
names the state and red where it does not. Prints the judge's own lines.
Needs Debian's python3-opencv and python3-numpy (./bootstrap.sh installs them).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import cv2
import numpy as np

from tool_paths import add_facial_and_judge

STATES = ["neutral", "happy", "sad", "surprise", "fear", "anger", "disgust"]
JUDGE_LABEL = {"anger": "angry"}  # the judge's word for a state, where it differs


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--model", default="", help="face file (default: the built-in head)")
    add_facial_and_judge(ap)
    ap.add_argument("--size", type=int, default=256)
    a = ap.parse_args()
    if not os.path.exists(a.judge):
        sys.exit(f"judged_sheet: {a.judge}: no judge here (it lives in ../shared/judge)")

    with tempfile.TemporaryDirectory() as tmp:
        tiles = []
        for state in STATES:
            path = os.path.join(tmp, state + ".png")
            cmd = [a.facial, "express", state, "--size", f"{a.size}x{a.size}", "--out", path]
            if a.model:
                cmd += ["--model", a.model]
            run = subprocess.run(cmd, capture_output=True, text=True)
            if run.returncode != 0:
                sys.exit(f"judged_sheet: facial express {state}: {run.stderr.strip()}")
            tiles.append(path)
        judged = subprocess.run([sys.executable, a.judge] + [t + ":" + s for t, s in zip(tiles, STATES)],
                                capture_output=True, text=True)
        if judged.returncode != 0:
            sys.exit(f"judged_sheet: {a.judge}: {judged.stderr.strip()}")
        print(judged.stdout, end="")
        verdicts = {}
        for line in judged.stdout.splitlines():
            name, _, rest = line.partition(": ")
            if not name.endswith(".png"):
                continue
            words = rest.split()
            probs = dict(w.split("=") for w in words if "=" in w and not w.startswith("expected"))
            verdicts[name[:-4]] = (words[0], probs)

        caption_h = 44
        row = []
        for state, path in zip(STATES, tiles):
            img = cv2.imread(path)
            said, probs = verdicts[state]
            want = JUDGE_LABEL.get(state, state)
            ok = said == want
            panel = np.full((caption_h, img.shape[1], 3), (38, 34, 33), np.uint8)
            colour = (110, 200, 110) if ok else (90, 90, 230)
            cv2.putText(panel, state, (8, 18), cv2.FONT_HERSHEY_SIMPLEX, 0.5, (235, 235, 235), 1, cv2.LINE_AA)
            text = f"judge: {said} ({want} {float(probs.get(want, 0)):.2f})"
            cv2.putText(panel, text, (8, 37), cv2.FONT_HERSHEY_SIMPLEX, 0.42, colour, 1, cv2.LINE_AA)
            row.append(np.vstack([img, panel]))
        cv2.imwrite(a.out, np.hstack(row))
        print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
