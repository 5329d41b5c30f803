"""Noise evaluations per second from Python, one process per instruction set, one thread, the methods
alternating within every round of that process (best of --reps rounds), over the same 2^20 random points
in [-100, 100]^d, every coordinate array starting on a 64-byte boundary for both sides, as FastNoiseSIMD's
`empty_coords` makes its own (from numpy's 16-byte start, udm1's 3D kernel took 2.33 ns a point against 2.00):

- FastNoiseSIMD (pyfastnoisesimd 0.4.2, float32, its `genFromCoords` over separate coordinate arrays, one
  worker): the anchor, the SIMD library a speed-minded user picks. The benchmark builds it from its PyPI
  sdist (fetched with pip) into --build/bench_noise/fastnoisesimd-LEVEL, once per level: "native" with
  every kernel its setup compiles (it picks the best at run time, as its wheel), "avx2" with its setup's
  `--with-avx512=no` (AVX2 + FMA at most, on any machine). It has 3D noise only, so its 2D figure is its
  3D noise at z = 0;
- FastNoise Lite (PyPI pyfastnoiselite: its batch `gen_from_coords`, a scalar C loop);
- udm1 (`udm1.Noise.noise`): float32 points (udm1_noise_eval_f32), the same with the analytic gradient,
  and float64 (the exact double path); with UDM1_ISA=avx2 in the avx2 process (the library fixes its
  kernels' instruction set once per process).

Perlin noise in 2D and 3D (improved noise, Perlin's table), and cellular noise (F1, Euclidean) against
FastNoiseSIMD's cellular distance. Each row names the instruction set both sides ran (FastNoiseSIMD's
SIMD_LEVEL, udm1_isa()). Prints a table and writes --json.

    PYTHONPATH=python python bench/bench_noise.py [--levels native,avx2] [--reps 9] [--clock cpu] [--json out.json]
"""

from __future__ import annotations

import argparse
import importlib.util
import ctypes
import json
import os
import shutil
import subprocess
import sys
import tarfile
import time
from pathlib import Path

import numpy as np

import udm1

N = 1 << 20


def aligned(a: np.ndarray) -> np.ndarray:
    """A copy of a whose data starts on a 64-byte boundary, as FastNoiseSIMD's own coordinate arrays
    (numpy's start on 16 bytes, and a 512-bit load from there straddles two cache lines)."""
    raw = np.empty(a.nbytes + 64, dtype=np.uint8)
    start = -raw.ctypes.data % 64
    out = raw[start:start + a.nbytes].view(a.dtype).reshape(a.shape)
    out[...] = a
    return out


def coords(d: int) -> np.ndarray:
    """(d, N) float32: the same points for every method (float64 methods read them widened), each axis
    on a 64-byte boundary (N floats are a multiple of 64 bytes)."""
    return aligned(np.random.default_rng(d).uniform(-100, 100, (d, N)).astype(np.float32))


CLOCK = time.perf_counter  # --clock cpu: time.process_time (the process's processor time, all its threads)


def best_interleaved(fs, reps):
    """Best time of each function over reps rounds, the functions alternating within a round; each timed
    call right after an untimed call of the same function, so that none pays for the one before it (on an
    Intel Xeon an AVX-512 kernel timed right after FastNoise Lite's scalar loop took 1.4x its time: the
    core's power state for wide vectors)."""
    best = [float("inf")] * len(fs)
    for _ in range(reps):
        for k, f in enumerate(fs):
            f()
            t0 = CLOCK()
            f()
            best[k] = min(best[k], CLOCK() - t0)
    return best


GROUPS = [("Perlin 2D", 2), ("Perlin 3D", 3), ("cellular 3D", 3)]


def udm1_methods(group: str, d: int):
    """(label, function) for udm1 in a group."""
    c = coords(d)
    c32 = tuple(c[k] for k in range(d))
    c64 = tuple(aligned(c[k].astype(np.float64)) for k in range(d))
    ours = udm1.Noise()
    if group.startswith("cellular"):
        return [("udm1 cellular F1, jitter 0.45, float32", lambda: ours.cellular(c32, jitter=0.45)),
                ("udm1 cellular F1, jitter 1, float32", lambda: ours.cellular(c32, jitter=1.0)),
                ("udm1 cellular F1, jitter 0.45, float64", lambda: ours.cellular(c64, jitter=0.45))]
    return [(f"udm1 improved noise {d}D, float32", lambda: ours.noise(c32)),
            (f"udm1 improved noise {d}D, float32, value and gradient", lambda: ours.noise(c32, gradient=True)),
            (f"udm1 improved noise {d}D, float64", lambda: ours.noise(c64))]


ROOT = Path(__file__).resolve().parent.parent
FNS_VERSION = "0.4.2"


def fastnoisesimd_build(build: Path, level: str, installed: bool = False) -> Path | None:
    """pyfastnoisesimd built from its PyPI sdist with its kernels up to `level` ("native": all that its
    setup compiles; "avx2": --with-avx512=no) into build/bench_noise/fastnoisesimd-LEVEL/lib, reused once
    built: the folder to put on sys.path, or None (with the reason on stderr) where it cannot be built."""
    if installed and level == "native":  # the installed wheel, as it is (--installed-anchor: no build)
        if importlib.util.find_spec("pyfastnoisesimd") is not None:
            return Path()
        print("bench_noise: pyfastnoisesimd is not installed (--installed-anchor: no build)", file=sys.stderr)
        return None
    top = build / "bench_noise" / f"fastnoisesimd-{level}"
    lib = top / "lib"
    if list(lib.glob("pyfastnoisesimd/extension*.so")):
        return lib
    sdist = build / "bench_noise" / "sdist"
    try:
        if not list(sdist.glob(f"pyfastnoisesimd-{FNS_VERSION}.tar.gz")):
            subprocess.run([sys.executable, "-m", "pip", "download", "-q", "--disable-pip-version-check", "--no-deps",
                            "--no-binary", ":all:", "-d", str(sdist), f"pyfastnoisesimd=={FNS_VERSION}"], check=True)
        src = top / "src"
        shutil.rmtree(src, ignore_errors=True)
        src.mkdir(parents=True)
        with tarfile.open(sdist / f"pyfastnoisesimd-{FNS_VERSION}.tar.gz") as t:
            t.extractall(src)
        import numpy
        env = dict(os.environ, CFLAGS=f"-I{numpy.get_include()}")
        cap = ["--with-avx512=no"] if level == "avx2" else []
        print(f"bench_noise: building FastNoiseSIMD {FNS_VERSION} ({level}) into {top}", file=sys.stderr)
        subprocess.run([sys.executable, "setup.py", "-q", "build", *cap, "--build-base", str(top / "tmp"),
                        "--build-lib", str(lib)], cwd=src / f"pyfastnoisesimd-{FNS_VERSION}", env=env, check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    except (subprocess.CalledProcessError, OSError, tarfile.TarError) as e:
        print(f"bench_noise: FastNoiseSIMD ({level}) could not be built: {e}", file=sys.stderr)
        return None
    return lib if list(lib.glob("pyfastnoisesimd/extension*.so")) else None


def udm1_isa() -> str:
    from udm1 import _native
    _native.lib.udm1_isa.restype = ctypes.c_char_p
    return _native.lib.udm1_isa().decode()


def level_rows(level: str, reps: int) -> list:
    """This process's rows: FastNoiseSIMD (from sys.path), FastNoise Lite and udm1 alternating."""
    try:
        import pyfastnoisesimd as fns
    except ImportError:
        fns = None
    try:
        from pyfastnoiselite.pyfastnoiselite import FastNoiseLite, FractalType, NoiseType
    except ImportError:
        FastNoiseLite = None
    isa = udm1_isa()
    fns_isa = fns.extension.SIMD_LEVEL if fns is not None else ""
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
            methods.append((f"{name}, {fns_isa} (anchor)", lambda simd=simd, c3=c3: simd.genFromCoords(c3)))
        if FastNoiseLite:
            lite = FastNoiseLite(seed=1)
            lite.noise_type = NoiseType.NoiseType_Cellular if cellular else NoiseType.NoiseType_Perlin
            lite.frequency = 1.0
            lite.fractal_type = FractalType.FractalType_None
            cl = np.ascontiguousarray(c)
            label = f"FastNoise Lite {'cellular (its defaults)' if cellular else 'Perlin'} {d}D"
            methods.append((label + ("" if methods else " (anchor)"), lambda lite=lite, cl=cl: lite.gen_from_coords(cl)))
        methods += [(f"{label}, {isa}", f) for label, f in udm1_methods(group, d)]
        times = best_interleaved([f for _, f in methods], reps)
        for (label, _), t in zip(methods, times):
            rows.append({"level": level, "group": group, "method": label, "seconds": t, "rate": N / t,
                         "x_anchor": times[0] / t, "anchor": methods[0][0], "udm1_isa": isa, "fastnoisesimd_isa": fns_isa})
    return rows


def run_level(level: str, build: Path, reps: int, installed: bool = False, clock: str = "wall") -> list:
    """level_rows in a child process: UDM1_ISA and FastNoiseSIMD's build for the level."""
    env = dict(os.environ)
    env.pop("UDM1_ISA", None)
    if level != "native":
        env["UDM1_ISA"] = level
    lib = fastnoisesimd_build(build, level, installed)
    if lib is None:
        print(f"bench_noise: no FastNoiseSIMD at {level}: FastNoise Lite is the anchor of those rows", file=sys.stderr)
    elif lib != Path():
        env["PYTHONPATH"] = os.pathsep.join([str(lib)] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    r = subprocess.run([sys.executable, __file__, "--child", level, "--reps", str(reps), "--clock", clock], env=env,
                       capture_output=True, text=True)
    if r.returncode != 0:
        sys.stderr.write(r.stderr)
        raise SystemExit(f"bench_noise: the {level} process failed")
    return json.loads(r.stdout)


def summary(rows: list) -> list:
    """The ratios the targets read, per level."""
    out = []
    for level in dict.fromkeys(r["level"] for r in rows):
        rs = [r for r in rows if r["level"] == level]

        def rate(group, needle):
            m = [r for r in rs if r["group"] == group and needle in r["method"] and "anchor" not in r["method"]
                 and r["method"].startswith("udm1")]
            return m[0] if m else None

        for d in (2, 3):
            g = f"Perlin {d}D"
            v, vg = rate(g, f"{d}D, float32,"), rate(g, "value and gradient")
            f64 = rate(g, "float64")
            if v and vg and f64:
                out.append(f"{level}: Perlin {d}D float32 {v['x_anchor']:.2f}x, value and gradient "
                           f"{v['rate'] / vg['rate']:.2f}x the value-only cost, float64 {f64['x_anchor']:.2f}x")
        f32, f64 = rate("cellular 3D", "jitter 0.45, float32"), rate("cellular 3D", "jitter 0.45, float64")
        if f32 and f64:
            out.append(f"{level}: cellular F1 float32 {f32['x_anchor']:.2f}x, float64 {f64['x_anchor']:.2f}x")
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--reps", type=int, default=9)
    ap.add_argument("--json", default="")
    ap.add_argument("--levels", default="native,avx2", help="comma-separated: native, avx2, baseline")
    ap.add_argument("--build", default=str(ROOT / "build"), help="where FastNoiseSIMD's builds go")
    ap.add_argument("--installed-anchor", action="store_true",
                    help="native level: the installed pyfastnoisesimd wheel, no build (FastNoise Lite where it is not "
                         "installed; for quick runs and tests: the "
                         "wheel measured slower than its sdist built here, so not the anchor of quoted figures)")
    ap.add_argument("--build-only", action="store_true",
                    help="only build FastNoiseSIMD for --levels (reused once built) and print where each is, or why "
                         "it is not (the main report builds it beside other work, before its timed noise step)")
    ap.add_argument("--clock", choices=("wall", "cpu"), default="wall",
                    help="cpu: each call timed by the process's processor time, not the wall clock (on a machine "
                         "shared with other jobs, time waiting for a core is not counted)")
    ap.add_argument("--child", default="", help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    global CLOCK
    CLOCK = time.process_time if args.clock == "cpu" else time.perf_counter
    if args.child:
        print(json.dumps(level_rows(args.child, args.reps)))
        return 0
    if args.build_only:
        for level in args.levels.split(","):
            lib = fastnoisesimd_build(Path(args.build), level, args.installed_anchor)
            print(f"{level}: {lib if lib is not None else 'not built (FastNoise Lite is the anchor of its rows)'}")
        return 0
    rows = []
    for level in args.levels.split(","):
        rows += run_level(level, Path(args.build), args.reps, args.installed_anchor, args.clock)
    print(f"{'level':<8} {'group':<12} {'method':<70} {'evals/s':>10} {'x anchor':>9}")
    for r in rows:
        print(f"{r['level']:<8} {r['group']:<12} {r['method']:<70} {r['rate']:10.4g} {r['x_anchor']:9.2f}")
    for line in summary(rows):
        print(line)
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rows": rows, "n": N, "reps": args.reps}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
