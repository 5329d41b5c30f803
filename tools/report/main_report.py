"""The main report: speed against error for every sampler in every application, in one folder.

Runs the report steps, each a program of its own whose progress is shown on the terminal, and records
what each did in OUT/steps.json. In the order they run:

    sampler-times  integration time per estimate of every sampler (udm1_bench_samplers error: 2
                randomizations per N, timed 4 times, the fastest kept), for the samplers step's error
                against time
    throughput  every sampler's values per second, bulk and per sample (udm1_bench_samplers throughput)
    ao          the paper's Figure 6 with udm1-ao (ao_report.py)
    pt          the paper's Figure 8/10 protocol with udm1-pt (pt_report.py)
    tent        beyond the paper: the tent transform's effect per integrand (udm1_bench_samplers error)
    mitsuba     udm1's samplers inside Mitsuba 3 against Mitsuba's own (bench/bench_mitsuba_sampler.py)
    crown       with --full, where ../shared has it: the same protocol on the paper's Crown as distributed
                (crown-volpath.pbrt: its gems' media) at 100 x 140
    renderers   with --full: udm1-pt against pbrt-v4 and Mitsuba 3 at equal error on the shared scenes
                (bench/bench_pt_scenes.py; skipped with a message where ../shared is absent)
    fastnoise   not with --quick: FastNoiseSIMD built from its sdist for the noise step, once per build folder
    screen      beyond the paper: blue-noise error from screen-space decorrelation (screen_report.py)
    samplers    integration RMSE against N and time, slopes, spectra, zone plates (sampler_report.py; the
                times are sampler-times')
    tolerance   integration to a tolerance against QMCPy and scipy (bench/bench_integrate.py)
    sequences   point plots, discrepancy against N, the constant-set check, exactness (sequence_report.py)
    accuracy    with --full: udm1-pt against pbrt-v4 on every shared and test scene (bench/bench_accuracy.py;
                pbrt-v4 built once from ../shared/anchors, skipped with a message where it is absent)
    noise       the paper's Figures 2 and 3 (udm1-noise figures), noise evaluations per second against
                libnoise (udm1_bench_noise) and FastNoiseSIMD (bench_noise.py;
                FastNoise Lite where FastNoiseSIMD is not installed), spectra (noise_report.py)

The steps whose figures are times (sampler-times to renderers, and noise) run one at a time, alone on
the machine, so that their times are not another step's; the others (fastnoise to accuracy) run two at a
time (--jobs) once those are done (tolerance's times, each method in turn within a trial, are compared
with each other only). Then it writes OUT/index.html (static, opens from disk) and OUT/report.md from the
steps' JSON: first the verdict (per application, the best sampler at equal time and at equal spp, its gain
over PRNG and over the best other sampler, and the machine), then the paper's claims from Figures 6, 8 and
10 next to ours with a verdict per claim, then the details: a table of the steps (a failed step is shown
failed, with its error, and its numbers are not shown; each step's time, processor time and whether it ran
alone), speed against error per application (tables and plots), and the machine, versions and commands.
Every table of the index is also in OUT/report.json (raw numbers, with the format each cell is shown with)
and OUT/csv/<table>.csv.

Resumable: a step whose command, programs and scripts (and the steps it needs) are unchanged since it last
finished is reused (--fresh redoes everything); a failed or interrupted step runs again. Exit status 1 if a
step failed. References are kept by content in OUT/cache (report_common.cached_reference): a step, or a
later run, asking for the same tool, scene and settings reuses the image. While a step runs, a line every
15 s names it and gives its elapsed time and the estimated time left in it and in all (EXPECTED, or the
step's last time in OUT, scaled by this run's pace; the order above simulated on those estimates). The
default configuration keeps the verdicts' seeds and leaves the long sweeps (AO and PT to 1024 spp, the
screen step's 4 seeds, tolerance at d = 32, the constant-set check at d = 64 to n = 1024) and the shared
scenes to --full.

    python tools/report/main_report.py --build build --out report [--quick | --full] [--jobs N]
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import html
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_common import file_digest, inline, log, md_table, writable_folder  # noqa: E402
import report_summary as summary  # noqa: E402

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]
SHARED = ROOT.parent / "shared" / "scenes"


@dataclass
class Step:
    name: str
    title: str
    commands: list[list[str]]            # run in order; a non-zero exit fails the step
    outputs: list[str]                   # files (relative to OUT) the step leaves; all must exist to reuse it
    page: str | None = None              # the step's own page, linked from the index
    stdout: dict[int, str] = field(default_factory=dict)  # command index -> file (relative to OUT) for its stdout
    exclusive: bool = False              # it measures time: it runs alone on the machine (run_steps)
    needs: tuple[str, ...] = ()          # steps whose results it uses: it starts after them


TENT_SAMPLERS = ["wr", "wr+tent", "rd", "rd+tent", "wopt", "wopt+tent", "lattice", "lattice+tent", "sobol-owen", "pmj02"]


def plan(args, out: Path) -> list[Step]:
    """The steps and their exact commands for this configuration."""
    py, b = sys.executable, Path(args.build)
    tools = {"bench_samplers": args.bench_samplers or str(b / "bin" / "udm1_bench_samplers"),
             "bench_noise": args.bench_noise or str(b / "bin" / "udm1_bench_noise"),
             "noise": args.noise or str(b / "bin" / "udm1-noise"),
             "ao": args.ao or str(b / "bin" / "udm1-ao"),
             "pt": args.pt or str(b / "bin" / "udm1-pt")}
    q = ["--quick"] if args.quick else []
    o = ["--out", str(out)]
    seeds = "16" if args.full else "8"
    reps = "4" if args.quick else ("64" if args.full else "32")
    seconds = "0.01" if args.quick else ("0.5" if args.full else "0.1")
    noise_reps = "1" if args.quick else "5"
    # this processor's instruction set; --full adds FastNoiseSIMD and udm1 capped at AVX2 (FastNoiseSIMD built
    # from its sdist for it)
    noise_levels = "native,avx2" if args.full else "native"
    noise_anchor = ["--installed-anchor"] if args.quick else []  # (--quick: no FastNoiseSIMD build)
    tolerance_args = (["--trials", "1", "--dims", "2,8", "--families", "oscillatory,gaussian"] if args.quick else
                      ["--trials", "50"] if args.full else ["--trials", "10", "--dims", "2,8"])  # --full: d = 32 too
    if args.quick:
        mitsuba_args = ["--size", "32", "--spps", "4,16", "--seeds", "1", "--ref-spp", "256", "--scalar-size", "16",
                        "--scalar-spps", "4", "--scalar-seeds", "1"]
    elif args.full:
        mitsuba_args = []  # the benchmark's own settings (BENCHMARKS.md)
    else:
        mitsuba_args = ["--size", "64", "--spps", "16,64", "--seeds", "2", "--ref-spp", "2048", "--scalar-size", "24",
                        "--scalar-spps", "16", "--scalar-seeds", "1"]
    ao = [py, str(HERE / "ao_report.py"), "--ao", tools["ao"], *o, *q]
    if not args.quick and not args.full:  # Figure 6's reference: its error is far below the compared RMSE (ao.md);
        ao += ["--ref-spp", "2048", "--sweep-spps", "16,32,64,128"]  # the sweep's 256 spp: with --full
    if args.full:
        ao += ["--size", "512x512", "--sweep-size", "256x256", "--sweep-spps", "16,32,64,128,256,512,1024"]
    screen = [py, str(HERE / "screen_report.py"), "--ao", tools["ao"], "--pt", tools["pt"], *o, *q]
    if args.full:  # more seeds, and udm1-pt's reference at 8192 spp rather than the pt step's own 4096
        screen += ["--seeds", "4", "--pt-ref-spp", "8192"]
    pt = [py, str(HERE / "pt_report.py"), "--pt", tools["pt"], *o, *q] + (["--full"] if args.full else [])
    # sampler-times: 2 randomizations per N, timed 4 times (2 with --quick), the fastest kept: a window of a
    # millisecond that another process interrupted is not the one reported
    times = ["--reps", "2", "--time-repeats", "2" if args.quick else "4"]
    # the integration sweep's N (the benchmark's own with --full and --quick; the default leaves out N = 10000, a
    # non-power of two between 4096 and 16384 that costs a third of the sweep), and the tent step's: its table reads
    # the largest N only
    ns = [] if args.quick or args.full else ["--ns", "64,256,1000,1024,4096,16384"]
    tent_ns = [] if args.quick else ["--ns", "16384"]
    # In the order they run (run_steps): the steps that measure time first, one at a time and alone on the machine;
    # then the others, two at a time (the sampler step's RMSE after its times were measured alone); then the noise
    # step, alone, once its anchor is built.
    timed = [
        Step("sampler-times", "Integration time per estimate, every sampler (alone on the machine; few randomizations)",
             [[tools["bench_samplers"], "error", *times, *ns, *q]], ["sampler_times.csv"],
             stdout={0: "sampler_times.csv"}, exclusive=True),
        Step("throughput", "Sampler throughput (values per second, one thread)",
             [[tools["bench_samplers"], "throughput", "--seconds", seconds]], ["throughput.txt"],
             stdout={0: "throughput.txt"}, exclusive=True),
        Step("ao", "Ambient occlusion: the paper's Figure 6 (udm1-ao)", [ao], ["ao.json"], "ao.html", exclusive=True),
        Step("pt", "Path tracing: the paper's Figures 8 and 10 protocol (udm1-pt)", [pt], ["pt.json"], "pt.html",
             exclusive=True),
        Step("tent", "Beyond the paper: the tent transform (+tent) on the integrands, against Sobol and PMJ02",
             [[tools["bench_samplers"], "error", "--samplers", ",".join(TENT_SAMPLERS), "--reps", reps, *tent_ns, *q]],
             ["tent.csv"], stdout={0: "tent.csv"}, exclusive=True),
        Step("mitsuba", "udm1's samplers inside Mitsuba 3 (its native plugin) against Mitsuba's own",
             [[py, str(ROOT / "bench" / "bench_mitsuba_sampler.py"), "--out", str(out / "mitsuba"), *mitsuba_args]],
             ["mitsuba/results.json"], exclusive=True),
    ] + crown_step(args, py, tools["pt"], out) + renderers_step(args, py, tools["pt"], out)
    # FastNoiseSIMD, the noise step's anchor, built from its sdist where it is not yet (a minute of one core): beside
    # other work, before the noise step measures alone
    fastnoise = [] if args.quick else [
        Step("fastnoise", "FastNoiseSIMD built from its sdist for the noise step (once per build folder)",
             [[py, str(ROOT / "bench" / "bench_noise.py"), "--build-only", "--levels", noise_levels]],
             ["fastnoise_build.txt"], stdout={0: "fastnoise_build.txt"})]
    # the longest first, two at a time: the screen step beside the tolerance step, then FastNoiseSIMD's build (whose
    # compile leaves a core partly idle), the sampler and sequence steps
    untimed = [
        Step("screen", "Beyond the paper: screen-space decorrelation of Weyl sequences (udm1-ao, udm1-pt)",
             [screen], ["screen.json"], "screen.html"),
        Step("tolerance", "Integration to a tolerance: udm1.integrate against QMCPy and scipy on Genz's families",
             [[py, str(ROOT / "bench" / "bench_integrate.py"), "--out", str(out / "tolerance"), *tolerance_args]],
             ["tolerance/results.json"]),
    ] + fastnoise + [
        Step("samplers", "Integration error against N and against time, every sampler",
             [[py, str(HERE / "sampler_report.py"), "--bench", tools["bench_samplers"], *o, "--reps", reps, *ns,
               "--times", str(out / "sampler_times.csv"), *q]],
             ["samplers.json"], "samplers.html", needs=("sampler-times",)),
        Step("sequences", "Sequences: points, discrepancy, constant-set check, exactness",
             [[py, str(HERE / "sequence_report.py"), *o, "--seeds", seeds, *q] + (["--full"] if args.full else [])],
             ["sequences.json"], "sequences.html"),
    ] + accuracy_step(args, py, tools["pt"], out)
    return timed + untimed + [
        Step("noise", "Noise: the paper's Figures 2 and 3, evaluations per second, spectra",
             [[tools["noise"], "figures", "-o", str(out / "noise")],
              [tools["bench_noise"], "--reps", noise_reps],
              [py, str(ROOT / "bench" / "bench_noise.py"), "--reps", noise_reps, "--levels", noise_levels,
               *noise_anchor, "--json", str(out / "noise_simd.json")],
              [py, str(HERE / "noise_report.py"), *o, *q]],
             ["noise/figures.md", "noise_libnoise.txt", "noise_simd.json", "noise_spectra.json"], "noise/figures.md",
             stdout={1: "noise_libnoise.txt", 2: "noise_fastnoise.txt"}, exclusive=True,
             needs=("fastnoise",) if fastnoise else ()),
    ]


def crown_step(args, py: str, pt: str, out: Path) -> list[Step]:
    """--full: the paper's Figure 10 scene itself, where ../shared has it."""
    crown = SHARED / "crown" / "crown-volpath.pbrt"  # as distributed: Integrator "volpath", its gems' media
    if not args.full:
        return []
    if not crown.exists():
        log(f"{crown} is absent: the Crown step is left out")
        return []
    return [Step("crown", "Path tracing: the Crown, the paper's Figure 10 scene (udm1-pt, 100 x 140)",
                 [[py, str(HERE / "pt_report.py"), "--pt", pt, "--out", str(out / "crown"), "--scene", str(crown),
                   "--size", "100x140", "--sweep-size", "50x70", "--sweep-spps", "16,64,256,1024"]], ["crown/pt.json"],
                 "crown/pt.html", exclusive=True)]


def accuracy_step(args, py: str, pt: str, out: Path) -> list[Step]:
    """--full: udm1-pt against pbrt-v4 on the same files (the tool skips, saying why, what is absent)."""
    if not args.full:
        return []
    return [Step("accuracy", "Path tracing: udm1-pt against pbrt-v4 on the same scene files (image means)",
                 [[py, str(ROOT / "bench" / "bench_accuracy.py"), "--tool", pt, "--out", str(out / "accuracy")]],
                 ["accuracy/accuracy.json"], "accuracy/accuracy.md")]


def renderers_step(args, py: str, pt: str, out: Path) -> list[Step]:
    """--full: udm1-pt against pbrt-v4 and Mitsuba 3 at equal error (the tool skips, saying why, what is absent)."""
    if not args.full:
        return []
    return [Step("renderers", "Path tracing: udm1-pt against pbrt-v4 and Mitsuba 3 at equal error on the shared scenes",
                 [[py, str(ROOT / "bench" / "bench_pt_scenes.py"), "--tool", pt, "--out", str(out / "renderers")]],
                 ["renderers/pt_scenes.json"], "renderers/pt_scenes.md", exclusive=True)]


def step_key(step: Step, shared: str, out: Path, needed: list[str]) -> str:
    """What a step's result depends on: its commands, the content of every program and script they name (not the
    files in OUT: those are other steps' results, `needed` has their keys), and `shared`: the digest of what every
    step uses (the report's shared module and the library)."""
    h = hashlib.sha256(json.dumps(step.commands).encode())
    h.update(shared.encode())
    for key in needed:
        h.update(key.encode())
    for cmd in step.commands:
        for a in cmd:
            if a != sys.executable and os.path.isfile(a) and not a.endswith((".json", ".txt")) and \
                    not Path(a).resolve().is_relative_to(out):
                h.update(file_digest(a).encode())
    return h.hexdigest()


# Rough seconds each step takes on an idle 2-core machine in each configuration (as run_steps runs it: the steps
# that measure no time two at a time): the estimate of the time left before a step has finished once in this output
# folder (then its last time there is used), scaled by this run's pace (a busier or slower machine).
# BENCHMARKS.md, "The main report", has measured times.
EXPECTED = {"default": {"sampler-times": 20, "throughput": 7, "ao": 90, "pt": 110, "tent": 6, "mitsuba": 20,
                        "fastnoise": 80, "screen": 300, "samplers": 110, "tolerance": 100, "sequences": 32, "noise": 10},
            "quick": {"sampler-times": 3, "throughput": 3, "ao": 6, "pt": 5, "tent": 2, "mitsuba": 8, "screen": 30,
                      "samplers": 12, "tolerance": 4, "sequences": 8, "noise": 10},
            "full": {"sampler-times": 30, "throughput": 25, "ao": 900, "pt": 900, "tent": 15, "mitsuba": 600,
                     "crown": 900, "renderers": 2700, "fastnoise": 160, "screen": 450, "samplers": 200, "tolerance": 400,
                     "sequences": 90, "accuracy": 900, "noise": 120}}
TICK = float(os.environ.get("UDM1_REPORT_TICK") or 15.0)  # seconds between two progress lines of a running step


def duration(seconds: float) -> str:
    return f"{seconds:.0f} s" if seconds < 90 else f"{seconds / 60:.1f} min"


def startable(pending: list[int], running: list[int], steps: list[Step], slots: int) -> int | None:
    """The step run_steps starts next, or None (wait for a running step to end). In plan order: a step waits for
    the steps it needs; a step that measures time (exclusive) starts only on an idle machine, and no later step
    starts before it; the others run up to `slots` at a time, never beside an exclusive step."""
    waiting = {steps[k].name for k in pending + running}
    for k in pending:
        if any(n in waiting for n in steps[k].needs):
            continue
        if steps[k].exclusive:
            return k if not running else None
        if len(running) < slots and not any(steps[r].exclusive for r in running):
            return k
    return None


def time_left(steps: list[Step], pending: list[int], running: dict[int, float], estimate: list[float],
              slots: int) -> float:
    """Seconds until the last step ends, simulating run_steps' order on the estimates: `running` maps each running
    step to its estimated seconds left."""
    now, run, todo = 0.0, dict(running), list(pending)
    while todo or run:
        while True:
            k = startable(todo, list(run), steps, slots)
            if k is None:
                break
            todo.remove(k)
            run[k] = now + estimate[k]
            if not run[k] > now:  # no estimate: counted as done at once
                run[k] = now
        if not run:  # (a step that needs a step that is not in this run: the order alone is kept)
            k = todo.pop(0)
            run[k] = now + estimate[k]
        k = min(run, key=run.get)
        now = max(now, run.pop(k))
    return now


class Progress:
    """A line every TICK seconds per running step: its elapsed time and the estimated time left in it and in the
    whole job (run_steps' order simulated on the estimates of the steps still to run). Each line names its step, so
    two steps running side by side stay apart."""

    def __init__(self):
        self.lock = threading.Lock()
        self.stop = threading.Event()
        self.thread = None
        self.rows: dict[int, tuple[str, float, float | None]] = {}  # step -> (label, start, estimate)
        self.rest = None  # (pending, running estimate) -> seconds in all, set by run_steps

    def say(self, line: str):
        with self.lock:
            print(line, file=sys.stderr, flush=True)

    def begin(self, rest):
        self.rest, self.rows = rest, {}
        self.stop.clear()

        def tick():
            while not self.stop.wait(TICK):
                with self.lock:
                    rows = dict(self.rows)
                now = time.time()
                left = {k: max(0.0, (est or 0.0) - (now - t0)) for k, (_, t0, est) in rows.items()}
                total = self.rest(left)
                for k, (label, t0, est) in sorted(rows.items()):
                    el = now - t0
                    if est is None:
                        what = f"no estimate for this step yet; about {duration(total)} in all"
                    elif el <= est:
                        what = f"about {duration(est - el)} left in this step, {duration(total)} in all"
                    else:  # past its estimate: say so rather than show a negative time
                        what = f"past its estimate of {duration(est)}; then about {duration(total)} for the rest"
                    self.say(f"[report] [{label}] {duration(el)} elapsed; {what}")

        self.thread = threading.Thread(target=tick, daemon=True)
        self.thread.start()

    def add(self, k: int, label: str, estimate: float | None):
        with self.lock:
            self.rows[k] = (label, time.time(), estimate)

    def remove(self, k: int):
        with self.lock:
            self.rows.pop(k, None)

    def end(self):
        self.stop.set()
        if self.thread:
            self.thread.join()


PROGRESS = Progress()


def say(msg: str) -> None:
    """A progress line of the job, whole among the lines of the steps running side by side."""
    PROGRESS.say(f"[report] {msg}")


def run_command(cmd: list[str], out: Path, stdout_name: str | None, label: str) -> float:
    """Run one command with its stderr shown as progress; its stdout goes to a file written under a temporary
    name and renamed on success. Returns its processor seconds (user and system, its own and its children's, every
    core). Raises RuntimeError with the command's last error line on failure."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(filter(None, [str(ROOT / "python"),
                                                                    os.environ.get("PYTHONPATH")])),
           "UDM1_REPORT_CACHE": str(out / "cache")}  # references by content, shared by the steps (report_common.py)
    target = out / stdout_name if stdout_name else None
    tmp = target.with_name(target.name + ".tmp") if target else None
    try:
        with open(tmp, "w") if tmp else open(os.devnull, "w") as sink:
            proc = subprocess.Popen(cmd, stdout=sink, stderr=subprocess.PIPE, text=True, env=env)
    except OSError as exc:
        raise RuntimeError(f"cannot run '{cmd[0]}': {exc.strerror}") from None
    last = []
    for line in proc.stderr:
        line = line.rstrip()
        if line:
            PROGRESS.say(f"  [{label}] {line.removeprefix('[report] ')}")
            last = (last + [line])[-3:]
    proc.stderr.close()
    # this command's own rusage (steps run side by side: the job's RUSAGE_CHILDREN would mix them)
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    if proc.returncode != 0:
        if tmp and tmp.exists():
            tmp.unlink()
        why = next((x for x in reversed(last) if not x.startswith("[report]")), last[-1] if last else "")
        raise RuntimeError(f"{Path(cmd[1] if cmd[0] == sys.executable else cmd[0]).name} exited with status "
                           f"{proc.returncode}" + (f": {why.removeprefix('[report] ')}" if why else ""))
    if tmp:
        tmp.replace(target)
    return usage.ru_utime + usage.ru_stime


def run_steps(steps: list[Step], out: Path, args) -> dict:
    library = Path(os.environ.get("UDM1_LIBRARY") or Path(args.build) / "libudm1" / "libudm1.so.1")
    shared = file_digest(str(HERE / "report_common.py")) + (file_digest(str(library)) if library.exists() else "")
    state_path = out / "steps.json"
    try:
        previous = json.loads(state_path.read_text()) if state_path.exists() and not args.fresh else {}
    except (OSError, ValueError):
        previous = {}
    state = {}
    only = set(args.only.split(",")) if args.only else None
    mode = "quick" if args.quick else ("full" if args.full else "default")
    slots = max(1, args.jobs)
    keys: list[str] = []
    for step in steps:  # (a step comes after the steps it needs)
        keys.append(step_key(step, shared, out, [keys[i] for i, st in enumerate(steps[:len(keys)]) if st.name in step.needs]))
    reusable = [previous.get(st.name, {}).get("status") in ("ok", "reused") and previous[st.name].get("key") == key
                and all((out / o).exists() for o in st.outputs) for st, key in zip(steps, keys)]
    to_run = [not r and (only is None or st.name in only) for st, r in zip(steps, reusable)]
    # the estimate: this step's last time in this folder in this configuration, else the table's
    estimate = [previous.get(st.name, {}).get("seconds") if previous.get(st.name, {}).get("status") in ("ok", "reused") and
                previous[st.name].get("mode") == mode else EXPECTED.get(mode, {}).get(st.name) for st in steps]
    labels = [f"{k + 1}/{len(steps)} {st.name}" for k, st in enumerate(steps)]
    records = [{"title": st.title, "commands": [" ".join(c) for c in st.commands], "key": key, "mode": mode,
                "alone": st.exclusive} for st, key in zip(steps, keys)]
    pending = [k for k in range(len(steps)) if to_run[k]]
    if pending:
        total = time_left(steps, pending, {}, [e or 0.0 for e in estimate], slots)
        say(f"{len(pending)} step(s) to run, about {duration(total)} in all on this machine ("
            + (f"the steps that measure no time {slots} at a time, " if slots > 1 else "")
            + f"those that measure time alone; a line every {TICK:.0f} s on long steps)")
    for k, step in enumerate(steps):
        old = previous.get(step.name, {})
        if reusable[k]:
            say(f"[{labels[k]}] reused: unchanged since it finished at {old.get('finished')} ({old.get('seconds', 0):.0f} s)")
            state[step.name] = {**records[k], "status": "reused", "seconds": old.get("seconds", 0.0), "error": "",
                                "cpu_seconds": old.get("cpu_seconds"), "finished": old.get("finished")}
        elif not to_run[k]:
            say(f"[{labels[k]}] not run (not in --only, and no finished result to reuse)")
            state[step.name] = {**records[k], "status": "not run", "seconds": 0.0, "error": ""}

    lock = threading.Condition()
    pace = [0.0, 0.0]  # the estimates and the times of the steps finished in this run: the estimates of the steps
    running: dict[int, float] = {}  # still to run are scaled by their ratio (a slower or busier machine than the table's)

    def scale() -> float:
        return pace[1] / pace[0] if pace[0] > 0 else 1.0

    def scaled(k: int) -> float | None:
        return estimate[k] * scale() if estimate[k] else None

    def rest(left: dict[int, float]) -> float:
        with lock:
            todo = list(pending)
        return time_left(steps, todo, left, [scaled(k) or 0.0 for k in range(len(steps))], slots)

    def save():  # (with the lock held) an interrupted step stays "running": it is not "ok" on the next run
        state_path.write_text(json.dumps({**previous, **state}, indent=1))

    def run_one(k: int):
        step, t0, cpu = steps[k], time.time(), 0.0
        try:
            for i, cmd in enumerate(step.commands):
                cpu += run_command(cmd, out, step.stdout.get(i), step.name)
            missing = [o for o in step.outputs if not (out / o).exists()]
            if missing:
                raise RuntimeError(f"finished without writing {', '.join(missing)}")
            status, error = "ok", ""
        except RuntimeError as exc:
            status, error = "failed", str(exc)
        except Exception as exc:  # noqa: BLE001 - a bug here must not leave the job waiting
            status, error = "failed", f"{type(exc).__name__}: {exc}"
        seconds = time.time() - t0
        PROGRESS.remove(k)
        with lock:
            state[step.name].update(status=status, error=error, seconds=seconds, cpu_seconds=cpu, started=t0,
                                    ended=t0 + seconds, finished=time.strftime("%Y-%m-%d %H:%M:%S"))
            if status == "ok" and estimate[k]:
                pace[0] += estimate[k]
                pace[1] += seconds
            running.pop(k)
            save()
            lock.notify_all()
        say(f"[{labels[k]}] {status} in {seconds:.0f} s ({cpu:.0f} processor s)" + (f": {error}" if error else ""))

    PROGRESS.begin(rest)
    try:
        with lock:
            while pending or running:
                k = startable(pending, list(running), steps, slots)
                if k is None and not running:  # (a step that needs one that comes after it: in plan order)
                    k = pending[0]
                if k is None:
                    lock.wait()
                    continue
                pending.remove(k)
                running[k] = time.time()
                s = scale()
                side = [labels[r] for r in running if r != k]
                say(f"[{labels[k]}] {steps[k].title}" + (f" (about {duration(scaled(k))}" + (
                    f"; the estimates x{s:.2f}, this run's pace so far" if abs(s - 1) > 0.1 else "") + ")"
                    if scaled(k) else "") + (" alone: it measures time" if steps[k].exclusive else
                                             f" beside {', '.join(side)}" if side else ""))
                state[steps[k].name] = {**records[k], "status": "running", "seconds": 0.0, "error": ""}
                save()
                PROGRESS.add(k, labels[k], scaled(k))
                threading.Thread(target=run_one, args=(k,), daemon=True).start()
    finally:
        PROGRESS.end()
    state_path.write_text(json.dumps(state, indent=1))
    return state


# ---- the index: blocks rendered to Markdown and HTML from the same data -------------------------------------

def cell(value, fmt: str) -> str:
    """How a value is shown: None as "-", numbers with their format, anything else as text."""
    if value is None:
        return "-"
    if isinstance(value, (int, float)) and not isinstance(value, bool) and fmt:
        if isinstance(value, float) and not math.isfinite(value):
            return str(value)
        return format(value, fmt)
    return str(value)


class Document:
    def __init__(self):
        self.blocks: list[tuple] = []
        self.tables: dict[str, dict] = {}
        self.failed_sections: list[str] = []

    def heading(self, level: int, text: str, anchor: str = ""):
        self.blocks.append(("h", level, text, anchor))

    def para(self, text: str):
        self.blocks.append(("p", text))

    def image(self, src: str, alt: str):
        self.blocks.append(("img", src, alt))

    def table(self, tid: str, title: str, columns: list[tuple[str, str, str]], rows: list[dict]):
        """columns: (key, label, format); the raw rows go to report.json and csv/<tid>.csv."""
        self.tables[tid] = {"title": title, "columns": [list(c) for c in columns], "rows": rows}
        self.blocks.append(("table", tid))

    def markdown(self) -> str:
        parts = []
        for b in self.blocks:
            if b[0] == "h":
                parts.append("#" * b[1] + " " + b[2])
            elif b[0] == "p":
                parts.append(b[1])
            elif b[0] == "img":
                parts.append(f"![{b[2]}]({b[1]})")
            else:
                t = self.tables[b[1]]
                parts.append(md_table([c[1] for c in t["columns"]],
                                      [[cell(r.get(c[0]), c[2]) for c in t["columns"]] for r in t["rows"]])
                             + f"\n\n[{b[1]}.csv](csv/{b[1]}.csv)")
        return "\n\n".join(parts) + "\n"

    def html(self, title: str) -> str:
        body = []
        for b in self.blocks:
            if b[0] == "h":
                anchor = f' id="{b[3]}"' if b[3] else ""
                body.append(f"<h{b[1]}{anchor}>{inline(b[2])}</h{b[1]}>")
            elif b[0] == "p":
                body.append(f"<p>{inline(b[1])}</p>")
            elif b[0] == "img":
                body.append(f'<p><img alt="{html.escape(b[2])}" src="{html.escape(b[1])}"></p>')
            else:
                t = self.tables[b[1]]
                head = "".join(f"<th>{html.escape(c[1])}</th>" for c in t["columns"])
                rows = "".join("<tr>" + "".join(
                    f"<td class='{cls(r.get(c[0]))}'>{html.escape(cell(r.get(c[0]), c[2]))}</td>" for c in t["columns"])
                    + "</tr>" for r in t["rows"])
                body.append(f'<table id="{b[1]}"><tr>{head}</tr>{rows}</table>'
                            f'<p class="raw"><a href="csv/{b[1]}.csv">{b[1]}.csv</a></p>')
        style = ("body{font-family:sans-serif;max-width:1150px;margin:auto;padding:1em}table{border-collapse:collapse}"
                 "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}img{max-width:100%}"
                 "td.failed,td.fails{background:#fdd}td.ok,td.holds{background:#dfd}td.tie{background:#ffd}"
                 ".raw{font-size:80%;margin-top:2px}")
        return (f"<!doctype html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
                f"<style>{style}</style></head><body>{''.join(body)}</body></html>\n")


def cls(value) -> str:
    s = str(value).split(" ")[0] if isinstance(value, str) else ""
    return s if s in ("failed", "fails", "ok", "holds", "tie", "reused") else ""


def machine_info(build: Path) -> dict:
    info = {"date": time.strftime("%Y-%m-%d %H:%M:%S %Z"), "platform": platform.platform(),
            "python": platform.python_version(), "cores": os.cpu_count()}
    try:
        cpu = re.search(r"model name\s*:\s*(.*)", Path("/proc/cpuinfo").read_text())
        info["cpu"] = cpu.group(1) if cpu else platform.processor()
        mem = re.search(r"MemTotal:\s*(\d+)", Path("/proc/meminfo").read_text())
        info["memory"] = f"{int(mem.group(1)) / 2**20:.1f} GiB" if mem else "?"
    except OSError:
        info["cpu"] = platform.processor()
    try:
        os_release = dict(re.findall(r'^(\w+)="?([^"\n]*)"?$', Path("/etc/os-release").read_text(), re.M))
        info["os"] = os_release.get("PRETTY_NAME", "?")
    except OSError:
        pass
    try:
        cache = (build / "CMakeCache.txt").read_text()
        compiler = re.search(r"CMAKE_CXX_COMPILER:[A-Z]+=(.*)", cache)
        build_type = re.search(r"CMAKE_BUILD_TYPE:[A-Z]+=(.*)", cache)
        if compiler:
            info["compiler"] = subprocess.run([compiler.group(1), "--version"], capture_output=True,
                                              text=True).stdout.splitlines()[0]
        info["build type"] = build_type.group(1) if build_type else "?"
    except (OSError, IndexError):
        pass
    try:
        import udm1
        info["udm1"] = udm1.version()
    except Exception as exc:  # the library may be what failed to build or load
        info["udm1"] = f"not loaded ({exc})"
    for mod in ("numpy", "scipy", "matplotlib", "mitsuba"):
        try:
            info[mod] = __import__(mod).__version__
        except Exception:
            info[mod] = "not installed"
    if shutil.which("dpkg-query"):
        r = subprocess.run(["dpkg-query", "-W", "-f", "${Package} ${Version}\n", "libembree-dev",
                            "libopenimageio-dev", "libtbb-dev", "libnoise-dev", "povray"],
                           capture_output=True, text=True)
        for line in r.stdout.splitlines():
            name, _, version = line.partition(" ")
            if version:
                info[name] = version
    if (ROOT / ".git").exists() and shutil.which("git"):
        r = subprocess.run(["git", "-C", str(ROOT), "describe", "--always", "--dirty"], capture_output=True, text=True)
        if r.returncode == 0:
            info["git"] = r.stdout.strip()
    return info


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"), help="the CMake build folder with the tools (default build)")
    ap.add_argument("--out", default=str(ROOT / "report"), help="output folder (default report)")
    size = ap.add_mutually_exclusive_group()
    size.add_argument("--quick", action="store_true", help="tiny sizes, for tests (a minute or two)")
    size.add_argument("--full", action="store_true", help="the shared pbrt-v4 scenes, larger sizes, more seeds")
    ap.add_argument("--fresh", action="store_true", help="redo every step (default: reuse unchanged finished steps)")
    ap.add_argument("--only", help="run only these steps (comma list); the others are reused if finished")
    ap.add_argument("--jobs", type=int, default=min(2, os.cpu_count() or 1),
                    help="steps that measure no time run this many at a time (default 2, or 1 on one core); the "
                         "steps that measure time always run alone")
    for tool in ("bench-samplers", "bench-noise", "noise", "ao", "pt"):
        ap.add_argument(f"--{tool}", help=f"path of the {tool} program (default: found in --build)")
    args = ap.parse_args(argv)
    out = writable_folder(args.out, "main_report")
    if out is None:
        return 1
    out = out.resolve()
    (out / "noise").mkdir(exist_ok=True)  # udm1-noise figures writes into an existing folder
    steps = plan(args, out)
    if args.only:
        unknown = [s for s in args.only.split(",") if s not in {st.name for st in steps}]
        if unknown:
            print(f"main_report: unknown step '{unknown[0]}' in --only (steps: "
                  f"{', '.join(s.name for s in steps)})", file=sys.stderr)
            return 2
    t0 = time.time()
    mode = "quick" if args.quick else ("full" if args.full else "default")
    log(f"the main report ({mode} configuration) into {out}: {len(steps)} steps, progress below")
    state = run_steps(steps, out, args)
    log("writing index.html, report.md, report.json and csv/ from the steps' results")
    doc = Document()
    info = machine_info(Path(args.build))
    figures = summary.build(doc, out, steps, state, mode, info)
    doc.heading(2, "Machine, versions and commands", "machine")
    doc.table("machine", "machine", [("key", "key", ""), ("value", "value", "")],
              [{"key": k, "value": str(v)} for k, v in info.items()])
    invoked = "python tools/report/main_report.py " + " ".join(argv if argv is not None else sys.argv[1:])
    doc.para(f"This report: `{invoked.strip()}` (through `./run.sh`, the README's main job). Each step's commands "
             "are in the steps table's JSON (report.json, \"steps\").")
    csv_dir = out / "csv"
    csv_dir.mkdir(exist_ok=True)
    for tid, t in doc.tables.items():
        with open(csv_dir / f"{tid}.csv", "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=[c[0] for c in t["columns"]], extrasaction="ignore")
            w.writeheader()
            w.writerows(t["rows"])
    failed = [s for s, r in state.items() if r["status"] == "failed"] + [f"section {s}" for s in doc.failed_sections]
    report = {"mode": mode, "steps": state, "tables": doc.tables, "figures": figures, "machine": info,
              "failed": failed, "seconds": time.time() - t0}
    tmp = out / "report.json.tmp"
    tmp.write_text(json.dumps(report, indent=1, default=str))
    tmp.replace(out / "report.json")
    (out / "report.md").write_text(doc.markdown())
    (out / "index.html").write_text(doc.html("udm1 report"))
    plt.close("all")
    if failed:
        log(f"done with {len(failed)} failed step(s): {', '.join(failed)}; see {out / 'index.html'}")
        return 1
    log(f"done in {time.time() - t0:.0f} s: open {out / 'index.html'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
