#!/usr/bin/python3
"""Every file of a model tree through `texsim render --model`, each under a memory and time bound:
each must render or stop with one `texsim: error:` line, within the bounds (issue 36). Prints one
line per file that does not (a crash, a signal, a silent failure, over the memory or the time),
then a summary line; exits 1 if there is any.

Usage: scripts/hostile_models.py [--texsim BUILD/texsim] [--root DIR] [--max-mib N] [--max-seconds S]
Defaults: build/texsim, /usr/share/assimp/models (Debian's assimp-testmodels), 1024 MiB, 30 s.
Each run's peak memory is GNU time's maximum resident set; its address space is also limited to
twice the bound (ulimit -v), so that a runaway allocation fails rather than takes the machine.
"""
import argparse
import os
import resource
import subprocess
import sys
import tempfile
import time


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--texsim", default="build/texsim")
    ap.add_argument("--root", default="/usr/share/assimp/models")
    ap.add_argument("--max-mib", type=int, default=1024)
    ap.add_argument("--max-seconds", type=float, default=30.0)
    a = ap.parse_args()
    if not os.access(a.texsim, os.X_OK):
        sys.exit(f"hostile_models: {a.texsim} is not an executable (build first, or --texsim)")
    if not os.path.isdir(a.root):
        sys.exit(f"hostile_models: {a.root} is not a directory (apt-get install assimp-testmodels, or --root)")
    files = sorted(os.path.join(d, f) for d, _, fs in os.walk(a.root) for f in fs)
    limit = 2 * a.max_mib * 1024 * 1024

    def bound():
        resource.setrlimit(resource.RLIMIT_AS, (limit, limit))

    rendered = errors = 0
    worst_mib, worst_s = 0.0, 0.0
    bad = []
    tty = sys.stderr.isatty()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "frame.png")
        for i, f in enumerate(files):
            if tty:
                print(f"\r{i + 1}/{len(files)} {os.path.relpath(f, a.root)[:60]:60}", end="", file=sys.stderr)
            t0 = time.monotonic()
            try:
                p = subprocess.run(["/usr/bin/time", "-f", "%M", a.texsim, "render", "--model", f, "--width", "64",
                                    "--height", "48", "--out", out], capture_output=True, text=True,
                                   timeout=2 * a.max_seconds, preexec_fn=bound)
            except subprocess.TimeoutExpired:
                bad.append(f"{f}: still running after {2 * a.max_seconds:.0f} s (killed)")
                continue
            seconds = time.monotonic() - t0
            lines = p.stderr.strip().split("\n")
            try:
                mib = int(lines[-1]) / 1024
            except ValueError:
                mib = 0.0
            worst_mib, worst_s = max(worst_mib, mib), max(worst_s, seconds)
            error = [l for l in lines if l.startswith("texsim: error:")]
            if p.returncode == 0:
                rendered += 1
            elif p.returncode == 1 and len(error) == 1:
                errors += 1
            else:
                last = next((l for l in reversed(lines[:-1]) if l.strip()), "")
                bad.append(f"{f}: exit {p.returncode} without one error line ({last[:120]})")
                continue
            if mib > a.max_mib:
                bad.append(f"{f}: {mib:.0f} MiB (over {a.max_mib})")
            if seconds > a.max_seconds:
                bad.append(f"{f}: {seconds:.1f} s (over {a.max_seconds:.0f})")
    if tty:
        print("\r" + " " * 80 + "\r", end="", file=sys.stderr)
    for b in bad:
        print(b)
    print(f"hostile_models: {len(files)} files of {a.root}: {rendered} rendered, {errors} one-line errors, "
          f"{len(bad)} exceptions; peak {worst_mib:.0f} MiB, slowest {worst_s:.1f} s "
          f"(bounds {a.max_mib} MiB, {a.max_seconds:.0f} s)")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
