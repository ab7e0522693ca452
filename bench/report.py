#!/usr/bin/python3
"""Turns the raw measurements of bench/report.sh (one folder) into report.md
(markdown tables, the issue's targets met or not) and morph_cost.png (cost
against vertices and instances per morph path). Debian's python3 and
python3-matplotlib only."""
import json
import re
import statistics
import sys
from collections import defaultdict
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

TIERS = ["high", "balanced", "fast"]
PATHS = ["cpu_lerp", "cpu_sparse", "gpu_morph", "gpu_vs", "static"]
PATH_LABEL = {
    "cpu_lerp": "CPU lerp (rewrites the vertex buffer)",
    "cpu_sparse": "CPU sparse (compacted deltas)",
    "gpu_morph": "GPU compute pre-pass, sparse deltas (once per frame)",
    "gpu_vs": "pre-pass + vertex-shader capture",
    "static": "static (no weights)",
}


def fields(line):
    return dict(re.findall(r"(\w+)=(\S+)", line))


def lines(path):
    return [l.rstrip("\n") for l in path.read_text().splitlines() if l.strip()] if path.exists() else []


def median(values):
    return statistics.median(values) if values else float("nan")


def fmt(x, digits=1):
    return "–" if x != x else f"{x:,.{digits}f}"


def frames_section(out, md, targets):
    rows = defaultdict(list)
    msaa = {}
    for line in lines(out / "frames.txt"):
        f = fields(line)
        rows[(f["quality"], f["animate"])].append(float(f["cpu_median_ms"]))
        msaa[f["quality"]] = f["msaa"]
    if not rows:
        return
    md.append("### Whole frames: facecap, 512x512, every target re-weighted every frame vs static\n")
    md.append("| tier | MSAA | animated: ms (fps) | static: ms (fps) | animated / static |")
    md.append("|---|---|---|---|---|")
    for q in TIERS:
        a, s = median(rows[(q, "all")]), median(rows[(q, "none")])
        md.append(f"| {q} | {msaa.get(q, '?')}x | {fmt(a)} ({fmt(1000 / a)}) | {fmt(s)} ({fmt(1000 / s)}) | {a / s:.2f} |")
        targets.setdefault("morph_vs_static", {})[q] = a / s
    md.append("")


def head_section(out, md, targets):
    rows = defaultdict(list)
    msaa = {}
    for line in lines(out / "head1280.txt"):
        f = fields(line)
        rows[f["quality"]].append(float(f["cpu_median_ms"]))
        msaa[f["quality"]] = f["msaa"]
    window = defaultdict(dict)
    for line in lines(out / "window.txt"):
        program, rest = line.split(" ", 1)
        f = fields(rest)
        window[f["quality"]][program] = float(f["fps"])
    if not rows and not window:
        return
    md.append("### The built-in head at 1280x800\n")
    md.append("Headless frames (`facial bench frames data/head.glb --size 1280x800`, drawn and finished, not presented), "
              "and the window demo and editor themselves under Xvfb (`window:` line at exit: presented frames in "
              "the second half of an 8 s run).\n")
    md.append("| tier | MSAA | headless ms (fps) | window demo fps | editor fps |")
    md.append("|---|---|---|---|---|")
    for q in TIERS:
        ms = median(rows[q])
        md.append(f"| {q} | {msaa.get(q, '?')}x | {fmt(ms)} ({fmt(1000 / ms)}) | {fmt(window[q].get('demo', float('nan')))} "
                  f"| {fmt(window[q].get('editor', float('nan')))} |")
        targets.setdefault("window", {})[q] = (window[q].get("demo", float("nan")), window[q].get("editor", float("nan")),
                                               1000 / ms)
    md.append("")


def peer_section(out, md, targets):
    summaries = [fields(l) for l in lines(out / "peer.txt") if l.startswith("peer summary")]
    if not summaries:
        return
    rounds = [l for l in lines(out / "peer.txt") if l.startswith("round")]
    peer_line = next((l for l in rounds if "three.js" in l), "")
    m = re.search(r"three\.js (r\d+)", peer_line)
    md.append("### The peer: three.js in headless Chromium (SwiftShader), same face, animation, size, framing\n")
    md.append(f"three.js {m.group(1) if m else ''} at 4x MSAA (antialias), hemisphere + directional light, no shadows; "
              "this project per tier. Medians of alternating runs.\n")
    md.append("| tier | facial fps | three.js fps | ratio |")
    md.append("|---|---|---|---|")
    for s in summaries:
        md.append(f"| {s['quality']} | {s['facial_fps']} | {s['threejs_fps']} | {s['ratio']}x |")
        targets.setdefault("peer", {})[s["quality"]] = float(s["ratio"])
    md.append("")


def load_benchmarks(path):
    if not path.exists():
        return []
    return [b for b in json.loads(path.read_text())["benchmarks"] if b.get("run_type", "iteration") == "iteration"]


def to_ms(b):
    scale = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}[b.get("time_unit", "ns")]
    return b["real_time"] * scale


def morph_section(out, md, targets):
    benches = load_benchmarks(out / "morph.json")
    if not benches:
        return
    cost = {}
    for b in benches:
        m = re.match(r"MorphSweep_(\w+?)/verts:(\d+)/active:(\d+)/instances:(\d+)", b["name"])
        if m:
            cost[(m.group(1), int(m.group(2)), int(m.group(3)), int(m.group(4)))] = (to_ms(b), b)
    copy = next((b for b in benches if b["name"].startswith("MorphCopyBandwidth")), None)
    copy_gbps = copy["gbps"] if copy else float("nan")
    verts = sorted({k[1] for k in cost})
    actives = sorted({k[2] for k in cost})
    instances = sorted({k[3] for k in cost})

    md.append("### Morph paths: ms per frame (the morph stage only)\n")
    md.append("Synthetic grid, 52 targets each moving a fifth of the vertices, position + normal deltas. "
              "CPU paths: morph every instance and copy it into a mapped Vulkan buffer; gpu_morph: the compute "
              "pre-pass every frame runs once (sparse vertex-major deltas); gpu_vs and static: that pre-pass "
              "plus the capture pass (every vertex of every instance read in the vertex shader and stored, no "
              "rasterisation), GPU timestamps.\n")
    header = "| path | vertices | " + " | ".join(f"{a} active x {k} inst." for a in actives for k in instances) + " |"
    md.append(header)
    md.append("|---|---|" + "---|" * (len(actives) * len(instances)))
    for p in PATHS:
        for v in verts:
            cells = [fmt(cost[(p, v, a, k)][0], 2) if (p, v, a, k) in cost else "–" for a in actives for k in instances]
            md.append(f"| {p} | {v:,} | " + " | ".join(cells) + " |")
    md.append("")

    md.append("### Bandwidth: delta bytes read per frame, effective GB/s, against the device's copy bandwidth\n")
    md.append(f"Device copy bandwidth (vkCmdCopyBuffer, 256 MiB, same run): **{fmt(copy_gbps, 1)} GB/s**.\n")
    md.append("| path | vertices | active | instances | delta MB / frame | GB/s | / copy |")
    md.append("|---|---|---|---|---|---|---|")
    for p in ["cpu_lerp", "cpu_sparse", "gpu_morph"]:
        for v in verts:
            for k in [instances[0], instances[-1]]:
                a = actives[-1]
                if (p, v, a, k) not in cost:
                    continue
                b = cost[(p, v, a, k)][1]
                md.append(f"| {p} | {v:,} | {a} | {k} | {b['delta_bytes'] / 1e6:,.1f} | {b['gbps']:.2f} | "
                          f"{b['gbps'] / copy_gbps:.3f} |")
    md.append("")
    key = (50176 if any(k[1] == 50176 for k in cost) else 50000)
    lerp, gpu = cost.get(("cpu_lerp", key, 52, 1)), cost.get(("gpu_morph", key, 52, 1))
    if lerp and gpu:
        targets["gpu_vs_cpu"] = lerp[0] / gpu[0]
    best = max((cost[("gpu_morph", v, 52, k)][1]["gbps"] for v in verts for k in instances
                if ("gpu_morph", v, 52, k) in cost),
               default=float("nan"))
    targets["morph_bandwidth"] = best / copy_gbps

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for p in PATHS:
        xs = [v for v in verts if (p, v, 52, 1) in cost]
        left.plot(xs, [cost[(p, v, 52, 1)][0] for v in xs], marker="o", label=PATH_LABEL[p])
        ks = [k for k in instances if (p, key, 52, k) in cost]
        right.plot(ks, [cost[(p, key, 52, k)][0] for k in ks], marker="o", label=PATH_LABEL[p])
    for ax, title, xlabel in [(left, "52 active targets, 1 instance", "vertices"),
                              (right, f"{key:,} vertices, 52 active targets", "instances")]:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(title)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("ms per frame")
        ax.grid(True, which="both", alpha=0.3)
    left.legend(fontsize=8)
    fig.suptitle("Morph cost per frame by path (lower is better)")
    fig.tight_layout()
    fig.savefig(out / "morph_cost.png", dpi=110)
    md.append("![Morph cost against vertices and instances](morph_cost.png)\n")


def graph_section(out, md, targets):
    benches = load_benchmarks(out / "graph.json")
    if not benches:
        return
    md.append("### Graph update: 60 channels, state machine mid-transition (CPU time)\n")
    md.append("| characters | ns per character | allocations per update | heap bytes per character |")
    md.append("|---|---|---|---|")
    for b in benches:
        md.append(f"| {int(b['characters']):,} | {b['ns_per_character']:.0f} | {b['allocs_per_update']:g} | "
                  f"{b['instance_bytes']:,.0f} |")
        if int(b["characters"]) == 10000:
            targets["graph_ns"] = b["ns_per_character"]
            targets["graph_allocs"] = b["allocs_per_update"]
    md.append("")


def memory_section(out, md):
    rows = [l.split(" ", 1) for l in lines(out / "memory.txt")]
    if not rows:
        return
    md.append("### Memory\n")
    md.append("| face | device buffers of the asset | each extra instance (GPU records per frame + CPU weights) |")
    md.append("|---|---|---|")
    for name, rest in rows:
        f = fields(rest)
        md.append(f"| {name} | {int(f['asset_buffer_bytes']):,} B | {int(f['per_instance_bytes']):,} B |")
    md.append("")


def targets_section(md, t):
    def verdict(ok):
        return "met" if ok else "**not met**"

    md.append("### The issue's targets (lavapipe)\n")
    md.append("| target | measured | |")
    md.append("|---|---|---|")
    for q, r in t.get("peer", {}).items():
        md.append(f"| >= 2x three.js's frame rate ({q}) | {r:.2f}x | {verdict(r >= 2.0)} |")
    for q, r in t.get("morph_vs_static", {}).items():
        md.append(f"| morphing 52 targets <= 1.25x the static draw ({q}) | {r:.2f}x | {verdict(r <= 1.25)} |")
    if "gpu_vs_cpu" in t:
        r = t["gpu_vs_cpu"]
        md.append(f"| GPU morph path >= 3x the CPU lerp, 50k vertices x 52 targets | {r:.2f}x | {verdict(r >= 3)} |")
    if "morph_bandwidth" in t:
        r = t["morph_bandwidth"]
        md.append(f"| morph pass at >= half the copy bandwidth (best case) | {r:.3f} of copy | {verdict(r >= 0.5)} |")
    if "graph_ns" in t:
        md.append(f"| graph update < 1 us per character at 10,000 | {t['graph_ns']:.0f} ns | {verdict(t['graph_ns'] < 1000)} |")
        md.append(f"| 0 allocations per update | {t['graph_allocs']:g} | {verdict(t['graph_allocs'] == 0)} |")
    for q, (demo, editor, headless) in t.get("window", {}).items():
        shown = f"demo {fmt(demo)}, editor {fmt(editor)} (headless {fmt(headless)})"
        ok = demo >= 30 and editor >= 30
        md.append(f"| window demo and editor >= 30 fps at 1280x800 ({q}) | {shown} fps | {verdict(ok)} |")
    md.append("")


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "bench/out")
    md = ["## Performance (measured by `bench/report.sh`)\n"]
    md.append("Machine: " + " ".join(lines(out / "machine.txt")) + "\n")
    targets = {}
    frames_section(out, md, targets)
    peer_section(out, md, targets)
    head_section(out, md, targets)
    morph_section(out, md, targets)
    graph_section(out, md, targets)
    memory_section(out, md)
    summary = []
    targets_section(summary, targets)
    md[2:2] = summary
    (out / "report.md").write_text("\n".join(md) + "\n")


if __name__ == "__main__":
    main()
