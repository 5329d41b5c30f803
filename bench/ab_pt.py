"""A/B of two udm1-pt builds: the same render, the two binaries alternating round by round (so that
the machine's drift falls on both alike), the render time each prints ("seconds"), and whether the
two images are identical value for value (`udm1-pt compare --exact` of NEW, or of --compare TOOL
for builds older than that option; their metadata, such as the version, may differ). The figures of a change's step in BENCHMARKS.md come from
this command: the minimum over the rounds is the least disturbed run of each build.

    python bench/ab_pt.py OLD NEW [--rounds 6] [--compare TOOL] -- [udm1-pt options, e.g. --size 128x128 --spp 64
                                                    --threads 1 --sampler wr]

OLD and NEW are udm1-pt executables (for two library builds, a wrapper script that sets
LD_LIBRARY_PATH). Each round renders with OLD, then NEW, into a temporary folder.
"""

from __future__ import annotations

import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

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


def main() -> None:
    argv = sys.argv[1:]
    pt_args = argv[argv.index("--") + 1:] if "--" in argv else []
    own = argv[:argv.index("--")] if "--" in argv else argv
    p = argparse.ArgumentParser(prog="ab_pt", description=__doc__.split("\n\n")[0])
    p.add_argument("old")
    p.add_argument("new")
    p.add_argument("--rounds", type=int, default=6)
    p.add_argument("--compare", help="the udm1-pt that compares the images (default: NEW)")
    a = p.parse_args(own)
    if not 1 <= a.rounds <= 100:
        fail(f"--rounds {a.rounds}: give 1 to 100")
    a.compare = a.compare or a.new
    for b in (a.old, a.new, a.compare):
        if not (os.path.isfile(b) and os.access(b, os.X_OK)):
            fail(f"{b}: not an executable file")
    if "-o" in pt_args or "--png" in pt_args:
        fail("the udm1-pt options must not name an output (-o, --png): ab_pt writes its own")
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
