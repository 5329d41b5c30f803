"""udm1: exact Weyl/Kronecker (uniformly distributed modulo 1) sampling.

Python bindings (ctypes) over libudm1. See ``udm1.Sequence`` for points as
numpy arrays, ``udm1.qmc`` for scipy.stats.qmc engines, ``udm1.discrepancy``,
``udm1.integrate`` (exactly summed estimates) and ``udm1.distributed`` (the same over a
Dask cluster, and AO / path-tracing renders split by sample ranges and tiles).
"""

from ._native import library_path
from .exact_sum import ExactSum
from .integrate import TRANSFORMS, Integral, ToleranceNotMet, ToleranceResult, integrate
from .metrics import (
    discrepancy,
    discrepancy_random,
    integrand,
    integrand_exact,
    integrands,
    min_distance,
    star_discrepancy,
)
from .noise import Noise, patterns
from .errors import UDM1Error
from .sequence import Fixed, Preset, Sequence, Sqrt, check_alphas, presets, version

__all__ = [
    "ExactSum",
    "Fixed",
    "Integral",
    "Noise",
    "Preset",
    "Sequence",
    "Sqrt",
    "UDM1Error",
    "check_alphas",
    "discrepancy",
    "discrepancy_random",
    "integrand",
    "integrate",
    "ToleranceNotMet",
    "ToleranceResult",
    "TRANSFORMS",
    "integrand_exact",
    "integrands",
    "min_distance",
    "patterns",
    "star_discrepancy",
    "library_path",
    "presets",
    "version",
]
__version__ = version()
