"""Per-sample draws, udm1 against OpenQMC (the Academy Software Foundation's header-only sampler library,
built from the snapshot in ../shared/anchors by scripts/anchors.sh), with the same compiler and flags:
bench/bench_per_sample.cpp compiled three times: -O3 -march=native (the machine's own), -O3 -march=x86-64-v3 (AVX2 and FMA:
what a renderer shipped for current x86 machines is built with) and plain -O3 (the x86-64 baseline, SSE2), each
binary alternating udm1 and OpenQMC inside every round (best of R rounds), the binaries run in turn twice.
Prints and writes (CSV, Markdown) nanoseconds per dimension and OpenQMC's time over udm1's for every udm1
sampler and way (domains, stream, cursor) against the matched OpenQMC sampler, in OpenQMC's own protocol
and a renderer-shaped one. Without the snapshot it times udm1 alone and says so.

    python bench/bench_per_sample.py [--build build] [--out build/bench_per_sample] [--rounds 5]
"""

from __future__ import annotations

import argparse
import csv
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
FLAGS = {"-O3 -march=native": ["-O3", "-march=native"], "-O3 -march=x86-64-v3": ["-O3", "-march=x86-64-v3"], "-O3": ["-O3"]}


def openqmc_include() -> str | None:
    r = subprocess.run([str(ROOT / "scripts" / "anchors.sh"), "openqmc"], capture_output=True, text=True)
    if r.returncode != 0:
        print(f"bench_per_sample: OpenQMC skipped: {r.stderr.strip().splitlines()[-1] if r.stderr.strip() else 'no snapshot'}",
              file=sys.stderr)
        return None
    return r.stdout.strip()


def compile_bench(build: Path, out: Path, flags: list[str], oqmc: str | None) -> Path:
    exe = out / ("bench_per_sample" + "".join(f.replace("=", "_").replace("-", "_") for f in flags))
    cmd = ["g++", "-std=c++17", *flags, "-I", str(ROOT / "libudm1" / "include"), str(ROOT / "bench" / "bench_per_sample.cpp"),
           "-o", str(exe), "-L", str(build / "libudm1"), "-ludm1", f"-Wl,-rpath,{build / 'libudm1'}"]
    cmd += ["-I", oqmc] if oqmc else ["-DUDM1_NO_OPENQMC"]
    subprocess.run(cmd, check=True)
    return exe


def parse(text: str) -> list[dict]:
    rows = []
    for line in text.splitlines():
        f = line.split()
        if len(f) == 6 and f[0] in ("openqmc", "renderer"):
            rows.append({"protocol": f[0], "sampler": f[1], "way": f[2], "ns_per_dim": float(f[3]), "anchor": f[4],
                         "anchor_over_udm1": None if f[5] == "-" else float(f[5])})
        elif len(f) == 7 and f[0] in ("openqmc", "renderer"):  # "wr screen"
            rows.append({"protocol": f[0], "sampler": f"{f[1]} {f[2]}", "way": f[3], "ns_per_dim": float(f[4]),
                         "anchor": f[5], "anchor_over_udm1": None if f[6] == "-" else float(f[6])})
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=str(ROOT / "build"))
    ap.add_argument("--out", default=str(ROOT / "build" / "bench_per_sample"))
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--runs", type=int, default=2, help="runs of each binary, in turn (default 2)")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    oqmc = openqmc_include()
    exes = {name: compile_bench(Path(args.build), out, flags, oqmc) for name, flags in FLAGS.items()}
    best: dict[tuple, dict] = {}
    header = ""
    for run in range(args.runs):
        for name, exe in exes.items():
            r = subprocess.run([str(exe), "--rounds", str(args.rounds)], capture_output=True, text=True, check=True)
            header = "\n".join(l for l in r.stdout.splitlines() if l.startswith("#"))
            for row in parse(r.stdout):
                key = (name, row["protocol"], row["sampler"], row["way"])
                if key not in best or row["ns_per_dim"] < best[key]["ns_per_dim"]:
                    best[key] = dict(row, flags=name)
    rows = list(best.values())
    # the ratios again from the best times of both (the same binary's run for each)
    for r in rows:
        a = best.get((r["flags"], r["protocol"], r["anchor"], "OpenQMC"))
        r["anchor_over_udm1"] = round(a["ns_per_dim"] / r["ns_per_dim"], 3) if a and r["way"] != "OpenQMC" else None
    with open(out / "per_sample.csv", "w", newline="") as f:
        w = csv.DictWriter(f, ["flags", "protocol", "sampler", "way", "ns_per_dim", "anchor", "anchor_over_udm1"])
        w.writeheader()
        w.writerows(rows)
    lines = [header, "", "| flags | protocol | sampler | way | ns / dimension | anchor | anchor / udm1 |",
             "|---|---|---|---|---|---|---|"]
    for r in rows:
        ratio = "" if r["anchor_over_udm1"] is None else f"{r['anchor_over_udm1']:.2f}"
        lines.append(f"| {r['flags']} | {r['protocol']} | {r['sampler']} | {r['way']} | {r['ns_per_dim']:.3f} | "
                     f"{r['anchor'] if r['anchor'] != '-' else ''} | {ratio} |")
    text = "\n".join(lines) + "\n"
    (out / "per_sample.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
