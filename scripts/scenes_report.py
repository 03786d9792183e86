#!/usr/bin/python3
"""Real frames through the RTL (docs/scenes.md): the assimp test models, cached unit, latency 200.

Usage: /usr/bin/python3 scripts/scenes_report.py [--texsim build/texsim] [--out out/scenes]
       [--width 640] [--height 480] [--latency 200] [--stalls none] [--engine rtl|systemc]

Renders each test model of Debian's assimp-testmodels with `texsim render --model ... --engine rtl
--memory cached` (or --engine systemc: the same RTL behind the TLM-2.0 sockets) (default caches, tiled order, each texture's glTF sampler or trilinear, --verify:
every sample against the golden model, every line read against its miss stream) and writes OUT/FRAME.png, OUT/contact_sheet.png,
OUT/report.md (the table of docs/scenes.md) and OUT/index.html. Lost clocks are the clocks after the
pipeline fill beyond one per sample; the RTL counts the clocks in which the FIFO's head waits for
memory (the first fill's included) and those in which the FIFO is full (req_ready low). Compulsory
bytes per sample: the distinct lines the frame touches, per sample (no cache can read fewer).
Needs matplotlib (Debian's python3-matplotlib, in /usr/bin/python3).
"""
import argparse
import html
import json
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

MODELS = "/usr/share/assimp/models/"
# name, file, frame of an 8-frame orbit (the spider's 5 shows all four of its textures)
SCENES = [
    ("CesiumMilkTruck", MODELS + "glTF/CesiumMilkTruck/CesiumMilkTruck.gltf", 0),
    ("BoxTextured", MODELS + "glTF2/BoxTextured-glTF/BoxTextured.gltf", 0),
    ("duck", MODELS + "Collada/duck.dae", 0),
    ("spider", MODELS + "OBJ/spider.obj", 5),
]


def render(exe, name, model, frame, a):
    stats = os.path.join(a.out, name + ".json")
    png = os.path.join(a.out, name + ".png")
    cmd = [exe, "render", "--model", model, "--frames", "8", "--frame", str(frame), "--engine", a.engine,
           "--memory", "cached", "--mem-latency", str(a.latency), "--stalls", a.stalls, "--verify",
           "--width", str(a.width), "--height", str(a.height), "--out", png, "--stats", stats]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"scenes_report: {' '.join(cmd)} failed: {run.stderr.strip()}")
    with open(stats) as f:
        s = json.load(f)
    s["name"], s["png"], s["command"] = name, png, " ".join(cmd[1:])
    return s


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--texsim", default="build/texsim")
    ap.add_argument("--out", default="out/scenes")
    ap.add_argument("--width", type=int, default=640)
    ap.add_argument("--height", type=int, default=480)
    ap.add_argument("--latency", type=int, default=200)
    ap.add_argument("--stalls", default="none")
    ap.add_argument("--engine", default="rtl", choices=["rtl", "systemc"],
                    help="a clocked engine: the Verilated RTL, alone or behind the SystemC sockets")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for name, model, frame in SCENES:
        s = render(a.texsim, name, model, frame, a)
        rows.append(s)
        print(f"scenes: {name}: {s['samples_per_clock']:.4f} samples/clock, {s['textures_used']} textures, "
              f"{s['bytes_per_sample']:.2f} B/sample", file=sys.stderr)

    header = ("| model | samples | quads | helper lanes | textures used | texture MiB resident / touched | "
              "hit rate even / odd levels | bytes/sample (compulsory) | samples/clock | lost clocks | "
              "head waiting for memory | FIFO full |")
    lines = [f"Engine {a.engine} (`{rows[0]['configuration']}`), cached, default caches ({rows[0]['cache_kib']:g} KiB x 2, "
             f"{rows[0]['ways']} ways, {rows[0]['block']} blocks), tiled order, each texture's glTF sampler or else trilinear, "
             f"{a.width}x{a.height}, memory "
             f"latency {a.latency} clocks, {rows[0]['mem_bytes_per_clock']} B/clock, stalls {a.stalls}; every sample "
             "verified against the golden model (`make scenes`, scripts/scenes_report.py).", "", header,
             "|" + "---|" * (header.count("|") - 1)]
    for s in rows:
        lost = s["cycles"] - s["latency_cycles"] - s["samples"]
        lines.append(
            f"| {s['name']} | {s['samples']} | {s['quads']} | {s['helper_samples']} | {s['textures_used']} of "
            f"{s['textures']} | {s['texture_bytes_resident'] / 2**20:.2f} / {s['texture_bytes_touched'] / 2**20:.2f} | "
            f"{100 * s['hit_rate_even_levels']:.1f} % / {100 * s['hit_rate_odd_levels']:.1f} % | "
            f"{s['bytes_per_sample']:.2f} ({s['texture_bytes_touched'] / s['samples']:.2f}) | "
            f"**{s['samples_per_clock']:.3f}** | {lost} | {s['memory_stall_cycles']} | {s['backpressure_cycles']} |")
    report = "\n".join(lines) + "\n"
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write(report)

    fig, axes = plt.subplots(2, 2, figsize=(12, 9.2))
    for ax, s in zip(axes.flat, rows):
        ax.imshow(mpimg.imread(s["png"]))
        ax.set_title(f"{s['name']}: {s['samples_per_clock']:.3f} samples/clock, {s['textures_used']} textures")
        ax.axis("off")
    fig.tight_layout()
    sheet = os.path.join(a.out, "contact_sheet.png")
    fig.savefig(sheet, dpi=80)

    with open(os.path.join(a.out, "index.html"), "w") as f:
        f.write("<!doctype html><meta charset=utf-8><title>texsim: real frames</title>"
                "<style>body{font-family:sans-serif;max-width:1100px;margin:auto}table{border-collapse:collapse}"
                "td,th{border:1px solid #999;padding:3px 6px;text-align:right}img{max-width:100%}</style>"
                "<h1>Real frames through the cached RTL</h1>")
        f.write(f"<p>{html.escape(lines[0])}</p><table><tr>")
        f.write("".join(f"<th>{html.escape(h.strip())}</th>" for h in header.strip("|").split("|")) + "</tr>")
        for line in lines[4:]:
            f.write("<tr>" + "".join(f"<td>{html.escape(c.strip().strip('*'))}</td>" for c in line.strip("|").split("|"))
                    + "</tr>")
        f.write("</table><p><img src=contact_sheet.png></p><h2>Commands</h2><pre>")
        f.write("\n".join(html.escape("texsim " + s["command"]) for s in rows) + "</pre>")
    print(report, end="")
    print(f"scenes: {os.path.join(a.out, 'index.html')}", file=sys.stderr)


if __name__ == "__main__":
    main()
