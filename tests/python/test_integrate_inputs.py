"""Every argument of udm1.integrate (and of integrate_range, replicate_ranges, values_range, the tolerance
rules and udm1.distributed's integrals) is checked before f is first called: a bad one is a TypeError or
udm1.UDM1Error (a ValueError) naming it, in one line, with f never called and no cluster reached. A
negative chunk used to return an estimate read from memory never written (met=True)."""

import numpy as np
import pytest

import udm1
from udm1.integrate import IntegralSpec, integrate_range, replicate_ranges, values_range


class Counting:
    """An integrand that counts its calls."""

    def __init__(self):
        self.calls = 0

    def __call__(self, x):
        self.calls += 1
        return np.cos(x).prod(axis=1)


# (what, kwargs of udm1.integrate besides f, the exception types, the name the message must contain)
BAD = [
    ("negative chunk, lattice", dict(sampler="lattice-seq", d=2, abs_tol=1e-3, chunk=-5, transform="baker"),
     ValueError, "chunk"),
    ("negative chunk, n", dict(sampler="wr", d=2, n=100, chunk=-5), ValueError, "chunk"),
    ("zero chunk", dict(sampler="wr", d=2, n=100, chunk=0), ValueError, "chunk"),
    ("fractional chunk", dict(sampler="wr", d=2, n=100, chunk=2.5), ValueError, "chunk"),
    ("bool chunk", dict(sampler="wr", d=2, n=100, chunk=True), TypeError, "chunk"),
    ("string chunk", dict(sampler="wr", d=2, n=100, chunk="64"), TypeError, "chunk"),
    ("zero n", dict(sampler="wr", d=2, n=0), ValueError, "n"),
    ("negative n", dict(sampler="wr", d=2, n=-3), ValueError, "n"),
    ("n past 2^64", dict(sampler="wr", d=2, n=2**64), ValueError, "n"),
    ("fractional n", dict(sampler="wr", d=2, n=10.5), ValueError, "n"),
    ("zero d", dict(sampler="wr", d=0, n=10), ValueError, "d"),
    ("d past 2^32", dict(sampler="wr", d=2**32, n=10), ValueError, "d"),
    ("d too many for the preset", dict(sampler="wr-ao", d=3, n=10), udm1.UDM1Error, "wr-ao"),
    ("unknown sampler", dict(sampler="nosuch", d=2, n=10), ValueError, "sampler"),
    ("sampler not a string", dict(sampler=3, d=2, n=10), TypeError, "sampler"),
    ("negative seed", dict(sampler="wr", d=2, n=10, seed=-1), ValueError, "seed"),
    ("seed past 2^64", dict(sampler="wr", d=2, n=10, seed=2**64), ValueError, "seed"),
    ("negative stream", dict(sampler="wr", d=2, n=10, stream=-1), ValueError, "stream"),
    ("stream with a tolerance", dict(sampler="wr", d=2, abs_tol=1e-3, stream=3), ValueError, "stream"),
    ("randomize unknown", dict(sampler="wr", d=2, n=10, randomize="scramble"), ValueError, "randomize"),
    ("randomize not for the preset", dict(sampler="sobol", d=2, n=10, randomize="screen"), udm1.UDM1Error, "sobol"),
    ("transform unknown", dict(sampler="wr", d=2, n=10, transform="sine"), ValueError, "transform"),
    ("transform empty", dict(sampler="wr", d=2, n=10, transform=""), ValueError, "transform"),
    ("transform not a string", dict(sampler="wr", d=2, n=10, transform=1), TypeError, "transform"),
    ("criterion unknown, with n", dict(sampler="wr", d=2, n=10, criterion="fourier"), ValueError, "criterion"),
    ("criterion unknown", dict(sampler="wr", d=2, abs_tol=1e-3, criterion="fourier"), ValueError, "criterion"),
    ("lattice criterion on wr", dict(sampler="wr", d=2, abs_tol=1e-3, criterion="lattice"), ValueError, "criterion"),
    ("negative abs_tol", dict(sampler="wr", d=2, abs_tol=-1.0), ValueError, "abs_tol"),
    ("zero abs_tol", dict(sampler="wr", d=2, abs_tol=0.0), ValueError, "abs_tol"),
    ("infinite rel_tol", dict(sampler="wr", d=2, rel_tol=np.inf), ValueError, "rel_tol"),
    ("nan rel_tol", dict(sampler="wr", d=2, rel_tol=float("nan")), ValueError, "rel_tol"),
    ("bool abs_tol", dict(sampler="wr", d=2, abs_tol=True), TypeError, "abs_tol"),
    ("confidence 1", dict(sampler="wr", d=2, abs_tol=1e-3, confidence=1.0), ValueError, "confidence"),
    ("confidence 0.4", dict(sampler="wr", d=2, abs_tol=1e-3, confidence=0.4), ValueError, "confidence"),
    ("confidence nan", dict(sampler="wr", d=2, abs_tol=1e-3, confidence=float("nan")), ValueError, "confidence"),
    ("confidence string", dict(sampler="wr", d=2, abs_tol=1e-3, confidence="0.9"), TypeError, "confidence"),
    ("confidence with n", dict(sampler="wr", d=2, n=10, confidence=2.0), ValueError, "confidence"),
    ("replications 1", dict(sampler="wr", d=2, abs_tol=1e-3, replications=1), ValueError, "replications"),
    ("replications fractional", dict(sampler="wr", d=2, abs_tol=1e-3, replications=4.5), ValueError, "replications"),
    ("replications with n", dict(sampler="wr", d=2, n=10, replications=-2), ValueError, "replications"),
    ("n_init 1", dict(sampler="wr", d=2, abs_tol=1e-3, n_init=1), ValueError, "n_init"),
    ("n_init negative", dict(sampler="wr", d=2, abs_tol=1e-3, n_init=-256), ValueError, "n_init"),
    ("n_init not a power of two, lattice", dict(sampler="lattice-seq", d=2, abs_tol=1e-3, n_init=100), ValueError,
     "n_init"),
    ("n_max 0", dict(sampler="wr", d=2, abs_tol=1e-3, n_max=0), ValueError, "n_max"),
    ("n_max below the first round", dict(sampler="wr", d=2, abs_tol=1e-3, n_max=100), ValueError, "n_max"),
    ("n_max below n_init, lattice", dict(sampler="lattice-seq", d=2, abs_tol=1e-3, n_max=128), ValueError, "n_max"),
    ("n_max string", dict(sampler="wr", d=2, abs_tol=1e-3, n_max="1e6"), TypeError, "n_max"),
    ("strict string", dict(sampler="wr", d=2, abs_tol=1e-3, strict="no"), TypeError, "strict"),
    ("n and a tolerance", dict(sampler="wr", d=2, n=10, abs_tol=1e-3), ValueError, "not both"),
    ("neither n nor a tolerance", dict(sampler="wr", d=2), ValueError, "give n"),
]


@pytest.mark.parametrize("what,kwargs,errors,name", BAD, ids=[c[0] for c in BAD])
def test_every_argument_is_checked_before_f_runs(what, kwargs, errors, name):
    f = Counting()
    with pytest.raises(errors) as e:
        udm1.integrate(f, **kwargs)
    assert name in str(e.value), f"{what}: {e.value}"
    assert "\n" not in str(e.value)
    assert f.calls == 0, f"{what}: f was called {f.calls} times before the refusal"


def test_f_must_be_callable():
    with pytest.raises(TypeError, match="f must be callable"):
        udm1.integrate(np.ones(4), "wr", 2, n=10)


def test_negative_chunk_no_longer_reads_unwritten_memory():
    # the reviewer's case: the lattice criterion with chunk -5 gave 2.4e-311 and met=True
    with pytest.raises(udm1.UDM1Error, match=r"chunk = -5 is outside \[1, "):
        udm1.integrate(lambda x: np.cos(x).prod(axis=1), "lattice-seq", 2, abs_tol=1e-3, chunk=-5, transform="baker")


@pytest.mark.parametrize("chunk", [1, 3, 100, 255, 256, 257, 1 << 20])
def test_any_valid_chunk_gives_the_same_result(chunk):
    def f(x):
        return np.cos(2 * x).prod(axis=1)

    whole = udm1.integrate(f, "lattice-seq", 2, abs_tol=1e-6, transform="baker")
    r = udm1.integrate(f, "lattice-seq", 2, abs_tol=1e-6, transform="baker", chunk=chunk)
    assert (r.estimate, r.error_bound, r.n, r.history) == (whole.estimate, whole.error_bound, whole.n, whole.history)
    a = udm1.integrate(f, "wr", 2, n=1000, seed=3)
    b = udm1.integrate(f, "wr", 2, n=1000, seed=3, chunk=chunk)
    assert (a.sum, a.sum_sq) == (b.sum, b.sum_sq)


def test_range_functions_check_their_arguments():
    spec = IntegralSpec("wr", 2, 1000, 1)
    f = Counting()
    cases = [
        (lambda: integrate_range(f, spec, 0, 10, chunk=0), ValueError, "chunk"),
        (lambda: integrate_range(f, spec, -1, 10), ValueError, "first"),
        (lambda: integrate_range(f, spec, 0, -10), ValueError, "count"),
        (lambda: integrate_range(f, spec, 995, 10), ValueError, "[995, 1005)"),
        (lambda: integrate_range(f, ("wr", 2, 1000), 0, 10), TypeError, "spec"),
        (lambda: replicate_ranges(f, [], 0, 10), ValueError, "specs"),
        (lambda: replicate_ranges(f, [spec, "wr"], 0, 10), TypeError, "spec"),
        (lambda: values_range(f, spec, 0, 100, chunk=-7), ValueError, "chunk"),
        (lambda: values_range(f, spec, 0, 2000), ValueError, "[0, 2000)"),
        (lambda: values_range(f, spec, 0.5, 10), ValueError, "first"),
        (lambda: IntegralSpec("wr", 2, 0), ValueError, "n"),
        (lambda: IntegralSpec("wr", 2, 10, seed=-1), ValueError, "seed"),
        (lambda: IntegralSpec("wr", 2, 10, stream=2**64), ValueError, "stream"),
        (lambda: IntegralSpec("wr", 2, 10, randomize="sideways"), ValueError, "randomize"),
        (lambda: IntegralSpec("nosuch", 2, 10), ValueError, "sampler"),
    ]
    for call, errors, name in cases:
        with pytest.raises(errors) as e:
            call()
        assert name in str(e.value), (name, str(e.value))
    assert f.calls == 0
    # numpy integers are taken, and the spec holds Python ints (equal specs compare equal)
    assert IntegralSpec("wr", np.int8(2), np.uint64(1000), np.int64(1)) == spec


def test_values_range_writes_every_value():
    spec = IntegralSpec("lattice-seq", 2, 1 << 12, 3)
    seq = spec.sequence()
    for chunk in (1, 7, 100, 4095, 4096, 5000):
        y, total = values_range(lambda x: x.sum(axis=1), spec, 5, 3000, chunk)
        assert np.array_equal(y, seq.points(3000, 5).sum(axis=1)) and total == udm1.ExactSum().add(y)


def test_distributed_integrals_check_their_arguments_before_reaching_a_cluster(monkeypatch):
    pytest.importorskip("distributed")
    import udm1.distributed as ud

    def no_cluster(*args, **kwargs):
        raise AssertionError("a cluster was reached before the arguments were checked")

    monkeypatch.setattr(ud, "connect", no_cluster)
    f = Counting()
    cases = [
        (lambda: ud.integrate(f, "wr", 2, 100, chunk=-1), ValueError, "chunk"),
        (lambda: ud.integrate(f, "wr", 2, 0), ValueError, "n"),
        (lambda: ud.integrate(f, "wr", 2, 100, tasks=0), ValueError, "tasks"),
        (lambda: ud.integrate(f, "wr", 2, 100, tasks=2.5), ValueError, "tasks"),
        (lambda: ud.integrate(f, "wr", 2, 100, timeout=-1), ValueError, "timeout"),
        (lambda: ud.integrate(f, "wr", 2, 100, timeout="1"), TypeError, "timeout"),
        (lambda: ud.integrate(f, "wr", 2, 100, on_done=3), TypeError, "on_done"),
        (lambda: ud.integrate(f, "wr", 2, 100, stream=-1), ValueError, "stream"),
        (lambda: ud.integrate(f, "wr-ao", 3, 100), udm1.UDM1Error, "wr-ao"),
        (lambda: ud.integrate(f, "wr", 2, 100, progress="yes"), TypeError, "progress"),
        (lambda: ud.integrate("f", "wr", 2, 100), TypeError, "f must be callable"),
        (lambda: ud.integrate_to_tolerance(f, "wr", 2, abs_tol=-1), ValueError, "abs_tol"),
        (lambda: ud.integrate_to_tolerance(f, "wr", 2, abs_tol=1e-3, chunk=0), ValueError, "chunk"),
        (lambda: ud.integrate_to_tolerance(f, "wr", 2, abs_tol=1e-3, blocks=0), ValueError, "blocks"),
        (lambda: ud.integrate_to_tolerance(f, "wr", 2, abs_tol=1e-3, replications=1), ValueError, "replications"),
        (lambda: ud.integrate_to_tolerance(f, "lattice-seq", 2, abs_tol=1e-3, n_init=48), ValueError, "n_init"),
        (lambda: ud.integrate_to_tolerance(f, "wr", 2, abs_tol=1e-3, timeout=0), ValueError, "timeout"),
        (lambda: ud.split_range(10, 0), ValueError, "parts"),
        (lambda: ud.split_range(-1, 2), ValueError, "n"),
        (lambda: ud.split_tiles(16, 16, (0, 4)), ValueError, "tile"),
    ]
    for call, errors, name in cases:
        with pytest.raises(errors) as e:
            call()
        assert name in str(e.value), (name, str(e.value))
    assert f.calls == 0
