#!/usr/bin/python3
"""Composite figures and index.html from `texsim figures` output (metrics.json and the PNGs).

Usage: /usr/bin/python3 scripts/figures.py OUT_DIR
Writes OUT_DIR/<scene>_comparison.png, OUT_DIR/flicker.png and OUT_DIR/index.html.
Needs numpy and matplotlib (Debian's python3-matplotlib, in /usr/bin/python3).
"""
import argparse
import html
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def comparison(out_dir, scene, full_scale):
    """Variants and reference on top, their error heat maps below, PSNR and max error in the titles."""
    variants = scene["variants"]
    cols = len(variants) + 1
    fig, axes = plt.subplots(2, cols, figsize=(3.2 * cols, 5.4), squeeze=False)
    for i, v in enumerate(variants):
        axes[0][i].imshow(plt.imread(os.path.join(out_dir, v["image"])))
        axes[0][i].set_title(f"{v['label']}\nPSNR {v['psnr_db']:.1f} dB, max {v['max_error_lsb']:.0f} LSB", fontsize=8)
        heat = axes[1][i].imshow(plt.imread(os.path.join(out_dir, v["error_image"])))
        axes[1][i].set_title(f"error of {v['name']} (mean {v['mean_error_lsb']:.2f} LSB)", fontsize=8)
    axes[0][-1].imshow(plt.imread(os.path.join(out_dir, scene["reference"])))
    axes[0][-1].set_title("real-valued reference", fontsize=8)
    # Colour key of the heat maps (black -> red -> yellow -> white).
    key = [[(min(1, 3 * t), min(1, max(0, 3 * t - 1)), min(1, max(0, 3 * t - 2))) for t in
            [k / 99 for k in range(100)]]]
    axes[1][-1].imshow(key, aspect=8, extent=(0, full_scale, 0, full_scale / 8))
    axes[1][-1].set_yticks([])
    axes[1][-1].set_title("heat map scale (LSB)", fontsize=8)
    for r in range(2):
        for c in range(cols if r == 0 else cols - 1):
            axes[r][c].set_xticks([])
            axes[r][c].set_yticks([])
    fig.suptitle(f"{scene['scene']}: {scene['caption']}", fontsize=9, wrap=True)
    fig.tight_layout(rect=(0, 0, 1, 0.9))
    name = f"{scene['scene']}_comparison.png"
    fig.savefig(os.path.join(out_dir, name), dpi=110)
    plt.close(fig)
    return name


def flicker_plot(out_dir, flicker):
    scenes = sorted({f["scene"] for f in flicker}, key=[f["scene"] for f in flicker].index)
    fig, axes = plt.subplots(1, len(scenes), figsize=(4.2 * len(scenes), 3.4), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        for f in (f for f in flicker if f["scene"] == scene):
            ax.plot(f["excess"], label=f"{f.get('label', f['filter'])} (mean {f['mean_excess']:.1f})")
        ax.set_title(f"{scene}: change the reference lacks", fontsize=9)
        ax.set_xlabel("frame step")
        ax.set_ylabel("mean |dF - dR| (LSB)")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, "flicker.png"), dpi=110)
    plt.close(fig)
    return "flicker.png"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out_dir", metavar="OUT_DIR", help="directory written by `texsim figures`")
    out_dir = parser.parse_args().out_dir
    path = os.path.join(out_dir, "metrics.json")
    if not os.path.exists(path):
        sys.exit(f"figures.py: {path}: no such file (run texsim figures first)")
    with open(path) as f:
        m = json.load(f)
    e = html.escape
    parts = [
        "<!doctype html><html><head><meta charset='utf-8'><title>Pyramidal parametrics: figures</title>",
        "<style>body{font-family:sans-serif;max-width:1200px;margin:auto}table{border-collapse:collapse}"
        "td,th{border:1px solid #aaa;padding:3px 8px;text-align:right}img{max-width:100%}</style></head><body>",
        "<h1>The paper's experiments through the simulator</h1>",
        f"<p>Engine <b>{e(m['engine'])}</b>, stills {m['width']}x{m['height']}. The reference is real-valued "
        f"filtering of level 0 in double precision (at least {m['reference_samples_per_axis']}<sup>2</sup> "
        "sub-pixel positions through the exact mapping, more where a pixel's footprint is longer so that a "
        "sub-pixel spans at most one texel per axis, up to "
        f"{m.get('reference_max_samples_per_axis', m['reference_samples_per_axis'])}<sup>2</sup>; each averages "
        "its own footprint widened by one texel; see docs/scenes.md). PSNR over R, G, B "
        "of the pixels on the surface; errors in 8-bit steps (LSB). Plain tables and single images: "
        "<a href='index.md'>index.md</a>.</p>",
    ]
    if os.path.exists(os.path.join(out_dir, "fig1_layout.png")):
        parts.append("<h2>Figure 1: the memory layout of a colour mip map</h2><p>R, G and B planes in three "
                     "quadrants, each level's planes in the upper-left quadrant of its parent "
                     "(<code>texsim mip --layout</code>).</p><p><img src='fig1_layout.png' alt='mip map layout'></p>")
    if m.get("filters"):
        parts.append("<h2>Filters compared: plane and panel</h2><p>Stills against the reference; flicker excess over "
                     "the animation (below). Variants rendered by another engine than the figures' name it.</p>")
        parts.append("<table><tr><th>scene</th><th>variant</th><th>engine</th><th>PSNR (dB)</th><th>max error (LSB)"
                     "</th><th>mean error (LSB)</th><th>flicker excess (LSB)</th></tr>")
        for r in m["filters"]:
            flick = f"{r['flicker_excess']:.2f}" if r["flicker_excess"] >= 0 else ""
            parts.append(f"<tr><td>{e(r['scene'])}</td><td>{e(r['label'])}</td><td>{e(r['engine'])}</td>"
                         f"<td>{r['psnr_db']:.2f}</td><td>{r['max_error_lsb']:.1f}</td>"
                         f"<td>{r['mean_error_lsb']:.2f}</td><td>{flick}</td></tr>")
        parts.append("</table>")
    for scene in m["scenes"]:
        name = comparison(out_dir, scene, m["heat_map_full_scale_lsb"])
        parts.append(f"<h2>{e(scene['scene'])}</h2><p>{e(scene['caption'])}</p>")
        parts.append("<table><tr><th>variant</th><th>PSNR (dB)</th><th>max error (LSB)</th><th>mean error (LSB)</th></tr>")
        for v in scene["variants"]:
            parts.append(f"<tr><td>{e(v['label'])}</td><td>{v['psnr_db']:.2f}</td><td>{v['max_error_lsb']:.1f}</td>"
                         f"<td>{v['mean_error_lsb']:.2f}</td></tr>")
        parts.append("</table>")
        if scene.get("vertex_errors"):
            parts.append("<p>Vertex space: the distance |P - P<sub>ref</sub>| between each sampled vertex position "
                         "(X, Y, Z) and the reference's (the box-filtered 16-bit map at the vertex's (u, v) and "
                         "footprint), in level-0 texels (1/256 of the map's full scale); RMS and max over all "
                         "vertices, the interior ones, and those on a face's border, where the pyramid's "
                         "clamp-to-edge pulls the vertex 2<sup>&lambda;-1</sup> texels inwards (docs/scenes.md). "
                         "Unlike the picture metrics it is not swayed by silhouette shifts and flat shading.</p>")
            parts.append("<table><tr><th>variant</th><th>RMS all</th><th>max all</th><th>RMS interior</th>"
                         "<th>max interior</th><th>RMS border</th><th>max border</th></tr>")
            for v in scene["vertex_errors"]:
                cells = "".join(f"<td>{v[p]['rms_texels']:.2f}</td><td>{v[p]['max_texels']:.2f}</td>"
                                for p in ("all", "interior", "border"))
                parts.append(f"<tr><td>{e(v['label'])}</td>{cells}</tr>")
            v0 = scene["vertex_errors"][0]
            parts.append(f"<tr><td>vertices</td><td colspan=2>{v0['all']['vertices']}</td>"
                         f"<td colspan=2>{v0['interior']['vertices']}</td><td colspan=2>{v0['border']['vertices']}</td></tr>")
            parts.append("</table>")
        parts.append(f"<p><img src='{name}' alt='{e(scene['scene'])} comparison'></p>")
    parts.append("<h2>Temporal aliasing (flicker)</h2><p>Per frame step, the mean |F(t+1) - F(t)| of a variant and of "
                 "the reference, and the excess mean |(F(t+1) - F(t)) - (R(t+1) - R(t))|: the frame-to-frame change "
                 "the real-valued reference does not have (0 = no flicker).</p>")
    parts.append("<table><tr><th>animation</th><th>variant</th><th>mean change</th><th>reference change</th>"
                 "<th>excess (flicker)</th></tr>")
    for f in m["flicker"]:
        parts.append(f"<tr><td>{e(f['scene'])}</td><td>{e(f.get('label', f['filter']))}</td><td>{f['mean_change']:.2f}</td>"
                     f"<td>{f['mean_reference_change']:.2f}</td><td>{f['mean_excess']:.2f}</td></tr>")
    parts.append(f"</table><p><img src='{flicker_plot(out_dir, m['flicker'])}' alt='flicker per frame'></p>")
    if m.get("mesh_vertex_jitter"):
        parts.append("<h3>The mesh animation in vertex space</h3><p>Each face as the bilinear patch through its "
                     "vertices, evaluated at the same 33x33 (u, v) points in every frame; per frame step the mean "
                     "distance the variant's surface moves, the reference's, and the excess "
                     "mean |(S(t+1) - S(t)) - (R(t+1) - R(t))| (0 = no popping beyond the ideal surface's), "
                     "averaged over the steps, in level-0 texels; over all points, and over the interior points "
                     "(inside both frames' inner quads, clear of the border vertices).</p>")
        parts.append("<table><tr><th>variant</th><th>change</th><th>reference change</th><th>excess (jitter)</th>"
                     "<th>interior change</th><th>interior reference change</th><th>interior excess</th></tr>")
        for j in m["mesh_vertex_jitter"]:
            cells = "".join(f"<td>{j[k]:.3f}</td>" for k in (
                "mean_change", "mean_reference_change", "mean_excess", "mean_interior_change",
                "mean_interior_reference_change", "mean_interior_excess"))
            parts.append(f"<tr><td>{e(j['label'])}</td>{cells}</tr>")
        parts.append("</table>")
    strips = m.get("panel_strips") or [{"name": n, "label": n, "image": f"panel_frames_{n}.png"}
                                       for n in ("point", "trilinear")]
    strips = strips + [{"name": "reference", "label": "reference", "image": "panel_frames_reference.png"}]
    parts.append("<h3>The rotating panel (fig. 8-11): " + e("; ".join(s["label"] for s in strips)) + "</h3>")
    for s in strips:
        parts.append(f"<p>{e(s['label'])}<br><img src='{e(s['image'])}' alt='panel frames, {e(s['name'])}'></p>")
    parts.append(f"<p>Generated in {m['seconds']:.1f} s by <code>make figures</code>.</p></body></html>")
    tmp = os.path.join(out_dir, "index.html.partial")
    with open(tmp, "w") as f:
        f.write("\n".join(parts) + "\n")
    os.replace(tmp, os.path.join(out_dir, "index.html"))
    print(f"figures.py: {len(m['scenes'])} comparison figures, flicker.png, {out_dir}/index.html")


if __name__ == "__main__":
    main()
