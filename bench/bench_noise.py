"""Noise evaluations per second from Python, side by side in one process, one thread, the methods
alternating within every round (best of --reps rounds), over the same 2^20 random points in [-100, 100]^d:

- FastNoiseSIMD (PyPI pyfastnoisesimd: float32, AVX-512 or AVX2 chosen at run time, its
  `genFromCoords` over separate coordinate arrays, one worker): the anchor, the SIMD library a
  speed-minded user picks; it has 3D noise only, so its 2D figure is its 3D noise at z = 0;
- FastNoise Lite (PyPI pyfastnoiselite: its batch `gen_from_coords`, a scalar C loop);
- udm1 (`udm1.Noise.noise`): float32 points (udm1_noise_eval_f32, 16 lanes with AVX-512 VBMI, 8
  with AVX2), the same with the analytic gradient, and float64 (the exact double path);

Perlin noise in 2D and 3D (improved noise, Perlin's table), and cellular noise (F1, Euclidean) against
FastNoiseSIMD's cellular distance. Then udm1 again capped at AVX2 in a second process (UDM1_ISA=avx2:
the library fixes its kernels' instruction set once per process), against the anchors' times of the
first. Prints a table and writes --json.

    PYTHONPATH=python python bench/bench_noise.py [--reps 9] [--json out.json]
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np

import udm1

N = 1 << 20


def coords(d: int) -> np.ndarray:
    """(d, N) float32: the same points for every method (float64 methods read them widened)."""
    return np.random.default_rng(d).uniform(-100, 100, (d, N)).astype(np.float32)


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


GROUPS = [("Perlin 2D", 2), ("Perlin 3D", 3), ("cellular 3D", 3)]


def udm1_methods(group: str, d: int):
    """(label, function) for udm1 in a group."""
    c = coords(d)
    c32 = tuple(c[k] for k in range(d))
    c64 = tuple(c[k].astype(np.float64) for k in range(d))
    ours = udm1.Noise()
    if group.startswith("cellular"):
        return [("udm1 cellular F1, jitter 0.45, float32", lambda: ours.cellular(c32, jitter=0.45)),
                ("udm1 cellular F1, jitter 1, float32", lambda: ours.cellular(c32, jitter=1.0)),
                ("udm1 cellular F1, jitter 0.45, float64", lambda: ours.cellular(c64, jitter=0.45))]
    return [(f"udm1 improved noise {d}D, float32", lambda: ours.noise(c32)),
            (f"udm1 improved noise {d}D, float32, value and gradient", lambda: ours.noise(c32, gradient=True)),
            (f"udm1 improved noise {d}D, float64", lambda: ours.noise(c64))]


def capped(reps: int) -> dict:
    """udm1's best times with its kernels capped at AVX2, in a second process: label -> seconds."""
    env = dict(os.environ, UDM1_ISA="avx2")
    r = subprocess.run([sys.executable, __file__, "--udm1-only", "--reps", str(reps)], env=env, capture_output=True,
                       text=True, check=True)
    return json.loads(r.stdout)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--json", default="")
    ap.add_argument("--udm1-only", action="store_true", help="print udm1's best times (JSON) only")
    args = ap.parse_args(argv)
    if args.udm1_only:
        out = []
        for group, d in GROUPS:
            ms = udm1_methods(group, d)
            for (label, _), t in zip(ms, best_interleaved([f for _, f in ms], args.reps)):
                out.append([group, label, t])
        print(json.dumps(out))
        return 0
    try:
        import pyfastnoisesimd as fns
    except ImportError:
        fns = None
        print("bench_noise: pyfastnoisesimd (FastNoiseSIMD, the anchor) is not installed: `./run.sh bench` installs "
              "it; FastNoise Lite is the anchor of this run", file=sys.stderr)
    try:
        from pyfastnoiselite.pyfastnoiselite import FastNoiseLite, FractalType, NoiseType
    except ImportError:
        FastNoiseLite = None
    if fns is None and FastNoiseLite is None:
        print("bench_noise: neither pyfastnoisesimd nor pyfastnoiselite is installed: no anchor to measure against",
              file=sys.stderr)
        return 2
    rows = []
    for group, d in GROUPS:
        c = coords(d)
        cellular = group.startswith("cellular")
        methods = []
        if fns is not None:
            c3 = fns.empty_coords(N)  # FastNoiseSIMD's own aligned (3, N) arrays; 2D: z = 0
            c3[:d] = c
            if d == 2:
                c3[2] = 0
            simd = fns.Noise(numWorkers=1)
            simd.frequency = 1.0
            if cellular:  # its defaults: Euclidean, the distance to the nearest, jitter 0.45
                simd.noiseType = fns.NoiseType.Cellular
                simd.cell.distanceFunc = fns.CellularDistanceFunction.Euclidean
                simd.cell.returnType = fns.CellularReturnType.Distance
                name = f"FastNoiseSIMD cellular F1 Euclidean, jitter {simd.cell.jitter:.2f}"
            else:
                simd.noiseType = fns.NoiseType.Perlin
                name = f"FastNoiseSIMD Perlin ({'3D at z = 0' if d == 2 else '3D'})"
            methods.append((f"{name}, {fns.extension.SIMD_LEVEL} (anchor)", lambda simd=simd, c3=c3: simd.genFromCoords(c3)))
        if FastNoiseLite:
            lite = FastNoiseLite(seed=1)
            lite.noise_type = NoiseType.NoiseType_Cellular if cellular else NoiseType.NoiseType_Perlin
            lite.frequency = 1.0
            lite.fractal_type = FractalType.FractalType_None
            cl = np.ascontiguousarray(c)
            label = f"FastNoise Lite {'cellular (its defaults)' if cellular else 'Perlin'} {d}D"
            methods.append((label + ("" if methods else " (anchor)"), lambda lite=lite, cl=cl: lite.gen_from_coords(cl)))
        methods += udm1_methods(group, d)
        times = best_interleaved([f for _, f in methods], args.reps)
        for (label, _), t in zip(methods, times):
            rows.append({"group": group, "method": label, "seconds": t, "rate": N / t, "x_anchor": times[0] / t,
                         "anchor": methods[0][0]})
    for group, label, t in capped(args.reps):
        a = next(r for r in rows if r["group"] == group and r["method"] == r["anchor"])
        rows.append({"group": group, "method": label + ", UDM1_ISA=avx2", "seconds": t, "rate": N / t,
                     "x_anchor": a["seconds"] / t, "anchor": a["method"]})
    order = [g for g, _ in GROUPS]
    rows.sort(key=lambda r: order.index(r["group"]))
    print(f"{'group':<12} {'method':<66} {'evals/s':>10} {'x anchor':>9}")
    for r in rows:
        print(f"{r['group']:<12} {r['method']:<66} {r['rate']:10.4g} {r['x_anchor']:9.2f}")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rows": rows, "n": N, "reps": args.reps, "isa": udm1.isa() if hasattr(udm1, "isa") else ""}, f,
                      indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
