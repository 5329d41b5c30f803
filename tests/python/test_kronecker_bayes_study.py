"""bench/kronecker_bayes_study.py, the measurement behind "no Fourier stopping rule for Kronecker
sequences": its pieces compute what they say, so that its figures (BENCHMARKS.md) are the method's and
not a slip of its code.

- The Gram's column: {j alpha} from the generators equals the unrandomized sequence's points.
- The Bayesian rule's quantities, written with the Gram of K - 1 (Sherman-Morrison), equal the direct
  ones with K.
- When the model holds (the values and the integral drawn jointly from the Gaussian process), the 99 %
  interval covers: at least 95 of 100 draws (binomial: fewer than 95 at a true 99 % has probability
  5e-4). Measured: 99; with the half-width scaled by 0.67, 90; by 0.5, 79: a mis-scaled width fails.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

import udm1

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "bench"))
study = pytest.importorskip("kronecker_bayes_study", reason="bench/kronecker_bayes_study.py is not in this tree")


def test_differences_are_the_sequence():
    for d in (1, 3, 8):
        got = study.differences(d, 500)
        want = udm1.Sequence("rd", d, randomize=False).points(500)
        want = (want - want[0]) % 1.0
        gap = np.abs(got - want)
        assert np.max(np.minimum(gap, 1 - gap)) < 1e-12


def test_rule_matches_the_direct_formulas():
    from scipy.linalg import toeplitz

    t = study.differences(2, 64)
    y = np.random.default_rng(3).normal(size=64) + 2.0
    for eta in (0.05, 0.5, 4.0):
        rule = study.Bayes(y, t, eta)
        col = study.kernel_column(t, eta)
        col[0] *= 1 + 1e-12
        k = toeplitz(col + 1.0)
        k1, ky = np.linalg.solve(k, np.ones(64)), np.linalg.solve(k, y)
        assert rule.estimate == pytest.approx(k1 @ y, rel=1e-8)
        assert rule.quad == pytest.approx(y @ ky, rel=1e-8)
        assert rule.remainder == pytest.approx(1 - k1.sum(), rel=1e-6)
        assert rule.logdet == pytest.approx(np.linalg.slogdet(k)[1], rel=1e-8)


def test_interval_covers_when_the_model_holds():
    # (values at the n points, integral) drawn jointly from the process: covariance K at the points, 1
    # between a value and the integral (the kernel integrates to 1), 1 for the integral itself
    from scipy.linalg import cholesky, toeplitz

    d, n, eta = 2, 256, 0.5
    t = study.differences(d, n)
    col = study.kernel_column(t, eta) + 1.0
    joint = np.ones((n + 1, n + 1))
    joint[:n, :n] = toeplitz(col) + 1e-9 * np.eye(n)
    lower = cholesky(joint, lower=True)
    rng = np.random.default_rng(11)
    covered = 0
    for _ in range(100):
        draw = lower @ rng.normal(size=n + 1) * 3.0  # any scale: the rule fits it
        rule, _ = study.fit(draw[:n], t)
        covered += abs(rule.estimate - draw[n]) <= rule.half_width()
    assert covered >= 95, f"the 99 % interval covered {covered} of 100 draws from its own model"
