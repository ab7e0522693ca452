#!/usr/bin/env python3
"""Whether a face can show a state to an independent expression classifier
(../shared/judge/fer_judge.py) at all: the preset against mixes around it.

usage: tools/judge_reach.py STATE [--model MODEL] [--samples 40] [--seed 1]
                            [--extra CHANNEL,CHANNEL_L+CHANNEL_R,...] [--size 256] [--best 5]
                            [--data data] [--facial build/bin/facial]
                            [--judge ../shared/judge/fer_judge.py]

When the judge does not name a state on a face, the cause is either the
preset's mix of action units or the face itself. This renders STATE's preset
(data/expressions.json) and --samples mixes around it with `facial express`:
each of the preset's action units at 0.5 to 1.5 times its weight (at most 1,
both sides of a unit alike) and each --extra action unit, with a chance of
0.3, at 0.2 to 0.8. It prints the judge's probability of STATE for the preset
and for the --best mixes, then one verdict line. If no mix is named either,
the face's shape, not the mix, is what the judge does not read as STATE (look
there: tools/judge_regions.py); if one is, that mix says which action units
the face needs more or less of. The mixes are for finding causes: a preset
serves every face, so judge a changed one on all of them (tools/judge_views.py).
Needs Debian's python3-opencv and python3-numpy (./bootstrap.sh installs them).
"""
import argparse
import json
import os
import random
import subprocess
import sys
import tempfile

from judge_regions import JUDGE_LABEL, load_judge

from tool_paths import ROOT, add_facial_and_judge

# The default --extra: action units that often come with the basic states (lids, lip press, blink).
DEFAULT_EXTRA = "AU6_CheekRaiser,AU7_LidTightener,AU24_LipPressor,AU45_Blink_L+AU45_Blink_R"


def channel_groups(text):
    """'AU7_LidTightener,AU45_Blink_L+AU45_Blink_R' -> [['AU7_LidTightener'], ['AU45_Blink_L', 'AU45_Blink_R']]:
    channels joined by + are set together (the two sides of one action unit)."""
    return [[c.strip() for c in group.split("+") if c.strip()] for group in text.split(",") if group.strip()]


def au_order(channel):
    """Sort key: FACS number, then the name ('AU4_BrowLowerer' before 'AU15_...')."""
    digits = "".join(ch for ch in channel[2:].split("_")[0] if ch.isdigit())
    return (int(digits) if digits else 999, channel)


def sample_mix(rng, preset, extra):
    mix, scale = {}, {}
    for channel, weight in preset.items():
        # One factor for both sides of an action unit, so the face stays symmetric.
        side = channel.removesuffix("_L").removesuffix("_R")
        scale.setdefault(side, rng.uniform(0.5, 1.5))
        mix[channel] = round(min(1.0, weight * scale[side]), 2)
    for group in extra:
        if any(c in preset for c in group) or rng.random() >= 0.3:
            continue
        weight = round(rng.uniform(0.2, 0.8), 2)
        for channel in group:
            mix[channel] = weight
    return mix


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("state")
    ap.add_argument("--model", default="", help="face file (default: the built-in head)")
    ap.add_argument("--samples", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--extra", default=DEFAULT_EXTRA,
                    help="action-unit channels to add to some mixes, comma-separated; + joins the sides of one unit")
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--best", type=int, default=5)
    ap.add_argument("--data", default=os.path.join(ROOT, "data"), help="data folder whose expressions.json holds STATE")
    add_facial_and_judge(ap)
    a = ap.parse_args()
    if not os.path.exists(a.judge):
        sys.exit(f"judge_reach: {a.judge}: no judge here (it lives in ../shared/judge)")
    if a.samples < 0 or a.size < 32 or a.best < 1:
        sys.exit("judge_reach: --samples must be >= 0, --size >= 32 and --best >= 1")
    expressions_path = os.path.join(a.data, "expressions.json")
    try:
        with open(expressions_path) as f:
            expressions = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"judge_reach: {expressions_path}: {e}")
    preset = expressions.get("expressions", {}).get(a.state)
    if preset is None:
        sys.exit(f"judge_reach: {expressions_path}: no preset named \"{a.state}\"")
    judge = load_judge(a.judge)
    label = JUDGE_LABEL.get(a.state, a.state)
    if label not in judge.LABELS:
        sys.exit(f"judge_reach: the judge has no state \"{label}\" (it knows {', '.join(judge.LABELS)})")

    rng = random.Random(a.seed)
    extra = channel_groups(a.extra)
    units = preset.get("actionUnits", {})
    mixes = [dict(units)] + [sample_mix(rng, units, extra) for _ in range(a.samples)]
    with tempfile.TemporaryDirectory() as tmp:
        # A data folder like a.data whose expressions.json also holds each mix, as reach_N.
        data = os.path.join(tmp, "data")
        os.mkdir(data)
        for entry in os.listdir(a.data):
            if entry != "expressions.json":
                os.symlink(os.path.join(os.path.abspath(a.data), entry), os.path.join(data, entry))
        for i, mix in enumerate(mixes):
            expressions["expressions"][f"reach_{i}"] = {
                "facs": preset.get("facs", ""), "description": f"judge_reach mix {i} around {a.state}",
                "actionUnits": mix, "emotions": preset.get("emotions", {})}
        with open(os.path.join(data, "expressions.json"), "w") as f:
            json.dump(expressions, f)
        env = dict(os.environ, FACIAL_DATA_DIR=data)
        results = []  # (p of the state, the judge's label, index)
        for i in range(len(mixes)):
            out = os.path.join(tmp, f"reach_{i}.png")
            cmd = [a.facial, "express", f"reach_{i}", "--size", f"{a.size}x{a.size}", "--out", out]
            if a.model:
                cmd += ["--model", a.model]
            run = subprocess.run(cmd, capture_output=True, text=True, env=env)
            if run.returncode != 0:
                sys.exit(f"judge_reach: facial express (mix {i}): {run.stderr.strip()}")
            said, p, _ = judge.judge(out)
            results.append((float(p[judge.LABELS.index(label)]), said, i))

    def describe(r):
        p, said, i = r
        weights = ", ".join(f"{c} {w:g}" for c, w in sorted(mixes[i].items(), key=lambda cw: au_order(cw[0])))
        return f"{label} {p:.2f} (says {said}): {weights}"

    print(f"{a.model or 'built-in head'}, {a.state} at {a.size} px, {len(mixes) - 1} mixes around the preset (seed {a.seed})")
    print(f"  preset   {describe(results[0])}")
    ranked = sorted(results[1:], key=lambda r: -r[0])
    for rank, r in enumerate(ranked[:a.best], 1):
        print(f"  best {rank:<3} {describe(r)}")
    named = [r for r in results if r[1] == label]
    top = max(results, key=lambda r: r[0])
    if named:
        print(f"reach: {len(named)} of {len(results)} mixes named {label} (best p {top[0]:.2f}): the mix can carry it on this face")
    else:
        print(f"reach: no mix named {label} (best p {top[0]:.2f} of {len(results)}): the face, not the mix, keeps it from reading")


if __name__ == "__main__":
    main()
