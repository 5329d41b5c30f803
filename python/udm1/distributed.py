"""Split an ambient-occlusion or path-tracing render, or a Monte Carlo integral, over a Dask
cluster (dask.distributed) and merge the parts exactly.

A udm1 sample is addressed by (pixel, sample index, dimension), so any range of sample
indices of the same sequence can be computed anywhere. Work is split by sample-index ranges
(and by tiles for large images); each task runs udm1-ao / udm1-pt on its range and tile and
returns the image with exact integer sums, or sums f exactly over its range of points
(udm1.exact_sum). The merge adds integers, so the result equals a single-process run of the
same samples bit for bit, whichever worker ran which part, in whatever order, and after a
worker died and the scheduler ran its part again elsewhere.

    import udm1.distributed as ud
    with ud.connect(n_workers=2) as client:              # a LocalCluster; or connect("tcp://host:8786")
        ud.render("pt", "out.exr", spp=256, args=["--scene", "builtin:cornell"], client=client)
        est = ud.integrate(lambda x: x.prod(axis=1), "wr", d=4, n=1 << 22, client=client)

Command line: ``python -m udm1.distributed render pt -o out.exr --spp 256 [--workers 2]
[--scheduler ADDR] [--tasks T] [--tile WxH] [-- TOOL OPTIONS]`` and ``python -m udm1.distributed
integrate --integrand NAME --sampler wr --d 8 --n 1000000``.

Every wait on the cluster has a timeout (`timeout`, seconds, default TIMEOUT = one hour): when no
part finishes for that long (a stuck or lost cluster, idle workers, a hung tool), the call cancels its
tasks and raises TimeoutError naming what it waited for and the parts still pending. Give more for
parts that run longer than that, or None to wait without limit.

Workers need the same udm1 (package and tools) at the same paths as the client: a LocalCluster
has them; on other machines install the project at the same place (or pass tool=PATH). For workers
you start yourself, set MALLOC_TRIM_THRESHOLD_=268435456 and MALLOC_MMAP_THRESHOLD_=33554432 in the Dask
config's distributed.nanny.pre-spawn-environ as connect() does for its LocalCluster (see connect).
"""

from __future__ import annotations

import contextlib
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tempfile
import time
import uuid
from dataclasses import dataclass, field

import numpy as np

from ._convert import U32, U64, flag, function, integer, real, text
from .integrate import Integral, IntegralSpec, ToleranceResult, _chunk, _integrate_to_tolerance, _tolerance_arguments
from .integrate import integrate_range, values_range

__all__ = ["connect", "integrate", "integrate_to_tolerance", "render", "split_range", "split_tiles", "tool_path",
           "RenderResult", "TIMEOUT"]

WHERE = "udm1.distributed"
TIMEOUT = 3600.0  # seconds without a part finishing before a wait gives up (see the module's docstring)


def _timeout(timeout) -> float | None:
    return None if timeout is None else real(timeout, "timeout", lo=0.0, lo_open=True, where=WHERE)


def _count(value, name: str, lo: int = 1):
    """None (the default), or an integer >= lo."""
    return None if value is None else integer(value, name, lo, U32, where=WHERE)


def _hook(on_done):
    return None if on_done is None else function(on_done, "on_done", where=WHERE)


def _distributed():
    try:
        import distributed
    except ImportError as e:  # pragma: no cover - the package's requirements have it
        raise ImportError("udm1.distributed needs dask.distributed (pip install distributed)") from e
    return distributed


@contextlib.contextmanager
def connect(address: str | None = None, *, n_workers: int | None = None, threads_per_worker: int = 1,
            **cluster_options):
    """A dask.distributed Client: to the scheduler at `address`, or to a new LocalCluster of
    `n_workers` worker processes (default: one per core) with `threads_per_worker` threads."""
    distributed = _distributed()
    if address is not None:
        text(address, "address", where=WHERE)
    n_workers = _count(n_workers, "n_workers")
    threads_per_worker = integer(threads_per_worker, "threads_per_worker", 1, U32, where=WHERE)
    if address:
        client = distributed.Client(address)
        try:
            yield client
        finally:
            client.close()
        return
    import dask

    n = n_workers or os.cpu_count() or 1
    cluster_options.setdefault("dashboard_address", ":0")  # any free port: never "port 8787 in use"
    cluster_options.setdefault("silence_logs", 40)  # errors only: a killed worker is expected to be reported
    # Dask starts workers with MALLOC_TRIM_THRESHOLD_=65536, which also turns off glibc's adaptive mmap
    # threshold: every array above 128 KiB is then mapped and unmapped again, and an integral's chunks ran
    # 3.5x slower on a worker than in the client (BENCHMARKS.md). Keep freed memory for reuse instead.
    environ = dict(dask.config.get("distributed.nanny.pre-spawn-environ", {}) or {})
    environ.update(MALLOC_TRIM_THRESHOLD_=str(256 << 20), MALLOC_MMAP_THRESHOLD_=str(32 << 20))
    with dask.config.set({"distributed.nanny.pre-spawn-environ": environ}), \
            distributed.LocalCluster(n_workers=n, threads_per_worker=threads_per_worker, processes=True,
                                     **cluster_options) as cluster, distributed.Client(cluster) as client:
        yield client


def split_range(n: int, parts: int) -> list[tuple[int, int]]:
    """[0, n) as `parts` contiguous (first, count) ranges of sizes differing by at most one (at most n
    of them; [(0, 0)] for n = 0)."""
    n, parts = integer(n, "n", 0, U64, where=WHERE), integer(parts, "parts", 1, U64, where=WHERE)
    parts = max(1, min(parts, n))
    q, r = divmod(n, parts)
    out, first = [], 0
    for k in range(parts):
        count = q + (k < r)
        out.append((first, count))
        first += count
    return out


def split_tiles(width: int, height: int, tile: tuple[int, int]) -> list[tuple[int, int, int, int]]:
    """The image as tiles (x0, y0, x1, y1) of at most tile = (tw, th) pixels, row by row."""
    width, height = integer(width, "width", 1, U32, where=WHERE), integer(height, "height", 1, U32, where=WHERE)
    tw, th = _tile(tile)
    return [(x, y, min(x + tw, width), min(y + th, height)) for y in range(0, height, th) for x in range(0, width, tw)]


def tool_path(tool: str) -> str:
    """The udm1-ao or udm1-pt executable: a path as given, else $UDM1_AO_TOOL / $UDM1_PT_TOOL,
    else the project's build folder, else PATH."""
    if os.sep in text(tool, "tool", where=WHERE):
        return str(pathlib.Path(tool).resolve())
    name = {"ao": "udm1-ao", "pt": "udm1-pt"}.get(tool, tool)
    if name not in ("udm1-ao", "udm1-pt"):
        raise ValueError(f"udm1.distributed: tool '{tool}' is not ao or pt (or a path to udm1-ao/udm1-pt)")
    env = os.environ.get("UDM1_AO_TOOL" if name == "udm1-ao" else "UDM1_PT_TOOL")
    built = pathlib.Path(__file__).resolve().parents[2] / "build" / name[5:] / name
    for candidate in (env, str(built) if built.is_file() else None, shutil.which(name)):
        if candidate:
            return str(pathlib.Path(candidate).resolve())
    raise FileNotFoundError(f"udm1.distributed: {name} not found (build the project, or set "
                            f"{'UDM1_AO_TOOL' if name == 'udm1-ao' else 'UDM1_PT_TOOL'})")


class _Progress:
    """One status line on stderr, rewritten in place on a terminal: parts done, elapsed, left."""

    def __init__(self, what: str, total: int, enabled: bool):
        self.what, self.total, self.enabled = what, total, enabled
        self.done, self.t0 = 0, time.perf_counter()
        self.tty = enabled and sys.stderr.isatty()

    def step(self, note: str = "") -> None:
        self.done += 1
        if not self.enabled:
            return
        elapsed = time.perf_counter() - self.t0
        left = elapsed / self.done * (self.total - self.done)
        width = 24
        bar = "#" * (width * self.done // self.total) + "." * (width - width * self.done // self.total)
        line = (f"udm1.distributed: {self.what} [{bar}] {self.done}/{self.total} parts, {elapsed:.1f} s, "
                f"about {left:.0f} s left{(' (' + note + ')') if note else ''}")
        end = "" if self.tty and self.done < self.total else "\n"
        sys.stderr.write(("\r" if self.tty else "") + line + end)
        sys.stderr.flush()


def _stuck(futures, what: str, timeout: float) -> TimeoutError:
    pending = [f.key for f in futures if f.status == "pending"]
    keys = ", ".join(map(str, pending[:4])) + (", ..." if len(pending) > 4 else "")
    return TimeoutError(f"udm1.distributed: waited {timeout:g} s for {what} and no part finished: {len(pending)} of "
                        f"{len(futures)} parts still pending ({keys}); the cluster is stuck or too slow (raise "
                        f"timeout=, or None to wait without limit)")


def _completed(client, futures, *, what: str, timeout: float | None, with_results: bool):
    """The futures as they finish ((future, result) pairs with with_results; a task's exception raised),
    waited for on the client's own loop (as_completed's default is the default client's, and with two
    clients in one process - a cluster's and one to another scheduler - waiting on the wrong loop can
    hang). TimeoutError (_stuck) when none finishes for `timeout` seconds (None: no limit)."""
    distributed = _distributed()
    done = distributed.as_completed(futures, loop=client.loop, with_results=with_results)
    finished = getattr(done, "thread_condition", None)  # notified as each future finishes
    last = time.monotonic()
    while not done.is_empty():
        if done.has_ready():
            last = time.monotonic()
            yield next(done)
            continue
        left = None if timeout is None else timeout - (time.monotonic() - last)
        if left is not None and left <= 0:
            raise _stuck(futures, what, timeout)
        pause = 0.1 if left is None else min(0.1, left)
        if finished is None:
            time.sleep(min(pause, 0.01))
        else:
            with finished:
                finished.wait(timeout=pause)


def _result(future, what: str, timeout: float | None):
    """A finished future's result, fetched within `timeout` seconds."""
    try:
        return future.result(timeout=timeout)
    except TimeoutError:
        raise _stuck([future], what, timeout) from None


def _run_all(client, fn, items, *, what: str, progress: bool, on_done, timeout: float | None, extra=()):
    """Submit fn(*item, *extra) for every item, collect the results in item order, showing progress.
    A worker that dies has its tasks run again elsewhere by the scheduler (its allowed-failures rule);
    an exception inside a task is final (our tasks are deterministic: running them again cannot help).
    No part finishing for `timeout` seconds cancels the rest and raises TimeoutError."""
    token = uuid.uuid4().hex[:12]  # keys "udm1-<token>-<k>": part k of this run
    futures = [client.submit(fn, *item, *extra, key=f"udm1-{token}-{k}") for k, item in enumerate(items)]
    index = {f.key: k for k, f in enumerate(futures)}
    results = [None] * len(futures)
    bar = _Progress(what, len(futures), progress)
    try:
        for future, result in _completed(client, futures, what=what, timeout=timeout, with_results=True):
            k = index[future.key]
            results[k] = result
            bar.step(result.get("worker", "") if isinstance(result, dict) else "")
            if on_done is not None:
                on_done(k, result)
    except BaseException:
        client.cancel(futures)
        raise
    return results


def _worker_address() -> str:
    try:
        from distributed import get_worker

        return get_worker().address
    except (ImportError, ValueError):
        return "local"


# ------------------------------------------------------------------------------------ integrals

def _integral_task(first: int, count: int, f, spec: IntegralSpec, chunk: int, squares: bool = True) -> dict:
    t0 = time.perf_counter()
    part = integrate_range(f, spec, first, count, chunk, squares)
    return {"integral": part, "worker": _worker_address(), "seconds": time.perf_counter() - t0}


def integrate(f, sampler: str, d: int, n: int, *, seed: int = 0, randomize=True, stream: int = 0,
              tasks: int | None = None, chunk: int = 1 << 16, client=None, address: str | None = None,
              progress: bool = True, on_done=None, timeout: float | None = TIMEOUT) -> Integral:
    """udm1.integrate(f, sampler, d, n, ...) computed over a Dask cluster: [0, n) is split into
    `tasks` ranges (default: 4 per worker thread), each summed exactly on a worker, and the exact
    sums added. The Integral equals udm1.integrate's bit for bit. f must be picklable (cloudpickle:
    lambdas and closures are). on_done(k, result) is called as each part arrives. Every argument is
    checked before a cluster is reached (as udm1.integrate checks it); no part finishing for `timeout`
    seconds raises TimeoutError (see the module's docstring)."""
    f = function(f, "f", where=WHERE)
    spec = IntegralSpec(sampler, d, n, seed, randomize, stream)
    tasks, chunk, timeout = _count(tasks, "tasks"), _chunk(chunk), _timeout(timeout)
    progress, on_done = flag(progress, "progress", where=WHERE), _hook(on_done)
    spec.sequence()  # a bad dimension count or randomization fails here, in one line, before any task
    with _client(client, address) as c:
        parts = split_range(spec.n, tasks or 4 * _threads(c, timeout))
        results = _run_all(c, _integral_task, parts, what=f"integral of {spec.n} {spec.sampler} points",
                           progress=progress, on_done=on_done, timeout=timeout, extra=(f, spec, chunk))
    total = results[0]["integral"]
    for r in results[1:]:
        total = total + r["integral"]
    return total


def integrate_to_tolerance(f, sampler: str, d: int, *, abs_tol=None, rel_tol=None, n_max: int = 1 << 24,
                           n_init: int = 1 << 8, replications: int = 16, confidence: float = 0.99,
                           transform: str | None = None, criterion: str | None = None, seed: int = 0,
                           randomize=True, blocks: int | None = None, chunk: int = 1 << 16, strict: bool = True,
                           client=None, address: str | None = None, progress: bool = False,
                           timeout: float | None = TIMEOUT) -> ToleranceResult:
    """udm1.integrate(f, sampler, d, abs_tol=..., rel_tol=...) over a Dask cluster: at each doubling
    the new index range (of every replicate, or of the one lattice) is split into `blocks` blocks
    (default: enough for 4 tasks per worker thread), each summed exactly on a worker; the lattice
    criterion also brings the values back for its Fourier transform. The same stopping rule on the same
    exact sums: the result equals udm1.integrate's bit for bit (its `seconds` aside). Every argument is
    checked before a cluster is reached; no part finishing for `timeout` seconds raises TimeoutError."""
    rule = _tolerance_arguments(f, sampler, d, abs_tol, rel_tol, n_max, n_init, replications, confidence, transform,
                                criterion, seed, randomize, chunk, strict)
    blocks, timeout = _count(blocks, "blocks"), _timeout(timeout)
    progress = flag(progress, "progress", where=WHERE)
    with _client(client, address) as c:
        def ranges(fn, specs, first, count):
            per = blocks or max(1, -(-4 * _threads(c, timeout) // len(specs)))
            items = [(a, b, s) for s in specs for a, b in split_range(count, min(per, count))]
            results = _run_all(c, _tolerance_task, [(first + a, b, s) for a, b, s in items],
                               what=f"{len(specs)} replicates of [{first}, {first + count})", progress=progress,
                               on_done=None, timeout=timeout, extra=(fn, rule.chunk))
            totals = {}
            for (a, b, s), r in zip(items, results):
                totals[s.stream] = r["integral"] if s.stream not in totals else totals[s.stream] + r["integral"]
            return [totals[s.stream] for s in specs]

        def values(fn, spec, first, count):
            parts = split_range(count, min(blocks or 4 * _threads(c, timeout), count))
            results = _run_all(c, _values_task, [(first + a, b) for a, b in parts],
                               what=f"lattice points [{first}, {first + count})", progress=progress, on_done=None,
                               timeout=timeout, extra=(spec, fn, rule.chunk))
            total = results[0]["sum"]
            for r in results[1:]:
                total = total + r["sum"]
            return np.concatenate([r["values"] for r in results]), total

        return _integrate_to_tolerance(rule, ranges, values)


def _values_task(first: int, count: int, spec: IntegralSpec, f, chunk: int) -> dict:
    y, part = values_range(f, spec, first, count, chunk)
    return {"values": y, "sum": part, "worker": _worker_address()}


def _tolerance_task(first: int, count: int, spec: IntegralSpec, f, chunk: int) -> dict:
    return _integral_task(first, count, f, spec, chunk, squares=False)  # the rule uses the means only


# --------------------------------------------------------------------------------------- renders

_IMAGE = re.compile(r" image (\d+)x(\d+) at ")


@dataclass
class RenderResult:
    output: str                 # the merged OpenEXR image (exact sums)
    png: str | None
    width: int
    height: int
    spp: int
    seconds: float              # wall time: submit, render, transfer, merge
    parts: list = field(default_factory=list)  # per render task: index, bounds, first, count, worker, seconds
    merges: int = 0             # merge tasks run on the workers (the tree)


def _render_task(bounds, first: int, count: int, index: int, tool: str, args: list, spp: int, threads: int) -> dict:
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="udm1-part-") as tmp:
        out = os.path.join(tmp, "part.exr")
        cmd = [tool, *args, "--spp", str(spp), "--spp-first", str(first), "--spp-count", str(count),
               "--pixel-bounds", ",".join(map(str, bounds)), "--threads", str(threads), "-o", out]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{os.path.basename(tool)} failed on samples [{first}, {first + count}) pixels "
                               f"{bounds}: {r.stderr.strip()}")
        data = pathlib.Path(out).read_bytes()
    return {"data": data, "index": index, "bounds": tuple(bounds), "first": first, "count": count,
            "worker": _worker_address(), "seconds": time.perf_counter() - t0}


FAN_IN = 16  # parts per merge; a tile cut into more ranges is merged in a tree on the workers


def _run_tool(cmd: list, what: str, timeout: float | None) -> subprocess.CompletedProcess:
    """A tool run on the client, waited for at most `timeout` seconds."""
    try:
        return subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        raise TimeoutError(f"udm1.distributed: waited {timeout:g} s for {what} ({os.path.basename(cmd[0])}) and it "
                           f"did not finish (raise timeout=, or None to wait without limit)") from None


def _merge_files(tool: str, datas, out: str, png: str | None = None, timeout: float | None = None) -> None:
    """`tool merge` of EXR parts given as bytes, into `out` (atomic: the tool writes a temporary file)."""
    with tempfile.TemporaryDirectory(prefix=".udm1-merge-", dir=os.path.dirname(os.path.abspath(out))) as tmp:
        names = []
        for k, data in enumerate(datas):
            names.append(os.path.join(tmp, f"part{k}.exr"))
            pathlib.Path(names[-1]).write_bytes(data)
        cmd = [tool, "merge", *names, "-o", out] + (["--png", png] if png else [])
        r = _run_tool(cmd, f"the merge of {len(names)} parts", timeout)
    if r.returncode != 0:
        raise RuntimeError(f"merging the parts failed: {r.stderr.strip()}")


def _leaves(part: dict) -> list:
    """The render parts (without their image) that a part holds: itself, or those a merge joined."""
    return part.get("leaves") or [{k: v for k, v in part.items() if k != "data"}]


def _merge_task(tool: str, parts: list) -> dict:
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory(prefix="udm1-tree-") as tmp:
        out = os.path.join(tmp, "merged.exr")
        _merge_files(tool, [p["data"] for p in parts], out)
        data = pathlib.Path(out).read_bytes()
    return {"data": data, "bounds": parts[0]["bounds"], "first": parts[0]["first"],
            "count": sum(p["count"] for p in parts), "worker": _worker_address(), "seconds": time.perf_counter() - t0,
            "leaves": [leaf for p in parts for leaf in _leaves(p)]}


def probe(tool: str, args, spp: int, timeout: float | None = TIMEOUT) -> tuple[int, int]:
    """Run the tool once on one pixel and one sample: checks the scene and options here, with the
    tool's one-line error, and returns the image's width and height."""
    with tempfile.TemporaryDirectory(prefix="udm1-probe-") as tmp:
        cmd = [tool, *args, "--spp", str(spp), "--spp-first", "0", "--spp-count", "1", "--pixel-bounds",
               "0,0,1,1", "--threads", "1", "-o", os.path.join(tmp, "probe.exr")]
        r = _run_tool(cmd, "the probe of the scene on one pixel", timeout)
    if r.returncode != 0:
        raise ValueError(r.stderr.strip().splitlines()[-1] if r.stderr.strip() else f"{tool} failed")
    m = _IMAGE.search(r.stdout)
    if not m:
        raise RuntimeError(f"{tool} did not report its image size: {r.stdout.strip()}")
    return int(m.group(1)), int(m.group(2))


def _tile(tile) -> tuple[int, int]:
    if not isinstance(tile, (tuple, list)) or len(tile) != 2:
        raise ValueError(f"{WHERE}: tile must be (width, height), not {tile!r}")
    return integer(tile[0], "tile width", 1, U32, where=WHERE), integer(tile[1], "tile height", 1, U32, where=WHERE)


def render(tool: str, output: str, *, spp: int, args=(), png: str | None = None, tasks: int | None = None,
           tile: tuple[int, int] | None = None, threads_per_task: int = 1, client=None, address: str | None = None,
           progress: bool = True, on_done=None, fan_in: int = FAN_IN, timeout: float | None = TIMEOUT) -> RenderResult:
    """Render with udm1-ao or udm1-pt (tool "ao", "pt" or a path) over a Dask cluster into `output`
    (.exr, exact sums; `png` optional). args are the tool's options except --spp, ranges, bounds,
    threads and outputs (e.g. ["--scene", "s.pbrt", "--sampler", "wr"]). The image is cut into tiles
    of `tile` = (w, h) pixels (default: whole images up to 1024 x 1024, else 512 x 512 tiles) and
    each tile's samples [0, spp) into ceil(tasks / tiles) ranges (tasks default: 4 per worker thread).
    A tile's parts are merged on the workers, fan_in at a time, in a tree; the client merges the tiles.
    The merged image equals the tool's own single-process render of `spp` samples bit for bit.
    on_done(k, {"worker": address}) is called as render part k completes. No part finishing for
    `timeout` seconds (and the probe or the final merge taking longer) raises TimeoutError."""
    t0 = time.perf_counter()
    tool = tool_path(text(tool, "tool", where=WHERE))
    if isinstance(args, (str, bytes)):
        raise TypeError(f"{WHERE}.render: args must be a list of the tool's options, not a string")
    args = [str(a) for a in args]
    for a in args:
        if a in ("--spp", "--spp-first", "--spp-count", "--pixel-bounds", "--threads", "-o", "--png"):
            raise ValueError(f"udm1.distributed.render: pass {a} through render()'s own parameters, not args")
    if not str(output).lower().endswith(".exr"):
        raise ValueError(f"udm1.distributed.render: output '{output}' must be OpenEXR (.exr)")
    out_dir = pathlib.Path(output).resolve().parent
    if not out_dir.is_dir() or not os.access(out_dir, os.W_OK):
        raise ValueError(f"udm1.distributed.render: output folder '{out_dir}' is not a writable folder")
    spp, fan_in = integer(spp, "spp", 1, U32, where=WHERE), integer(fan_in, "fan_in", 0, U32, where=WHERE)
    if fan_in < 2:
        raise ValueError(f"udm1.distributed.render: fan_in {fan_in} must be at least 2")
    tasks, threads_per_task = _count(tasks, "tasks"), integer(threads_per_task, "threads_per_task", 1, U32, where=WHERE)
    tile = None if tile is None else _tile(tile)
    progress, on_done, timeout = flag(progress, "progress", where=WHERE), _hook(on_done), _timeout(timeout)
    width, height = probe(tool, args, spp, timeout)
    if tile is None:
        tile = (width, height) if width * height <= 1024 * 1024 else (512, 512)
    tiles = split_tiles(width, height, tile)
    what = f"{os.path.basename(tool)} {width}x{height} {spp} spp"
    with _client(client, address) as c:
        want = tasks or 4 * _threads(c, timeout)
        per_tile = max(1, min(spp, -(-want // len(tiles))))
        token = uuid.uuid4().hex[:12]  # keys "udm1-<token>-<k>": render part k of this run
        extra = (tool, args, spp, threads_per_task)
        leaves, merges, roots = [], [], []
        for t in tiles:
            group = []
            for first, count in split_range(spp, per_tile):
                k = len(leaves)
                leaves.append(c.submit(_render_task, t, first, count, k, *extra, key=f"udm1-{token}-{k}"))
                group.append(leaves[-1])
            while len(group) > fan_in:  # a tree of merges on the workers: parts never travel to the client
                group = [c.submit(_merge_task, tool, group[i:i + fan_in], key=f"udm1-{token}-merge-{len(merges) + j}")
                         for j, i in enumerate(range(0, len(group), fan_in))]
                merges.extend(group)
            roots.extend(group)
        try:
            _watch(c, leaves, merges, progress, on_done, what, timeout)
            tops = [_result(f, f"the merged tiles of {what}", timeout) for f in roots]
        except BaseException:
            c.cancel(leaves + merges)
            raise
    results = sorted((leaf for top in tops for leaf in _leaves(top)), key=lambda leaf: leaf["index"])
    _merge_files(tool, [top["data"] for top in tops], str(output), str(png) if png else None, timeout)
    return RenderResult(str(output), png, width, height, spp, time.perf_counter() - t0, results, len(merges))


def _watch(client, leaves, merges, progress: bool, on_done, what: str, timeout: float | None) -> None:
    """Wait for every render part and merge, showing progress, without moving images to the client.
    on_done(k, {"worker": address}) follows each render part. A task's error is raised (the caller
    cancels the rest); no part finishing for `timeout` seconds raises TimeoutError."""
    index = {f.key: k for k, f in enumerate(leaves)}
    bar = _Progress(what + (f", {len(merges)} merges" if merges else ""), len(leaves) + len(merges), progress)
    for future in _completed(client, leaves + merges, what=what, timeout=timeout, with_results=False):
        if future.status == "error":
            future.result()  # raises the task's exception
        try:
            holders = client.sync(client.scheduler.who_has, keys=[future.key], callback_timeout=timeout)
        except TimeoutError:
            raise TimeoutError(f"udm1.distributed: waited {timeout:g} s for the scheduler to say where part "
                               f"{future.key} of {what} is (raise timeout=, or None to wait without limit)") from None
        holders = holders.get(future.key, ())
        worker = sorted(holders)[0] if holders else ""
        bar.step(worker)
        if on_done is not None and future.key in index:
            on_done(index[future.key], {"worker": worker})


# ----------------------------------------------------------------------------------------- common

def _threads(client, timeout: float | None = TIMEOUT) -> int:
    """The cluster's worker threads, asked of the scheduler within `timeout` seconds."""
    try:
        return max(1, sum(client.nthreads(callback_timeout=timeout).values()))
    except TimeoutError:
        raise TimeoutError(f"udm1.distributed: waited {timeout:g} s for the scheduler to list its workers "
                           f"(raise timeout=, or None to wait without limit)") from None


@contextlib.contextmanager
def _client(client, address):
    if client is not None:
        yield client
    else:
        with connect(address) as c:
            yield c


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(prog="python -m udm1.distributed", description=__doc__.split("\n\n")[0])
    ap.add_argument("--scheduler", help="a Dask scheduler address (default: a LocalCluster)")
    ap.add_argument("--workers", type=int, help="LocalCluster worker processes (default: one per core)")
    ap.add_argument("--tasks", type=int, help="parts to split the work into (default: 4 per worker thread)")
    ap.add_argument("--quiet", action="store_true", help="no progress line")
    ap.add_argument("--timeout", type=float, default=TIMEOUT,
                    help=f"seconds to wait for the next part to finish before giving up (default {TIMEOUT:g}; 0: no "
                         f"limit)")
    sub = ap.add_subparsers(dest="command", required=True)
    r = sub.add_parser("render", help="udm1-ao or udm1-pt over the cluster; tool options after --")
    r.add_argument("tool", help="ao, pt, or a path to udm1-ao / udm1-pt")
    r.add_argument("-o", dest="output", required=True, help="the merged image (.exr)")
    r.add_argument("--png", help="also a PNG of it")
    r.add_argument("--spp", type=int, required=True)
    r.add_argument("--tile", help="tile size WxH (default: whole images up to 1024x1024)")
    r.add_argument("--threads-per-task", type=int, default=1)
    i = sub.add_parser("integrate", help="a test integrand of the library over the cluster")
    i.add_argument("--integrand", required=True, help="a name from udm1.integrands()")
    i.add_argument("--sampler", default="wr")
    i.add_argument("--d", type=int, default=8)
    i.add_argument("--n", type=int, default=1 << 20)
    i.add_argument("--seed", type=int, default=1)
    argv = list(sys.argv[1:] if argv is None else argv)
    tool_args = argv[argv.index("--") + 1:] if "--" in argv else []  # the tool's own options (--scene, ...)
    argv = argv[:argv.index("--")] if "--" in argv else argv
    ap.epilog = "render: the tool's options (--scene, --sampler, --size, ...) follow --"
    a = ap.parse_args(argv)
    try:
        if a.command == "integrate":
            from .metrics import integrands

            if a.integrand not in integrands():  # before starting a cluster
                raise ValueError(f"--integrand '{a.integrand}' is not one of {', '.join(integrands())}")
        with connect(a.scheduler, n_workers=a.workers) as client:
            if a.command == "render":
                args = tool_args
                tile = None
                if a.tile:
                    m = re.fullmatch(r"(\d+)x(\d+)", a.tile)
                    if not m or int(m.group(1)) < 1 or int(m.group(2)) < 1:
                        raise ValueError(f"--tile '{a.tile}' is not WxH")
                    tile = (int(m.group(1)), int(m.group(2)))
                res = render(a.tool, a.output, spp=a.spp, args=args, png=a.png, tasks=a.tasks, tile=tile,
                             threads_per_task=a.threads_per_task, client=client, progress=not a.quiet,
                             timeout=a.timeout or None)
                workers = sorted({p["worker"] for p in res.parts})
                print(f"wrote {res.output} ({res.width}x{res.height}, {res.spp} spp) from {len(res.parts)} parts on "
                      f"{len(workers)} worker(s) in {res.seconds:.2f} s")
            else:
                from .metrics import integrand, integrand_exact

                name = a.integrand
                est = integrate(lambda x: integrand(name, x), a.sampler, a.d, a.n, seed=a.seed, tasks=a.tasks,
                                client=client, progress=not a.quiet, timeout=a.timeout or None)
                exact = integrand_exact(name, a.d)
                print(f"{name} d={a.d} n={a.n} {a.sampler}: {est.value!r} (exact {exact!r}, error "
                      f"{abs(est.value - exact):.3g}, stderr {est.stderr:.3g})")
    except (ValueError, TypeError, FileNotFoundError, RuntimeError, TimeoutError) as e:
        print(f"udm1.distributed: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
