#!/usr/bin/python3
"""Throughput of the cached memory hierarchy through the RTL (docs/memory.md §5).

Usage: /usr/bin/python3 scripts/memory_report.py [--texsim build/texsim] [--out out/memory]

Runs `texsim` (engine rtl) on the issue's workload: the plane scene, 640x480, trilinear, the
1024x1024 test card, memory latency 200 clocks, 16 B/clock; onchip against cached, scanline and
8x8-tile order, cache sizes 8/16/32 KiB; random queries over the whole pyramid (a worst case);
the texture held as RGBA8, BC1 and BC7 (engine model: the cached RTL takes no block format yet);
then samples/clock per memory latency and FIFO depth (--fifo-depth). Writes OUT/report.md (the tables of docs/memory.md §5) and OUT/latency.png.
Needs matplotlib (Debian's python3-matplotlib, in /usr/bin/python3).
"""
import argparse
import json
import os
import random
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCENE = ["render", "--scene", "plane", "--texture", "testcard:1024x1024", "--filter", "trilinear"]


def texsim(args, exe, out_dir):
    """Runs texsim with --stats and returns the counters (a dict)."""
    stats = os.path.join(out_dir, "stats.json")
    cmd = [exe] + args + ["--stats", stats]
    if args[0] == "render":
        cmd += ["-o", os.path.join(out_dir, "frame.png")]
    run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"memory_report: {' '.join(cmd)} failed: {run.stderr.strip()}")
    with open(stats) as f:
        return json.load(f)


def random_queries(path, count, seed):
    """u, v uniform over the texture and lambda uniform over the pyramid's levels 0..10."""
    rng = random.Random(seed)
    with open(path, "w") as f:
        f.write("u,v,lod\n")
        for _ in range(count):
            f.write(f"{rng.random():.6f},{rng.random():.6f},{rng.uniform(0, 10):.4f}\n")


def row(label, onchip, cached, texel_bytes):
    ratio = cached["samples_per_clock"] / onchip["samples_per_clock"]
    saving = texel_bytes / cached["bytes_per_sample"] if cached["bytes_per_sample"] else float("inf")
    return (f"| {label} | {cached['cache_kib']} KiB × {cached['ways']} | {onchip['samples_per_clock']:.3f} | "
            f"{cached['samples_per_clock']:.3f} | **{ratio:.3f}** | {100 * cached['hit_rate']:.1f} % | "
            f"{cached['bytes_per_sample']:.2f} | {saving:.1f}× | {cached['fifo_max_occupancy']} | "
            f"{cached['memory_stall_cycles']} |")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--texsim", default="build/texsim")
    ap.add_argument("--out", default="out/memory")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    exe = a.texsim
    mem = ["--mem-latency", "200", "--mem-bytes-per-clock", "16"]
    header = ("| workload | caches | onchip samples/clock | cached samples/clock | cached / onchip | hit rate "
              "| bytes/sample | saving vs no cache | FIFO max | clocks waiting for memory |\n"
              "|---|---|---|---|---|---|---|---|---|---|")
    lines = ["# Cached memory hierarchy through the RTL", "",
             "`/usr/bin/python3 scripts/memory_report.py` (`make memory-report`): engine rtl, latency 200 clocks, "
             "16 B/clock, 64 reads in flight, 4x4 row-major blocks, 2 ways. 'saving vs no cache' = the bytes "
             "the needed texels would cost read one by one (4 B each) / the bytes read as lines.", "", header]

    for order in ["scanline", "tiled"]:
        extra = ["--order", order]
        onchip = texsim(SCENE + extra + ["-e", "rtl"], exe, a.out)
        texel_bytes = 4 * texsim(SCENE + extra, exe, a.out)["texel_reads"] / onchip["samples"]
        for kib in [8, 16, 32]:
            cached = texsim(SCENE + extra + ["-e", "rtl", "--memory", "cached", "--cache-kib", str(kib)] + mem,
                            exe, a.out)
            label = f"plane, {order}" + (" 8×8" if order == "tiled" else "")
            lines.append(row(label, onchip, cached, texel_bytes))
            print(lines[-1], flush=True)

    queries = os.path.join(a.out, "random_queries.csv")
    random_queries(queries, 100000, 1)
    sample = ["sample", "--texture", "testcard:1024x1024", "--filter", "trilinear", "--queries", queries, "-o",
              os.path.join(a.out, "random_out.csv")]
    onchip = texsim(sample + ["-e", "rtl"], exe, a.out)
    texel_bytes = 4 * texsim(sample, exe, a.out)["texel_reads"] / onchip["samples"]
    for kib in [8, 32]:
        cached = texsim(sample + ["-e", "rtl", "--memory", "cached", "--cache-kib", str(kib)] + mem, exe, a.out)
        lines.append(row("random u, v, λ (100 000)", onchip, cached, texel_bytes))
        print(lines[-1], flush=True)

    # Texture formats: the caches and memory hold compressed blocks (docs/memory.md §1), decoded by
    # the cached RTL's 8 tap decoders.
    lines += ["", "Texture formats, plane 640×480, 8 KiB × 2 caches, latency 200, 16 B/clock: each level compressed "
              "(`--format`: libsquish for BC1, Mesa's BC7 encoder, ours for ETC2 and EAC, astcenc for ASTC), engine rtl; "
              "'bytes vs RGBA8' = RGBA8's bytes per sample / this format's.", "",
              "| workload | format | samples/clock | cached / onchip | hit rate | bytes/sample | bytes vs RGBA8 | "
              "clocks waiting for memory |", "|---|---|---|---|---|---|---|---|"]
    for order in ["scanline", "tiled"]:
        extra = ["--order", order]
        onchip = texsim(SCENE + extra + ["-e", "rtl"], exe, a.out)
        rgba_bytes = None
        for fmt in ["rgba8", "bc1", "bc7", "etc2", "eac_r11", "eac_rg11", "astc4x4", "astc6x6", "astc8x8", "astc12x12"]:
            r = texsim(SCENE + extra + ["-e", "rtl", "--memory", "cached", "--format", fmt] + mem, exe, a.out)
            rgba_bytes = rgba_bytes or r["bytes_per_sample"]
            label = f"plane, {order}" + (" 8×8" if order == "tiled" else "")
            lines.append(f"| {label} | {fmt} | {r['samples_per_clock']:.3f} | "
                         f"**{r['samples_per_clock'] / onchip['samples_per_clock']:.3f}** | {100 * r['hit_rate']:.1f} % | "
                         f"{r['bytes_per_sample']:.2f} | {rgba_bytes / r['bytes_per_sample']:.1f}× | "
                         f"{r['memory_stall_cycles']} |")
            print(lines[-1], flush=True)

    # Latency x FIFO depth (cfg_fifo_limit), tiled order, default caches: the FIFO a latency needs.
    latencies = [50, 100, 200, 500, 1000, 2000]
    depths = [16, 32, 64, 128, 256, 512, 1024, 2048]
    lines += ["", "Tiled 8×8, 8 KiB × 2 caches, 16 B/clock, reads in flight = latency / 4 + 16: samples/clock "
              "per memory latency (rows) and FIFO depth (`--fifo-depth`, columns); **bold**: the shallowest FIFO "
              "that reaches 0.97 of onchip.", "",
              "| latency | " + " | ".join(f"FIFO {d}" for d in depths) + " |", "|---" * (len(depths) + 1) + "|"]
    curves = {}
    for lat in latencies:
        cells, first = [], True
        for d in depths:
            r = texsim(SCENE + ["--order", "tiled", "-e", "rtl", "--memory", "cached", "--mem-latency", str(lat),
                                "--mem-outstanding", str(lat // 4 + 16), "--fifo-depth", str(d)], exe, a.out)
            spc = r["samples_per_clock"]
            curves.setdefault(d, []).append(spc)
            bold = first and spc >= 0.97
            first = first and not bold
            cells.append(f"**{spc:.3f}**" if bold else f"{spc:.3f}")
        lines.append(f"| {lat} | " + " | ".join(cells) + " |")
        print(lines[-1], flush=True)

    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    for d, ys in curves.items():
        ax.plot(latencies, ys, marker="o", label=f"FIFO {d}")
    ax.axhline(0.97, color="grey", linestyle="--", linewidth=0.8, label="0.97 of onchip")
    ax.set_xscale("log")
    ax.set_xlabel("memory latency (clocks)")
    ax.set_ylabel("samples per clock")
    ax.set_ylim(0, 1.05)
    ax.set_title("plane 640×480 tiled 8×8, testcard 1024², trilinear, 8 KiB × 2 caches, 16 B/clock", fontsize=8)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "latency.png"), dpi=120)
    for tmp in ["stats.json", "frame.png", "random_out.csv"]:
        os.remove(os.path.join(a.out, tmp))
    with open(os.path.join(a.out, "report.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print(f"memory_report: {a.out}/report.md, {a.out}/latency.png")


if __name__ == "__main__":
    main()
