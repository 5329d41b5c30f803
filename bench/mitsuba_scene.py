"""Build a scene exported by `udm1-pt export DIR` in Mitsuba 3 (PyPI `mitsuba`; the variant set by the
caller, scalar_rgb when none is), so that udm1-pt and Mitsuba render one parse of the same file.

How the scenes are matched: the same triangles (world-space PLY files written by udm1-pt,
face normals, the winding pbrt's emitting side implies), the same spheres, the same RGB
reflectances (diffuse only) and area-light radiance (L * scale, one- or two-sided), the same
camera (eye, target, up; fov along the shorter axis), a box pixel filter, and Mitsuba's path
integrator with max_depth = pbrt's maxdepth + 1 (Mitsuba counts the camera segment). pbrt's
camera space is left-handed, Mitsuba's right-handed: the sensor is mirrored in x so that the
images line up pixel for pixel.

    python bench/mitsuba_scene.py DIR --spp 64 -o mitsuba.exr   (prints the mean RGB and the time)
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path


def load(dir: str | Path, spp: int = 16, sampler: str = "independent", seed: int = 0):
    import mitsuba as mi

    if mi.variant() is None:
        mi.set_variant("scalar_rgb")
    d = Path(dir)
    js = json.loads((d / "scene.json").read_text())
    cam = js["camera"]
    T = mi.ScalarTransform4f
    to_world = T().look_at(origin=cam["eye"], target=cam["target"], up=cam["up"])
    if cam.get("world_from_camera_determinant", 1) > 0:
        to_world = to_world @ T().scale([-1, 1, 1])  # pbrt's left-handed camera: x to the right
    scene = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": js["maxdepth"] + 1},
        "sensor": {
            "type": "perspective", "fov": cam["fov"], "fov_axis": cam["fov_axis"], "to_world": to_world,
            "film": {"type": "hdrfilm", "width": js["width"], "height": js["height"], "rfilter": {"type": "box"},
                     "pixel_format": "rgb"},
            "sampler": {"type": sampler, "sample_count": spp, "seed": seed},
        },
    }
    for k, s in enumerate(js["shapes"]):
        if "sphere" in s:
            sp = s["sphere"]
            shape = {"type": "sphere", "center": sp["center"], "radius": sp["radius"], "flip_normals": sp["flip_normals"]}
        else:
            shape = {"type": "ply", "filename": str(d / s["ply"]), "face_normals": True}
        m = s.get("material", {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]})
        if m["type"] != "diffuse":
            raise ValueError(f"shape {k}: material '{m['type']}' has no Mitsuba counterpart here (diffuse only)")
        # pbrt's diffuse reflects on both sides; Mitsuba's on the front side only
        shape["bsdf"] = {"type": "twosided", "bsdf": {"type": "diffuse",
                                                      "reflectance": {"type": "rgb", "value": m.get("reflectance", [0.5] * 3)}}}
        if "emission" in s:
            e = s["emission"]
            shape["emitter"] = {"type": "area", "radiance": {"type": "rgb", "value": e["L"]}}
            if e["twosided"]:
                # Mitsuba's area emitter is one-sided: a two-sided light is a second, flipped copy that only emits
                back = {k2: v for k2, v in shape.items() if k2 != "bsdf"}
                back["flip_normals"] = not shape.get("flip_normals", False)
                back["bsdf"] = {"type": "null"}
                scene[f"shape{k}_back"] = back
        scene[f"shape{k}"] = shape
    return mi.load_dict(scene)


def render(dir, spp: int, sampler: str = "independent", seed: int = 0, counts: list | None = None):
    """Render; return (linear RGB image as a numpy array, seconds of mi.render). Some samplers take
    another sample count than asked (orthogonal: the square of a prime at or above it); the count
    rendered is appended to `counts` when given."""
    import mitsuba as mi
    import numpy as np

    import drjit as dr

    scene = load(dir, spp, sampler, seed)
    n = scene.sensors()[0].sampler().sample_count()
    t0 = time.perf_counter()
    img = mi.render(scene, spp=n, seed=seed)
    dr.eval(img)  # the JIT variants (llvm_*) return a lazy image: the render ends when it is evaluated
    dr.sync_thread()
    seconds = time.perf_counter() - t0
    if counts is not None:
        counts.append(n)
    return np.array(img, dtype=np.float64)[..., :3], seconds


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("dir")
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--sampler", default="independent")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("-o", dest="output")
    args = ap.parse_args(argv)
    counts: list = []
    img, seconds = render(args.dir, args.spp, args.sampler, args.seed, counts)
    mean = img.reshape(-1, 3).mean(axis=0)
    print(f"mitsuba {args.sampler} spp {counts[0]} seconds {seconds:.4f} mean {mean[0]:.6g} {mean[1]:.6g} {mean[2]:.6g}")
    if args.output:
        import mitsuba as mi

        mi.util.write_bitmap(args.output, img.astype("float32"), write_async=False)
    return 0


if __name__ == "__main__":
    sys.exit(main())
