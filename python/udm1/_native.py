"""Loading libudm1 with ctypes and declaring its C functions.

The shared library is looked for, in order:

1. the path in the environment variable ``UDM1_LIBRARY`` (nothing else is
   tried when it is set);
2. this package's own directory: the copy a wheel or ``pip install`` put
   there (``udm1/libudm1.so.1``);
3. the build trees of a source checkout (``build/libudm1``, then
   ``build-asan/libudm1``, relative to the repository that holds this package);
4. the system's library path (``ctypes.util.find_library("udm1")``).
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
from pathlib import Path

ABI_MAJOR = 1
ABI_MINOR = 11  # the oldest libudm1 1.x with every function this package binds (udm1_lattice_bound_*)

u8p = ctypes.POINTER(ctypes.c_uint8)
u64p = ctypes.POINTER(ctypes.c_uint64)
f64p = ctypes.POINTER(ctypes.c_double)
f32p = ctypes.POINTER(ctypes.c_float)


class SeqDesc(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("dimensions", ctypes.c_uint32),
        ("preset", ctypes.c_char_p),
        ("alphas", ctypes.c_void_p),
        ("offsets", u64p),
        ("point_count", ctypes.c_uint64),
        ("seed", ctypes.c_uint64),
        ("randomize", ctypes.c_uint32),
        ("screen_spp", ctypes.c_uint32),
    ]


class Alpha(ctypes.Structure):
    _fields_ = [
        ("kind", ctypes.c_uint32),
        ("reserved", ctypes.c_uint32),
        ("k", ctypes.c_uint64),
        ("fixed_hi", ctypes.c_uint64),
        ("fixed_lo", ctypes.c_uint64),
        ("value", ctypes.c_double),
    ]


class PresetInfo(ctypes.Structure):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("description", ctypes.c_char_p),
        ("max_dimensions", ctypes.c_uint32),
        ("flags", ctypes.c_uint32),
    ]


class AlphaReport(ctypes.Structure):
    _fields_ = [
        ("rational", ctypes.c_uint32),
        ("rational_dim", ctypes.c_uint32),
        ("dependent", ctypes.c_uint32),
        ("dependent_exact", ctypes.c_uint32),
        ("dependent_dims", ctypes.c_uint32 * 2),
        ("worst_dims", ctypes.c_uint32 * 2),
        ("worst_l2_star", ctypes.c_double),
        ("worst_wrap_around", ctypes.c_double),
        ("random_l2_star", ctypes.c_double),
        ("random_wrap_around", ctypes.c_double),
        ("message", ctypes.c_char * 256),
    ]


class Cursor(ctypes.Structure):
    _fields_ = [
        ("seq", ctypes.c_void_p),
        ("stream", ctypes.c_uint64),
        ("index", ctypes.c_uint64),
        ("key", ctypes.c_uint64),
        ("dimension", ctypes.c_uint32),
        ("padded", ctypes.c_uint32),
    ]


class NoiseDesc(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("kind", ctypes.c_uint32),
        ("table", ctypes.c_char_p),
        ("seed", ctypes.c_uint64),
        ("period", ctypes.c_uint32 * 3),
        ("reserved", ctypes.c_uint32),
        ("period_w", ctypes.c_uint32),
        ("reserved_w", ctypes.c_uint32),
    ]


class PatternParams(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("pattern", ctypes.c_uint32),
        ("octaves", ctypes.c_uint32),
        ("wave", ctypes.c_uint32),
        ("omega", ctypes.c_double),
        ("lambda_", ctypes.c_double),
        ("turbulence", ctypes.c_double * 3),
        ("frequency", ctypes.c_double),
        ("phase", ctypes.c_double),
        ("exponent", ctypes.c_double),
        ("agate_turb", ctypes.c_double),
        ("crackle_form", ctypes.c_double * 3),
        ("crackle_metric", ctypes.c_double),
        ("crackle_offset", ctypes.c_double),
        ("crackle_solid", ctypes.c_uint32),
        ("reserved", ctypes.c_uint32),
    ]


class CellularParams(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("metric", ctypes.c_uint32),
        ("output", ctypes.c_uint32),
        ("reserved", ctypes.c_uint32),
        ("jitter", ctypes.c_double),
        ("exponent", ctypes.c_double),
    ]


STATUS_NAMES = {
    0: "UDM1_OK",
    1: "UDM1_ERROR_NULL_ARGUMENT",
    2: "UDM1_ERROR_INVALID_ARGUMENT",
    3: "UDM1_ERROR_DIMENSION",
    4: "UDM1_ERROR_UNKNOWN_PRESET",
    5: "UDM1_ERROR_RATIONAL_ALPHA",
    6: "UDM1_ERROR_POINT_COUNT",
    7: "UDM1_ERROR_INDEX_RANGE",
    8: "UDM1_ERROR_OUT_OF_MEMORY",
}


def _candidates():
    env = os.environ.get("UDM1_LIBRARY")
    if env:
        yield env
        return
    here = Path(__file__).resolve().parent
    yield str(here / "libudm1.so.1")
    repo = here.parent.parent
    for build in ("build", "build-asan"):
        yield str(repo / build / "libudm1" / "libudm1.so.1")
    found = ctypes.util.find_library("udm1")
    if found:
        yield found


def _load():
    tried = []
    for path in _candidates():
        if os.path.sep in path and not os.path.exists(path):
            tried.append(f"{path} (missing)")
            continue
        try:
            lib = ctypes.CDLL(path)
        except OSError as exc:
            tried.append(f"{path} ({exc})")
            continue
        lib.udm1_version.restype = ctypes.c_uint32
        version = lib.udm1_version()
        major, minor = version // 10000, version // 100 % 100
        if major != ABI_MAJOR or minor < ABI_MINOR:
            tried.append(f"{path} (libudm1 {major}.{minor}, need {ABI_MAJOR}.{ABI_MINOR} or a later {ABI_MAJOR}.x)")
            continue
        return lib, path
    raise ImportError(
        "udm1: cannot load libudm1; install the package (pip install .), build it (cmake --build build) or set "
        "UDM1_LIBRARY. Tried: "
        + "; ".join(tried)
    )


lib, library_path = _load()

_S = ctypes.c_int  # udm1_status
_SEQ = ctypes.c_void_p


def _proto(name, restype, *argtypes):
    fn = getattr(lib, name)
    fn.restype = restype
    fn.argtypes = list(argtypes)


_proto("udm1_version_string", ctypes.c_char_p)
_proto("udm1_status_string", ctypes.c_char_p, _S)
_proto("udm1_last_error", ctypes.c_char_p)
_proto("udm1_preset_count", ctypes.c_size_t)
_proto("udm1_preset_get", _S, ctypes.c_size_t, ctypes.POINTER(PresetInfo))
_proto("udm1_preset_find", _S, ctypes.c_char_p, ctypes.POINTER(PresetInfo))
_proto("udm1_seq_desc_init", None, ctypes.POINTER(SeqDesc))
_proto("udm1_seq_create_desc", _S, ctypes.POINTER(SeqDesc), ctypes.POINTER(_SEQ))
_proto("udm1_seq_create", _S, ctypes.c_char_p, ctypes.c_uint32, ctypes.c_uint64, ctypes.c_uint64, ctypes.POINTER(_SEQ))
_proto("udm1_seq_destroy", None, _SEQ)
_proto("udm1_seq_dimensions", ctypes.c_uint32, _SEQ)
_proto("udm1_seq_name", ctypes.c_char_p, _SEQ)
_proto("udm1_seq_point_count", ctypes.c_uint64, _SEQ)
_proto("udm1_seq_seed", ctypes.c_uint64, _SEQ)
_proto("udm1_seq_randomize", ctypes.c_uint32, _SEQ)
_proto("udm1_seq_randomization", ctypes.c_uint32, _SEQ)
_proto("udm1_seq_flags", ctypes.c_uint32, _SEQ)
_proto("udm1_seq_alpha", _S, _SEQ, ctypes.c_uint32, u64p, u64p)
_proto("udm1_seq_offset", _S, _SEQ, ctypes.c_uint64, ctypes.c_uint32, u64p)
_proto("udm1_seq_sample_u64", _S, _SEQ, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_uint32, u64p)
_proto("udm1_seq_sample_f64", _S, _SEQ, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_uint32, f64p)
_proto("udm1_seq_sample_f32", _S, _SEQ, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_uint32, f32p)
_proto("udm1_seq_fill_points_f64", _S, _SEQ, ctypes.c_size_t, u64p, u64p, ctypes.c_uint32, ctypes.c_uint32, f64p)
for _suffix, _ptr in (("u64", ctypes.c_void_p), ("f64", ctypes.c_void_p), ("f32", ctypes.c_void_p)):
    _proto(
        f"udm1_seq_fill_{_suffix}", _S, _SEQ, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_size_t,
        ctypes.c_uint32, ctypes.c_uint32, _ptr, ctypes.c_size_t,
    )
_proto("udm1_cursor_start", _S, ctypes.POINTER(Cursor), _SEQ, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_uint32)
_proto("udm1_cursor_1d_f64", ctypes.c_double, ctypes.POINTER(Cursor))
_proto("udm1_cursor_1d", ctypes.c_float, ctypes.POINTER(Cursor))
_proto("udm1_cursor_fill", None, ctypes.POINTER(Cursor), ctypes.c_uint32, f32p)
_proto("udm1_cursor_padded", ctypes.c_uint32, ctypes.POINTER(Cursor))
_proto("udm1_discrepancy", _S, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_uint32, ctypes.c_size_t, ctypes.c_uint32, f64p)
_proto("udm1_discrepancy_random", _S, ctypes.c_size_t, ctypes.c_uint32, ctypes.c_uint32, f64p)
_proto("udm1_seq_check", _S, _SEQ, ctypes.c_uint64, ctypes.POINTER(AlphaReport))
_proto("udm1_star_discrepancy_2d", _S, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t, f64p)
_proto("udm1_min_distance", _S, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_uint32, ctypes.c_size_t, ctypes.c_int, f64p)
_proto("udm1_integrand_name", ctypes.c_char_p, ctypes.c_uint32)
_proto("udm1_integrand_eval", _S, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t,
       ctypes.c_void_p)
_proto("udm1_integrand_exact", _S, ctypes.c_uint32, ctypes.c_uint32, f64p)
_proto("udm1_exact_sum_add", _S, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_void_p)  # addresses: no cast per call
EXACT_SUM_WORDS = 36  # UDM1_EXACT_SUM_WORDS
_proto("udm1_lattice_bound_create", _S, ctypes.c_uint32, ctypes.c_double, ctypes.c_uint64, ctypes.POINTER(ctypes.c_void_p))
_proto("udm1_lattice_bound_destroy", None, ctypes.c_void_p)
_proto("udm1_lattice_bound_reset", None, ctypes.c_void_p)
_proto("udm1_lattice_bound_add", _S, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_uint64)
_proto("udm1_lattice_bound_points", ctypes.c_uint64, ctypes.c_void_p)
_proto("udm1_lattice_bound_error", _S, ctypes.c_void_p, f64p)
_proto("udm1_lattice_bound_coefficients", _S, ctypes.c_void_p, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_void_p)
_proto("udm1_lattice_bound_order", _S, ctypes.c_void_p, ctypes.c_uint64, ctypes.c_uint64, ctypes.c_void_p)
_proto("udm1_integration_error", _S, _SEQ, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_uint64, ctypes.c_uint32, f64p, f64p)
_proto("udm1_spectrum_2d", _S, _SEQ, ctypes.c_uint32, ctypes.c_uint64, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_void_p)
_proto("udm1_zoneplate", _S, _SEQ, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_uint32, ctypes.c_void_p)
_proto("udm1_alpha_check", _S, ctypes.c_void_p, ctypes.c_uint32, ctypes.c_uint64, ctypes.POINTER(AlphaReport))
_proto("udm1_noise_desc_init", None, ctypes.POINTER(NoiseDesc))
_proto("udm1_noise_create", _S, ctypes.POINTER(NoiseDesc), ctypes.POINTER(ctypes.c_void_p))
_proto("udm1_noise_destroy", None, ctypes.c_void_p)
_proto("udm1_noise_tables", _S, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p)
_proto("udm1_noise_points", _S, ctypes.c_void_p, ctypes.c_uint32, ctypes.c_void_p, ctypes.c_size_t, ctypes.c_size_t,
       ctypes.c_void_p)
_proto("udm1_noise_3d", ctypes.c_double, ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_double)
_proto("udm1_noise_eval", _S, ctypes.c_void_p, ctypes.c_uint32, ctypes.POINTER(ctypes.c_void_p), ctypes.c_size_t,
       ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p)
_proto("udm1_noise_eval_f32", _S, ctypes.c_void_p, ctypes.c_uint32, ctypes.POINTER(ctypes.c_void_p), ctypes.c_size_t,
       ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p)
_proto("udm1_cellular_params_init", None, ctypes.POINTER(CellularParams))
_proto("udm1_cellular_eval", _S, ctypes.c_void_p, ctypes.POINTER(CellularParams), ctypes.c_uint32,
       ctypes.POINTER(ctypes.c_void_p), ctypes.c_size_t, ctypes.c_size_t, ctypes.c_void_p)
_proto("udm1_cellular_eval_f32", _S, ctypes.c_void_p, ctypes.POINTER(CellularParams), ctypes.c_uint32,
       ctypes.POINTER(ctypes.c_void_p), ctypes.c_size_t, ctypes.c_size_t, ctypes.c_void_p)
_proto("udm1_cellular_offsets", _S, ctypes.c_void_p, ctypes.c_void_p)
_proto("udm1_pattern_params_init", None, ctypes.POINTER(PatternParams), ctypes.c_uint32)
_proto("udm1_pattern_name", ctypes.c_char_p, ctypes.c_uint32)
_proto("udm1_pattern_from_name", ctypes.c_uint32, ctypes.c_char_p)
_proto("udm1_pattern_points", _S, ctypes.c_void_p, ctypes.POINTER(PatternParams), ctypes.c_void_p, ctypes.c_size_t,
       ctypes.c_size_t, ctypes.c_void_p)
_proto("udm1_pattern_gradient", _S, ctypes.c_void_p, ctypes.POINTER(PatternParams), ctypes.c_void_p, ctypes.c_size_t,
       ctypes.c_size_t, ctypes.c_void_p, ctypes.c_void_p)
_proto("udm1_pattern_grid", _S, ctypes.c_void_p, ctypes.POINTER(PatternParams), ctypes.c_uint32, ctypes.c_uint32,
       ctypes.c_uint32, ctypes.c_uint32, ctypes.POINTER(ctypes.c_double), ctypes.POINTER(ctypes.c_double),
       ctypes.POINTER(ctypes.c_double), ctypes.c_void_p)
