"""Scale-out (udm1.distributed) and the exact sums it rests on (udm1.ExactSum, udm1.integrate):
sums independent of split and order and equal to exact rational arithmetic; integrals, AO and
path-tracing renders over a LocalCluster of 3 worker processes equal to single-process runs bit
for bit, also with tiles and with a worker killed mid-run; the command line; bad input."""

import math
import os
import pathlib
import random
import signal
import subprocess
import sys
import time
from fractions import Fraction

import numpy as np
import pytest

import udm1
from udm1.exact_sum import ExactSum

distributed = pytest.importorskip("distributed")
import udm1.distributed as ud  # noqa: E402

PT = os.environ.get("UDM1_PT_TOOL", "")
AO = os.environ.get("UDM1_AO_TOOL", "")
HERE = pathlib.Path(__file__).resolve().parent


# ---------------------------------------------------------------------------------- exact sums

def hard_values(rng, n):
    """Values over the whole double range, cancelling pairs, subnormals, signed zeros."""
    x = rng.standard_normal(n) * 10.0 ** rng.integers(-300, 300, n)
    extra = [5e-324, -5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, -1.7976931348623157e308,
             0.0, -0.0, 1e16, 1.0, -1e16, 3e-320]
    return rng.permutation(np.concatenate([x, -x[: n // 4], extra]))


def test_exact_sum_equals_rational_arithmetic():
    rng = np.random.default_rng(7)
    for trial in range(5):
        x = hard_values(rng, 2000)
        s = ExactSum().add(x)
        exact = sum(Fraction(float(v)) for v in x)
        assert s.fraction() == exact
        assert s.value() == float(exact)  # rounded once
        assert s.mean() == float(exact / x.size) and s.count == x.size


def test_exact_sum_does_not_depend_on_split_or_order():
    rng = np.random.default_rng(11)
    x = hard_values(rng, 5000)
    whole = ExactSum().add(x)
    for trial in range(20):
        cuts = sorted(rng.choice(np.arange(1, x.size), size=int(rng.integers(1, 40)), replace=False))
        parts = [ExactSum().add(p) for p in np.split(x, cuts)]
        random.Random(trial).shuffle(parts)
        total = ExactSum()
        for p in parts:
            total = total + p
        assert total == whole
    # a naive float sum does depend on the order: the exactness is not vacuous here
    y = rng.standard_normal(5000) * 10.0 ** rng.integers(-8, 8, 5000)
    assert len({float(np.sum(rng.permutation(y))) for _ in range(10)}) > 1


def test_exact_sum_refuses_non_finite_values():
    for bad in (np.nan, np.inf, -np.inf):
        with pytest.raises(ValueError, match="value 2 is"):
            ExactSum().add([1.0, 2.0, bad])


# ---------------------------------------------------------------------------------- integrals

def prod(x):
    return np.prod(x, axis=1)


def test_integrate_is_the_rounded_exact_mean():
    spec = dict(sampler="wr", d=3, n=5000, seed=4)
    est = udm1.integrate(prod, **spec)
    x = udm1.Sequence("wr", 3, seed=4).points(5000)
    exact = sum(Fraction(float(v)) for v in prod(x)) / 5000
    assert est.value == float(exact)
    assert abs(est.value - 1 / 8) < 1e-3
    for chunk in (1, 7, 4096, 1 << 20):  # chunking changes nothing
        assert udm1.integrate(prod, **spec, chunk=chunk).sum == est.sum
    # ranges join exactly, in either order
    a = udm1.integrate(prod, **spec)
    from udm1.integrate import IntegralSpec, integrate_range

    s = IntegralSpec("wr", 3, 5000, 4)
    left, right = integrate_range(prod, s, 0, 1234), integrate_range(prod, s, 1234, 5000 - 1234)
    assert (right + left).value == a.value and (left + right).sum == a.sum
    with pytest.raises(ValueError, match="not adjacent"):
        left + integrate_range(prod, s, 2000, 10)
    # a crude check of the standard error: PRNG's estimate lies within 5 of them
    r = udm1.integrate(prod, "pcg32", 3, 20000, seed=3)
    assert abs(r.value - 1 / 8) < 5 * r.stderr and 0 < r.stderr < 1e-2


@pytest.mark.parametrize(
    "f,kwargs,words",
    [
        (prod, dict(sampler="nosuch", d=2, n=10), "unknown sampler 'nosuch'"),
        (prod, dict(sampler="wr", d=2, n=0), "n = 0"),
        (lambda x: x, dict(sampler="wr", d=2, n=10), "shape (10, 2)"),
        (lambda x: np.where(np.arange(len(x)) == 6, np.nan, 1.0), dict(sampler="wr", d=2, n=10), "at sample 6"),
    ],
)
def test_integrate_bad_input(f, kwargs, words):
    with pytest.raises(ValueError) as e:
        udm1.integrate(f, **kwargs)
    assert words in str(e.value)


# ---------------------------------------------------------------------------------- the cluster

@pytest.fixture(scope="module")
def client():
    with ud.connect(n_workers=3, threads_per_worker=1) as c:
        c.wait_for_workers(3)
        yield c


def split_key(key):
    return int(str(key).rsplit("-", 1)[1])


class KillOne:
    """on_done hook: after the first part arrives, SIGKILL a worker that is running a part, and
    remember which parts it was running."""

    def __init__(self, client):
        self.client, self.victim, self.lost = client, None, set()

    def __call__(self, k, result):
        if self.victim is not None:
            return
        busy = self.client.run_on_scheduler(
            lambda dask_scheduler: {w.address: [str(t.key) for t in w.processing] for w in dask_scheduler.workers.values()})
        busy = {w: keys for w, keys in busy.items() if keys and w != result["worker"]} or \
            {w: keys for w, keys in busy.items() if keys}
        if not busy:
            return
        self.victim = sorted(busy)[0]
        self.lost = {split_key(key) for key in busy[self.victim]}
        pid = self.client.run(os.getpid, workers=[self.victim])[self.victim]
        os.kill(pid, signal.SIGKILL)


@pytest.mark.parametrize("sampler,d,n", [("wr", 4, 300000), ("episwr", 2, 65536), ("sobol-owen", 5, 100000)])
def test_distributed_integral_equals_one_process(client, sampler, d, n):
    whole = udm1.integrate(prod, sampler, d, n, seed=9)
    for tasks in (1, 5, 13):
        est = ud.integrate(prod, sampler, d, n, seed=9, tasks=tasks, client=client, progress=False)
        assert est.sum == whole.sum and est.value == whole.value and est.count == n


def test_distributed_tolerance_equals_one_process(client):
    # replicates x index blocks as tasks, the same stopping rule on the same exact sums: bit for bit
    def f(x):
        return np.cos(2 * np.pi * 0.1 + x @ np.array([0.7, 1.1]))

    # the lattice criterion: index blocks as tasks, the values brought back for the transform
    for sampler, transform in (("wr", None), ("sobol-owen", "tent"), ("lattice-seq", "baker")):
        one = udm1.integrate(f, sampler, 2, abs_tol=1e-5, seed=4, transform=transform)
        many = ud.integrate_to_tolerance(f, sampler, 2, abs_tol=1e-5, seed=4, transform=transform, client=client,
                                         blocks=3)
        assert (many.estimate, many.error_bound, many.n, many.history, many.criterion) == (
            one.estimate, one.error_bound, one.n, one.history, one.criterion)
        assert one.criterion == ("lattice" if sampler == "lattice-seq" else "replications")
    with pytest.raises(udm1.ToleranceNotMet):
        ud.integrate_to_tolerance(f, "wr", 2, abs_tol=1e-14, n_max=4096, n_init=128, replications=4, client=client)


def test_any_scheduler_address(client):
    # connect(address) and address= reach an existing scheduler (here the fixture's cluster)
    address = client.scheduler.address
    whole = udm1.integrate(prod, "halton", 3, 50000, seed=1)
    est = ud.integrate(prod, "halton", 3, 50000, seed=1, tasks=4, address=address, progress=False)
    assert est.sum == whole.sum
    with ud.connect(address) as other:
        assert set(other.nthreads()) == set(client.nthreads())


def test_distributed_integral_survives_a_killed_worker(client):
    def slow(x):  # long enough that parts are running when the worker dies
        import time

        time.sleep(0.3)
        return np.cos(x).prod(axis=1)

    whole = udm1.integrate(slow, "wr", 6, 24000, seed=2, chunk=4000)
    kill = KillOne(client)
    est = ud.integrate(slow, "wr", 6, 24000, seed=2, tasks=12, chunk=4000, client=client, progress=False,
                       on_done=kill)
    assert kill.victim is not None and kill.lost, "no worker was killed mid-run"
    assert est.sum == whole.sum and est.value == whole.value
    client.wait_for_workers(3)


class Blocked:
    """An integrand that waits until a file exists (a stuck part), then computes."""

    def __init__(self, flag):
        self.flag = str(flag)

    def __call__(self, x):
        while not os.path.exists(self.flag):
            time.sleep(0.02)
        return np.cos(x).prod(axis=1)


def test_a_stuck_wait_raises_naming_what_it_waited_for(client, tmp_path):
    """Every wait has a timeout: parts that never finish give a TimeoutError within about the timeout (not
    a hang), naming what was waited for and the parts still pending; the tasks are cancelled and the
    workers are usable again once the parts return."""
    flag = tmp_path / "release"
    blocked = Blocked(flag)
    cases = [
        (lambda: ud.integrate(blocked, "wr", 2, 3000, tasks=3, client=client, progress=False, timeout=1.5),
         r"waited 1.5 s for integral of 3000 wr points and no part finished: 3 of 3 parts still pending \(udm1-"),
        (lambda: ud.integrate_to_tolerance(blocked, "lattice-seq", 2, abs_tol=1e-6, transform="baker", blocks=2,
                                           client=client, timeout=1.5),
         r"waited 1.5 s for lattice points \[0, 256\) and no part finished: 2 of 2 parts still pending"),
        (lambda: ud.integrate_to_tolerance(blocked, "wr", 2, abs_tol=1e-6, replications=2, blocks=1, client=client,
                                           timeout=1.5),
         r"waited 1.5 s for 2 replicates of \[0, 256\) and no part finished"),
    ]
    try:
        for call, words in cases:
            t0 = time.monotonic()
            with pytest.raises(TimeoutError, match=words):
                call()
            assert time.monotonic() - t0 < 60  # the timeout acted: without it the call never returns
    finally:
        flag.touch()  # the cancelled parts return; the workers are free again
    # a part no worker can take (workers idle, as in the hang this guards against) and a render's wait
    never = client.submit(np.sum, [1, 2], resources={"no-such-resource": 1}, key="udm1-test-never")
    with pytest.raises(TimeoutError, match=r"waited 1 s for a part nobody runs and no part finished: 1 of 1 parts "
                                           r"still pending \(udm1-test-never\)"):
        list(ud._completed(client, [never], what="a part nobody runs", timeout=1.0, with_results=True))
    with pytest.raises(TimeoutError, match=r"waited 1 s for tiles and no part finished"):
        ud._watch(client, [never], [], False, None, "tiles", 1.0)
    client.cancel([never])
    one = udm1.integrate(prod, "wr", 3, 3000, seed=1)
    again = ud.integrate(prod, "wr", 3, 3000, seed=1, tasks=3, client=client, progress=False, timeout=60)
    assert again.sum == one.sum


@pytest.mark.skipif(not PT or not AO, reason="UDM1_PT_TOOL / UDM1_AO_TOOL not set")
@pytest.mark.parametrize("tool", ["pt", "ao"])
def test_distributed_render_equals_one_process(client, tool, tmp_path):
    exe = PT if tool == "pt" else AO
    args = ["--size", "40x30", "--sampler", "wmmr" if tool == "pt" else "sobol-owen", "--seed", "5"]
    subprocess.run([exe, *args, "--spp", "12", "-o", str(tmp_path / "one.exr"), "--png", str(tmp_path / "one.png")],
                   check=True, capture_output=True)
    def tree_merges(ranges, fan_in):
        m = 0
        while ranges > fan_in:
            ranges = -(-ranges // fan_in)
            m += ranges
        return m

    # every split and merge tree with udm1-pt; udm1-ao (the same machinery over another tool's files) on one tiled
    # split with a merge tree
    splits = ((3, None, 16), (10, (16, 11), 16), (6, None, 2), (12, (27, 30), 3))
    for tasks, tile, fan_in in (splits if tool == "pt" else splits[3:]):
        out = tmp_path / f"d{tasks}.exr"
        res = ud.render(exe, str(out), spp=12, args=args, png=str(tmp_path / f"d{tasks}.png"), tasks=tasks, tile=tile,
                        client=client, progress=False, fan_in=fan_in)
        assert out.read_bytes() == (tmp_path / "one.exr").read_bytes()
        assert (tmp_path / f"d{tasks}.png").read_bytes() == (tmp_path / "one.png").read_bytes()
        tiles = {p["bounds"] for p in res.parts}
        assert len(tiles) == {None: 1, (16, 11): 9, (27, 30): 2}[tile] and (res.width, res.height) == (40, 30)
        assert [p["index"] for p in res.parts] == list(range(len(res.parts)))
        ranges = len(res.parts) // len(tiles)
        assert res.merges == len(tiles) * tree_merges(ranges, fan_in)
        assert res.merges > 0 or fan_in == 16
        assert sum(p["count"] * (p["bounds"][2] - p["bounds"][0]) * (p["bounds"][3] - p["bounds"][1])
                   for p in res.parts) == 12 * 40 * 30
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".udm1-")]  # no temporary folder left


@pytest.mark.skipif(not PT, reason="UDM1_PT_TOOL not set")
def test_distributed_render_survives_a_killed_worker(client, tmp_path):
    args = ["--size", "64x48", "--sampler", "hwmmr"]
    subprocess.run([PT, *args, "--spp", "48", "-o", str(tmp_path / "one.exr")], check=True, capture_output=True)
    kill = KillOne(client)
    res = ud.render(PT, str(tmp_path / "d.exr"), spp=48, args=args, tasks=24, client=client, progress=False,
                    on_done=kill)
    assert kill.victim is not None and kill.lost, "no worker was killed mid-run"
    assert (tmp_path / "d.exr").read_bytes() == (tmp_path / "one.exr").read_bytes()
    # the parts the dead worker was running were run again, elsewhere
    for k in kill.lost:
        assert res.parts[k]["worker"] != kill.victim
    client.wait_for_workers(3)


@pytest.mark.skipif(not PT, reason="UDM1_PT_TOOL not set")
def test_render_bad_input(client, tmp_path):
    cases = [
        (dict(args=["--sampler", "nosuch"]), "unknown sampler 'nosuch'"),
        (dict(args=["--scene", str(tmp_path / "none.pbrt")]), "none.pbrt"),
        (dict(args=["--spp-first", "2"]), "pass --spp-first through render()"),
        (dict(output=str(tmp_path / "x.png")), "must be OpenEXR"),
        (dict(output=str(tmp_path / "no" / "x.exr")), "not a writable folder"),
    ]
    for kw, words in cases:
        kw.setdefault("output", str(tmp_path / "out.exr"))
        before = set(tmp_path.iterdir())
        with pytest.raises(ValueError) as e:
            ud.render(PT, spp=4, client=client, progress=False, **kw)
        assert words in str(e.value)
        assert set(tmp_path.iterdir()) == before
    with pytest.raises(ValueError, match="is not ao or pt"):
        ud.render("xx", str(tmp_path / "out.exr"), spp=4, client=client)


@pytest.mark.skipif(not PT, reason="UDM1_PT_TOOL not set")
def test_command_line(tmp_path):
    env = dict(os.environ)
    cmd = [sys.executable, "-m", "udm1.distributed", "--workers", "2", "--tasks", "6"]
    r = subprocess.run([*cmd, "render", PT, "-o", str(tmp_path / "d.exr"), "--spp", "6", "--tile", "20x20", "--",
                        "--size", "32x24"], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr
    # 4 tiles of at most 20x20, each in ceil(6 / 4) = 2 ranges: 8 parts
    assert "from 8 parts" in r.stdout and "8/8 parts" in r.stderr.replace("\r", "\n")
    subprocess.run([PT, "--size", "32x24", "--spp", "6", "-o", str(tmp_path / "one.exr")], check=True,
                   capture_output=True)
    assert (tmp_path / "d.exr").read_bytes() == (tmp_path / "one.exr").read_bytes()
    r = subprocess.run([*cmd, "integrate", "--integrand", "nosuch"], capture_output=True, text=True, env=env,
                       timeout=300)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1 and "'nosuch'" in r.stderr, r.stderr
    r = subprocess.run([*cmd, "render", PT, "-o", str(tmp_path / "e.exr"), "--spp", "4", "--", "--sampler", "nosuch"],
                       capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 2 and "unknown sampler 'nosuch'" in r.stderr and not (tmp_path / "e.exr").exists()
