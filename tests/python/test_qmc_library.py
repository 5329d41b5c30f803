"""The scipy.stats.qmc engines of udm1.qmc against the library: every engine class (and the generic Weyl
engine over every preset) x scramble on and off x every form of rng / seed, drawn in several random()
calls, after fast_forward and after reset: every value equal bit for bit (float64) to the library's
point at the same (stream 0, index, dimension), read through two other C entry points than the engine's
fill (udm1_seq_fill_points_f64 and udm1_seq_sample_f64 per value), on a sequence made independently
with the key the engine must have drawn (its documented derivation: 64 bits from the spawned Generator
scipy keeps, or from a legacy RandomState). What cannot be drawn as the library draws it (scipy's
optimization, a point past a point set) is refused with one line."""

import numpy as np
import pytest

import udm1
import udm1.qmc as uq

PRESETS = {p.name: p for p in udm1.presets()}
CLASSES = [(uq.WR, "wr"), (uq.WRAO, "wr-ao"), (uq.WE, "we"), (uq.WGR, "wgr"), (uq.WMMR, "wmmr"), (uq.HWMMR, "hwmmr"),
           (uq.Rd, "rd"), (uq.Golden, "golden")]
K = 64  # the point sets' size here


def key_of(form, value):
    """The 64-bit key an engine given rng/seed `value` in `form` must draw."""
    if form == "RandomState":
        return int(np.random.RandomState(value).randint(0, 2**64, dtype=np.uint64))
    # scipy spawns the Generator it is given (or makes from an int) and keeps the child
    child = np.random.default_rng(value).spawn(1)[0]
    return int(child.integers(0, 2**64, dtype=np.uint64))


FORMS = {  # name: (kwargs for the engine, the key's derivation)
    "rng=int": (lambda: {"rng": 12345}, ("int", 12345)),
    "seed=int": (lambda: {"seed": 12345}, ("int", 12345)),
    "rng=numpy int": (lambda: {"rng": np.uint32(777)}, ("int", 777)),
    "rng=Generator": (lambda: {"rng": np.random.default_rng(99)}, ("Generator", 99)),
    "seed=Generator": (lambda: {"seed": np.random.default_rng(99)}, ("Generator", 99)),
    "seed=RandomState": (lambda: {"seed": np.random.RandomState(5)}, ("RandomState", 5)),
    "rng=None": (lambda: {}, None),  # entropy: the key is whatever was drawn, read back
}


def library_points(preset, d, k, key, scramble, indices):
    """Point indices[i] of stream 0, dimensions 0..d-1, from a sequence made here: once through
    udm1_seq_fill_points_f64, and value by value through udm1_seq_sample_f64 (they must agree)."""
    s = udm1.Sequence(preset, d, point_count=k, seed=key, randomize=scramble)
    idx = np.asarray(indices, dtype=np.uint64)
    many = s.points_at(np.zeros(idx.size, dtype=np.uint64), idx)
    one = np.array([[s.sample(int(i), j) for j in range(d)] for i in idx]).reshape(idx.size, d)
    assert np.array_equal(many.view(np.uint64), one.view(np.uint64))
    return many


def check_engine(engine, preset, d, k, scramble, key):
    """Draws in several calls, a fast_forward, a reset: each row equal to the library's point."""
    assert engine.sequence.seed == key and engine.num_generated == 0
    end = k or 1 << 64
    plan = [("random", 3), ("random", 1), ("random", 0), ("ff", 7), ("random", 5), ("ff", end - 8 - 16 - 2)
            if k else ("ff", (1 << 62) + 3), ("random", 2), ("reset", 0), ("random", 4)]
    at = 0
    for op, n in plan:
        if op == "ff":
            assert engine.fast_forward(n) is engine
            at += n
        elif op == "reset":
            engine.reset()
            at = 0
        else:
            x = engine.random(n)
            assert x.shape == (n, d) and x.dtype == np.float64
            want = library_points(preset, d, k, key, scramble, range(at, at + n))
            assert np.array_equal(x.view(np.uint64), want.view(np.uint64)), (preset, scramble, op, at)
            at += n
        assert engine.num_generated == at


@pytest.mark.parametrize("form", sorted(FORMS))
@pytest.mark.parametrize("scramble", [True, False])
@pytest.mark.parametrize("cls,preset", CLASSES, ids=[c[1] for c in CLASSES])
def test_preset_engines_equal_the_library(cls, preset, scramble, form):
    kwargs, derivation = FORMS[form]
    d = min(PRESETS[preset].max_dimensions, 4)
    engine = cls(d, scramble=scramble, **kwargs())
    key = 0 if not scramble else (engine.sequence.seed if derivation is None else key_of(*derivation))
    check_engine(engine, preset, d, 0, scramble, key)


@pytest.mark.parametrize("scramble", [True, False])
@pytest.mark.parametrize("form", ["rng=int", "seed=Generator", "seed=RandomState", "rng=None"])
def test_episwr_engine_equals_the_library(scramble, form):
    kwargs, derivation = FORMS[form]
    engine = uq.EPISWR(n=K, scramble=scramble, **kwargs())
    key = 0 if not scramble else (engine.sequence.seed if derivation is None else key_of(*derivation))
    check_engine(engine, "episwr", 2, K, scramble, key)
    with pytest.raises(udm1.UDM1Error):  # the set's end: refused, never wrapped
        engine.random(K)


@pytest.mark.parametrize("preset", sorted(PRESETS))
def test_the_generic_engine_equals_the_library_for_every_preset(preset):
    """Weyl(preset=...) over every preset of the library, scrambled and not, two rng forms each."""
    info = PRESETS[preset]
    d = min(info.max_dimensions, 3)
    k = K if info.point_set else 0
    for scramble in (True, False):
        for form in ("rng=int", "seed=RandomState"):
            kwargs, derivation = FORMS[form]
            engine = uq.Weyl(d, preset=preset, point_count=k, scramble=scramble, **kwargs())
            check_engine(engine, preset, d, k, scramble, key_of(*derivation) if scramble else 0)


def test_what_the_library_cannot_draw_is_refused_at_construction():
    cases = [
        (lambda: uq.WR(2, seed=1, optimization="random-cd"), ValueError, "optimization"),
        (lambda: uq.WR(2, seed=1, optimization="lloyd"), ValueError, "optimization"),
        (lambda: uq.WRAO(3, seed=1), udm1.UDM1Error, "wr-ao"),
        (lambda: uq.Golden(2), udm1.UDM1Error, "golden"),
        (lambda: uq.EPISWR(3, n=16), udm1.UDM1Error, "episwr"),
        (lambda: uq.Weyl(2, preset="episwr"), udm1.UDM1Error, "episwr"),
        (lambda: uq.Weyl(2, preset="nosuch"), udm1.UDM1Error, "nosuch"),
        (lambda: uq.WR(2, rng=np.random.RandomState(1)), TypeError, "seed="),
        (lambda: uq.WR(2, rng=-1), ValueError, "rng"),
        (lambda: uq.WR(2, rng="abc"), TypeError, "rng"),
        (lambda: uq.WR(2, seed=True), TypeError, "seed"),
        (lambda: uq.WR(2, seed=1, rng=1), ValueError, "not both"),
    ]
    for call, errors, words in cases:
        with pytest.raises(errors) as e:
            call()
        assert words in str(e.value) and "\n" not in str(e.value), str(e.value)
    e = uq.EPISWR(n=16, seed=1)
    e.fast_forward(16)  # to the end: allowed, nothing is drawn
    with pytest.raises(ValueError, match="fast_forward"):
        e.fast_forward(1)
    w = uq.WR(1, seed=1).fast_forward(2**64 - 1)
    assert w.random(1).shape == (1, 1)  # the last index of a sequence
    with pytest.raises(ValueError, match="fast_forward"):
        w.fast_forward(1)


def test_qmc_quad_engines_are_the_library_too():
    """scipy.integrate.qmc_quad makes new engines from _init_quad with spawned Generators: they are the
    library's sequences with the keys those Generators give."""
    base = uq.Weyl(3, preset="sobol-owen", seed=4)
    for child_seed in (1, 2):
        g = np.random.default_rng(child_seed)
        clone = type(base)(seed=g, **base._init_quad)
        key = int(np.random.default_rng(child_seed).spawn(1)[0].integers(0, 2**64, dtype=np.uint64))
        assert clone.sequence.name == "sobol-owen" and clone.sequence.seed == key
        check_engine(clone, "sobol-owen", 3, 0, True, key)
