"""A/B of two udm1-pt builds: the same render, the two binaries alternating round by round (so that
the machine's drift falls on both alike), the render time each prints ("seconds"), and whether the
two images are identical value for value (`udm1-pt compare --exact` of NEW, or of --compare TOOL
for builds older than that option; their metadata, such as the version, may differ). The figures of a change's step in BENCHMARKS.md come from
this command: the minimum over the rounds is the least disturbed run of each build.

    python bench/ab_pt.py OLD NEW [--rounds 6] [--compare TOOL] -- [udm1-pt options, e.g. --size 128x128 --spp 64
                                                    --threads 1 --sampler wr]

OLD and NEW are udm1-pt executables (for two library builds, a wrapper script that sets
LD_LIBRARY_PATH). Each round renders with OLD, then NEW, into a temporary folder.

--instructions renders once with each under valgrind's callgrind instead and prints the instructions executed,
by binary (udm1-pt's own code, Embree, the rest, and the dynamic loader's start-up apart): a count that a loaded
machine does not disturb, for changes of a few per cent that the clock cannot resolve there (give a small
render: callgrind runs some 50 times slower).
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import callgrind_counts  # noqa: E402

SECONDS = re.compile(r"\bseconds ([0-9.]+)")


def fail(message: str) -> None:
    print(f"ab_pt: {message}", file=sys.stderr)
    sys.exit(2)


def render(binary: str, args: list[str], out: str) -> float:
    r = subprocess.run([binary, *args, "-o", out], capture_output=True, text=True)
    if r.returncode != 0:
        lines = r.stderr.strip().splitlines()
        fail(f"{binary} failed (exit {r.returncode}): {lines[-1] if lines else 'no message'}")
    m = SECONDS.search(r.stdout)
    if not m:
        fail(f"{binary} printed no render time ('seconds N'): is it udm1-pt?")
    return float(m.group(1))


def instructions(binary: str, args: list[str], tmp: str, name: str) -> dict[str, int]:
    """Instructions executed by one render under callgrind, summed by the binary they belong to."""
    try:
        rows = callgrind_counts.count([binary, *args, "-o", os.path.join(tmp, f"{name}.exr")],
                                      os.path.join(tmp, f"{name}.callgrind"))
    except RuntimeError as e:
        fail(str(e))
    by: dict[str, int] = {"udm1-pt": 0, "embree": 0, "loader": 0, "rest": 0}
    for n, _, path in rows:
        obj = os.path.basename(path)
        key = ("udm1-pt" if obj == os.path.basename(binary) else "embree" if "embree" in obj
               else "loader" if obj.startswith("ld-linux") else "rest")
        by[key] += n
    return by


def main() -> None:
    argv = sys.argv[1:]
    pt_args = argv[argv.index("--") + 1:] if "--" in argv else []
    own = argv[:argv.index("--")] if "--" in argv else argv
    p = argparse.ArgumentParser(prog="ab_pt", description=__doc__.split("\n\n")[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--rounds", type=int, default=6)
    p.add_argument("--compare", help="the udm1-pt that compares the images (default: NEW)")
    p.add_argument("--instructions", action="store_true", help="count instructions under callgrind instead of timing")
    a = p.parse_args(own)
    if not 1 <= a.rounds <= 100:
        fail(f"--rounds {a.rounds}: give 1 to 100")
    a.compare = a.compare or a.new
    for b in (a.old, a.new, a.compare):
        if not (os.path.isfile(b) and os.access(b, os.X_OK)):
            fail(f"{b}: not an executable file")
    if "-o" in pt_args or "--png" in pt_args:
        fail("the udm1-pt options must not name an output (-o, --png): ab_pt writes its own")
    if a.instructions:
        tool = callgrind_counts.missing_tool()
        if tool:
            fail(f"--instructions needs {tool} (Debian package valgrind), which is not on PATH")
        with tempfile.TemporaryDirectory(prefix="ab_pt_") as tmp:
            counts = {k: instructions(b, pt_args, tmp, k) for k, b in (("old", a.old), ("new", a.new))}
        print(f"udm1-pt {' '.join(pt_args)}: instructions executed (callgrind), millions")
        print("| binary | old | new | new / old |\n|---|---|---|---|")
        for key in ("udm1-pt", "embree", "rest", "loader"):
            o, n = counts["old"][key], counts["new"][key]
            print(f"| {key} | {o / 1e6:.1f} | {n / 1e6:.1f} | {n / o if o else float('nan'):.3f} |")
        return
    times: dict[str, list[float]] = {"old": [], "new": []}
    with tempfile.TemporaryDirectory(prefix="ab_pt_") as tmp:
        images = {k: os.path.join(tmp, f"{k}.exr") for k in times}
        for r in range(a.rounds):
            for k, b in (("old", a.old), ("new", a.new)):
                times[k].append(render(b, pt_args, images[k]))
            print(f"[ab_pt] round {r + 1}/{a.rounds}: old {times['old'][-1]:.4f} s, new {times['new'][-1]:.4f} s",
                  file=sys.stderr, flush=True)
        cmp = subprocess.run([a.compare, "compare", images["new"], images["old"], "--exact"], capture_output=True, text=True)
        verdict = [line for line in cmp.stdout.splitlines() if line.startswith(("identical", "different"))]
        if cmp.returncode != 0 or not verdict:
            lines = cmp.stderr.strip().splitlines()
            fail(f"{a.compare} compare --exact failed: {lines[-1] if lines else 'no verdict'}")
    print(f"udm1-pt {' '.join(pt_args)}: {a.rounds} alternating rounds")
    for k, b in (("old", a.old), ("new", a.new)):
        t = times[k]
        print(f"{k}: {b}: min {min(t):.4f} s, median {statistics.median(t):.4f} s")
    print(f"old / new, minimum: {min(times['old']) / min(times['new']):.3f}; "
          f"median: {statistics.median(times['old']) / statistics.median(times['new']):.3f}")
    print(f"images: {verdict[0]}")


if __name__ == "__main__":
    main()
