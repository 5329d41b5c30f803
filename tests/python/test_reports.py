"""The report commands, on their quick settings: every figure and page they
link exists, and the numbers in the pages come from their JSON."""

import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
BENCH = os.environ.get("UDM1_BENCH_SAMPLERS", "")


def run_report(script, out, *extra):
    cmd = [sys.executable, str(ROOT / "tools" / "report" / script), "--out", str(out), "--quick", *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=600,
                          env={**os.environ, "PYTHONPATH": str(ROOT / "python")})


def links(html: str) -> list[str]:
    return re.findall(r'(?:src|href)="([^"]+)"', html)


def test_sequence_report(tmp_path):
    r = run_report("sequence_report.py", tmp_path)
    assert r.returncode == 0, r.stderr
    html = (tmp_path / "index.html").read_text()
    for link in links(html):
        if link not in ("samplers.html", "noise/figures.md"):  # written by the other report steps
            assert (tmp_path / link).exists(), link
    data = json.loads((tmp_path / "data.json").read_text())
    worst = [c for c in data["check"] if c["preset"] == "wmmr" and c["d"] == 22][0]
    assert f"{worst['worst_l2_star']:.3g}" in html


@pytest.mark.skipif(not BENCH, reason="UDM1_BENCH_SAMPLERS (the udm1_bench_samplers binary) is not set")
def test_sampler_report(tmp_path):
    r = run_report("sampler_report.py", tmp_path, "--bench", BENCH, "--reps", "4")
    assert r.returncode == 0, r.stderr
    html = (tmp_path / "samplers.html").read_text()
    for link in links(html):
        assert (tmp_path / link).exists(), link
    data = json.loads((tmp_path / "samplers.json").read_text())
    samplers = {row["sampler"] for row in data["error"]}
    for name in ["wr", "wmmr", "hwmmr", "rd", "sobol-owen", "pmj02", "halton", "pcg32", "cmj", "grps", "lp"]:
        assert name in samplers and name in html  # no sampler hidden
    for row in data["verdicts"][:5]:
        assert row[-1] in html


def test_bad_output_folder(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = run_report("sequence_report.py", blocker / "sub")
    assert r.returncode == 1 and "cannot write" in r.stderr and len(r.stderr.strip().splitlines()) == 1
