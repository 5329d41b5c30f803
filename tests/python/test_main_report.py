"""The main report (tools/report/main_report.py, the README's main job) on its quick configuration:
every figure, page and table it links exists; the numbers in index.html are those of report.json, and
those come from the steps' own JSON; every sampler a step ran is in every table made from it; a second
run reuses the finished steps; a failed step is shown failed (its stale numbers are not shown); an
interrupted step runs again. The report opens with the verdict (the best sampler per application, at equal
spp and at equal time, with the machine), then the paper's claims, then the details."""

import csv
import json
import os
import re
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import pytest

import udm1

ROOT = Path(__file__).resolve().parents[2]
ENV = {k: os.environ.get(k, "") for k in ("UDM1_BENCH_SAMPLERS", "UDM1_BENCH_NOISE", "UDM1_NOISE_TOOL", "UDM1_AO_TOOL",
                                          "UDM1_PT_TOOL", "UDM1_BUILD_DIR")}
pytestmark = pytest.mark.skipif(not all(ENV.values()), reason="the tools' paths (UDM1_*_TOOL, UDM1_BENCH_*, "
                                "UDM1_BUILD_DIR) are not set: run through CTest")


def run(out, *extra, noise=None):
    cmd = [sys.executable, str(ROOT / "tools" / "report" / "main_report.py"), "--quick", "--out", str(out),
           "--build", ENV["UDM1_BUILD_DIR"], "--bench-samplers", ENV["UDM1_BENCH_SAMPLERS"],
           "--bench-noise", ENV["UDM1_BENCH_NOISE"], "--noise", noise or ENV["UDM1_NOISE_TOOL"],
           "--ao", ENV["UDM1_AO_TOOL"], "--pt", ENV["UDM1_PT_TOOL"], *extra]
    return subprocess.run(cmd, capture_output=True, text=True, timeout=900,  # a progress line every second
                          env={**os.environ, "PYTHONPATH": str(ROOT / "python"), "UDM1_REPORT_TICK": "1"})


class Tables(HTMLParser):
    """Every <table id=...> of a page as rows of cell texts, and every src/href."""

    def __init__(self):
        super().__init__()
        self.tables, self.links, self.current, self.row, self.text = {}, [], None, None, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        for k in ("src", "href"):
            if k in a:
                self.links.append(a[k])
        if tag == "table":
            self.current = a.get("id")
            self.tables[self.current] = []
        elif tag == "tr" and self.current is not None:
            self.row = []
            self.tables[self.current].append(self.row)
        elif tag in ("td", "th") and self.row is not None:
            self.text = ""

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self.text is not None:
            self.row.append(self.text)
            self.text = None
        elif tag == "table":
            self.current, self.row = None, None

    def handle_data(self, data):
        if self.text is not None:
            self.text += data


def parse(path: Path) -> Tables:
    t = Tables()
    t.feed(path.read_text())
    return t


def shown(value, fmt):
    """The test's own statement of how a number must appear: None as '-', else Python's format()."""
    if value is None:
        return "-"
    if fmt and isinstance(value, (int, float)) and not isinstance(value, bool):
        return format(value, fmt)
    return str(value)


def check_page(out: Path) -> dict:
    report = json.loads((out / "report.json").read_text())
    page = parse(out / "index.html")
    for link in page.links:  # every figure, page and table the index links exists
        assert (out / link).exists(), link
    md = (out / "report.md").read_text()
    for tid, t in report["tables"].items():
        rows = page.tables[tid]
        assert rows[0] == [c[1] for c in t["columns"]], tid
        assert len(rows) - 1 == len(t["rows"]), tid
        for html_row, raw in zip(rows[1:], t["rows"]):  # the HTML numbers are the JSON numbers
            assert html_row == [shown(raw.get(c[0]), c[2]) for c in t["columns"]], (tid, html_row, raw)
            assert "| " + " | ".join(html_row) + " |" in md, (tid, html_row)  # and the Markdown's
        with open(out / "csv" / f"{tid}.csv") as f:  # the CSV holds the same raw values
            got = list(csv.DictReader(f))
        assert len(got) == len(t["rows"])
        for c in t["columns"]:
            for g, raw in zip(got, t["rows"]):
                v = raw.get(c[0])
                if isinstance(v, float):
                    assert float(g[c[0]]) == pytest.approx(v, rel=1e-12), (tid, c[0])
                else:
                    assert g[c[0]] == ("" if v is None else str(v)), (tid, c[0])
    assert set(page.tables) == set(report["tables"])  # no table in the page that the JSON lacks
    return report


def check_verdict_first(out: Path, report: dict):
    """The first screen is the verdict: the best sampler per application, at equal spp and at equal time, each
    the one the step's own numbers make best, with the machine; then the paper's claims; then the details."""
    md = (out / "report.md").read_text()
    heads = [line for line in md.splitlines() if line.startswith("#")]
    assert heads[0].startswith("# udm1 report: which sampler") and heads[1] == "## Verdict", heads[:3]
    assert heads[2] == "## The paper's claims next to ours" and heads.index("## Details") == 3, heads[:5]
    assert report["machine"]["cpu"] in md.split("## Verdict")[0] and f"{report['machine']['cores']} cores" in md
    assert list(parse(out / "index.html").tables)[:2] == ["verdict", "claims"]  # the page's order too
    rows = report["tables"]["verdict"]["rows"]
    best = {(r["application"], r["when"].split(" (")[0]): r["best"] for r in rows}

    def top(rs, key, low=False):
        return (min if low else max)(rs, key=lambda r: r[key])["sampler"]

    ao = json.loads((out / "ao.json").read_text())
    assert best[("ambient occlusion (udm1-ao)", "equal spp")] == top(ao["figure6"], "psnr_mean")
    assert best[("ambient occlusion (udm1-ao)", "equal time")] == top(ao["equal_time"], "psnr_mean")
    for sc in json.loads((out / "pt.json").read_text())["scenes"]:
        app = f"path tracing (udm1-pt), {sc['title']}"
        assert best[(app, "equal spp")] == top(sc["figure"], "psnr_mean")
        assert best[(app, "equal time")] == top(sc["equal_time"], "psnr_mean")
    err = json.loads((out / "samplers.json").read_text())["error"]
    integrands = {r["application"] for r in rows if r["application"].startswith("integration")}
    assert len(integrands) == 3
    for app in integrands:
        integ = app.split(", ")[1].split(" ")[0]
        n = max(r["n"] for r in err if r["integrand"] == integ)
        at = [r for r in err if r["integrand"] == integ and r["n"] == n]
        assert best[(app, "equal N")] == top(at, "relative_rmse", low=True)
        for r in at:
            r["cost"] = r["rmse"] ** 2 * r["seconds_per_estimate"]
        assert best[(app, "equal time")] == top(at, "cost", low=True)
    screen = {r["application"] for r in rows if r["application"].startswith("screen-space")}
    assert screen == {"screen-space, ambient occlusion", "screen-space, path tracing"}
    assert any(r["application"].startswith("noise") for r in rows)
    for r in rows:  # each names its gain over PRNG (noise: over the other library) and over the best other
        assert r["best"] and r["peer"] and r["peer"] != r["best"] and r["over_peer"], r
        assert r["over_prng"] or r["application"].startswith("noise"), r


def test_main_report(tmp_path):
    out = tmp_path / "report"
    r = run(out)
    assert r.returncode == 0, r.stderr[-3000:]
    assert "[1/11 sampler-times]" in r.stderr and "[11/11 noise]" in r.stderr  # progress on the terminal
    # with the time elapsed and an estimate of the time left, in the step and in all, for each of two steps running
    # side by side
    for step in ("7/11 screen", "8/11 tolerance"):
        assert re.search(rf"^\[report\] \[{step}\] \d+ s elapsed; (about \d+ s left in this step, .* in all|past its "
                         "estimate)", r.stderr, re.M), r.stderr[-3000:]
    report = check_page(out)
    check_verdict_first(out, report)
    assert {s: v["status"] for s, v in report["steps"].items()} == {s: "ok" for s in report["steps"]}
    # the steps that measure time ran alone; the others two at a time; each with its own processor time
    steps = report["steps"]
    for name, v in steps.items():
        others = [(w["started"], w["ended"]) for o, w in steps.items() if o != name]
        overlap = [o for o in others if o[0] < v["ended"] and o[1] > v["started"]]
        assert v["alone"] == (name in ("sampler-times", "throughput", "noise", "ao", "pt", "tent", "mitsuba")), name
        assert not overlap if v["alone"] else overlap, name
        assert v["cpu_seconds"] > 0, name
    tables = report["tables"]

    # every sampler a step ran is in every table made from it, with the step's own numbers
    ao = json.loads((out / "ao.json").read_text())
    fig6 = {row["sampler"]: row for row in ao["figure6"]}
    assert {row["sampler"] for row in tables["ao"]["rows"]} == set(fig6) and len(fig6) == 23
    for row in tables["ao"]["rows"]:
        assert row["psnr"] == fig6[row["sampler"]]["psnr_mean"]
    pt = json.loads((out / "pt.json").read_text())
    fig = {row["sampler"]: row for row in pt["scenes"][0]["figure"]}
    assert {row["sampler"] for row in tables["pt_s0"]["rows"]} == set(fig) and len(fig) == 11
    for row in tables["pt_s0"]["rows"]:
        assert row["psnr"] == fig[row["sampler"]]["psnr_mean"]
        assert row["gain"] == pytest.approx(fig[row["sampler"]]["psnr_mean"] - fig["pcg32"]["psnr_mean"])
    gains = tables["pt_gains"]["rows"]
    assert [g["source"].split(",")[0] for g in gains] == ["paper", "paper", "ours"]
    assert gains[0]["halton"] == pytest.approx(1.47, abs=0.005)  # the paper's Figure 8, Halton over PRNG
    samplers = json.loads((out / "samplers.json").read_text())
    assert {row["sampler"] for row in tables["integration"]["rows"]} == {r["sampler"] for r in samplers["error"]}
    presets = {p.name for p in udm1.presets() if p.max_dimensions >= 2}  # every 2D-capable sampler
    assert {row["sampler"] for row in tables["throughput"]["rows"] if row["d"] == 2} == presets | {"(memset)"}
    assert any(row["anchor"].startswith("FastNoise") for row in tables["noise_speed"]["rows"])
    for res in json.loads((out / "mitsuba" / "results.json").read_text()):  # both Mitsuba variants, every sampler
        rows = tables[f"mitsuba_{res['variant']}"]["rows"]
        assert [(x["sampler"], x["spp"], x["rmse"]) for x in rows] == [(x["sampler"], x["spp"], x["rmse"])
                                                                      for x in res["rows"]]
        assert {"independent", "udm1 wr", "udm1 sobol-owen"} <= {x["sampler"] for x in rows}
    tolerance = json.loads((out / "tolerance" / "results.json").read_text())["rows"]  # every method of every case
    assert [(x["family"], x["d"], x["method"], x["success"]) for x in tables["tolerance"]["rows"]] == \
        [(x["family"], x["d"], x["method"], x["success"]) for x in tolerance]
    assert {x["method"] for x in tolerance} >= {"udm1 sobol-owen", "QMCPy CubQMCNetG", "scipy qmc_quad"}
    screen = json.loads((out / "screen.json").read_text())["summary"]
    tent = tables["tent"]["rows"]
    assert {r["integrand"] for r in tent} == {r["integrand"] for r in samplers["error"]} and all(
        r["gain_wr"] > 0 and r["best_tent"].endswith("+tent") and r["best_anchor"] in ("sobol-owen", "pmj02") for r in tent)
    assert [(r["source"], r["pair"], r["scheme"], r["worst_low"]) for r in tables["screen"]["rows"]] == \
        [(r["source"], str(r["pair"]), r["scheme"], r["worst_low"]) for r in screen]
    assert {r["scheme"] for r in screen} == {"shift", "progressive", "fixed-N", "Z-order"}
    assert {r["source"] for r in screen} == {"ao", "pt", "ao-shape", "pt-shape"}
    claims = tables["claims"]["rows"]
    assert {c["figure"] for c in claims} == {"6", "8", "10", "8, 10"}
    assert all(c["verdict"].split(" ")[0] in ("holds", "tie", "fails", "partly") for c in claims)
    assert set(report["figures"]) == {"speed_vs_error.png", "equal_time.png"}

    # a second run reuses every finished step and gives the same tables
    r = run(out)
    assert r.returncode == 0, r.stderr[-3000:]
    again = check_page(out)
    assert {v["status"] for v in again["steps"].values()} == {"reused"}
    assert {k: v for k, v in again["tables"].items() if k not in ("steps", "machine")} == \
        {k: v for k, v in tables.items() if k not in ("steps", "machine")}

    # a failing step is shown failed, with its error, and its stale numbers (its files are still there) are not
    # shown (the noise step: the steps that render are not run again for this)
    r = run(out, noise=str(tmp_path / "missing" / "udm1-noise"))
    assert r.returncode == 1
    failed = check_page(out)
    assert failed["steps"]["noise"]["status"] == "failed" and "missing/udm1-noise" in failed["steps"]["noise"]["error"]
    assert failed["failed"] == ["noise"] and (out / "noise_simd.json").exists()
    assert all(v["status"] == "reused" for s, v in failed["steps"].items() if s != "noise")
    assert "noise_speed" not in failed["tables"] and "ao" in failed["tables"]
    steps_row = next(row for row in parse(out / "index.html").tables["steps"] if row[0] == "noise")
    assert steps_row[2] == "failed" and steps_row[5] == "alone" and "missing/udm1-noise" in steps_row[6]
    assert "This step failed" in (out / "index.html").read_text()

    # an interrupted step (left "running") runs again; the failed one too; the others are reused
    state = json.loads((out / "steps.json").read_text())
    state["tent"]["status"] = "running"
    (out / "steps.json").write_text(json.dumps(state))
    r = run(out)
    assert r.returncode == 0, r.stderr[-3000:]
    final = check_page(out)
    assert {s: v["status"] for s, v in final["steps"].items()} == {
        "sampler-times": "reused", "sequences": "reused", "samplers": "reused", "throughput": "reused", "noise": "ok", "ao": "reused",
        "pt": "reused", "mitsuba": "reused", "tolerance": "reused", "tent": "ok", "screen": "reused"}
    assert "noise_speed" in final["tables"] and "tent" in final["tables"]


def test_bad_arguments(tmp_path):
    r = run(tmp_path / "r", "--only", "sequences,nonsense")
    assert r.returncode == 2 and "nonsense" in r.stderr and len(r.stderr.strip().splitlines()) == 1
    blocker = tmp_path / "file"
    blocker.write_text("x")
    r = run(blocker / "sub")
    assert r.returncode == 1 and "cannot write" in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_unreadable_step_output_is_a_failed_section(tmp_path):
    out = tmp_path / "report"
    r = run(out, "--only", "sequences")
    assert r.returncode == 0, r.stderr[-3000:]
    (out / "sequences.json").write_text("{ not json")  # a finished step whose output was damaged afterwards
    r = run(out, "--only", "sequences")
    assert r.returncode == 1
    report = json.loads((out / "report.json").read_text())
    assert report["steps"]["sequences"]["status"] == "reused" and "section sequences_section" in report["failed"]
    assert "This section failed" in (out / "index.html").read_text()
    assert report["steps"]["ao"]["status"] == "not run"  # and what was not asked for is shown as not run
    assert "This step did not run" in (out / "index.html").read_text()
