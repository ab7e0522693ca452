#!/usr/bin/env python3
"""How a face's rig holds up when its landmarks are a little off, as dlib's
are on a face it does not know.

usage: tools/landmark_noise.py MODEL [--sigma 0.02,0.03] [--draws 4] [--seed 1]
                               [--judge] [--size 384] [--keep DIR]
                               [--facial build/bin/facial] [--judge-script ../shared/judge/fer_judge.py]

Rigs MODEL once with the landmarks `facial autorig` finds (or reads beside
it), then again for each draw with Gaussian noise of --sigma eye spans (the
distance between the outer eye corners) on the points 17-67 in the face's
plane (the jaw line, 0-16, is left as found: on the outline a step across
the face is a step off the surface, which --landmarks refuses). Prints, per
rig, what changed in `facial autorig`'s notes (a mouth cut open, a landmark
refused) and, with --judge, how many of the seven states the shared
expression judge names (tools/judged_sheet.py, --size px), and how many
skin triangles near the mouth the lips' units (AU10-AU27, each at 1) turn
over: a warp bent by a point off folds the skin there. --keep DIR keeps
the landmark files, the rigs and the judged sheets there to look at.
docs/autorig.md has what it found.
Needs Debian's python3-numpy (./bootstrap.sh installs it), and python3-opencv with --judge.
"""
import argparse
import json
import os
import re
import struct
import subprocess
import sys
import tempfile

import numpy as np

from tool_paths import ROOT, add_facial_and_judge


def face_plane(points):
    """The face's side and up axes (as autorig::LandmarkFrame) and its eye span."""
    span = np.linalg.norm(points[45] - points[36])
    side = (points[45] - points[36]) / span
    rise = (points[36] + points[39] + points[42] + points[45]) / 4.0 - points[8]
    up = rise - rise.dot(side) * side
    return side, up / np.linalg.norm(up), span


LIP_UNITS = ["AU10_UpperLipRaiser", "AU12_LipCornerPuller_L", "AU12_LipCornerPuller_R", "AU15_LipCornerDepressor",
             "AU16_LowerLipDepressor", "AU18_LipPucker", "AU20_LipStretcher", "AU22_LipFunneler", "AU23_LipTightener",
             "AU25_LipsPart", "AU26_JawDrop", "AU27_MouthStretch"]
COMPONENTS = {5120: "b", 5121: "B", 5122: "h", 5123: "H", 5125: "I", 5126: "f"}
WIDTH = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


class Glb:
    """The JSON and the accessors of a binary glTF, as `facial autorig` writes it."""

    def __init__(self, path):
        data = open(path, "rb").read()
        if data[:4] != b"glTF":
            raise ValueError(f"{path}: not a binary glTF")
        offset, self.bin = 12, b""
        while offset + 8 <= len(data):
            length, kind = struct.unpack_from("<II", data, offset)
            chunk = data[offset + 8:offset + 8 + length]
            if kind == 0x4E4F534A:
                self.json = json.loads(chunk)
            elif kind == 0x004E4942:
                self.bin = chunk
            offset += 8 + length

    def accessor(self, index):
        a = self.json["accessors"][index]
        dtype = np.dtype("<" + COMPONENTS[a["componentType"]])
        width, count = WIDTH[a["type"]], a["count"]
        out = np.zeros((count, width), dtype)
        if "bufferView" in a:
            view = self.json["bufferViews"][a["bufferView"]]
            start = view.get("byteOffset", 0) + a.get("byteOffset", 0)
            stride = view.get("byteStride", 0) or width * dtype.itemsize
            for i in range(width):
                out[:, i] = np.ndarray((count,), dtype, self.bin, start + i * dtype.itemsize, (stride,))
        sparse = a.get("sparse")
        if sparse:
            def read(part, kind, n):
                view = self.json["bufferViews"][part["bufferView"]]
                return np.frombuffer(self.bin, kind, n, view.get("byteOffset", 0) + part.get("byteOffset", 0))
            rows = read(sparse["indices"], np.dtype("<" + COMPONENTS[sparse["indices"]["componentType"]]), sparse["count"])
            out[rows] = read(sparse["values"], dtype, sparse["count"] * width).reshape(-1, width)
        return out

    def world(self, mesh):
        """The world matrix of the first node that draws `mesh`."""
        nodes = self.json["nodes"]
        parent = {c: i for i, n in enumerate(nodes) for c in n.get("children", [])}

        def local(n):
            if "matrix" in n:
                return np.array(n["matrix"], float).reshape(4, 4).T
            x, y, z, w = n.get("rotation", [0, 0, 0, 1])
            rotation = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
            m = np.eye(4)
            m[:3, :3] = rotation @ np.diag(n.get("scale", [1, 1, 1]))
            m[:3, 3] = n.get("translation", [0, 0, 0])
            return m
        i = next(i for i, n in enumerate(nodes) if n.get("mesh") == mesh)
        m = np.eye(4)
        while True:
            m = local(nodes[i]) @ m
            if i not in parent:
                return m
            i = parent[i]


def folded_about_the_mouth(path, points):
    """Skin triangles within 0.75 of the mouth's width of its middle that a lip unit at 1 turns
    over, summed over LIP_UNITS, on the mesh with the most vertices among those with AU26."""
    glb = Glb(path)
    meshes = [(sum(glb.json["accessors"][p["attributes"]["POSITION"]]["count"] for p in m["primitives"]), i)
              for i, m in enumerate(glb.json["meshes"]) if "AU26_JawDrop" in (m.get("extras") or {}).get("targetNames", [])]
    if not meshes:
        return 0
    index = max(meshes)[1]
    mesh, world = glb.json["meshes"][index], glb.world(index)
    names = mesh["extras"]["targetNames"]
    middle, width = points[48:68].mean(0), np.linalg.norm(points[54] - points[48])
    folded = 0
    for primitive in mesh["primitives"]:
        rest = glb.accessor(primitive["attributes"]["POSITION"]).astype(float) @ world[:3, :3].T + world[:3, 3]
        triangles = glb.accessor(primitive["indices"]).reshape(-1, 3).astype(int)
        triangles = triangles[(np.linalg.norm(rest - middle, axis=1) < 0.75 * width)[triangles].all(1)]
        a, b, c = (rest[triangles[:, k]] for k in range(3))
        facing = np.cross(b - a, c - a)
        for unit in LIP_UNITS:
            if unit not in names:
                continue
            moved = rest + glb.accessor(primitive["targets"][names.index(unit)]["POSITION"]).astype(float) @ world[:3, :3].T
            a2, b2, c2 = (moved[triangles[:, k]] for k in range(3))
            folded += int(((facing * np.cross(b2 - a2, c2 - a2)).sum(1) < 0).sum())
    return folded


def rig(facial, model, out, details, extra=()):
    """Runs `facial autorig`; returns (ok, the notes worth comparing, its last error line)."""
    cmd = [facial, "autorig", model, "--out", out, *extra] + ([] if details else ["--no-details"])
    run = subprocess.run(cmd, capture_output=True, text=True)
    lines = (run.stdout + run.stderr).splitlines()
    notes = [re.sub(r"^parts: ", "", l) for l in lines if "lips welded" in l or "error" in l or "warning" in l]
    errors = [l for l in lines if "error" in l]
    return run.returncode == 0, notes, errors[-1] if errors else "autorig failed"


def cuts_the_mouth(notes):
    return any("lips welded" in n for n in notes)


def judged(facial, judge, model, sheet, size):
    """The judge's count of named states and the states it missed."""
    run = subprocess.run([sys.executable, os.path.join(ROOT, "tools", "judged_sheet.py"), sheet, "--model", model,
                          "--facial", facial, "--judge", judge, "--size", str(size)], capture_output=True, text=True)
    if run.returncode != 0:
        return f"judge failed: {run.stderr.strip()}"
    count = re.search(r"recognized (\d+/\d+)", run.stdout)
    missed = [m.group(1) for m in re.finditer(r"^(\w+)\.png: .*MISS$", run.stdout, re.M)]
    return f"{count.group(1) if count else '?'} named" + (f" (missed {', '.join(missed)})" if missed else "")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("model")
    ap.add_argument("--sigma", default="0.02", help="noise per coordinate, eye spans (comma-separated list)")
    ap.add_argument("--draws", type=int, default=4)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--judge", action="store_true", help="judge each rig's seven states (about 20 s a rig)")
    ap.add_argument("--size", type=int, default=384)
    ap.add_argument("--keep", default="", help="folder for the landmarks, rigs and sheets")
    add_facial_and_judge(ap, "--judge-script")
    a = ap.parse_args()
    if not os.path.exists(a.model):
        sys.exit(f"landmark_noise: {a.model}: no such file")
    if a.judge and not os.path.exists(a.judge_script):
        sys.exit(f"landmark_noise: {a.judge_script}: no judge here (it lives in ../shared/judge)")
    try:
        sigmas = [float(s) for s in a.sigma.split(",")]
    except ValueError:
        sys.exit(f"landmark_noise: --sigma {a.sigma}: not a comma-separated list of numbers")

    with tempfile.TemporaryDirectory() as tmp:
        work = a.keep or tmp
        os.makedirs(work, exist_ok=True)
        found = os.path.join(work, "landmarks.json")
        clean = os.path.join(work, "rig.glb")
        ok, baseline, error = rig(a.facial, a.model, clean, a.judge, ["--landmarks-out", found])
        if not ok:
            sys.exit(f"landmark_noise: {error}")
        points = np.array(json.load(open(found))["landmarks68"], dtype=float)
        side, up, span = face_plane(points)
        line = f"as found: {'; '.join(baseline) or 'no mouth cut'}; {folded_about_the_mouth(clean, points)} folded"
        if a.judge:
            line += "; " + judged(a.facial, a.judge_script, clean, os.path.join(work, "sheet.png"), a.size)
        print(line, flush=True)

        rng = np.random.default_rng(a.seed)
        cut_before = cuts_the_mouth(baseline)
        cut_otherwise = refused = total = 0
        for sigma in sigmas:
            for draw in range(a.draws):
                noisy = points.copy()
                shift = rng.standard_normal((68, 2)) * sigma * span
                noisy[17:] += shift[17:, :1] * side + shift[17:, 1:] * up
                name = f"sigma{sigma:g}_draw{draw}"
                path = os.path.join(work, name + ".json")
                with open(path, "w") as f:
                    json.dump({"landmarks68": noisy.tolist()}, f)
                out = os.path.join(work, name + ".glb")
                ok, notes, _ = rig(a.facial, a.model, out, a.judge, ["--landmarks", path])
                total += 1
                refused += not ok
                cut_otherwise += ok and cuts_the_mouth(notes) != cut_before
                line = f"sigma {sigma:g} draw {draw}: {'; '.join(notes) or 'no mouth cut'}"
                if ok:
                    line += f"; {folded_about_the_mouth(out, points)} folded"
                if ok and a.judge:
                    line += "; " + judged(a.facial, a.judge_script, out, os.path.join(work, name + ".png"), a.size)
                print(line, flush=True)
        print(f"of {total} noisy landmark sets: {refused} refused (a point off the surface), "
              f"{cut_otherwise} {'left the welded lips joined' if cut_before else 'cut the separate lips'}")


if __name__ == "__main__":
    main()
