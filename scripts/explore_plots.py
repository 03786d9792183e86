#!/usr/bin/python3
"""Plots and index.html of a `texsim explore` sweep (docs/memory.md §6).

Usage: /usr/bin/python3 scripts/explore_plots.py DIR

Reads DIR/explore.csv (one row per sweep point, written by `texsim explore`) and writes into DIR:
  latency.png   samples/clock (timing model or RTL) against memory latency, a line per cache size
  throughput.png  samples/clock against cache size, a line per block shape
  hit_rate.png  hit rate (golden model's caches) against cache size, a line per block shape
  bytes.png     bytes read from memory per sample against cache size, a line per block shape
  index.html    the plots, the smallest cache reaching 0.97 samples/clock per latency, every row
One panel per (workload, order). A sweep parameter that is on neither a plot's axes nor its series
is held at one value (the default if the sweep has it: ways 2, 4x4 blocks, row-major, 16 B/clock,
latency 200, the deepest FIFO; else the smallest), named in the figure's title. A plot without
rows (no point timed: --timing none) is left out and index.html says so. The outputs are written
to temporary files and renamed into place once all of them are complete.
Needs numpy and matplotlib (Debian's python3-matplotlib, in /usr/bin/python3).
"""
import argparse
import csv
import html
import math
import os
import re
import sys
import tempfile

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import NullLocator
except ImportError as missing:
    sys.exit(f"explore_plots: error: {missing} (run it with /usr/bin/python3, which has python3-matplotlib)")

COLUMNS = ["workload", "order", "texture", "format", "width", "height", "filter", "cache_kib", "ways", "block", "block_order",
           "mem_latency", "mem_bytes_per_clock", "fifo_depth", "samples", "cache_lookups", "cache_hits",
           "cache_misses", "hit_rate", "memory_read_bytes", "bytes_per_sample", "timing_engine",
           "samples_per_clock", "cycles", "memory_stall_cycles", "fifo_max_occupancy", "confirmed"]
# Numbers every row has; the other numeric columns may be empty (not measured).
REQUIRED_NUMBERS = ["cache_kib", "ways", "mem_latency", "mem_bytes_per_clock", "hit_rate", "bytes_per_sample"]
OPTIONAL_NUMBERS = ["width", "height", "fifo_depth", "samples", "cache_lookups", "cache_hits", "cache_misses",
                    "memory_read_bytes", "samples_per_clock", "cycles", "memory_stall_cycles", "fifo_max_occupancy"]
DEFAULTS = {"ways": 2.0, "block": "4x4", "block_order": "row-major", "mem_bytes_per_clock": 16.0,
            "mem_latency": 200.0}
HELD = ["ways", "block", "block_order", "mem_bytes_per_clock", "mem_latency", "fifo_depth"]
TARGET = 0.97
OUTPUTS = ["latency.png", "throughput.png", "hit_rate.png", "bytes.png", "index.html"]
NUMBER = re.compile(r"-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", re.ASCII)


class Failure(Exception):
    """A one-line error for the user (bad input, an output that cannot be written)."""


def fmt(x):
    return f"{x:g}"


def block_key(b):
    """Block shapes by area, then by name ("2x4" < "4x4" < "4x8" < "8x8")."""
    m = re.fullmatch(r"(\d+)x(\d+)", b)
    return (0, int(m.group(1)) * int(m.group(2)), b) if m else (1, 0, b)


def value_key(param):
    if param == "block":
        return block_key
    if param == "fifo_depth":  # empty = the deepest the hardware has ("max")
        return lambda v: math.inf if v is None else v
    return lambda v: v


def read_rows(path):
    """The CSV's header and rows (dicts: numbers as floats or None, the raw text under '_raw')."""
    try:
        with open(path, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if header is None:
                raise Failure(f"{path}: empty file (no header line)")
            header = [h.strip() for h in header]
            missing = [c for c in COLUMNS if c not in header]
            if missing:
                raise Failure(f"{path}: no column {missing[0]} in the header line"
                              + (f" (nor {', '.join(missing[1:])})" if len(missing) > 1 else ""))
            rows = []
            for fields in reader:
                line = reader.line_num
                if not fields or fields == [""]:
                    continue
                if len(fields) != len(header):
                    raise Failure(f"{path} line {line}: {len(fields)} fields, the header has {len(header)}")
                raw = dict(zip(header, fields))
                row = dict(raw)
                row["_raw"] = fields
                for c in REQUIRED_NUMBERS + OPTIONAL_NUMBERS:
                    text = raw[c].strip()
                    if text == "" and c in OPTIONAL_NUMBERS:
                        row[c] = None
                        continue
                    value = float(text) if NUMBER.fullmatch(text) else math.nan
                    if not math.isfinite(value):
                        raise Failure(f"{path} line {line}: column {c}: {text!r} is not a number")
                    if c == "cache_kib" and value <= 0:
                        raise Failure(f"{path} line {line}: column cache_kib: {text!r} is not a positive number")
                    row[c] = value
                rows.append(row)
            # A sweep over texture formats: each format is a panel of its own, next to the orders.
            if len({r["format"] for r in rows}) > 1:
                for r in rows:
                    r["order"] = f"{r['order']}, {r['format']}"
            return header, rows
    except OSError as e:
        raise Failure(f"cannot read {path}: {e.strerror or e}")
    except UnicodeDecodeError:
        raise Failure(f"{path}: not UTF-8 text")
    except csv.Error as e:
        raise Failure(f"{path}: not a CSV file ({e})")


def describe(param, values):
    v = values[0] if len(values) == 1 else None
    if param == "ways":
        return f"ways {fmt(v)}"
    if param == "block":
        return f"{v} blocks"
    if param == "block_order":
        return f"block order {v}"
    if param == "mem_bytes_per_clock":
        return f"{fmt(v)} B/clock"
    if param == "mem_latency":
        return f"latency {fmt(v)}"
    names = ["max" if d is None else fmt(d) for d in sorted(set(values), key=value_key("fifo_depth"))]
    return "FIFO " + " / ".join(names) + (" (the deepest)" if len(names) > 1 else "")


def hold(rows, free, series):
    """Keeps the rows at one value of each held parameter not in `free`: the default if present, else the
    smallest; the FIFO at its deepest within each (workload, order, series), as model-only rows leave it
    empty (the deepest). Returns the rows kept and what was held, for a title."""
    note = []
    for p in HELD:
        if p in free or not rows:
            continue
        key = value_key(p)
        if p == "fifo_depth":
            deepest = {}
            for r in rows:
                g = (r["workload"], r["order"], r[series])
                if g not in deepest or key(r[p]) > key(deepest[g]):
                    deepest[g] = r[p]
            rows = [r for r in rows if r[p] == deepest[(r["workload"], r["order"], r[series])]]
            note.append(describe(p, [r[p] for r in rows]))
            continue
        values = sorted({r[p] for r in rows}, key=key)
        keep = DEFAULTS[p] if DEFAULTS[p] in values else values[0]
        rows = [r for r in rows if r[p] == keep]
        note.append(describe(p, [keep]))
    return rows, ", ".join(note)


def panels(rows):
    """The (workload, order) pairs in the order of the CSV."""
    keys = []
    for r in rows:
        if (r["workload"], r["order"]) not in keys:
            keys.append((r["workload"], r["order"]))
    return keys


def tex(s):
    """Text for matplotlib without mathtext ($ would start a formula)."""
    return str(s).replace("$", r"\$")


def grid(keys):
    """(rows, columns, position per key): workloads x orders when the sweep is their full product, else
    wrapped at three columns."""
    workloads = list(dict.fromkeys(w for w, _ in keys))
    orders = list(dict.fromkeys(o for _, o in keys))
    if len(keys) == len(workloads) * len(orders) and len(orders) <= 4 and len(keys) > 1:
        return len(workloads), len(orders), {k: (workloads.index(k[0]), orders.index(k[1])) for k in keys}
    cols = min(len(keys), 3)
    return (len(keys) + cols - 1) // cols, cols, {k: divmod(i, cols) for i, k in enumerate(keys)}


def plot(rows, path, x, y, series, title, xlabel, ylabel, log2x=False, scale=1.0, ylim=None, target=None):
    """One panel per (workload, order); returns False (and draws nothing) without rows."""
    rows, note = hold(rows, [x, series], series)
    keys = panels(rows)
    if not keys:
        return False
    nrows, ncols, where = grid(keys)
    fig, axes = plt.subplots(nrows, ncols, figsize=(1.2 + 3.9 * ncols, 0.9 + 3.0 * nrows), sharex=True,
                             sharey=True, squeeze=False)
    skey = value_key(series)
    names = sorted({r[series] for r in rows}, key=skey)
    colour = {s: f"C{i % 10}" for i, s in enumerate(names)}
    label = {s: (f"{fmt(s)} KiB" if series == "cache_kib" else f"{s}") for s in names}
    xs = sorted({r[x] for r in rows})
    used = set()
    for (workload, order), (i, j) in where.items():
        ax = axes[i][j]
        used.add((i, j))
        mine = [r for r in rows if r["workload"] == workload and r["order"] == order]
        for s in names:
            points = {}
            for r in mine:
                if r[series] == s and r[y] is not None:
                    points.setdefault(r[x], r[y] * scale)  # the first row of a point, if it repeats
            if points:
                px = sorted(points)
                ax.plot(px, [points[p] for p in px], marker="o", markersize=4, color=colour[s], label=tex(label[s]))
        ax.set_title(tex(f"{workload}, {order}"), fontsize=10)
        ax.grid(True, alpha=0.3)
    for i in range(nrows):
        for j in range(ncols):
            ax = axes[i][j]
            if (i, j) not in used:
                ax.set_visible(False)
                continue
            if target is not None:
                ax.axhline(target, color="grey", linestyle="--", linewidth=1)
                ax.text(1.0, target, f"{target:g} ", transform=ax.get_yaxis_transform(), ha="right", va="bottom",
                        fontsize=8, color="dimgrey")
            ax.tick_params(labelbottom=True, labelsize=8)
            ax.set_xlabel(xlabel, fontsize=9)
            if j == 0:
                ax.set_ylabel(ylabel, fontsize=9)
    ax0 = axes[0][0]
    if log2x:
        ax0.set_xscale("log", base=2)
        ax0.set_xticks(xs)
        ax0.set_xticklabels([fmt(v) for v in xs])
        ax0.xaxis.set_minor_locator(NullLocator())
        if len(xs) == 1:
            ax0.set_xlim(xs[0] / 2, xs[0] * 2)
    if ylim is not None:
        ax0.set_ylim(*ylim)
    handles = [plt.Line2D([], [], color=colour[s], marker="o", markersize=4, label=tex(label[s])) for s in names]
    fig.legend(handles=handles, loc="center right", fontsize=8, title={"cache_kib": "cache", "block": "block"}[series],
               title_fontsize=8)
    fig.suptitle(tex(title) + ("\n" + tex(note) if note else ""), fontsize=9)
    fig.tight_layout(rect=(0, 0, 1 - 1.1 / (1.2 + 3.9 * ncols), 1))
    fig.savefig(path, dpi=100, format="png")
    plt.close(fig)
    return True


def smallest_cache_table(rows, all_rows):
    """Per (workload, order) and latency, the smallest cache whose samples/clock reaches TARGET."""
    timed, note = hold([r for r in rows if r["samples_per_clock"] is not None], ["cache_kib", "mem_latency"],
                       "cache_kib")
    e = html.escape
    if not timed:
        return (f"<p>No point was timed (samples_per_clock is empty in every row: --timing none), so the "
                f"smallest cache reaching {TARGET:g} samples/clock is not known.</p>")
    latencies = sorted({r["mem_latency"] for r in timed})
    out = [f"<p>The smallest cache (KiB) whose samples/clock reaches {TARGET:g}, per memory latency (clocks). "
           f"Timed by the timing model (timing_engine model, clock for clock the RTL's) or the RTL "
           f"(timing_engine rtl), with {e(note)}.</p>",
           "<table><tr><th>workload</th><th>order</th>"
           + "".join(f"<th>latency {fmt(lat)}</th>" for lat in latencies) + "</tr>"]
    for workload, order in panels(all_rows):
        cells = []
        for lat in latencies:
            mine = [r for r in timed if r["workload"] == workload and r["order"] == order and r["mem_latency"] == lat]
            good = sorted(r["cache_kib"] for r in mine if r["samples_per_clock"] >= TARGET)
            if good:
                cells.append(f"{fmt(good[0])} KiB")
            elif mine:
                cells.append(f"none up to {fmt(max(r['cache_kib'] for r in mine))} KiB")
            else:
                cells.append("not timed")
        out.append(f"<tr><td>{e(workload)}</td><td>{e(order)}</td>" + "".join(f"<td>{c}</td>" for c in cells)
                   + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def page(header, rows, made):
    e = html.escape
    workloads = list(dict.fromkeys(r["workload"] for r in rows))
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>texsim explore</title>",
        "<style>body{font-family:sans-serif;margin:1.5em;max-width:1800px}table{border-collapse:collapse;"
        "font-size:12px;margin-bottom:1em}td,th{border:1px solid #bbb;padding:2px 6px;text-align:right}"
        "th{background:#eee}img{max-width:100%}.wide{overflow-x:auto}</style></head><body>",
        "<h1>texsim explore</h1>",
        f"<p>{len(rows)} points; workloads: {e(', '.join(workloads)) if workloads else 'none'}. Hit rate and "
        "bytes/sample from the golden model's caches (every point); samples/clock from the model's timing layer "
        "(timing_engine model: the RTL's clocks exactly, at every point, compiled or not; confirmed rtl where "
        "--confirm rtl re-ran the point through the Verilated RTL) or from the RTL itself (timing_engine rtl).</p>",
    ]
    captions = {
        "latency.png": ("Samples per clock against memory latency, a line per cache size",
                        "No point was timed (samples_per_clock is empty in every row: --timing none), so there is "
                        "no latency plot."),
        "throughput.png": ("Samples per clock against cache size, a line per block shape",
                           "No point was timed (samples_per_clock is empty in every row: --timing none), so there "
                           "is no throughput plot."),
        "hit_rate.png": ("Hit rate against cache size, a line per block shape", "The CSV has no rows to plot."),
        "bytes.png": ("Bytes read from memory per sample against cache size, a line per block shape",
                      "The CSV has no rows to plot."),
    }
    for name, (caption, why) in captions.items():
        parts.append(f"<h2>{e(caption)}</h2>")
        parts.append(f"<p><img src='{name}' alt='{e(caption)}'></p>" if made[name] else f"<p>{e(why)}</p>")
        if name == "latency.png":
            parts.append(f"<h3>Smallest cache reaching {TARGET:g} samples/clock</h3>")
            parts.append(smallest_cache_table(rows, rows))
    parts.append("<h2>Every point</h2><p>All rows of <a href='explore.csv'>explore.csv</a>; an empty cell was not "
                 "measured.</p><div class='wide'><table><tr>" + "".join(f"<th>{e(c)}</th>" for c in header) + "</tr>")
    for r in rows:
        parts.append("<tr>" + "".join(f"<td>{e(v)}</td>" for v in r["_raw"]) + "</tr>")
    parts.append("</table></div></body></html>")
    return "\n".join(parts) + "\n"


def targets(out_dir):
    """The files to replace (a symlink's target, so the link stays); refuses what is not a regular file."""
    out = {}
    for name in OUTPUTS:
        path = os.path.join(out_dir, name)
        real = os.path.realpath(path)
        if os.path.lexists(path) and not os.path.isfile(real):
            what = "a directory" if os.path.isdir(real) else ("a dangling symlink" if not os.path.lexists(real)
                                                                else "not a regular file")
            raise Failure(f"{path} exists and is {what}; remove it or choose another directory")
        out[name] = real
    return out


def write_all(out_dir, header, rows):
    """Writes every output to a temporary file next to it, then renames them all into place."""
    dest = targets(out_dir)
    temps = {}
    try:
        for name, real in dest.items():
            fd, temps[name] = tempfile.mkstemp(dir=os.path.dirname(real), prefix=f".{name}.",
                                               suffix=os.path.splitext(name)[1])
            os.close(fd)
        timed = [r for r in rows if r["samples_per_clock"] is not None]
        made = {
            "latency.png": plot(timed, temps["latency.png"], "mem_latency", "samples_per_clock", "cache_kib",
                                "samples per clock", "memory latency (clocks)", "samples / clock",
                                ylim=(0, 1.05), target=TARGET),
            "throughput.png": plot(timed, temps["throughput.png"], "cache_kib", "samples_per_clock", "block",
                                   "samples per clock", "cache size (KiB)", "samples / clock", log2x=True,
                                   ylim=(0, 1.05), target=TARGET),
            "hit_rate.png": plot(rows, temps["hit_rate.png"], "cache_kib", "hit_rate", "block",
                                 "cache hit rate (golden model's caches)", "cache size (KiB)", "hit rate (%)",
                                 log2x=True, scale=100.0),
            "bytes.png": plot(rows, temps["bytes.png"], "cache_kib", "bytes_per_sample", "block",
                              "bytes read from memory per sample (golden model's caches)", "cache size (KiB)",
                              "bytes / sample", log2x=True),
        }
        with open(temps["index.html"], "w", encoding="utf-8") as f:
            f.write(page(header, rows, made))
        made["index.html"] = True
        mask = os.umask(0)
        os.umask(mask)
        for name in OUTPUTS:
            if made[name]:
                os.chmod(temps[name], 0o666 & ~mask)
        for name in OUTPUTS:
            if made[name]:
                os.replace(temps[name], dest[name])
                del temps[name]
        return made
    except OSError as e:
        where = e.filename if getattr(e, "filename", None) else out_dir
        raise Failure(f"cannot write into {out_dir}: {where}: {e.strerror or e}")
    finally:
        for t in temps.values():
            try:
                os.remove(t)
            except OSError:
                pass


def main():
    ap = argparse.ArgumentParser(
        description=__doc__.splitlines()[0],
        epilog="Writes DIR/latency.png, DIR/hit_rate.png, DIR/bytes.png and DIR/index.html (all or none; an "
               "existing regular file is replaced). Errors: one line on stderr, exit code 1.")
    ap.add_argument("dir", metavar="DIR",
                    help="directory holding explore.csv (texsim explore's --out); the outputs are written there")
    out_dir = ap.parse_args().dir
    try:
        header, rows = read_rows(os.path.join(out_dir, "explore.csv"))
        targets(out_dir)  # refuse before drawing anything
        write_all(out_dir, header, rows)
    except Failure as e:
        print(f"explore_plots: error: {e}", file=sys.stderr)
        return 1
    except Exception as e:  # never a traceback
        print(f"explore_plots: error: {type(e).__name__}: {e}".splitlines()[0], file=sys.stderr)
        return 1
    print(f"explore_plots: {len(rows)} points, index in {os.path.join(out_dir, 'index.html')}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
