#!/usr/bin/python3
"""Resource and timing report of `make synth` (scripts/synth.sh calls it; Python 3 standard library).

  synth_report.py row --rows ROWS.jsonl --config NAME --params TEXT --target ecp5|xc7|ice40
                      --stat YOSYS_STAT [--seconds S] [--pnr PART=NEXTPNR_REPORT.json:LOG ...]
      parse one Yosys `stat` output (and the nextpnr-ice40 runs of that configuration), count
      LUTs, flip-flops, block RAMs and DSPs, decide which parts hold it, append one JSON row.
  synth_report.py row ... --skipped REASON
      a row without counts (synth_ice40 not run; see ice40-skip).
  synth_report.py ice40-skip --rows ROWS.jsonl --config NAME
      print why synth_ice40 is not worth running for NAME (its ECP5 LUT4s in ROWS exceed 4x the
      largest iCE40), or nothing.
  synth_report.py ice40-candidates --stat YOSYS_STAT
      print the iCE40 parts (one per line) whose LUTs, flip-flops, BRAMs and DSPs hold the
      synth_ice40 counts: those are placed with nextpnr-ice40.
  synth_report.py pnr --report NEXTPNR_REPORT.json --log NEXTPNR_LOG
      print "fmax_mhz<TAB>critical path" of one nextpnr-ice40 run (for the terminal).
  synth_report.py collect --rows ROWS.jsonl [--reference REF.jsonl] --out synth.json
                          [--seconds TOTAL] [--commit C] [--tools TEXT]
      write the JSON: {"parts", "rows", "ice40_reference", ...}.
  synth_report.py markdown --json synth.json --out synth.md
      the Markdown tables (docs/rtl.md, README.md) from the JSON alone.

How each target's cells are counted (the Yosys 0.23 cell names; every other cell is listed in the
row's "cells" and, if it is not a known non-logic cell, in "unclassified" with a warning):
  ecp5  LUTs = LUT4 + 2 x CCU2C (a carry cell fills both LUT4s of a slice)
               + 6 x TRELLIS_DPR16X4 (a 16x4 distributed RAM takes 3 slices, ECP5 data sheet
               table "Number of Slices Required to Implement Distributed RAM");
        FFs = TRELLIS_FF; BRAM = DP16KD (18 Kb EBR); DSP = MULT18X18D (18x18 multipliers);
        PFUMX, L6MUX21 are the slices' wide-function muxes (no LUT).
  xc7   LUTs = LUT1..LUT6 + INV (Vivado makes an INV a LUT1) + the LUTs of LUT RAMs and shift
               registers (RAM32M, RAM64M, RAM128X1D, RAM256X1S: 4; RAM32X1D, RAM64X1D, RAM128X1S: 2;
               RAM16X1S, RAM32X1S, RAM64X1S, SRL16E, SRLC32E: 1);
        FFs = FDRE + FDSE + FDCE + FDPE; BRAM = RAMB36E1 + RAMB18E1 / 2 (36 Kb blocks);
        DSP = DSP48E1; CARRY4, MUXF7, MUXF8 and the I/O buffers are not LUTs.
  ice40 LUTs = SB_LUT4 (SB_CARRY shares its logic cell); FFs = SB_DFF*; BRAM = SB_RAM40_4K;
        DSP = SB_MAC16.
A part fits when every one of its four capacities holds the count; for iCE40, also when
nextpnr-ice40 then places and routes it.
"""
import argparse
import json
import os
import re
import sys

# Part capacities from the vendors' data sheets: LUTs, flip-flops, block RAMs, DSPs; smallest first.
#   ECP5 (Lattice FPGA-DS-02012): LUT4s (2 per slice, 2 flip-flops per slice), sysMEM EBR blocks
#   of 18 Kb, 18x18 multipliers.
#   Artix-7 (Xilinx DS180): 6-input LUTs (4 per slice, 8 flip-flops per slice), 36 Kb block
#   RAMs, DSP48E1 slices.
#   iCE40 (Lattice DS1040 HX, FPGA-DS-02008 UltraPlus): logic cells (one LUT4 and one flip-flop
#   each), 4 Kb RAM blocks, SB_MAC16 DSPs (UP5K only; its 4 SPRAMs are not counted).
PARTS = {
    "ecp5": [
        {"part": "LFE5U-25F", "luts": 24288, "ffs": 24288, "brams": 56, "dsps": 28},
        {"part": "LFE5U-45F", "luts": 43848, "ffs": 43848, "brams": 108, "dsps": 72},
        {"part": "LFE5U-85F", "luts": 83640, "ffs": 83640, "brams": 208, "dsps": 156},
    ],
    "xc7": [
        {"part": "XC7A35T", "luts": 20800, "ffs": 41600, "brams": 50, "dsps": 90},
        {"part": "XC7A100T", "luts": 63400, "ffs": 126800, "brams": 135, "dsps": 240},
        {"part": "XC7A200T", "luts": 134600, "ffs": 269200, "brams": 365, "dsps": 740},
    ],
    "ice40": [
        {"part": "iCE40UP5K", "luts": 5280, "ffs": 5280, "brams": 30, "dsps": 8,
         "nextpnr": "--up5k --package sg48"},
        {"part": "iCE40HX8K", "luts": 7680, "ffs": 7680, "brams": 32, "dsps": 0,
         "nextpnr": "--hx8k --package ct256"},
    ],
}
TARGET_NAMES = {"ecp5": "ECP5 (synth_ecp5)", "xc7": "Artix-7 (synth_xilinx -family xc7)",
                "ice40": "iCE40 (synth_ice40)"}
BRAM_UNIT = {"ecp5": "DP16KD (18 Kb)", "xc7": "RAMB36E1 (36 Kb)", "ice40": "SB_RAM40_4K (4 Kb)"}

XC7_LUTRAM = {"RAM32M": 4, "RAM64M": 4, "RAM128X1D": 4, "RAM256X1S": 4, "RAM32X1D": 2,
              "RAM64X1D": 2, "RAM128X1S": 2, "RAM16X1S": 1, "RAM32X1S": 1, "RAM64X1S": 1,
              "RAM16X1D": 2, "SRL16E": 1, "SRLC32E": 1}
XC7_FF = ("FDRE", "FDSE", "FDCE", "FDPE")
NON_LOGIC = {
    "ecp5": {"PFUMX", "L6MUX21", "TRELLIS_IO", "VHI", "VLO"},
    "xc7": {"CARRY4", "MUXF7", "MUXF8", "IBUF", "OBUF", "BUFG", "IOBUF", "OBUFT", "GND", "VCC"},
    "ice40": {"SB_CARRY", "SB_IO", "SB_GB", "SB_GB_IO"},
}


def parse_stat(path):
    """Cell counts of the last 'Number of cells' block of a Yosys `stat` output."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    start = max((i for i, l in enumerate(lines) if "Number of cells:" in l), default=None)
    if start is None:
        sys.exit(f"synth_report: no 'Number of cells' in {path}")
    cells = {}
    for line in lines[start + 1:]:
        m = re.match(r"^\s+(\S+)\s+(\d+)\s*$", line)
        if not m:
            if cells:
                break
            continue
        cells[m.group(1)] = int(m.group(2))
    return cells


def count(target, cells):
    """(luts, ffs, brams, dsps, unclassified) of one target's cell counts."""
    used = set()

    def take(name, weight=1):
        used.add(name)
        return cells.get(name, 0) * weight

    if target == "ecp5":
        luts = take("LUT4") + take("CCU2C", 2) + take("TRELLIS_DPR16X4", 6)
        ffs = take("TRELLIS_FF")
        brams = take("DP16KD")
        dsps = take("MULT18X18D")
    elif target == "xc7":
        luts = sum(take(f"LUT{k}") for k in range(1, 7)) + take("INV")
        luts += sum(take(name, w) for name, w in XC7_LUTRAM.items())
        ffs = sum(take(name) for name in XC7_FF)
        brams = take("RAMB36E1") + take("RAMB18E1") / 2
        brams = int(brams) if brams == int(brams) else brams
        dsps = take("DSP48E1")
    elif target == "ice40":
        luts = take("SB_LUT4")
        ffs = sum(take(name) for name in cells if name.startswith("SB_DFF"))
        brams = take("SB_RAM40_4K")
        dsps = take("SB_MAC16")
    else:
        sys.exit(f"synth_report: unknown target {target}")
    unclassified = {k: v for k, v in cells.items() if k not in used and k not in NON_LOGIC[target]}
    return luts, ffs, brams, dsps, unclassified


def holds(part, luts, ffs, brams, dsps):
    return (luts <= part["luts"] and ffs <= part["ffs"] and brams <= part["brams"]
            and dsps <= part["dsps"])


def read_pnr(report_path, log_path):
    """fmax (MHz), critical path summary, logic cells used, placed? of one nextpnr-ice40 run."""
    with open(log_path, encoding="utf-8", errors="replace") as f:
        log = f.read()
    placed = "Max frequency for clock" in log and not re.search(r"ERROR: ", log)
    lcs = None
    m = re.findall(r"ICESTORM_LC:\s*(\d+)/\s*(\d+)", log)
    if m:
        lcs = int(m[-1][0])
    if not placed:
        return {"placed": False, "lcs": lcs, "fmax_mhz": None, "critical_path": None}
    fmax = float(re.findall(r"Max frequency for clock '[^']*': ([0-9.]+) MHz", log)[-1])
    path = None
    try:
        with open(report_path, encoding="utf-8") as f:
            report = json.load(f)
        fmax_r = report.get("fmax", {})
        if fmax_r:
            # the clock with the lowest achieved frequency limits the design
            clk = min(fmax_r, key=lambda c: fmax_r[c].get("achieved", 1e9))
            fmax = round(fmax_r[clk]["achieved"], 2)
        # the register-to-register path of the clock (not the <async> I/O paths)
        paths = [p for p in report.get("critical_paths", [])
                 if p.get("path") and "async" not in p.get("from", "") + p.get("to", "")]
        if paths:
            path = summarize_path(paths[0]["path"])
    except (OSError, ValueError, KeyError, IndexError, TypeError):
        path = None
    if path is None:
        path = critical_path_from_log(log)
    return {"placed": True, "lcs": lcs, "fmax_mhz": round(fmax, 2), "critical_path": path}


def register_name(cell):
    """A packed logic cell's name back to the register or signal it is named after."""
    name = re.split(r"_SB_|\$", cell, maxsplit=1)[0]
    return name[len("u_unit."):] if name.startswith("u_unit.") else name


def scope(cell):
    name = register_name(cell)
    return name.rsplit(".", 1)[0] if "." in name else name


def summarize_path(steps):
    """'start -> end: total ns, N logic levels (routing ns); via scopes' of a nextpnr path."""
    first = steps[0]
    src = first["to"]["cell"] if first.get("type") == "clk-to-q" else first["from"]["cell"]
    dst = steps[-1]["to"]["cell"]
    logic = sum(1 for s in steps if s.get("type") == "logic")
    total = sum(s.get("delay", 0) for s in steps)
    route = sum(s.get("delay", 0) for s in steps if s.get("type") == "routing")
    via = []
    for s in steps:
        if s.get("type") != "logic" or s["to"]["cell"].startswith("$nextpnr"):
            continue
        sc = scope(s["to"]["cell"])
        if not via or via[-1] != sc:
            via.append(sc)
    return (f"{register_name(src)} -> {register_name(dst)}: {total:.1f} ns, {logic} logic levels "
            f"({route:.1f} ns of it routing); through {' > '.join(via)}")


def critical_path_from_log(log):
    """Start and end cell of the first 'Critical path report' section of a nextpnr log."""
    sect = log.split("Critical path report for clock", 1)
    if len(sect) < 2:
        return None
    src = re.search(r"Source (\S+)", sect[1])
    sinks = re.findall(r"Sink (\S+)", sect[1].split("Critical path report", 1)[0])
    if not src or not sinks:
        return None
    return f"{src.group(1)} -> {sinks[-1]}"


ICE40_SKIP_FACTOR = 4   # synth_ice40 is skipped when ECP5 needs more LUT4s than 4x the largest iCE40


def cmd_ice40_skip(a):
    """Print why synth_ice40 of a configuration is not run (nothing when it is): the ECP5 LUT4s of
    the same run exceed ICE40_SKIP_FACTOR x the largest iCE40's logic cells. (Measured so far:
    synth_ice40 needs 1.1-2.7x the LUT4s of synth_ecp5, which maps multipliers to DSPs.)"""
    largest = max(PARTS["ice40"], key=lambda p: p["luts"])
    for r in reversed(read_rows(a.rows)):  # the newest ECP5 row (SYNTH_APPEND runs add rows)
        if r["config"] == a.config and r["target"] == "ecp5" and r.get("luts") is not None:
            if r["luts"] > ICE40_SKIP_FACTOR * largest["luts"]:
                print(f"not synthesized: ECP5 needs {r['luts']} LUT4s, over {ICE40_SKIP_FACTOR} x "
                      f"the {largest['part']}'s {largest['luts']} logic cells")
            return


def cmd_row(a):
    if a.skipped:
        row = {"config": a.config, "params": a.params, "target": a.target, "luts": None,
               "ffs": None, "brams": None, "dsps": None, "fits": [], "fmax_mhz": None,
               "critical_path": None, "note": a.skipped, "seconds": None}
        with open(a.rows, "a", encoding="utf-8") as f:
            f.write(json.dumps(row) + "\n")
        print(f"synth:   {a.target}: {a.skipped}")
        return
    cells = parse_stat(a.stat)
    luts, ffs, brams, dsps, unclassified = count(a.target, cells)
    if unclassified:
        print(f"synth_report: warning: {a.config} {a.target}: cells not counted as logic: "
              f"{unclassified}", file=sys.stderr)
    fits = [p["part"] for p in PARTS[a.target] if holds(p, luts, ffs, brams, dsps)]
    row = {"config": a.config, "params": a.params, "target": a.target, "luts": luts, "ffs": ffs,
           "brams": brams, "dsps": dsps, "fits": fits, "fmax_mhz": None}
    if a.target == "ice40":
        pnr = {}
        for spec in a.pnr or []:
            part, _, files = spec.partition("=")
            report, _, log = files.partition(":")
            pnr[part] = read_pnr(report, log)
        # a part holds it only when nextpnr placed it; Fmax of the largest part that did
        row["fits"] = [p for p in fits if pnr.get(p, {}).get("placed")]
        row["critical_path"] = None
        for part in reversed(row["fits"]):
            row["fmax_mhz"] = pnr[part]["fmax_mhz"]
            row["critical_path"] = pnr[part]["critical_path"]
            break
        row["pnr"] = pnr
    row["seconds"] = a.seconds
    row["cells"] = cells
    if unclassified:
        row["unclassified"] = unclassified
    with open(a.rows, "a", encoding="utf-8") as f:
        f.write(json.dumps(row) + "\n")
    print(f"synth:   {a.target}: {luts} LUTs, {ffs} FFs, {brams} BRAM, {dsps} DSP; "
          f"fits: {', '.join(row['fits']) or 'none'}"
          + (f"; Fmax {row['fmax_mhz']} MHz" if row["fmax_mhz"] else ""))


def cmd_candidates(a):
    luts, ffs, brams, dsps, _ = count("ice40", parse_stat(a.stat))
    for p in PARTS["ice40"]:
        if holds(p, luts, ffs, brams, dsps):
            print(f"{p['part']} {p['nextpnr']}")


def cmd_pnr(a):
    r = read_pnr(a.report, a.log)
    print(f"{r['fmax_mhz']}\t{r['lcs']}\t{r['critical_path']}")


def read_rows(path):
    rows = []
    if path and os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            rows = [json.loads(line) for line in f if line.strip()]
    return rows


def last_per_key(rows):
    """One row per (config, target), the last measured (a resumed run appends)."""
    keep = {}
    for r in rows:
        keep[(r["config"], r["target"])] = r
    order = []
    for r in rows:
        if (r["config"], r["target"]) not in order:
            order.append((r["config"], r["target"]))
    return [keep[k] for k in order]


def cmd_collect(a):
    doc = {
        "generator": "scripts/synth.sh (make synth) through scripts/synth_report.py",
        "commit": a.commit,
        "tools": a.tools,
        "total_seconds": a.seconds,
        "parts": PARTS,
        "rows": last_per_key(read_rows(a.rows)),
        "ice40_reference": read_rows(a.reference),
    }
    with open(a.out, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


def num(x):
    if x is None:
        return "—"
    if isinstance(x, float) and x != int(x):
        return f"{x:,.1f}".replace(",", " ")
    return f"{int(x):,}".replace(",", " ")


def over(parts, r):
    """The resources over capacity in the part just below the smallest that fits (or in the
    largest part when none fits); '—' when the smallest part fits."""
    names = [p["part"] for p in parts]
    fitting = [names.index(f) for f in r["fits"] if f in names]
    if fitting and min(fitting) == 0:
        return "—"
    p = parts[min(fitting) - 1] if fitting else parts[-1]
    what = [label for key, label in (("luts", "LUTs"), ("ffs", "FFs"), ("brams", "BRAM"),
                                     ("dsps", "DSP")) if r[key] > p[key]]
    if not what and r["target"] == "ice40":
        what = ["place and route"]
    return f"{', '.join(what)} ({p['part']})"


def cmd_markdown(a):
    with open(a.json, encoding="utf-8") as f:
        doc = json.load(f)
    rows = doc["rows"]
    out = []
    out.append("Part capacities (data sheets; a configuration fits a part when all four hold):")
    out.append("")
    out.append("| family | part | LUTs | FFs | block RAMs | DSPs |")
    out.append("|---|---|---|---|---|---|")
    for target, parts in doc["parts"].items():
        for p in parts:
            out.append(f"| {TARGET_NAMES[target].split(' (')[0]} | {p['part']} | {num(p['luts'])} "
                       f"| {num(p['ffs'])} | {num(p['brams'])} × {BRAM_UNIT[target]} "
                       f"| {num(p['dsps'])} |")
    out.append("")
    out.append("Configurations (TEX_RTL_CONFIGS; every one with TAG_W 16, the unit itself the top):")
    out.append("")
    out.append("| configuration | parameters |")
    out.append("|---|---|")
    configs = []
    for r in rows:
        if r["config"] not in configs:
            configs.append(r["config"])
            out.append(f"| `{r['config']}` | {r['params']} |")
    out.append("")
    out.append("Results (\"over\": the resources that exceed the next smaller part of the family, "
               "or the largest part when none fits):")
    out.append("")
    out.append("| configuration | target | LUTs | FFs | BRAM | DSP | fits | over | Fmax | wall time |")
    out.append("|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        fmax = f"{r['fmax_mhz']:.1f} MHz" if r.get("fmax_mhz") else "—"
        secs = f"{r['seconds'] / 60:.1f} min" if r.get("seconds") is not None else "—"
        if r.get("luts") is None:
            out.append(f"| `{r['config']}` | {r['target']} | — | — | — | — | none | "
                       f"{r.get('note', '')} | — | — |")
            continue
        out.append(f"| `{r['config']}` | {r['target']} | {num(r['luts'])} | "
                   f"{num(r['ffs'])} | {num(r['brams'])} | {num(r['dsps'])} | "
                   f"{', '.join(r['fits']) or 'none'} | {over(doc['parts'][r['target']], r)} | "
                   f"{fmax} | {secs} |")
    ref = doc.get("ice40_reference") or []
    if ref:
        out.append("")
        out.append("iCE40 place and route of a reduced on-chip unit (not a compiled configuration: "
                   "λ requests only, the LOD/anisotropy unit tied off; the largest that places):")
        out.append("")
        out.append("| configuration | part | LUTs | FFs | BRAM | logic cells | Fmax | critical path |")
        out.append("|---|---|---|---|---|---|---|---|")
        for r in ref:
            for part, p in r.get("pnr", {}).items():
                fmax = f"{p['fmax_mhz']:.1f} MHz" if p.get("fmax_mhz") else "does not place"
                out.append(f"| {r['params']} | {part} | {num(r['luts'])} | {num(r['ffs'])} | "
                           f"{num(r['brams'])} | {num(p.get('lcs'))} | {fmax} | "
                           f"{p.get('critical_path') or '—'} |")
    # The short table of README.md: per configuration, LUTs and the smallest part of each family.
    out.append("")
    out.append("Short form (README.md):")
    out.append("")
    out.append("| configuration | ECP5 LUTs / BRAM / DSP | smallest ECP5 | Artix-7 LUTs / BRAM / DSP "
               "| smallest Artix-7 | iCE40 LUTs | iCE40 Fmax |")
    out.append("|---|---|---|---|---|---|---|")
    for c in configs:
        by = {r["target"]: r for r in rows if r["config"] == c}

        def res(t):
            r = by.get(t)
            if not r or r.get("luts") is None:
                return "—"
            return f"{num(r['luts'])} / {num(r['brams'])} / {num(r['dsps'])}"

        def smallest(t):
            r = by.get(t)
            if not r:
                return "—"
            return r["fits"][0] if r["fits"] else "none"

        ice = by.get("ice40")
        ice_luts = num(ice["luts"]) if ice and ice.get("luts") is not None else "—"
        ice_f = (f"{ice['fmax_mhz']:.1f} MHz" if ice and ice.get("fmax_mhz")
                 else ("does not fit" if ice else "—"))
        out.append(f"| `{c}` | {res('ecp5')} | {smallest('ecp5')} | {res('xc7')} | "
                   f"{smallest('xc7')} | {ice_luts} | {ice_f} |")
    text = "\n".join(out) + "\n"
    with open(a.out, "w", encoding="utf-8") as f:
        f.write(text)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    sub = ap.add_subparsers(dest="cmd", required=True)
    p = sub.add_parser("row")
    p.add_argument("--rows", required=True)
    p.add_argument("--config", required=True)
    p.add_argument("--params", required=True)
    p.add_argument("--target", required=True, choices=sorted(PARTS))
    p.add_argument("--stat")
    p.add_argument("--seconds", type=float)
    p.add_argument("--pnr", action="append")
    p.add_argument("--skipped", help="not synthesized, and why (the row has no counts)")
    p.set_defaults(func=cmd_row)
    p = sub.add_parser("ice40-skip")
    p.add_argument("--rows", required=True)
    p.add_argument("--config", required=True)
    p.set_defaults(func=cmd_ice40_skip)
    p = sub.add_parser("ice40-candidates")
    p.add_argument("--stat", required=True)
    p.set_defaults(func=cmd_candidates)
    p = sub.add_parser("pnr")
    p.add_argument("--report", required=True)
    p.add_argument("--log", required=True)
    p.set_defaults(func=cmd_pnr)
    p = sub.add_parser("collect")
    p.add_argument("--rows", required=True)
    p.add_argument("--reference")
    p.add_argument("--out", required=True)
    p.add_argument("--seconds", type=float)
    p.add_argument("--commit")
    p.add_argument("--tools")
    p.set_defaults(func=cmd_collect)
    p = sub.add_parser("markdown")
    p.add_argument("--json", required=True)
    p.add_argument("--out", required=True)
    p.set_defaults(func=cmd_markdown)
    a = ap.parse_args()
    a.func(a)


if __name__ == "__main__":
    main()
