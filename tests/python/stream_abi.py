"""The ctypes mirror of udm1_stream (udm1/stream.h) and udm1_domain (udm1/domain.h) for the tests: the
structs, the library's fill functions' prototypes, and the domains' key derivation (the header's inline
functions, which ctypes cannot call), written out from the header's documentation."""

import ctypes

from udm1._native import lib

M32, M64 = (1 << 32) - 1, (1 << 64) - 1
DIMS = 64  # UDM1_STREAM_DIMS
DIMENSION_INDEX_LIMIT = M32  # UDM1_DIMENSION_INDEX_LIMIT
GOLDEN_GAMMA = 0x9E3779B97F4A7C15


class Stream(ctypes.Structure):
    _fields_ = [("struct_size", ctypes.c_uint32), ("flags", ctypes.c_uint32), ("seq", ctypes.c_void_p),
                ("stream", ctypes.c_uint64), ("key", ctypes.c_uint64), ("index_base", ctypes.c_uint64),
                ("point_count", ctypes.c_uint64), ("first", ctypes.c_uint32), ("count", ctypes.c_uint32),
                ("held", ctypes.c_uint32), ("dimensions", ctypes.c_uint32), ("a_hi", ctypes.c_uint64 * DIMS),
                ("a_lo", ctypes.c_uint64 * DIMS), ("offset", ctypes.c_uint64 * DIMS),
                ("base", ctypes.c_uint64 * DIMS), ("dim_key", ctypes.c_uint64 * DIMS),
                ("table", ctypes.c_void_p), ("table_bits", ctypes.c_uint32), ("table_mode", ctypes.c_uint32)]


class Domain(ctypes.Structure):
    _fields_ = [("stream", ctypes.POINTER(Stream)), ("key", ctypes.c_uint64), ("index", ctypes.c_uint64),
                ("dim", ctypes.c_uint32), ("reserved", ctypes.c_uint32)]


lib.udm1_stream_init.argtypes = [ctypes.POINTER(Stream), ctypes.c_void_p, ctypes.c_uint64, ctypes.c_uint32,
                                 ctypes.c_uint32]
lib.udm1_stream_fill_raw.argtypes = [ctypes.POINTER(Stream), ctypes.c_uint64, ctypes.c_uint32, ctypes.c_uint32,
                                     ctypes.POINTER(ctypes.c_uint64)]
lib.udm1_stream_fill_f32.argtypes = [ctypes.POINTER(Stream), ctypes.c_uint64, ctypes.c_uint32, ctypes.c_uint32,
                                     ctypes.POINTER(ctypes.c_float)]
lib.udm1_domain_fill_raw.argtypes = [ctypes.POINTER(Domain), ctypes.c_uint32, ctypes.POINTER(ctypes.c_uint64)]
lib.udm1_domain_fill_f32.argtypes = [ctypes.POINTER(Domain), ctypes.c_uint32, ctypes.POINTER(ctypes.c_float)]
for _name in ("udm1_stream_init", "udm1_stream_fill_raw", "udm1_stream_fill_f32", "udm1_domain_fill_raw",
              "udm1_domain_fill_f32"):
    getattr(lib, _name).restype = ctypes.c_int


def mix64(z: int) -> int:
    z &= M64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & M64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & M64
    return z ^ (z >> 31)


def child_key(parent_key: int, parent_dim: int, stream_key: int, key: int) -> int:
    """udm1_domain_child's key: mix64(K + dim + (key + 1) G), K the parent's key (the stream's for the
    root's chain), never 0."""
    base = ((parent_key or stream_key) + parent_dim) & M64
    k = mix64(base + ((key + 1) * GOLDEN_GAMMA & M64))
    return k or GOLDEN_GAMMA
