"""Noise evaluations per second from Python, side by side in one run:
FastNoise Lite (PyPI pyfastnoiselite, Perlin, its batch gen_from_coords: a
serial C++ loop, one thread) against udm1's batch call (udm1.Noise.noise, a C
loop, one thread, with the best kernel of the processor), over the same 2^20
random points, 2D and 3D, alternating; then udm1 capped at AVX2 in a second
process (UDM1_ISA=avx2: the library fixes its kernels' instruction set once per
process), against the FastNoise Lite time of the first.

    PYTHONPATH=python python bench/bench_noise.py [--reps 7]
"""

import argparse
import os
import subprocess
import sys
import time

import numpy as np

import udm1


def points(d: int, n: int = 1 << 20) -> np.ndarray:
    return np.random.default_rng(d).uniform(-100, 100, (n, d))


def avx2_only(d: int, reps: int) -> float:
    """udm1's best batch time in d dimensions with its kernels capped at AVX2, in a second process."""
    env = dict(os.environ, UDM1_ISA="avx2")
    r = subprocess.run([sys.executable, __file__, "--udm1-only", str(d), "--reps", str(reps)], env=env,
                       capture_output=True, text=True, check=True)
    return float(r.stdout.split()[0])


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
    ap.add_argument("--udm1-only", type=int, metavar="D", help="print udm1's best batch time in D dimensions only")
    args = ap.parse_args(argv)
    if args.udm1_only:
        pts, ours = points(args.udm1_only), udm1.Noise("wr", seed=1)
        print(best_interleaved([lambda: ours.noise(pts)], args.reps)[0])
        return 0
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
        pts = points(d, n)
        coords = np.ascontiguousarray(pts.T.astype(np.float32))
        t_fnl, t_ours = best_interleaved([lambda: fnl.gen_from_coords(coords), lambda: ours.noise(pts)], args.reps)
        t_avx2 = avx2_only(d, args.reps)
        print(f"{d:>2} {'FastNoise Lite Perlin, gen_from_coords (anchor)':<46} {n / t_fnl:12.4g} {1.0:17.2f}")
        print(f"{d:>2} {'udm1 improved noise, Noise.noise (batch)':<46} {n / t_ours:12.4g} {t_fnl / t_ours:17.2f}")
        print(f"{d:>2} {'udm1 ditto, UDM1_ISA=avx2':<46} {n / t_avx2:12.4g} {t_fnl / t_avx2:17.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
