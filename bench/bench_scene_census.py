"""Census of the public pbrt-v4 scene collection: which of its scenes udm1-pt renders, and where it stops.

A scene is a main file of the collection: a .pbrt file that holds WorldBegin itself (the files only included
by others are not scenes); main files whose text is not in the collection folder but which its MANIFEST.txt
lists as scenes are counted too, as not readable. Each scene is read in an overlay (DIR/overlay: the
collection's .pbrt text copied, its other files linked, the collection folder untouched) in which every file
the scene names that is absent gets a small valid stand-in (tools/pbrt_placeholders.py), placed where
pbrt-v4 reads it: names are relative to the directory of the main scene file, in included files too
(tools/pbrt_references.py). No stand-in is made for a .pbrt include whose text is absent (it is reported as
not readable), nor where none can be written (measured BSDF tables; NanoVDB grids unless --nvdb-writer names
the tests' writer, tests/cpp/nvdb_write.cpp, which writes a fog sphere with a temperature grid through
NanoVDB's own builder), which is reported.

With --absent-includes empty, a .pbrt include whose text is absent (not fetched, or not held by the index the
text was read through: mostly the large files of inline meshes) is an empty file in the overlay (but for one
tiny triangle far below the scene, so that what would be refused of its shapes is still seen), so that the
rest of the scene is judged: such a scene says "empty includes" in the stand-ins column, the summary counts
those that render apart, and it is not the scene as distributed (a named material or object defined in the
absent file makes it refused, which is reported as such; parameters after the Include that continue the absent
file's last directive, as pbrt-v4 reads them, make it not readable: its text is needed).

Where a file's full text is absent but the collection folder holds a condensed transcription of it under
.condensed/ (same path; every directive and parameter as in the file, the long numeric arrays of inline meshes
cut to a one-triangle stand-in), the scene is read with it: an include or a main file. Such a scene is never
counted as read whole: its stand-ins column says "condensed geometry" and the summary counts the scenes that
render on condensed text apart ("renders N (of which M on condensed text)").

udm1-pt renders each scene at a tiny size with 1 sample per pixel on one thread, under a time limit. The
result is `renders` (with the notes udm1-pt printed) or the first refusal: udm1-pt stops at its first error,
so a scene's later refusals are not listed; the tally counts scenes by their first refusal only.

The collection's text is not part of this project: it is read from --collection, by default
$UDM1_PBRT_SCENES, else ../pbrt-v4-scenes next to the checkout. Where it is absent this prints one line and
exits 0 (skipped).

Writes DIR/census.md (also printed) and DIR/census.json.

    python bench/bench_scene_census.py [--collection DIR] [--tool build/bin/udm1-pt] [--out build/census]
                                       [--only SUBSTRING,...] [--size 16x16] [--timeout 120] [--readme-table]
                                       [--absent-includes report|empty] [--nvdb-writer build/bin/udm1_test_nvdb_write]
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tools"))
from pbrt_placeholders import stand_in  # noqa: E402
from pbrt_references import main_files, scan  # noqa: E402

LOCATED = re.compile(r"^udm1-pt: (?P<file>.+?):(?P<line>\d+): (?P<msg>.*)$")
NOTE = "udm1-pt: note: "
RULE = ("a scene is a main file of the collection: a .pbrt file that holds WorldBegin itself; files only "
        "included by others are not scenes")


def default_collection() -> Path:
    env = os.environ.get("UDM1_PBRT_SCENES")
    return Path(env) if env else ROOT.parent / "pbrt-v4-scenes"


def read_manifest(collection: Path) -> dict[str, dict]:
    """MANIFEST.txt of the collection folder, if any: path -> {fetched, role, total_chars, note}."""
    out = {}
    path = collection / "MANIFEST.txt"
    if not path.is_file():
        return out
    for line in path.read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        cols = line.split("\t") + [""] * 6
        out[cols[0]] = {"commit": cols[1], "total_chars": cols[2], "fetched": cols[3], "role": cols[4], "note": cols[5]}
    return out


def build_overlay(collection: Path, overlay: Path) -> None:
    """The collection's files under overlay/: .pbrt text copied, anything else linked (hidden files and the
    manifest left out)."""
    if overlay.exists():
        shutil.rmtree(overlay)
    for src in sorted(collection.rglob("*")):
        rel = src.relative_to(collection)
        if any(part.startswith(".") for part in rel.parts) or rel.as_posix() == "MANIFEST.txt" or not src.is_file():
            continue
        dst = overlay / rel
        dst.parent.mkdir(parents=True, exist_ok=True)
        if src.suffix == ".pbrt":
            shutil.copyfile(src, dst)
        else:
            os.symlink(src.resolve(), dst)


# What an absent include becomes with --absent-includes empty: one tiny triangle far below the scene, in the material
# and under the transforms then in force (the absent files are mostly geometry: a shape keeps what would be refused
# of them, such as a transform that moves while the shutter is open, from passing unseen).
EMPTY_INCLUDE = ("# udm1 census: this include's text is absent from the collection folder\n"
                 "AttributeBegin\n  Shape \"trianglemesh\" \"integer indices\" [0 1 2]\n"
                 "    \"point3 P\" [0 -1e5 0  1e-3 -1e5 0  0 -1e5 1e-3]\nAttributeEnd\n")
CONDENSED = ".condensed"  # the collection's condensed transcriptions of files whose full text is absent


NVDB_STAND_IN = "a NanoVDB fog sphere with a temperature grid (NanoVDB's builder, through --nvdb-writer)"


def prepare_scene(main: Path, collection: Path, overlay: Path, manifest: dict, empty_includes: bool = False,
                  nvdb_writer: str = "") -> dict:
    """Stand-ins in the overlay for what the scene names and the collection lacks, the condensed texts it is
    read with (copied into the overlay where the full text would be); what could not be made. With nvdb_writer
    (the tests' udm1_test_nvdb_write) an absent .nvdb grid gets a stand-in too."""
    condensed_dir = collection / CONDENSED
    main_rel = main.relative_to(collection).as_posix()
    condensed = []
    if not main.is_file():  # a main file read from its condensed transcription
        short = condensed_dir / main_rel
        files = scan(short, collection, condensed=condensed_dir, base=main.parent, label=main_rel)
        condensed.append(main_rel)
    else:
        files = scan(main, collection, condensed=condensed_dir)
    condensed += files.condensed
    for rel in condensed:
        target = overlay / rel
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(condensed_dir / rel, target)
    made, blocked, unreadable, emptied = {}, {}, {}, []
    for ref in files.references:
        try:
            rel = ref.path.resolve().relative_to(collection.resolve()).as_posix()
        except ValueError:
            continue  # an absolute name outside the collection: left to the renderer
        if ref.path.exists() or rel in condensed:
            continue
        if ref.include and not ref.name.lower().endswith(".gz"):
            entry = manifest.get(rel)
            if empty_includes:
                target = overlay / rel
                target.parent.mkdir(parents=True, exist_ok=True)
                target.write_text(EMPTY_INCLUDE)
                if rel not in emptied:
                    emptied.append(rel)
                continue
            unreadable[rel] = ("not fetched" if entry else "not in the collection's text") + (
                f" ({entry['note']})" if entry and entry.get("note") else "")
            continue
        data, what = stand_in(ref.name, ref.normal_map)
        target = overlay / rel
        if data is None and nvdb_writer and ref.name.lower().endswith(".nvdb"):
            if rel not in made:
                target.parent.mkdir(parents=True, exist_ok=True)
                subprocess.run([nvdb_writer, str(target), "fire"], check=True, capture_output=True)
                made[rel] = NVDB_STAND_IN
            continue
        if data is None:
            blocked[rel] = what
            continue
        if rel not in made:
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
            made[rel] = what
    return {"references": len(files.references), "stand_ins": made, "blocked": blocked, "unreadable": unreadable,
            "condensed": condensed, "emptied": emptied}


def feature_of(msg: str, tried: str | None, scene: dict) -> str:
    """A short name for what a refusal is about, by which the tally groups scenes."""
    m = re.search(r'"(?P<n>[^"]+)" is one of pbrt-v4\'s named spectra, whose measured data udm1 does not hold', msg)
    if m:
        return f'a named spectrum udm1 does not hold ({m.group("n")})'
    if tried:
        if tried in scene["unreadable"]:
            return "text not available (include not fetched)"
        if tried in scene["blocked"]:
            return "no stand-in (" + scene["blocked"][tried].split(" (")[0] + ")"
        return "a named file not found (pbrt-v4's path rule: names relative to the main file)"
    if re.search(r"\.gz\b", msg):
        return "gzip-compressed file (.ply.gz, .pbrt.gz)"
    m = re.search(r"(?:^|: )(?P<what>[A-Z]\w*(?: (?:\"[^\"]*\"|\w+))?): unsupported parameter '(?P<p>[^']+)'", msg)
    if m:
        return f"{_unnamed(m.group('what'))} '{m.group('p')}'"
    m = re.search(r"unsupported directive '(?P<d>[^']{1,40})'", msg)
    if m:
        return f"directive {m.group('d')}" if m.group("d").isprintable() else "binary data (a gzipped file?)"
    m = re.search(r'participating media need Integrator "(?P<i>[^"]+)"', msg)
    if m:
        return f'participating media (Integrator "{m.group("i")}")'
    m = re.search(r"MakeNamedMedium \"[^\"]*\": type \"(?P<t>[^\"]+)\" is not supported", msg)
    if m:
        return f'medium "{m.group("t")}"'
    m = re.search(r"(?P<what>[A-Z]\w*(?: \w+)?) \"(?P<t>[^\"]+)\" is not supported", msg)
    if m:
        return f'{m.group("what")} "{m.group("t")}"'
    m = re.search(r'^(?P<what>[A-Z]\w*(?: "[^"]+")?): (?P<d>.+?) is not (?:modelled|supported)', msg)
    if m and not re.match(r"\w+ \(", m.group("d")):
        return f"{m.group('what')}: {_hintless(m.group('d'))}"
    m = re.search(r"^(?P<what>[A-Z]\w*): (?P<p>\w+) .*is not supported", msg)
    if m:
        return f"{m.group('what')} {m.group('p')}"
    if "expected a directive" in msg:
        binary = not msg.isprintable() or "\ufffd" in msg
        return "binary data (a gzipped file?)" if binary else "syntax: " + _hintless(msg)
    return _hintless(msg)


def _unnamed(what: str) -> str:
    return re.sub(r'^(MakeNamedMaterial|MakeNamedMedium|NamedMaterial|ObjectBegin|ObjectInstance) "[^"]*"', r"\1", what)


def _hintless(msg: str) -> str:
    msg = re.sub(r"\s*\([^()]*\)\s*$", "", msg)
    msg = re.sub(r'"[^"]{21,}"', '"…"', msg)
    return msg[:80]


def run_scene(tool: str, main_in_overlay: Path, overlay: Path, size: str, timeout: float, out_image: Path) -> dict:
    cmd = [tool, "--scene", str(main_in_overlay), "--size", size, "--spp", "1", "--threads", "1", "-o", str(out_image)]
    t0 = time.perf_counter()
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout,
                           cwd=main_in_overlay.parent)
    except subprocess.TimeoutExpired:
        return {"result": "timeout", "seconds": round(time.perf_counter() - t0, 2), "stderr": []}
    seconds = round(time.perf_counter() - t0, 2)
    prefix = str(overlay.resolve()) + os.sep
    lines = [ln.replace(prefix, "").replace(str(overlay) + os.sep, "") for ln in r.stderr.splitlines() if ln.strip()]
    return {"returncode": r.returncode, "seconds": seconds, "stderr": lines}


ANSI = re.compile(r"\x1b\[[0-9;]*m")


def run_pbrt(pbrt: str, main_in_overlay: Path, size: str, timeout: float, out_image: Path) -> dict:
    """pbrt-v4 on the same overlay at the same spp, only the first size pixels of its film: renders, or its
    first error (refused), or what it died of (crash: a failed check), or timeout."""
    w, h = size.split("x")
    cmd = [pbrt, "--nthreads", "1", "--spp", "1", "--pixelbounds", f"0,{w},0,{h}", "--outfile", str(out_image),
           main_in_overlay.name]
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, errors="replace", timeout=timeout,
                           cwd=main_in_overlay.parent)
    except subprocess.TimeoutExpired:
        return {"result": "timeout", "message": ""}
    lines = [ANSI.sub("", ln).strip() for ln in (r.stdout + "\n" + r.stderr).splitlines()]
    errors = [ln.removeprefix("Error: ") for ln in lines if ln.startswith("Error:")]
    fatal = [ln.split("] ", 1)[-1] for ln in lines if " FATAL " in ln]
    if r.returncode == 0:
        return {"result": "renders", "message": ""}
    if errors:
        return {"result": "refused", "message": errors[0]}
    return {"result": "crash", "message": fatal[0] if fatal else f"exit {r.returncode}"}


def judge(run: dict, scene: dict) -> dict:
    """renders / refused / not readable / blocked / timeout / crash, the first refusal and its feature."""
    out = {"seconds": run.get("seconds")}
    if run.get("result") == "timeout":
        out.update(result="timeout", refusal="", feature="timeout")
        return out
    notes = [ln[len(NOTE):] for ln in run["stderr"] if ln.startswith(NOTE)]
    errors = [ln for ln in run["stderr"] if not ln.startswith(NOTE)]
    out["notes"] = notes
    if run["returncode"] == 0:
        out.update(result="renders", refusal="", feature="")
        return out
    if run["returncode"] < 0 or not errors:
        out.update(result="crash", refusal=(errors[0] if errors else f"signal {-run['returncode']}"), feature="crash")
        return out
    first = errors[0]
    m = LOCATED.match(first)
    msg = m.group("msg") if m else first.removeprefix("udm1-pt: ")
    tried = None
    opened = re.search(r"(?:^|: )(?P<path>[^:]+): cannot open", msg)
    if opened:
        tried = opened.group("path")
    refusal = first.removeprefix("udm1-pt: ")
    result = "refused"
    continued = re.match(r"expected a directive, found '\w+ \w+'", msg)
    if tried in scene["unreadable"]:
        result, refusal = "not readable", f"{tried}: {scene['unreadable'][tried]}"
    elif continued and scene.get("emptied"):
        # pbrt-v4 reads a parameter list on past the end of an included file: these parameters continue the last
        # directive of an include that is only an empty stand-in here, so the scene cannot be judged without its text
        result = "not readable"
        refusal = (f"{m.group('file')}:{m.group('line')}: " if m else "") + (
            "parameters that continue the last directive of an absent include (" + ", ".join(scene["emptied"])
            + "): its text is needed")
        out.update(result=result, refusal=refusal, feature="text not available (parameters continue an absent include)")
        return out
    elif tried in scene["blocked"]:
        result, refusal = "blocked", f"{tried}: no stand-in: {scene['blocked'][tried]}"
    out.update(result=result, refusal=refusal, feature=feature_of(msg, tried, scene))
    return out


def census(args) -> dict:
    collection = args.collection.resolve()
    out = args.out.resolve()
    overlay = out / "overlay"
    out.mkdir(parents=True, exist_ok=True)
    manifest = read_manifest(collection)
    build_overlay(collection, overlay)
    present = [p.relative_to(collection).as_posix() for p in main_files(collection)]
    absent = sorted(p for p, e in manifest.items()
                    if e["role"] == "scene" and e["fetched"] != "yes" and p not in present)
    present += [p for p in absent if (collection / CONDENSED / p).is_file()]  # read on condensed text
    absent = [p for p in absent if p not in present]
    scenes = sorted(present + absent)
    if args.only:
        keys = [k.strip() for k in args.only.split(",") if k.strip()]
        scenes = [s for s in scenes if any(k in s for k in keys)]
    rows = []
    images = out / "images"
    images.mkdir(exist_ok=True)
    for rel in scenes:
        row = {"scene": rel, "folder": rel.split("/")[0]}
        if rel in absent:
            entry = manifest[rel]
            row.update(result="not readable", refusal=f"{rel}: main file not fetched ({entry['note']})",
                       feature="text not available (main file not fetched)", stand_ins={}, blocked={}, unreadable={})
            rows.append(row)
            continue
        prep = prepare_scene(collection / rel, collection, overlay, manifest, args.absent_includes == "empty",
                             args.nvdb_writer)
        run = run_scene(args.tool, overlay / rel, overlay, args.size, args.timeout,
                        images / (rel.replace("/", "__") + ".exr"))
        row.update(judge(run, prep))
        row.update(stand_ins=prep["stand_ins"], blocked=prep["blocked"], unreadable=prep["unreadable"],
                   references=prep["references"], condensed=prep["condensed"], emptied=prep["emptied"])
        if args.pbrt:
            row["pbrt"] = run_pbrt(args.pbrt, overlay / rel, args.size, args.timeout,
                                   images / (rel.replace("/", "__") + ".pbrt.exr"))
        rows.append(row)
        print(f"  {rel}: {row['result']}" + (f" - {row['refusal']}" if row["refusal"] else ""), file=sys.stderr)
    return {"collection": str(collection), "tool": args.tool, "pbrt": args.pbrt, "size": args.size, "spp": 1,
            "rule": RULE,
            "folders": len({r["folder"] for r in rows}), "rows": rows}


def tally(rows) -> list[tuple[str, int, list[str]]]:
    by = defaultdict(list)
    for r in rows:
        if r["result"] != "renders":
            by[r["feature"]].append(r["scene"])
    return sorted(((f, len(s), s) for f, s in by.items()), key=lambda t: (-t[1], t[0]))


def markdown(data: dict) -> str:
    rows = data["rows"]
    counts = Counter(r["result"] for r in rows)
    on_condensed = Counter(r["result"] for r in rows if r.get("condensed"))
    on_empty = Counter(r["result"] for r in rows if r.get("emptied"))
    lines = [f"# udm1-pt on the pbrt-v4 scene collection: {len(rows)} scenes in {data['folders']} folders", "",
             f"Collection: `{data['collection']}`; renderer: `{data['tool']}` at {data['size']}, 1 spp, one thread.",
             f"Scenes: {data['rule']}.",
             "Each scene's absent meshes, images and spectra are stand-ins (tools/pbrt_placeholders.py) placed by "
             "pbrt-v4's path rule; udm1-pt stops at its first refusal, so only the first is listed.", "",
             "Results: " + ", ".join(f"{k} {v}" + (f" (of which {on_condensed[k]} on condensed text)"
                                                   if on_condensed[k] else "")
                                     + (f" (of which {on_empty[k]} with absent includes empty)" if on_empty[k] else "")
                                     for k, v in sorted(counts.items(), key=lambda kv: -kv[1])) + "."]
    if any(r.get("condensed") for r in rows):
        lines += ["", "Condensed text: a file whose full text is absent, read from the collection's "
                  f"{CONDENSED}/ transcription (its directives as in the file, its inline meshes cut to one "
                  "triangle); such scenes say \"condensed geometry\" in the stand-ins column and are not the "
                  "scene as distributed."]
    if any(r.get("emptied") for r in rows):
        lines += ["", "Empty includes (--absent-includes empty): a .pbrt include whose text is absent is an empty file, "
                  "so the rest of the scene is judged; such scenes say \"empty includes\" in the stand-ins column and "
                  "are not the scene as distributed."]
    pbrt = data.get("pbrt")
    if pbrt:
        pc = Counter(r["pbrt"]["result"] for r in rows if "pbrt" in r)
        lines += ["", f"pbrt-v4 (`{pbrt}`) on the same overlay, same pixels and spp: "
                  + ", ".join(f"{k} {v}" for k, v in sorted(pc.items(), key=lambda kv: -kv[1]))
                  + "; its first error in the last column."]
    lines += ["", "| scene | result | first refusal | feature | stand-ins |" + (" pbrt-v4 |" if pbrt else ""),
              "|---|---|---|---|---|" + ("---|" if pbrt else "")]
    for r in rows:
        refusal = r["refusal"].replace("|", "\\|")
        if r["result"] == "renders" and r.get("notes"):
            refusal = "notes: " + "; ".join(n.replace("|", "\\|") for n in r["notes"])
        made = len(r.get("stand_ins", {}))
        extra = f"{made}" + (f", {len(r['blocked'])} impossible" if r.get("blocked") else "") + (
            f", {len(r['unreadable'])} includes absent" if r.get("unreadable") else "") + (
            f", condensed geometry ({', '.join(r['condensed'])})" if r.get("condensed") else "") + (
            f", empty includes ({', '.join(r['emptied'])})" if r.get("emptied") else "")
        line = f"| {r['scene']} | {r['result']} | {refusal} | {r['feature']} | {extra} |"
        if pbrt:
            pr = r.get("pbrt", {"result": "-", "message": ""})
            line += f" {pr['result']}" + (f": {pr['message']}".replace("|", "\\|") if pr["message"] else "") + " |"
        lines.append(line)
    lines += ["", "## First refusals by feature", ""] + _tally_table(data, which=True)
    return "\n".join(lines) + "\n"


def _tally_table(data: dict, which: bool) -> list[str]:
    """The first refusals by feature; with pbrt-v4's column, how many of those scenes pbrt-v4 renders."""
    pbrt = bool(data.get("pbrt"))
    by_scene = {r["scene"]: r for r in data["rows"]}
    out = ["| first refusal | scenes |" + (" pbrt-v4 renders |" if pbrt else "") + (" which |" if which else ""),
           "|---|---|" + ("---|" if pbrt else "") + ("---|" if which else "")]
    for feature, n, scenes in tally(data["rows"]):
        line = f"| {feature} | {n} |"
        if pbrt:
            line += f" {sum(by_scene[s].get('pbrt', {}).get('result') == 'renders' for s in scenes)} |"
        if which:
            line += " " + ", ".join(scenes[:6]) + (f", and {len(scenes) - 6} more" if len(scenes) > 6 else "") + " |"
        out.append(line)
    return out


def readme_table(data: dict) -> str:
    """What stops the collection's scenes in udm1-pt today, by first refusal: the table the README's list of
    what udm1-pt models is checked against."""
    rows = data["rows"]
    renders = [r["scene"] for r in rows if r["result"] == "renders"]
    condensed = [r["scene"] for r in rows if r["result"] == "renders" and r.get("condensed")]
    emptied = [r["scene"] for r in rows if r["result"] == "renders" and r.get("emptied")]
    lines = [f"udm1-pt renders {len(renders)} of the collection's {len(rows)} scenes"
             + (f" ({', '.join(renders)})" if renders else "")
             + (f", of which {len(condensed)} on condensed text" if condensed else "")
             + (f", {len(emptied)} with absent includes empty" if emptied else "") + "; the others stop first at:",
             ""]
    if data.get("pbrt"):
        both = sum(r.get("pbrt", {}).get("result") == "renders" for r in rows)
        lines[0] = lines[0][:-1] + f" (pbrt-v4 renders {both} of the {len(rows)} with the same stand-ins):"
    return "\n".join(lines + _tally_table(data, which=False)) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--collection", type=Path, default=default_collection(),
                    help="the collection's text (default: $UDM1_PBRT_SCENES, else ../pbrt-v4-scenes)")
    ap.add_argument("--tool", default=str(ROOT / "build" / "bin" / "udm1-pt"))
    ap.add_argument("--out", type=Path, default=ROOT / "build" / "census")
    ap.add_argument("--only", default="", help="comma-separated substrings of the scenes to run")
    ap.add_argument("--size", default="16x16")
    ap.add_argument("--timeout", type=float, default=120.0, help="seconds per scene")
    anchors = ROOT / "build" / "anchors" / "pbrt-v4-build" / "pbrt"
    ap.add_argument("--pbrt", default=str(anchors) if anchors.is_file() else "",
                    help="pbrt-v4 to run on the same overlay for comparison ('' for none; default: "
                         "build/anchors/pbrt-v4-build/pbrt where scripts/anchors.sh built it)")
    ap.add_argument("--readme-table", action="store_true", help="print the table of first refusals only")
    ap.add_argument("--absent-includes", choices=("report", "empty"), default="report",
                    help="a .pbrt include whose text is absent: reported as not readable (default), or an empty "
                         "file so that the rest of the scene is judged (labelled)")
    ap.add_argument("--nvdb-writer", default="",
                    help="the tests' NanoVDB writer (build/bin/udm1_test_nvdb_write): absent .nvdb grids get a stand-in "
                         "(a fog sphere with a temperature grid) in place of being reported as impossible")
    args = ap.parse_args(argv)
    if not args.collection.is_dir():
        print(f"skipped: the pbrt-v4 scene collection's text is absent ({args.collection}; "
              f"set UDM1_PBRT_SCENES or --collection)")
        return 0
    if not Path(args.tool).is_file():
        print(f"bench_scene_census: {args.tool}: no such renderer (build it, or give --tool)", file=sys.stderr)
        return 2
    args.tool = str(Path(args.tool).resolve())  # the renderer runs in each scene's folder
    if args.nvdb_writer:
        if not Path(args.nvdb_writer).is_file():
            print(f"bench_scene_census: {args.nvdb_writer}: no such NanoVDB writer (built where NanoVDB is)", file=sys.stderr)
            return 2
        args.nvdb_writer = str(Path(args.nvdb_writer).resolve())
    if args.pbrt:
        if not Path(args.pbrt).is_file():
            print(f"bench_scene_census: {args.pbrt}: no such pbrt-v4 (give --pbrt '' for none)", file=sys.stderr)
            return 2
        args.pbrt = str(Path(args.pbrt).resolve())
    data = census(args)
    text = markdown(data)
    (args.out / "census.md").write_text(text)
    (args.out / "census.json").write_text(json.dumps(data, indent=1) + "\n")
    print(readme_table(data) if args.readme_table else text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
