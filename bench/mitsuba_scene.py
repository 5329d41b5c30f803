"""Build a scene exported by `udm1-pt export DIR` in Mitsuba 3 (PyPI `mitsuba`; the variant set by the
caller, scalar_rgb when none is), so that udm1-pt and Mitsuba render one parse of the same file.

How the scenes are matched: the same triangles (world-space PLY files written by udm1-pt, with
their vertex normals where the mesh has them, else face normals; the winding pbrt's emitting side
implies), the same spheres, the same area-light radiance (L * scale, one- or two-sided), the same
camera (eye, target, up; fov along the shorter axis), a box pixel filter, and Mitsuba's path
integrator with max_depth = pbrt's maxdepth + 1 (Mitsuba counts the camera segment). pbrt's
camera space is left-handed, Mitsuba's right-handed: the sensor is mirrored in x so that the
images line up pixel for pixel.

Materials, pbrt-v4's by Mitsuba's nearest (RGB parameters, untextured): diffuse as a two-sided
diffuse; dielectric (one index) as dielectric or roughdielectric; conductor (RGB eta and k, or
pbrt-v4's named metal spectra, metal-Au-eta and the like, as Mitsuba's material of that name;
pbrt-v4's default copper) as conductor or roughconductor; coateddiffuse as plastic or roughplastic
(two-sided; Mitsuba's plastic is an analytic model where pbrt-v4's coated diffuse is a stochastic
random walk through its layers, so the two render alike but not equally: compare each renderer with
its own reference). Roughness becomes GGX alpha as pbrt-v4 makes it (sqrt(roughness) unless
remaproughness is false). Anything else (textures, mixes, bump maps, spectra given by samples,
anisotropic roughness) raises ValueError naming the shape and parameter: such a scene is not given
to Mitsuba.

    python bench/mitsuba_scene.py DIR --spp 64 -o mitsuba.exr   (prints the mean RGB and the time)
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import time
from pathlib import Path


def load(dir: str | Path, spp: int = 16, sampler: str | dict = "independent", seed: int = 0,
         size: tuple[int, int] | None = None):
    """The exported scene in Mitsuba: `sampler` a Mitsuba sampler's type or its whole dictionary (a plugin's
    parameters: udm1's takes the film's size); `size` (width, height) another film size than the file's, the
    camera's field of view along its axis kept."""
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
            "film": {"type": "hdrfilm", "width": (size or (js["width"], js["height"]))[0],
                     "height": (size or (js["width"], js["height"]))[1], "rfilter": {"type": "box"}, "pixel_format": "rgb"},
            "sampler": dict(sampler if isinstance(sampler, dict) else {"type": sampler}, sample_count=spp, seed=seed),
        },
    }
    for k, s in enumerate(js["shapes"]):
        if "sphere" in s:
            sp = s["sphere"]
            shape = {"type": "sphere", "center": sp["center"], "radius": sp["radius"], "flip_normals": sp["flip_normals"]}
        else:
            shape = {"type": "ply", "filename": str(d / s["ply"]), "face_normals": not s.get("normals", False)}
        shape["bsdf"] = bsdf_of(k, s.get("material", {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5]}))
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


# pbrt-v4's named metal spectra and Mitsuba's conductor materials of the same metal
METALS = {"Ag": "Ag", "Al": "Al", "Au": "Au", "Cu": "Cu", "CuZn": "CuZn", "MgO": "MgO", "TiO2": "TiO2"}


def bsdf_of(k: int, m: dict) -> dict:
    """Mitsuba's BSDF for pbrt-v4 material m of shape k (see the module's docstring)."""
    kind = m["type"]
    known = {"diffuse": {"reflectance"}, "coateddiffuse": {"reflectance", "roughness", "remaproughness", "eta",
                                                           "thickness", "maxdepth", "nsamples"},
             "dielectric": {"eta", "roughness", "remaproughness"},
             "conductor": {"eta", "k", "roughness", "remaproughness"}}
    if kind not in known:
        raise ValueError(f"shape {k}: material '{kind}' has no Mitsuba counterpart here")
    for name, value in m.items():
        if name == "type":
            continue
        if name not in known[kind] or isinstance(value, dict):
            raise ValueError(f"shape {k}: material '{kind}': parameter '{name}' = {value!r} has no Mitsuba counterpart here")

    def rgb(name, default):
        v = m.get(name, default)
        return {"type": "rgb", "value": [v] * 3 if isinstance(v, (int, float)) else v}

    def alpha():
        r = m.get("roughness", 0.0)
        return math.sqrt(r) if m.get("remaproughness", True) else r

    def index(default):
        e = m.get("eta", default)
        if not isinstance(e, (int, float)):
            raise ValueError(f"shape {k}: material '{kind}': eta {e!r} is not one index")
        return e

    a = alpha()
    if kind == "diffuse":  # pbrt's diffuse reflects on both sides; Mitsuba's on the front side only
        return {"type": "twosided", "bsdf": {"type": "diffuse", "reflectance": rgb("reflectance", 0.5)}}
    if kind == "coateddiffuse":
        b = {"type": "plastic" if a < 1e-3 else "roughplastic", "int_ior": index(1.5),
             "diffuse_reflectance": rgb("reflectance", 0.5)}
        if a >= 1e-3:
            b.update(distribution="ggx", alpha=a)
        return {"type": "twosided", "bsdf": b}
    if kind == "dielectric":
        b = {"type": "dielectric" if a < 1e-3 else "roughdielectric", "int_ior": index(1.5)}
        if a >= 1e-3:
            b.update(distribution="ggx", alpha=a)
        return b
    eta, kk = m.get("eta", "metal-Cu-eta"), m.get("k", "metal-Cu-k")  # pbrt-v4's default conductor: copper
    b = {"type": "conductor" if a < 1e-3 else "roughconductor"}
    if isinstance(eta, str) or isinstance(kk, str):
        metal = re.fullmatch(r"metal-(\w+)-eta", str(eta))
        if not metal or kk != f"metal-{metal.group(1)}-k" or metal.group(1) not in METALS:
            raise ValueError(f"shape {k}: conductor eta {eta!r}, k {kk!r}: not a metal Mitsuba names")
        b["material"] = METALS[metal.group(1)]
    else:
        b["eta"], b["k"] = rgb("eta", 1.0), rgb("k", 0.0)
    if a >= 1e-3:
        b.update(distribution="ggx", alpha=a)
    return {"type": "twosided", "bsdf": b}


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
