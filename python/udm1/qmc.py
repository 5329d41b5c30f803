"""scipy.stats.qmc engines over udm1's sequences.

Each engine is a ``scipy.stats.qmc.QMCEngine``: ``random(n)``, ``reset()``,
``fast_forward(n)`` (O(1): any index is computed directly), and it works with
``qmc.discrepancy``, ``qmc.scale`` and ``scipy.integrate.qmc_quad``.

``scramble=True`` (the default, as in scipy) applies the preset's default
randomization (a random shift for the Weyl presets), keyed by a 64-bit seed
drawn from ``rng`` (an int, a numpy Generator, or a legacy RandomState given as
``seed=``); ``scramble=False`` gives the deterministic sequence, whose first
point is the origin. The engine's points are the library's, bit for bit: row k
of the engine's draws is point k of stream 0 of ``engine.sequence``, however the
draws are split over ``random`` calls, ``fast_forward`` and ``reset``. scipy's
``optimization`` (a post-processing that moves the points) would break that and
is refused; ``workers`` is accepted and not needed (the library fills the
points).

    >>> from udm1.qmc import WR
    >>> WR(2, seed=1).random(4).shape
    (4, 2)
"""

from __future__ import annotations

import numpy as np
from scipy.stats import qmc

from ._convert import U64, flag, integer, text, u32, u64
from .sequence import Sequence


def _random_key(rng) -> int:
    """A 64-bit key from a numpy Generator or a legacy RandomState."""
    if isinstance(rng, np.random.RandomState):
        return int(rng.randint(0, 2**64, dtype=np.uint64))
    return int(rng.integers(0, 2**64, dtype=np.uint64))


WHERE = "udm1.qmc"


class Weyl(qmc.QMCEngine):
    """A udm1 preset as a QMC engine. ``preset`` is any udm1 preset name;
    ``point_count`` is K for the point-set presets (epis, episwr)."""

    _preset: str | None = None  # fixed by the subclasses

    def __init__(self, d: int, *, preset: str = "wr", scramble: bool = True, point_count: int = 0,
                 optimization=None, rng=None, seed=None):
        d = u32(d, "d", where=WHERE)
        scramble = flag(scramble, "scramble", where=WHERE)
        point_count = u64(point_count, "point_count", where=WHERE)
        if optimization is not None:
            raise ValueError(f"{WHERE}: optimization {optimization!r} moves the points after they are drawn, so they "
                             f"would not be udm1's; only None is supported")
        if seed is not None and rng is not None:
            raise ValueError("udm1.qmc: give rng or seed, not both")
        for name, value in (("rng", rng), ("seed", seed)):
            if isinstance(value, (bool, np.bool_)):
                raise TypeError(f"{WHERE}: {name} must be an int, Generator or bit generator, not bool")
        if isinstance(rng, np.random.RandomState):
            raise TypeError("udm1.qmc: a legacy RandomState goes in seed= (as scipy's own engines take it), not rng=")
        try:
            if isinstance(seed, np.random.RandomState):  # scipy's legacy keyword, as its own engines take it
                super().__init__(d=d, optimization=optimization, seed=seed)
            else:  # an int or Generator given as seed= is taken as rng= (the same points for both)
                super().__init__(d=d, optimization=optimization, rng=seed if seed is not None else rng)
        except (TypeError, ValueError) as e:
            given = "seed" if seed is not None else "rng"
            detail = str(e).splitlines()[0] if str(e) else type(e).__name__
            raise type(e)(f"{WHERE}: {given} = {seed if seed is not None else rng!r} is not an int, Generator or "
                          f"bit generator ({detail})") from None
        self.preset = self._preset or text(preset, "preset", where=WHERE)
        self.scramble = scramble
        key = _random_key(self.rng) if scramble else 0
        self._seq = Sequence(self.preset, d, point_count=point_count, seed=key, randomize=self.scramble)
        self._init_quad = self._quad_args(d, point_count, optimization)

    def _quad_args(self, d, point_count, optimization) -> dict:
        args = {"d": d, "scramble": True, "optimization": optimization}
        if self._preset is None:
            args["preset"] = self.preset
            args["point_count"] = point_count
        return args

    def _end(self) -> int:
        """One past the last index that can be drawn: K of a point set, 2^64 for a sequence."""
        return self._seq.point_count or U64 + 1

    def random(self, n: int = 1, *, workers: int = 1) -> np.ndarray:
        """Points [num_generated, num_generated + n) of stream 0 of the sequence, as an (n, d) float64 array."""
        n = u64(n, "n", where=WHERE)
        integer(workers, "workers", -1, None, where=WHERE)  # scipy's convention; the library needs none
        sample = self._random(n)
        self.num_generated += n
        return sample

    def _random(self, n: int = 1, *, workers: int = 1) -> np.ndarray:
        return self._seq.points(n, first=self.num_generated)

    def fast_forward(self, n: int) -> "Weyl":
        """Skip n points in O(1)."""
        n = u64(n, "n", where=WHERE)
        if self.num_generated + n > self._end():
            raise ValueError(f"{WHERE}: fast_forward({n}) from point {self.num_generated} passes the end of the "
                             f"{'point set' if self._seq.point_count else 'sequence'} ({self._end()} points)")
        self.num_generated += n
        return self

    @property
    def sequence(self) -> Sequence:
        """The underlying udm1.Sequence (stream 0)."""
        return self._seq


def _preset_engine(name: str, preset: str, doc: str):
    def __init__(self, d: int, *, scramble: bool = True, optimization=None, rng=None, seed=None):
        Weyl.__init__(self, d, scramble=scramble, optimization=optimization, rng=rng, seed=seed)

    return type(name, (Weyl,), {"_preset": preset, "__init__": __init__, "__doc__": doc})


WR = _preset_engine("WR", "wr", "WeylRichtmyer: square roots of the primes (paper 5.1).")
WRAO = _preset_engine("WRAO", "wr-ao", "The paper's AO pair (sqrt2, sqrt13); d <= 2.")
WE = _preset_engine("WE", "we", "(e, e^2); d <= 2.")
WGR = _preset_engine("WGR", "wgr", "((1+sqrt5)/2, (1+sqrt3)/2); d <= 2.")
WMMR = _preset_engine("WMMR", "wmmr", "The paper's 22 metallic-means square roots; d <= 22.")
HWMMR = _preset_engine("HWMMR", "hwmmr", "The paper's hybrid set of 22 values; d <= 22.")
Rd = _preset_engine("Rd", "rd", "R_d, the generalized golden ratio sequence (Roberts 2018).")
Golden = _preset_engine("Golden", "golden", "The golden-ratio Weyl sequence; d = 1.")


class EPISWR(Weyl):
    """The paper's EPISWR point set of n points: ({i/n + u}, {i sqrt137 + v})."""

    _preset = "episwr"

    def __init__(self, d: int = 2, *, n: int, scramble: bool = True, optimization=None, rng=None, seed=None):
        self.n = u64(n, "n", where=WHERE)
        Weyl.__init__(self, d, point_count=self.n, scramble=scramble, optimization=optimization, rng=rng, seed=seed)

    def _quad_args(self, d, point_count, optimization) -> dict:
        return {"d": d, "n": point_count, "scramble": True, "optimization": optimization}


__all__ = ["Weyl", "WR", "WRAO", "WE", "WGR", "WMMR", "HWMMR", "Rd", "Golden", "EPISWR"]
