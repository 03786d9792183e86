#!/usr/bin/python3
"""The README's picture: the receding plane (fig. 7) point-sampled, trilinear and anisotropic, stacked.

Usage: /usr/bin/python3 scripts/plane_filters.py [--texsim build/texsim] [--engine model] [--out docs/plane_filters.png]
Renders `texsim render --scene plane --texture checker --filter F` (640x480) for each filter, keeps the
band from just above the horizon down to the large checks, and stacks the three with a label each.
Needs PIL (Debian's python3-pil, in /usr/bin/python3).
"""
import argparse
import os
import subprocess
import tempfile

from PIL import Image, ImageDraw, ImageFont

FILTERS = [("point", "point sampling"), ("trilinear", "trilinear mip-map"),
           ("anisotropic", "anisotropic, up to 16 probes")]
TOP, BOTTOM = 120, 400  # rows kept of the 640x480 frame (the horizon is at row 144)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--texsim", default="build/texsim")
    parser.add_argument("--engine", default="model", help="texsim engine (the RTL refuses anisotropic for now)")
    parser.add_argument("--out", default="docs/plane_filters.png")
    args = parser.parse_args()
    try:
        font = ImageFont.truetype("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf", 16)
    except OSError:
        font = ImageFont.load_default()
    bands = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, label in FILTERS:
            path = os.path.join(tmp, f"plane_{name}.png")
            subprocess.run([args.texsim, "render", "--scene", "plane", "--texture", "checker", "--filter", name,
                            "--engine", args.engine, "--out", path], check=True)
            img = Image.open(path).convert("RGB")
            band = img.crop((0, TOP, img.width, BOTTOM))
            ImageDraw.Draw(band).text((8, 4), label, fill=(0, 0, 0), font=font)
            bands.append(band)
    gap = 4
    out = Image.new("RGB", (bands[0].width, sum(b.height for b in bands) + gap * (len(bands) - 1)), (255, 255, 255))
    y = 0
    for b in bands:
        out.paste(b, (0, y))
        y += b.height + gap
    out.save(args.out, optimize=True)
    print(f"plane_filters.py: {args.out} ({out.width}x{out.height})")


if __name__ == "__main__":
    main()
