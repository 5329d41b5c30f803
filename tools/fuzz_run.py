"""Runs every libFuzzer target of tests/fuzz for a time budget each and reports what it measured.

For each target: its committed corpus (tests/fuzz/corpus/<target>/) is copied to a work folder, the
fuzzer runs there for --seconds (ASan + UBSan, 10 s per input at most, 2 GiB of memory at most), and the
report gives the executions, executions per second, the corpus size before and after, and the crashes
(artifacts kept in the work folder). --update-corpus merges what the run found that adds coverage back
into the committed corpus (libFuzzer -merge=1), so the test command's replay covers it from then on.

    python tools/fuzz_run.py --build build-fuzz --seconds 60 [--update-corpus]
    (./run.sh fuzz [SECONDS] builds build-fuzz with clang and runs this)
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
TARGETS = ["api", "noise", "scene", "mesh", "bsdf", "stream"]


def run_target(fuzzer: Path, corpus: Path, work: Path, seconds: int) -> dict:
    live = work / "corpus"
    if live.exists():
        shutil.rmtree(live)
    shutil.copytree(corpus, live)
    before = len(list(live.iterdir()))
    artifacts = work / "artifacts"
    if artifacts.exists():
        shutil.rmtree(artifacts)  # only this run's findings
    artifacts.mkdir(parents=True)
    t0 = time.time()
    p = subprocess.run([str(fuzzer), str(live), f"-max_total_time={seconds}", "-print_final_stats=1", "-timeout=10",
                        "-rss_limit_mb=2048", f"-artifact_prefix={artifacts}/", "-close_fd_mask=3"],
                       capture_output=True, text=True)
    log = p.stderr
    (work / "fuzz.log").write_text(log)
    stats = dict(re.findall(r"stat::(\w+):\s+(\d+)", log))
    runs = int(stats.get("number_of_executed_units", 0))
    elapsed = time.time() - t0
    return {"target": fuzzer.name, "seconds": round(elapsed), "executions": runs,
            "per_second": runs / max(elapsed, 1e-9), "corpus_before": before,
            "corpus_after": len(list(live.iterdir())), "crashes": sorted(a.name for a in artifacts.iterdir()),
            "exit": p.returncode, "coverage": int(stats.get("new_units_added", 0))}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build-fuzz"), help="a build with -DUDM1_FUZZ=ON")
    ap.add_argument("--seconds", type=int, default=60, help="time per target (default 60)")
    ap.add_argument("--targets", default=",".join(TARGETS))
    ap.add_argument("--update-corpus", action="store_true", help="merge new coverage into tests/fuzz/corpus")
    args = ap.parse_args(argv)
    targets = args.targets.split(",")
    bad = [t for t in targets if t not in TARGETS]
    if bad or not 1 <= args.seconds <= 86400:
        print(f"fuzz_run: targets are {', '.join(TARGETS)} (got '{args.targets}'), --seconds 1..86400", file=sys.stderr)
        return 2
    build = Path(args.build)
    rows = []
    for t in targets:
        fuzzer = build / "tests" / "fuzz" / f"fuzz_{t}"
        if not fuzzer.exists():
            print(f"fuzz_run: no fuzzer at '{fuzzer}' (configure with -DUDM1_FUZZ=ON and clang)", file=sys.stderr)
            return 2
        print(f"[fuzz] {t}: {args.seconds} s", file=sys.stderr, flush=True)
        r = run_target(fuzzer, ROOT / "tests" / "fuzz" / "corpus" / t, build / "fuzz-work" / t, args.seconds)
        rows.append(r)
        print(f"[fuzz] {t}: {r['executions']} executions ({r['per_second']:.0f}/s), corpus {r['corpus_before']} -> "
              f"{r['corpus_after']}, crashes {len(r['crashes'])}", file=sys.stderr, flush=True)
        if args.update_corpus and not r["crashes"]:
            dest = ROOT / "tests" / "fuzz" / "corpus" / t
            subprocess.run([str(fuzzer), "-merge=1", str(dest), str(build / "fuzz-work" / t / "corpus")],
                           capture_output=True, text=True)
    lines = ["| target | seconds | executions | executions/s | corpus (start -> end) | crashes |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['target']} | {r['seconds']} | {r['executions']} | {r['per_second']:.0f} | "
                     f"{r['corpus_before']} -> {r['corpus_after']} | {len(r['crashes'])} |")
    table = "\n".join(lines)
    print(table)
    (build / "fuzz-report.md").write_text(table + "\n")
    return 1 if any(r["crashes"] for r in rows) else 0


if __name__ == "__main__":
    sys.exit(main())
