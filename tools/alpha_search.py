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


def candidate_pool(kinds: list[str], max_prime: int, max_cube: int, max_rd: int) -> list[tuple[str, float, object]]:
    """(label, frac in double for the search, exact generator for the library) for each candidate:
    sqrt(p) for primes p; cube roots of cube-free integers (algebraic of degree 3); R_d's generators
    phi_d^-k (phi_d the root of x^(d+1) = x + 1, algebraic of degree d + 1) for d = 2 .. max_rd."""
    pool = []
    if "sqrt" in kinds:
        pool += [(f"sqrt({p})", math.sqrt(p) % 1.0, udm1.Sqrt(int(p))) for p in primes_upto(max_prime)]
    if "cbrt" in kinds or "rd" in kinds:
        import mpmath
        mpmath.mp.dps = 60

        def fixed(x):
            return udm1.Fixed(int(mpmath.floor(mpmath.frac(x) * mpmath.mpf(2) ** 128)))
    if "cbrt" in kinds:
        for k in range(2, max_cube + 1):
            if any(k % (q ** 3) == 0 for q in range(2, int(round(k ** (1 / 3))) + 2)):
                continue  # not cube-free (a perfect cube is not cube-free either)
            x = mpmath.cbrt(k)
            pool.append((f"cbrt({k})", float(mpmath.frac(x)), fixed(x)))
    if "rd" in kinds:
        for d in range(2, max_rd + 1):
            phi = mpmath.findroot(lambda x, d=d: x ** (d + 1) - x - 1, 1.1)
            for k in range(1, d + 1):
                x = phi ** -k
                pool.append((f"phi_{d}^-{k}", float(mpmath.frac(x)), fixed(x)))
    return pool


def search(candidates: np.ndarray, dims: int, ns: np.ndarray, log=None, alphas: np.ndarray | None = None) -> list[int]:
    """Greedy choice of dims candidates; returns the chosen entries of `candidates` (square roots of those
    integers unless `alphas`, the fractional parts, are given)."""
    if alphas is None:
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
            log(f"dimension {j}: {candidates[k]}, worst pair ratio {worst[k]:.3f}")
        if j + 1 < dims:  # every candidate's worst pair now includes the new dimension
            worst = np.maximum(worst, ratios(g * g[k], ns, 2).max(axis=1))
    return [candidates[k] for k in chosen]


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
    ap.add_argument("--candidates", default="sqrt", help="comma list of sqrt (primes), cbrt (cube-free integers), "
                    "rd (R_d's generators, d = 2..--max-rd); default sqrt, the preset wopt's pool")
    ap.add_argument("--max-cube", type=int, default=2000, help="cbrt candidates: cube-free k <= this (default 2000)")
    ap.add_argument("--max-rd", type=int, default=64, help="rd candidates: d up to this (default 64)")
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
    kinds = args.candidates.split(",")
    bad = [k for k in kinds if k not in ("sqrt", "cbrt", "rd")]
    if bad or not 2 <= args.max_cube <= 1 << 20 or not 2 <= args.max_rd <= 256:
        print(f"alpha_search: --candidates takes sqrt, cbrt, rd (got '{args.candidates}'); --max-cube 2..1048576, "
              "--max-rd 2..256", file=sys.stderr)
        return 2
    pool = candidate_pool(kinds, args.max_prime, args.max_cube, args.max_rd)
    if len(pool) < args.dims:
        print(f"alpha_search: only {len(pool)} candidates ({args.candidates}), fewer than --dims {args.dims}",
              file=sys.stderr)
        return 2
    ns = np.unique(np.round(np.geomspace(args.n_min, args.n_max, 48)).astype(int))
    t0 = time.time()
    log = lambda m: print(f"[alpha_search] {m}", file=sys.stderr, flush=True)  # noqa: E731
    log(f"{len(pool)} candidates ({args.candidates}); N from {ns[0]} to {ns[-1]} ({len(ns)} values)")
    labels = np.array([c[0] for c in pool], dtype=object)
    chosen = search(np.arange(len(pool)), args.dims, ns, lambda m: log(m.replace("dimension", "dim")),
                    alphas=np.array([c[1] for c in pool]))
    picked = [pool[int(i)] for i in chosen]
    seconds = time.time() - t0
    log(f"chosen in {seconds:.1f} s: {[c[0] for c in picked]}")
    exact = [c[2] for c in picked]
    dep = udm1.check_alphas(exact, 256)
    log(f"library check of the chosen set: {dep['message']}")
    check_ns = [int(x) for x in args.check_n.split(",")]
    dims_list = [d for d in (2, 8, 16, 32, 64, 128) if d <= args.dims]
    sets = {"search": lambda d: udm1.Sequence(alphas=exact[:d], randomize=False)}
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
            "generators": [c[0] for c in picked], "candidates": args.candidates, "dims": args.dims,
            "max_prime": args.max_prime, "n_grid": ns.tolist(), "seconds": seconds, "dependent": dep["dependent"],
            "quality": quality}, indent=1))

        def spec(c):
            if isinstance(c[2], udm1.Sqrt):
                return f"SQRT({c[2].k})"
            v = c[2].value
            return f"FIXED(0x{v >> 64:016X}ull, 0x{v & (2**64 - 1):016X}ull) /* {c[0]} */"
        (out / "preset.inc").write_text(
            "/* tools/alpha_search.py --dims %d --candidates %s --max-prime %d --n-min %d --n-max %d */\n"
            % (args.dims, args.candidates, args.max_prime, args.n_min, args.n_max)
            + ",\n".join(spec(c) for c in picked) + "\n")
        log(f"wrote {out / 'search.json'} and {out / 'preset.inc'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
