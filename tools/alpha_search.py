"""Search for Weyl generators that are good for sampling: square roots of primes chosen greedily so that
the worst 2D projection of the first d dimensions stays as close to a well-spread set as possible at
every N in a range (the paper's future work: "a method to find irrationals good for sampling").

Figure of merit. For a Kronecker set x_n = {n a}, n < N, the wrap-around L2 discrepancy (WD, squared, as
scipy.stats.qmc.discrepancy) depends only on the differences x_n - x_m = {(n - m) a}, so

    WD^2(N) = -(4/3)^2 + (1/N^2) sum_{|m| < N} (N - |m|) g({m a_i}) g({m a_j}),  g(t) = 3/2 - t (1 - t),

exact in O(N) per pair and per N at once (prefix sums), and invariant under the random shift udm1 applies
to a Weyl set (WD is shift-invariant on the torus): it is the quality the user gets with any seed. A pair's
score is the largest ratio WD^2(N) / E[WD^2(N)] of random points (E = ((3/2)^2 - (4/3)^2) / N) over a
geometric grid of N; a candidate's score is its worst pair with the dimensions already chosen (and its
own 1D ratio). Greedy: each next dimension is the candidate whose score is lowest. Frac(sqrt p) is taken
in double for the search (N <= 2^16: errors below 1e-11), the chosen set is then measured exactly by the
library (L2-star of the worst 2D projection, as udm1_seq_check, against WR, WMMR, HWMMR and R_d).

    PYTHONPATH=python python tools/alpha_search.py --dims 64 --out build/alpha_search
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

import numpy as np

import udm1


def primes_upto(n: int) -> np.ndarray:
    sieve = np.ones(n + 1, dtype=bool)
    sieve[:2] = False
    for p in range(2, int(n ** 0.5) + 1):
        if sieve[p]:
            sieve[p * p::p] = False
    return np.nonzero(sieve)[0]


def g_table(alphas: np.ndarray, n_max: int) -> np.ndarray:
    """g({m a}) for m = 0 .. n_max - 1, one row per generator."""
    m = np.arange(n_max, dtype=np.float64)
    t = np.mod(np.outer(alphas, m), 1.0)
    return 1.5 - t * (1.0 - t)


def ratios(h: np.ndarray, ns: np.ndarray, d: int) -> np.ndarray:
    """WD^2(N) / E[WD^2(N)] for rows h[k, m] = prod_j g({m a_j}) (m >= 0; the sum is symmetric in m)."""
    m = np.arange(h.shape[-1], dtype=np.float64)
    s0 = np.cumsum(h, axis=-1)            # sum_{0 <= m < N} h(m)
    s1 = np.cumsum(h * m, axis=-1)        # sum_{0 <= m < N} m h(m)
    idx = ns - 1
    n = ns.astype(np.float64)
    total = 2 * (n * s0[..., idx] - s1[..., idx]) - n * h[..., :1]   # sum over |m| < N of (N - |m|) h(m)
    wd2 = -(4.0 / 3.0) ** d + total / n ** 2
    expected = (1.5 ** d - (4.0 / 3.0) ** d) / n
    return wd2 / expected


def search(candidates: np.ndarray, dims: int, ns: np.ndarray, log=None) -> list[int]:
    alphas = np.mod(np.sqrt(candidates.astype(np.float64)), 1.0)
    g = g_table(alphas, int(ns.max()))
    worst = ratios(g, ns, 1).max(axis=1)  # a candidate's own 1D quality
    chosen: list[int] = []
    free = np.ones(len(candidates), dtype=bool)
    for j in range(dims):
        k = int(np.argmin(np.where(free, worst, np.inf)))
        chosen.append(k)
        free[k] = False
        if log:
            log(f"dimension {j}: sqrt({candidates[k]}), worst pair ratio {worst[k]:.3f}")
        if j + 1 < dims:  # every candidate's worst pair now includes the new dimension
            worst = np.maximum(worst, ratios(g * g[k], ns, 2).max(axis=1))
    return [int(candidates[k]) for k in chosen]


def measure(seq_of, dims_list, ns) -> dict:
    """Worst 2D projection (L2-star, as udm1_seq_check, and the ratio to random) of each set at each d and n."""
    out = {}
    for d in dims_list:
        for n in ns:
            seq = seq_of(d)
            if seq is None:
                out[f"{d}|{n}"] = None
                continue
            r = seq.check(n)
            out[f"{d}|{n}"] = {"worst_l2_star": r["worst_l2_star"], "ratio": r["worst_l2_star"] / r["random_l2_star"],
                               "worst_dims": list(r["worst_dims"])}
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dims", type=int, default=64, help="dimensions to choose (default 64)")
    ap.add_argument("--max-prime", type=int, default=16384, help="candidates: sqrt(p), p prime <= this (default 16384)")
    ap.add_argument("--n-min", type=int, default=32)
    ap.add_argument("--n-max", type=int, default=4096)
    ap.add_argument("--check-n", default="256,1024", help="n of the exact L2-star measurement (default 256,1024)")
    ap.add_argument("--out", help="folder for search.json and preset.inc (default: print only)")
    ap.add_argument("--no-compare", action="store_true", help="skip measuring WR, WMMR, HWMMR and R_d")
    args = ap.parse_args(argv)
    if not 1 <= args.dims <= 1024 or not 3 <= args.max_prime <= 1 << 22 or not 2 <= args.n_min < args.n_max <= 1 << 16:
        print("alpha_search: need 1 <= --dims <= 1024, 3 <= --max-prime <= 4194304, 2 <= --n-min < --n-max <= 65536",
              file=sys.stderr)
        return 2
    cands = primes_upto(args.max_prime)
    if len(cands) < args.dims:
        print(f"alpha_search: only {len(cands)} primes up to {args.max_prime}, fewer than --dims {args.dims}",
              file=sys.stderr)
        return 2
    ns = np.unique(np.round(np.geomspace(args.n_min, args.n_max, 48)).astype(int))
    t0 = time.time()
    log = lambda m: print(f"[alpha_search] {m}", file=sys.stderr, flush=True)  # noqa: E731
    log(f"{len(cands)} candidates sqrt(p), p <= {args.max_prime}; N from {ns[0]} to {ns[-1]} ({len(ns)} values)")
    ks = search(cands, args.dims, ns, log)
    seconds = time.time() - t0
    log(f"chosen in {seconds:.1f} s: {ks}")
    check_ns = [int(x) for x in args.check_n.split(",")]
    dims_list = [d for d in (2, 8, 16, 32, 64, 128) if d <= args.dims]
    sets = {"search": lambda d: udm1.Sequence(alphas=[udm1.Sqrt(k) for k in ks[:d]], randomize=False)}
    if not args.no_compare:
        maxd = {p.name: p.max_dimensions for p in udm1.presets()}
        for name in ("wr", "wmmr", "hwmmr", "rd"):
            sets[name] = (lambda d, name=name: udm1.Sequence(name, d, randomize=False) if d <= maxd[name] else None)
    quality = {}
    for name, make in sets.items():
        log(f"measuring the worst 2D projection of {name} at d = {dims_list}, n = {check_ns}")
        quality[name] = measure(make, dims_list, check_ns)
    header = f"{'set':8s}" + "".join(f" {f'd={d} n={n}':>14s}" for d in dims_list for n in check_ns)
    print("worst 2D projection, L2-star as a multiple of random points' expected value (lower is better)")
    print(header)
    for name, q in quality.items():
        print(f"{name:8s}" + "".join(f" {q[f'{d}|{n}']['ratio']:14.2f}" if q[f"{d}|{n}"] else f" {'-':>14s}"
                                     for d in dims_list for n in check_ns))
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "search.json").write_text(json.dumps({
            "generators_sqrt": ks, "dims": args.dims, "max_prime": args.max_prime, "n_grid": ns.tolist(),
            "seconds": seconds, "quality": quality}, indent=1))
        rows = [", ".join(f"SQRT({k})" for k in ks[i:i + 8]) for i in range(0, len(ks), 8)]
        (out / "preset.inc").write_text("/* tools/alpha_search.py --dims %d --max-prime %d --n-min %d --n-max %d */\n"
                                        % (args.dims, args.max_prime, args.n_min, args.n_max)
                                        + ",\n".join(rows) + "\n")
        log(f"wrote {out / 'search.json'} and {out / 'preset.inc'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
