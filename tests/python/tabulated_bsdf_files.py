"""Tabulated BSDF files of known content, in the tensor-file format that pbrt-v4's Material "measured" reads
(RGL's tabulated BSDFs, Dupuy and Jakob 2018; the format: apps/scene/tabulated_bsdf.h), and damaged copies.

The BSDF tabulated is a rough conductor in closed form: Trowbridge-Reitz (GGX) normals of roughness alpha,
  ndf   D(m) = alpha^2 / (pi (cos^2 theta_m (alpha^2 - 1) + 1)^2)
  sigma sigma(w) = (cos theta + sqrt(cos^2 theta + alpha^2 sin^2 theta)) / 2   (the projected area, cos/G1)
  vndf  D(m) max(0, w . m) / sigma(w), tabulated per unit of the table's coordinates (x the sqrt(theta / (pi /
        2)) of the normal, y its azimuth relative to w's over 2 pi, plus 1/2), which multiplies the density
        per solid angle by 2 pi^2 x sin theta_m
  luminance uniform, spectra F(lambda) everywhere,
so that pbrt-v4's MeasuredBxDF, f = spectra D(m) / (4 sigma(wo) cos theta_i), is
  f(wo, wi) = F(lambda) D(m) / (4 sigma(wo) cos theta_i),   m the half vector,
exactly where the tables are (wo's elevation on a node of theta_i and of sigma's grid, m on a node of ndf's),
and within the bilinear interpolation's error between them. Its albedo is at most F (the visible normals'
density integrates to 1).

python tests/python/tabulated_bsdf_files.py OUT_DIR writes ggx_grey.bsdf (F 0.8 at every wavelength),
ggx_ramp.bsdf (F rising from 0.2 at 360 nm to 0.9 at 830 nm), ggx_sharp.bsdf (alpha 0.15) and
ggx_warped.bsdf (the ramp, and luminance and spectra varying over their square) and ggx_aniso.bsdf (anisotropic:
alpha 0.2 along the surface's dp/du, 0.6 across, ggx_aniso_fields) there.
"""

import struct
import sys
from pathlib import Path

import numpy as np

TYPES = {np.dtype(np.uint8): 1, np.dtype(np.int8): 2, np.dtype(np.uint16): 3, np.dtype(np.int16): 4,
         np.dtype(np.uint32): 5, np.dtype(np.int32): 6, np.dtype(np.uint64): 7, np.dtype(np.int64): 8,
         np.dtype(np.float16): 9, np.dtype(np.float32): 10, np.dtype(np.float64): 11}


def tensor_bytes(fields, magic=b"tensor_file\0", version=(1, 0)):
    """The tensor file of `fields` (name -> numpy array, or (name, array) pairs, in order): header, field records,
    then the data."""
    fields = list(fields.items()) if isinstance(fields, dict) else list(fields)
    head = magic + bytes(version) + struct.pack("<I", len(fields))
    records_size = sum(2 + len(name.encode()) + 2 + 1 + 8 + 8 * np.asarray(a).ndim for name, a in fields)
    offset = len(head) + records_size
    records, data = b"", b""
    for name, a in fields:
        a = np.ascontiguousarray(a)
        raw = a.astype(a.dtype.newbyteorder("<")).tobytes()
        records += struct.pack("<H", len(name.encode())) + name.encode() + struct.pack("<HBQ", a.ndim, TYPES[a.dtype],
                                                                                      offset + len(data))
        records += b"".join(struct.pack("<Q", s) for s in a.shape)
        data += raw
    return head + records + data


def u_to_theta(u):
    return np.asarray(u) ** 2 * (np.pi / 2)


def ggx_D(cos_m, alpha):
    return alpha ** 2 / (np.pi * (cos_m ** 2 * (alpha ** 2 - 1) + 1) ** 2)


def ggx_sigma(cos_o, alpha):
    return (cos_o + np.sqrt(cos_o ** 2 + alpha ** 2 * (1 - cos_o ** 2))) / 2


def ggx_fields(alpha=0.5, spectrum=None, n_theta_i=9, grid=33, square=8, warped=False):
    """The fields of the rough conductor (module docstring). theta_i on the nodes x = k / (n_theta_i - 1) of the
    tables' elevation coordinate, which are nodes of ndf's and sigma's grids too ((grid - 1) a multiple of
    n_theta_i - 1). spectrum: (wavelengths, values), default F 0.8 at 360 and 830 nm."""
    assert (grid - 1) % (n_theta_i - 1) == 0
    nm, F = spectrum if spectrum is not None else ([360.0, 830.0], [0.8, 0.8])
    # warped: luminance and the spectral factor vary over the square vndf warps (f is then not the closed form,
    # but sampling, evaluation and density must still agree: the inverse warp is exercised)
    theta_i = u_to_theta(np.linspace(0, 1, n_theta_i))
    x = np.linspace(0, 1, grid)                      # elevation coordinate
    y = np.linspace(0, 1, grid)                      # azimuth coordinate
    theta_m = u_to_theta(x)
    ndf = np.tile(ggx_D(np.cos(theta_m), alpha), (3, 1))             # [phi][theta], constant in phi
    sigma = np.tile(ggx_sigma(np.cos(theta_m), alpha), (3, 1))
    phi_m = (2 * y - 1) * np.pi
    tm, pm = np.meshgrid(theta_m, phi_m)            # [y][x]
    m = np.stack([np.sin(tm) * np.cos(pm), np.sin(tm) * np.sin(pm), np.cos(tm)], -1)
    vndf = np.empty((1, n_theta_i, grid, grid))
    for k, t in enumerate(theta_i):
        wo = np.array([np.sin(t), 0.0, np.cos(t)])
        vndf[0, k] = ggx_D(m[..., 2], alpha) * np.maximum(0, m @ wo) / ggx_sigma(np.cos(t), alpha) * \
            2 * np.pi ** 2 * np.meshgrid(x, y)[0] * np.sin(tm)
    luminance = np.ones((1, n_theta_i, square, square))
    spectra = np.broadcast_to(np.asarray(F, float)[None, None, :, None, None], (1, n_theta_i, len(nm), square, square))
    if warped:
        sx, sy = np.meshgrid(np.linspace(0, 1, square), np.linspace(0, 1, square))
        for k in range(n_theta_i):
            luminance[0, k] = 0.2 + np.exp(-((sx - 0.3) ** 2 + (sy - 0.6 + 0.02 * k) ** 2) / 0.05)
        spectra = spectra * (0.4 + 0.6 * sx * (1 - sy) + 0.1 * np.arange(n_theta_i)[None, :, None, None, None] / n_theta_i)
    f32 = np.float32
    return {
        "description": np.frombuffer(b"udm1 test: tabulated Trowbridge-Reitz conductor", np.uint8),
        "jacobian": np.array([1], np.uint8),
        "theta_i": theta_i.astype(f32), "phi_i": np.array([0.0], f32), "wavelengths": np.asarray(nm, f32),
        "ndf": ndf.astype(f32), "sigma": sigma.astype(f32), "vndf": vndf.astype(f32),
        "luminance": luminance.astype(f32), "spectra": spectra.astype(f32),
    }


def ggx_aniso_D(m, ax, ay):
    return 1 / (np.pi * ax * ay * (m[..., 0] ** 2 / ax ** 2 + m[..., 1] ** 2 / ay ** 2 + m[..., 2] ** 2) ** 2)


def ggx_aniso_sigma(w, ax, ay):
    return (w[..., 2] + np.sqrt(w[..., 2] ** 2 + ax ** 2 * w[..., 0] ** 2 + ay ** 2 * w[..., 1] ** 2)) / 2


def ggx_aniso_fields(ax=0.2, ay=0.6, n_phi_i=9, n_theta_i=9, grid=33, square=8, F=0.8):
    """The anisotropic rough conductor: Trowbridge-Reitz of roughness ax along the surface's x (pbrt-v4's dp/du)
    and ay along y, D(m) = 1 / (pi ax ay (m_x^2 / ax^2 + m_y^2 / ay^2 + m_z^2)^2), sigma(w) = (w_z + sqrt(w_z^2 +
    ax^2 w_x^2 + ay^2 w_y^2)) / 2, tabulated over absolute azimuths (phi_i over the whole circle, so pbrt-v4 reads
    it as anisotropic), F at every wavelength: f = F D(m) / (4 sigma(wo) cos theta_i), exact where wo's (phi,
    theta) is on a node of phi_i and theta_i and m on one of ndf's."""
    assert (grid - 1) % (n_theta_i - 1) == 0 and (grid - 1) % (n_phi_i - 1) == 0
    theta_i = u_to_theta(np.linspace(0, 1, n_theta_i))
    phi_i = (2 * np.linspace(0, 1, n_phi_i) - 1) * np.pi
    x = np.linspace(0, 1, grid)
    tm, pm = np.meshgrid(u_to_theta(x), (2 * np.linspace(0, 1, grid) - 1) * np.pi)  # [y][x]
    m = np.stack([np.sin(tm) * np.cos(pm), np.sin(tm) * np.sin(pm), np.cos(tm)], -1)
    vndf = np.empty((n_phi_i, n_theta_i, grid, grid))
    for j, p in enumerate(phi_i):
        for k, t in enumerate(theta_i):
            wo = np.array([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p), np.cos(t)])
            vndf[j, k] = ggx_aniso_D(m, ax, ay) * np.maximum(0, m @ wo) * 2 * np.pi ** 2 * np.meshgrid(x, x)[0] * np.sin(tm)
    f32 = np.float32
    return {
        "description": np.frombuffer(b"udm1 test: tabulated anisotropic Trowbridge-Reitz conductor", np.uint8),
        "jacobian": np.array([1], np.uint8),
        "theta_i": theta_i.astype(f32), "phi_i": phi_i.astype(f32), "wavelengths": np.array([360, 830], f32),
        "ndf": ggx_aniso_D(m, ax, ay).astype(f32), "sigma": ggx_aniso_sigma(m, ax, ay).astype(f32),
        "vndf": vndf.astype(f32), "luminance": np.ones((n_phi_i, n_theta_i, square, square), f32),
        "spectra": np.full((n_phi_i, n_theta_i, 2, square, square), F, f32),
    }


RAMP = (list(np.linspace(360, 830, 11)), list(np.linspace(0.2, 0.9, 11)))


def write_test_files(out):
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "ggx_grey.bsdf").write_bytes(tensor_bytes(ggx_fields()))
    (out / "ggx_ramp.bsdf").write_bytes(tensor_bytes(ggx_fields(spectrum=RAMP)))
    (out / "ggx_sharp.bsdf").write_bytes(tensor_bytes(ggx_fields(alpha=0.15, grid=65)))
    (out / "ggx_warped.bsdf").write_bytes(tensor_bytes(ggx_fields(spectrum=RAMP, warped=True)))
    (out / "ggx_aniso.bsdf").write_bytes(tensor_bytes(ggx_aniso_fields()))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: tabulated_bsdf_files.py OUT_DIR")
    write_test_files(sys.argv[1])
