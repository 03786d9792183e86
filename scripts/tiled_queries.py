#!/usr/bin/env python3
"""One query per texel centre of a W x W texture, in T x T tiles (a rasterizer's order), for
texsim sample: --op sample (u,v,lod at lambda 0), gather (u,v) or fetch (i,j,level of level 0).

  scripts/tiled_queries.py [--size W] [--tile T] [--op sample|gather|fetch] > q.csv
"""
import argparse
import sys


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--size", type=int, default=512, help="texels a side (default 512)")
    p.add_argument("--tile", type=int, default=8, help="tile side in texels (default 8)")
    p.add_argument("--op", choices=["sample", "gather", "fetch"], default="sample")
    a = p.parse_args()
    if a.size < 1 or a.tile < 1 or a.size % a.tile:
        p.error(f"--tile {a.tile} must divide --size {a.size} (both at least 1)")
    out = sys.stdout
    out.write({"sample": "u,v,lod\n", "gather": "u,v\n", "fetch": "i,j,level\n"}[a.op])
    w, t = a.size, a.tile
    for ty in range(0, w, t):
        for tx in range(0, w, t):
            for y in range(ty, ty + t):
                for x in range(tx, tx + t):
                    if a.op == "fetch":
                        out.write(f"{x},{y},0\n")
                    else:
                        out.write(f"{(x + 0.5) / w:.7f},{(y + 0.5) / w:.7f}" + (",0\n" if a.op == "sample" else "\n"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
