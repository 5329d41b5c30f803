"""Why udm1 has no Fourier stopping rule for Kronecker sequences: measures the candidate, Bayesian
cubature with a shift-invariant kernel at Kronecker points (the analogue of QMCPy's CubBayesLatticeG,
and of the Toeplitz prototype CubBayesKronecker in QMCPy's repository).

The model: f is a draw of a Gaussian process with covariance s^2 K(x - t), K(t) = prod_l (1 + eta
2 pi^2 B_2(t_l)), B_2 the Bernoulli polynomial: f's Fourier coefficient at wavenumber h is normal with
variance s^2 prod_{l: h_l != 0} eta / h_l^2. At the Kronecker points x_i = {i alpha + shift}, the Gram
matrix K(x_i - x_j) = K({(i - j) alpha}) depends on i - j only (Toeplitz). eta by maximum likelihood
(bounded search over log eta), s^2 = y' K^-1 y / n, the estimate 1' K^-1 y, the 99 % credible
half-width 2.576 s sqrt(1 - 1' K^-1 1) (written with the Gram of K - 1 so that no difference of nearly
equal numbers is formed). The sampler is R_d with Baker's transform ("rd+tent", a random shift per trial).

Part 1: the interval's coverage at n points on Genz's six families (coefficients drawn as in bench_integrate.py),
d = 2 and 8: the share of trials whose error is within the half-width, against the 99 % it states.
Part 2: the cost at the n a tolerance needs: conjugate gradients on the Toeplitz Gram (products by FFT),
plain and with T. Chan's circulant preconditioner, iterations to a relative residual of 1e-10 (at most
--cg-max); the direct alternative, Levinson's recursion, costs about n^2 per solve (2.7e11 at 2^19
points: the lattice criterion needs 2^19-2^20 on the 2D peaks, BENCHMARKS.md).

    python bench/kronecker_bayes_study.py [--trials 100] [--n 1024] [--dims 2,8]

Prints two markdown tables (BENCHMARKS.md, "Integration to a tolerance").
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent
sys.path.insert(0, str(ROOT))

from bench_integrate import DIFFICULTY, coefficients, genz, udm1  # noqa: E402

Z99 = 2.5758293035489004  # the normal's 0.995 quantile


def differences(d: int, n: int) -> np.ndarray:
    """{j alpha} for j < n, (n, d), from the top 64 bits of R_d's 128-bit generators (error < n 2^-64)."""
    seq = udm1.Sequence("rd", d, randomize=False)
    top = np.array([seq.alpha(l) >> 64 for l in range(d)], dtype=np.uint64)
    j = np.arange(n, dtype=np.uint64)[:, None]
    return (j * top[None, :]).astype(np.float64) * 2.0 ** -64  # the product wraps mod 2^64: {j alpha}


def kernel_column(t: np.ndarray, eta: float) -> np.ndarray:
    """K({j alpha}) - 1 for the rows of t: the Gram's first column without its constant term."""
    b2 = t * t - t + 1.0 / 6.0
    return np.prod(1.0 + eta * 2.0 * np.pi ** 2 * b2, axis=1) - 1.0


def gram_column(t: np.ndarray, eta: float, constant: float) -> np.ndarray:
    """The first column of the Gram of K - 1 + constant, with a nugget: positive definite in exact
    arithmetic, barely so in doubles."""
    col = kernel_column(t, eta) + constant
    col[0] *= 1 + 1e-12
    return col


class Bayes:
    """The Bayesian rule at one eta: Gram K = 1 1' + M, M Toeplitz positive definite (Sherman-Morrison
    for everything involving the 1 1' term)."""

    def __init__(self, y: np.ndarray, t: np.ndarray, eta: float):
        from scipy.linalg import cho_factor, cho_solve, toeplitz

        n = y.size
        c = cho_factor(toeplitz(gram_column(t, eta, 0.0)), lower=True, check_finite=False)
        m1, my = cho_solve(c, np.ones(n), check_finite=False), cho_solve(c, y, check_finite=False)
        a = float(m1.sum())  # 1' M^-1 1
        b = float(m1 @ y)    # 1' M^-1 y
        self.quad = float(y @ my) - b * b / (1 + a)  # y' K^-1 y
        self.logdet = 2 * float(np.sum(np.log(np.diag(c[0])))) + math.log1p(a)
        self.estimate = b / (1 + a)                  # 1' K^-1 y
        self.remainder = 1 / (1 + a)                 # 1 - 1' K^-1 1
        self.n = n

    def nll(self) -> float:  # the profile likelihood's -2 log, up to a constant (s^2 at its maximum)
        return self.n * math.log(max(self.quad, 1e-300)) + self.logdet

    def half_width(self) -> float:
        return Z99 * math.sqrt(max(self.quad, 0.0) / self.n * self.remainder)


def fit(y: np.ndarray, t: np.ndarray) -> Bayes:
    from scipy.optimize import minimize_scalar

    r = minimize_scalar(lambda le: Bayes(y, t, math.exp(le)).nll(), bounds=(-10.0, 5.0), method="bounded",
                        options={"xatol": 0.05})
    return Bayes(y, t, math.exp(r.x)), math.exp(r.x)


def coverage(family: str, d: int, n: int, trials: int, t: np.ndarray) -> tuple[int, float, float]:
    """(trials covered, median error / half-width, median eta)."""
    rng = np.random.default_rng(20261126 + d)
    covered, ratios, etas = 0, [], []
    for trial in range(trials):
        f, exact = genz(family, *coefficients(family, d, rng))
        x = udm1.Sequence("rd+tent", d, seed=trial + 1).points(n)
        rule, eta = fit(np.asarray(f(x), dtype=np.float64), t[:n])
        err, width = abs(rule.estimate - exact), rule.half_width()
        covered += err <= width
        ratios.append(err / width if width > 0 else math.inf)
        etas.append(eta)
    return covered, float(np.median(ratios)), float(np.median(etas))


def cg_iterations(t: np.ndarray, eta: float, preconditioned: bool, cap: int) -> int:
    """Conjugate-gradient iterations for K x = 1 at the n = len(t) points, to relative residual 1e-10."""
    n = t.shape[0]
    col = gram_column(t, eta, 1.0)
    spectrum = np.fft.rfft(np.concatenate([col, [0.0], col[:0:-1]]))  # circulant embedding, size 2n

    def times(v):
        return np.fft.irfft(spectrum * np.fft.rfft(v, 2 * n), 2 * n)[:n]

    if preconditioned:  # T. Chan's optimal circulant: eigenvalues of the averaged diagonals
        j = np.arange(n)
        chan = np.fft.fft(((n - j) * col + j * np.concatenate([[0.0], col[:0:-1]])) / n).real
        chan = np.maximum(chan, chan.max() * 1e-14)

        def solve(v):
            return np.fft.ifft(np.fft.fft(v) / chan).real
    else:
        def solve(v):
            return v
    b = np.ones(n)
    r = b.copy()  # the residual of x = 0 (x itself is not needed to count the iterations)
    z = solve(r)
    p, rz = z.copy(), r @ z
    for it in range(1, cap + 1):
        q = times(p)
        r -= rz / (p @ q) * q
        if np.linalg.norm(r) <= 1e-10 * np.linalg.norm(b):
            return it
        z = solve(r)
        rz, rz_old = r @ z, rz
        p = z + rz / rz_old * p
    return cap + 1


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--trials", type=int, default=100)
    ap.add_argument("--n", type=int, default=1024, help="points per trial in part 1")
    ap.add_argument("--dims", default="2,8")
    ap.add_argument("--cg-sizes", default="12,16", help="log2 n of part 2")
    ap.add_argument("--cg-max", type=int, default=2000)
    args = ap.parse_args()
    dims = [int(v) for v in args.dims.split(",")]
    sizes = [int(v) for v in args.cg_sizes.split(",")]
    t0 = time.perf_counter()
    print(f"Part 1: coverage of the 99 % interval at n = {args.n}, {args.trials} trials per case (R_d, Baker's transform)\n")
    print("| family | " + " | ".join(f"d = {d}: covered, median err/half-width, median eta" for d in dims) + " |")
    print("|---|" + "---|" * len(dims))
    etas = {d: [] for d in dims}
    tables = {d: differences(d, max(args.n, 1 << max(sizes))) for d in dims}
    for family in DIFFICULTY:
        cells = []
        for d in dims:
            covered, ratio, eta = coverage(family, d, args.n, args.trials, tables[d])
            etas[d].append(eta)
            cells.append(f"{covered}/{args.trials} ({100 * covered / args.trials:.0f} %), {ratio:.2f}, {eta:.3g}")
            print(f"[study] {family} d={d}: {cells[-1]} ({time.perf_counter() - t0:.0f} s)", file=sys.stderr)
        print(f"| {family} | " + " | ".join(cells) + " |")
    print(f"\nPart 2: conjugate-gradient iterations for K x = 1 (eta: the median of part 1's over the families; "
          f"> {args.cg_max}: not converged)\n")
    print("| d | eta | " + " | ".join(f"n = 2^{m}: plain, T. Chan" for m in sizes) + " |")
    print("|---|---|" + "---|" * len(sizes))
    for d in dims:
        eta = float(np.median(etas[d]))
        cells = []
        for m in sizes:
            its = [cg_iterations(tables[d][:1 << m], eta, pre, args.cg_max) for pre in (False, True)]
            cells.append(", ".join(str(i) if i <= args.cg_max else f"> {args.cg_max}" for i in its))
        print(f"| {d} | {eta:.3g} | " + " | ".join(cells) + " |")
    print(f"\n({time.perf_counter() - t0:.0f} s)")


if __name__ == "__main__":
    main()
