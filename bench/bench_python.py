"""Python throughput of udm1 beside numpy's PCG64 and scipy's Sobol, in one run.

Values per second (one thread) for generating an (n, d) float64 array:
  udm1 Sequence.points      a new array per call, and into a preallocated one
  udm1.qmc.WR.random        through scipy's QMCEngine interface
  numpy Generator.random    PCG64, the anchor for "random"
  scipy qmc.Sobol.random    scramble=True, the anchor for QMC
  numpy ndarray.fill        writing the same array: the memory ceiling
and Python per-sample calls (Sequence.sample). Each figure is the best of R
repetitions; ratios to scipy's Sobol are printed beside.

    PYTHONPATH=python python bench/bench_python.py [--points 65536] [--reps 15] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time

import numpy as np
import scipy
from scipy.stats import qmc

import udm1
import udm1.qmc as uq


def best_rates(cases, values: int, reps: int) -> list[float]:
    """Best time of each case over reps rounds; the cases alternate within a round so
    that drift of the machine's speed hits all of them alike."""
    best = [float("inf")] * len(cases)
    for _, fn in cases:
        fn()  # warm up
    for _ in range(reps):
        for i, (_, fn) in enumerate(cases):
            t0 = time.perf_counter()
            fn()
            best[i] = min(best[i], time.perf_counter() - t0)
    return [values / b for b in best]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=int, default=1 << 16, help="points per call (default 65536)")
    ap.add_argument("--reps", type=int, default=15, help="repetitions, best taken (default 15)")
    ap.add_argument("--json", help="also write the results to this file")
    args = ap.parse_args(argv)
    if not 1 <= args.points <= 1 << 24 or not 1 <= args.reps <= 1000:
        print("bench_python: --points must be in 1..2^24 and --reps in 1..1000", file=sys.stderr)
        return 2
    n = args.points
    rows = []
    print(f"udm1 {udm1.version()}, numpy {np.__version__}, scipy {scipy.__version__}, {platform.processor() or platform.machine()}")
    print(f"{'d':>3} {'method':<34} {'values/s':>12} {'x scipy Sobol':>14}")
    for d in (2, 32):
        seq = udm1.Sequence("wr", d, seed=1)
        out = np.empty((n, d))
        eng = uq.WR(d, seed=1)
        gen = np.random.default_rng(1)
        sob = qmc.Sobol(d, scramble=True, rng=np.random.default_rng(1))

        cases = [
            ("scipy qmc.Sobol(scramble).random", lambda: sob.random(n)),
            ("numpy PCG64 Generator.random", lambda: gen.random((n, d))),
            ("numpy ndarray.fill (write ceiling)", lambda: out.fill(0.5)),
            ("udm1 Sequence.points (new array)", lambda: seq.points(n, first=1 << 40)),
            ("udm1 Sequence.points(out=...)", lambda: seq.points(n, first=1 << 40, out=out)),
            ("udm1.qmc.WR.random", lambda: eng.random(n)),
        ]
        rates = best_rates(cases, n * d, args.reps)
        anchor = rates[0]
        for (name, _), rate in zip(cases, rates):
            rows.append({"d": d, "method": name, "values_per_second": rate, "ratio_to_scipy_sobol": rate / anchor})
            print(f"{d:>3} {name:<34} {rate:12.4g} {rate / anchor:14.2f}")
        k = 2000
        per = best_rates([("sample", lambda: [seq.sample(i, i % d) for i in range(k)])], k, max(3, args.reps // 5))[0]
        rows.append({"d": d, "method": "udm1 Sequence.sample (per call)", "values_per_second": per,
                     "ratio_to_scipy_sobol": per / anchor})
        print(f"{d:>3} {'udm1 Sequence.sample (per call)':<34} {per:12.4g} {per / anchor:14.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"points": n, "reps": args.reps, "rows": rows}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
