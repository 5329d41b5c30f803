"""Noise evaluations per second from Python, side by side in one run:
FastNoise Lite (PyPI pyfastnoiselite, Perlin, its batch gen_from_coords: a
serial C++ loop, one thread) against udm1's batch call (udm1.Noise.noise, a C
loop, one thread, with the best kernel of the processor and capped at AVX2),
over the same 2^20 random points, 2D and 3D.

    PYTHONPATH=python python bench/bench_noise.py [--reps 7]
"""

import argparse
import os
import sys
import time

import numpy as np

import udm1


def avx2_only(f, *args):
    """f(*args) with udm1's noise kernels capped at AVX2 (as on a processor without AVX-512)."""
    os.environ["UDM1_NOISE_ISA"] = "avx2"
    try:
        return f(*args)
    finally:
        del os.environ["UDM1_NOISE_ISA"]


def best_interleaved(fs, reps):
    """Best time of each function over reps rounds, the functions alternating within a round."""
    for f in fs:
        f()
    best = [float("inf")] * len(fs)
    for _ in range(reps):
        for k, f in enumerate(fs):
            t0 = time.perf_counter()
            f()
            best[k] = min(best[k], time.perf_counter() - t0)
    return best


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps", type=int, default=15)
    args = ap.parse_args(argv)
    try:
        from pyfastnoiselite.pyfastnoiselite import FastNoiseLite, FractalType, NoiseType
    except ImportError:
        print("bench_noise: pyfastnoiselite is not installed (pip install pyfastnoiselite)", file=sys.stderr)
        return 2
    n = 1 << 20
    fnl = FastNoiseLite(seed=1)
    fnl.noise_type = NoiseType.NoiseType_Perlin
    fnl.frequency = 1.0
    fnl.fractal_type = FractalType.FractalType_None
    ours = udm1.Noise("wr", seed=1)
    print(f"{'d':>2} {'method':<46} {'evals/s':>12} {'x FastNoise Lite':>17}")
    for d in (2, 3):
        pts = np.random.default_rng(d).uniform(-100, 100, (n, d))
        coords = np.ascontiguousarray(pts.T.astype(np.float32))
        t_fnl, t_ours, t_avx2 = best_interleaved(
            [lambda: fnl.gen_from_coords(coords), lambda: ours.noise(pts), lambda: avx2_only(ours.noise, pts)],
            args.reps)
        print(f"{d:>2} {'FastNoise Lite Perlin, gen_from_coords (anchor)':<46} {n / t_fnl:12.4g} {1.0:17.2f}")
        print(f"{d:>2} {'udm1 improved noise, Noise.noise (batch)':<46} {n / t_ours:12.4g} {t_fnl / t_ours:17.2f}")
        print(f"{d:>2} {'udm1 ditto, UDM1_NOISE_ISA=avx2':<46} {n / t_avx2:12.4g} {t_fnl / t_avx2:17.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
