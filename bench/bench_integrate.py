"""Integration to a tolerance: udm1.integrate's stopping rule against QMCPy's (PyPI qmcpy:
CubQMCLatticeG, CubQMCNetG, CubQMCRepStudentT) and scipy's qmc_quad, on Genz's six test families.

For each family (oscillatory, product peak, corner peak, Gaussian, continuous, discontinuous) and
dimension d (--dims, default 2, 8, 32), --trials trials with random coefficients (a_i uniform, scaled so
that sum a_i is the family's difficulty, Genz's 1987 table divided by d^e; w_i uniform) and a
tolerance abs_tol = --rel x |I| (the exact integral I from its closed form; the corner peak's from a
1D integral): every method integrates to that tolerance with at most --n-max evaluations, and the
table gives the share of trials whose error was within the tolerance, the median evaluations and
the median seconds. Methods run in turn within each trial, so the machine's drift falls on all.

- udm1: `udm1.integrate(f, sampler, d, abs_tol=...)`: the embedded rank-1 lattice "lattice-seq" with
  Baker's transform and the lattice criterion (one shifted lattice, the bound from its Fourier
  coefficients); and 16 randomized replicates (streams of one seed), doubling n, Student-t at 99 %, of
  sobol-owen and of wr with the tent transform.
- QMCPy: CubQMCLatticeG (its lattice with its default periodization), CubQMCNetG (digital net),
  CubQMCRepStudentT (16 replications of a digital net, Student-t), each at the same abs_tol.
- scipy: qmc_quad (scrambled Sobol, 8 estimates) with its point count doubled until its interval
  (Student-t at 99 % on its standard error) is within the tolerance.

    python bench/bench_integrate.py [--trials 1000] [--dims 2,8,32] [--rel 1e-3] [--out DIR]
    python bench/bench_integrate.py --table DIR1/results.json [DIR2/results.json ...]   # runs split by case,
                                                                                        # as one table

It writes DIR/results.json and DIR/results.md (the table of BENCHMARKS.md).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
import warnings
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "python"))

import udm1  # noqa: E402

# Genz's difficulties: sum a_i = B / d^E (his 1987 test package's table)
DIFFICULTY = {"oscillatory": (110, 1.5), "product_peak": (600, 2.0), "corner_peak": (600, 2.0),
              "gaussian": (100, 1.0), "continuous": (150, 2.0), "discontinuous": (100, 2.0)}


def genz(family: str, a: np.ndarray, w: np.ndarray):
    """(f, exact integral) of a Genz family with coefficients a and shifts w."""
    from scipy.special import erf, gammaln

    d = a.size
    if family == "oscillatory":
        return (lambda x: np.cos(2 * np.pi * w[0] + x @ a)), (
            np.exp(2j * np.pi * w[0]) * np.prod((np.exp(1j * a) - 1) / (1j * a))).real
    if family == "product_peak":
        return (lambda x: np.prod(1 / (a ** -2.0 + (x - w) ** 2), axis=-1)), float(
            np.prod(a * (np.arctan(a * (1 - w)) + np.arctan(a * w))))
    if family == "corner_peak":
        # (1 + a.x)^-(d+1) = (1/d!) int_0^inf t^d e^{-t(1 + a.x)} dt: the x integral is a product
        from scipy.integrate import quad

        def g(t):
            return math.exp(-t + float(np.sum(np.log(-np.expm1(-t * a)) - np.log(a))) - gammaln(d + 1))

        exact = quad(g, 0, np.inf, limit=500, epsabs=0, epsrel=1e-13)[0]
        return (lambda x: (1 + x @ a) ** (-(d + 1.0))), exact
    if family == "gaussian":
        return (lambda x: np.exp(-np.sum((a * (x - w)) ** 2, axis=-1))), float(
            np.prod(np.sqrt(np.pi) / (2 * a) * (erf(a * (1 - w)) + erf(a * w))))
    if family == "continuous":
        return (lambda x: np.exp(-np.sum(a * np.abs(x - w), axis=-1))), float(
            np.prod((2 - np.exp(-a * w) - np.exp(-a * (1 - w))) / a))
    if family == "discontinuous":
        k = min(2, d)
        inside = np.concatenate([np.expm1(a[:k] * w[:k]), np.expm1(a[k:])]) / a
        return (lambda x: np.where(np.all(x[..., :k] < w[:k], axis=-1), np.exp(x @ a), 0.0)), float(np.prod(inside))
    raise ValueError(family)


def coefficients(family: str, d: int, rng) -> tuple[np.ndarray, np.ndarray]:
    b, e = DIFFICULTY[family]
    a = rng.uniform(0, 1, d)
    a = a / a.sum() * b / d ** e
    return np.maximum(a, 1e-9), rng.uniform(0, 1, d)


def run_udm1(f, d, tol, n_max, seed, sampler, transform):
    r = udm1.integrate(f, sampler, d, abs_tol=tol, n_max=n_max, seed=seed, transform=transform, strict=False)
    return r.estimate, r.n_total


def run_qmcpy(f, d, tol, n_max, seed, method):
    import qmcpy as qp

    if method == "CubQMCLatticeG":
        integrand = qp.CustomFun(qp.Uniform(qp.Lattice(d, seed=seed)), g=f)
        algo = qp.CubQMCLatticeG(integrand, abs_tol=tol, n_limit=n_max)
    elif method == "CubQMCNetG":
        integrand = qp.CustomFun(qp.Uniform(qp.DigitalNetB2(d, seed=seed)), g=f)
        algo = qp.CubQMCNetG(integrand, abs_tol=tol, n_limit=n_max)
    else:
        integrand = qp.CustomFun(qp.Uniform(qp.DigitalNetB2(d, seed=seed, replications=16)), g=f)
        algo = qp.CubQMCRepStudentT(integrand, abs_tol=tol, n_limit=n_max)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            sol, data = algo.integrate()
        except qp.util.exceptions_warnings.ParameterError:  # past its generator's 2^20 points: not met
            return float("nan"), n_max
    return float(np.asarray(sol).ravel()[0]), int(np.asarray(data.n_total).ravel()[0])


def run_scipy(f, d, tol, n_max, seed):
    from scipy.integrate import qmc_quad
    from scipy.stats import qmc, t

    q, n = t.ppf(0.995, 7), 256
    while True:
        r = qmc_quad(lambda x: f(x.T), np.zeros(d), np.ones(d), n_points=n, n_estimates=8,
                     qrng=qmc.Sobol(d, rng=seed))
        if q * r.standard_error <= tol or 2 * n * 8 > n_max:
            return float(r.integral), n * 8
        n *= 2


METHODS = {
    "udm1 lattice-seq baker": lambda f, d, tol, n_max, s: run_udm1(f, d, tol, n_max, s, "lattice-seq", "baker"),
    "udm1 sobol-owen": lambda f, d, tol, n_max, s: run_udm1(f, d, tol, n_max, s, "sobol-owen", None),
    "udm1 wr tent": lambda f, d, tol, n_max, s: run_udm1(f, d, tol, n_max, s, "wr", "tent"),
    "QMCPy CubQMCLatticeG": lambda f, d, tol, n_max, s: run_qmcpy(f, d, tol, n_max, s, "CubQMCLatticeG"),
    "QMCPy CubQMCNetG": lambda f, d, tol, n_max, s: run_qmcpy(f, d, tol, n_max, s, "CubQMCNetG"),
    "QMCPy CubQMCRepStudentT": lambda f, d, tol, n_max, s: run_qmcpy(f, d, tol, n_max, s, "CubQMCRepStudentT"),
    "scipy qmc_quad": lambda f, d, tol, n_max, s: run_scipy(f, d, tol, n_max, s),
}


def markdown_table(rows: list[dict]) -> str:
    """The results as BENCHMARKS.md's table: per case, every method's success, median evaluations and median
    time, and the fastest udm1 method meeting the tolerance in at least 95 % of trials over the fastest such
    QMCPy criterion."""
    methods = list(dict.fromkeys(r["method"] for r in rows))
    cases = sorted(dict.fromkeys((r["family"], r["d"]) for r in rows),  # Genz's order, then d
                   key=lambda c: (list(DIFFICULTY).index(c[0]) if c[0] in DIFFICULTY else len(DIFFICULTY), c[1]))
    at = {(r["family"], r["d"], r["method"]): r for r in rows}
    out = ["| family | d | " + " | ".join(methods) + " | udm1 / QMCPy, fastest at >= 95 % |",
           "|---|---|" + "---|" * (len(methods) + 1)]
    for family, d in cases:
        cells = []
        for m in methods:
            r = at.get((family, d, m))
            cells.append("-" if r is None else
                         f"{r['success']:.1%}, {r['median_n']:.0f}, {r['median_seconds'] * 1e3:.2f} ms")

        def fastest(prefix):
            ok = [at[(family, d, m)] for m in methods if m.startswith(prefix) and (family, d, m) in at
                  and at[(family, d, m)]["success"] >= 0.95]
            return min(ok, key=lambda r: r["median_seconds"]) if ok else None

        u, q = fastest("udm1"), fastest("QMCPy")
        last = ("udm1 and QMCPy below 95 %" if not u and not q else "udm1 below 95 %" if not u else
                "QMCPy below 95 %" if not q else f"{u['median_seconds'] / q['median_seconds']:.2f}")
        out.append(f"| {family.replace('_', ' ')} | {d} | " + " | ".join(cells) + f" | {last} |")
    return "\n".join(out) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--trials", type=int, default=1000)
    ap.add_argument("--dims", default="2,8,32")
    ap.add_argument("--families", default=",".join(DIFFICULTY))
    ap.add_argument("--rel", type=float, default=1e-3, help="abs_tol = rel x |exact integral|")
    ap.add_argument("--n-max", type=int, default=1 << 20, help="evaluations at most (QMCPy's lattice has 2^20 points)")
    ap.add_argument("--methods", default=",".join(METHODS))
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_integrate"))
    ap.add_argument("--table", nargs="+", metavar="RESULTS_JSON", help="print the table of these results and stop")
    args = ap.parse_args(argv)
    if args.table:
        print(markdown_table([r for path in args.table for r in json.loads(Path(path).read_text())["rows"]]), end="")
        return 0
    try:
        import qmcpy  # noqa: F401
    except ImportError:
        print("bench_integrate: QMCPy is not installed (pip install qmcpy): its methods are left out", file=sys.stderr)
    methods = [m for m in args.methods.split(",") if not (m.startswith("QMCPy") and "qmcpy" not in sys.modules)]
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for family in args.families.split(","):
        for d in (int(x) for x in args.dims.split(",")):
            rng = np.random.default_rng(zlib.crc32(f"{family} {d}".encode()))  # the same trials in every run
            res = {m: {"ok": 0, "n": [], "s": []} for m in methods}
            t_case = time.perf_counter()
            for trial in range(args.trials):
                a, w = coefficients(family, d, rng)
                f, exact = genz(family, a, w)
                tol = args.rel * abs(exact)
                for m in methods:
                    t0 = time.perf_counter()
                    est, n = METHODS[m](f, d, tol, args.n_max, trial + 1)
                    res[m]["s"].append(time.perf_counter() - t0)
                    res[m]["n"].append(n)
                    res[m]["ok"] += abs(est - exact) <= tol
            for m in methods:
                rows.append({"family": family, "d": d, "method": m, "trials": args.trials,
                             "success": res[m]["ok"] / args.trials, "median_n": float(np.median(res[m]["n"])),
                             "median_seconds": float(np.median(res[m]["s"]))})
            print(f"[bench_integrate] {family} d = {d}: {args.trials} trials in {time.perf_counter() - t_case:.0f} s",
                  file=sys.stderr, flush=True)
            for r in rows[-len(methods):]:
                print(f"  {r['method']:<24} success {r['success']:6.1%}  median n {r['median_n']:>10.0f}  "
                      f"median {r['median_seconds'] * 1e3:8.2f} ms", flush=True)
    (out / "results.json").write_text(json.dumps({"rows": rows, "rel": args.rel, "n_max": args.n_max,
                                                  "trials": args.trials}, indent=1))
    (out / "results.md").write_text(markdown_table(rows))
    print(f"wrote {out / 'results.json'} and {out / 'results.md'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
