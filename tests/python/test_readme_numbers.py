"""The README is the front door: short, every number in it traced to its source, every link in it and in
the docs pointing at a file (and heading) that exists.

- Numbers. Every number in the README's prose (text, tables, link text, the comments of its code blocks)
  must be one of: part of a name (x86-64, AVX2, C11, udm1-seq: digits attached to a word); a version after
  a name (Debian 12, Clang 14, Embree 3), found in the build scripts, CMake files, python/requirements.txt
  or BENCHMARKS.md's machine line; a power of two (2^64) that the public headers state; the random draws
  of the cross-build comparison (tests/CMakeLists.txt's UDM1_DIGEST_DRAWS); or a figure quoted beside a
  link to a BENCHMARKS.md section in which it appears verbatim. Anything else fails, naming the line:
  measured figures live in BENCHMARKS.md, with their command, machine and date, and are linked, so that
  none can drift. Code (fenced blocks and inline code spans, comments aside) is what the user types, not a
  claim, and is not checked.
- BENCHMARKS.md's summary table: each row's figures appear in the section the row links to.
- Links. Every relative link of README.md, BENCHMARKS.md, TESTING.md and docs/**/*.md names an existing
  file or folder, and an anchor names a heading of the linked Markdown file.
- The README's folder table has one row per top-level folder of the project, and nothing else.
"""

import pathlib
import re
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
BENCHMARKS = ROOT / "BENCHMARKS.md"

# Pages another branch adds (the Mitsuba 3 page): a link to one passes while it is absent and is checked
# like any other once it exists.
PAGES_PENDING: set[str] = set()  # pages linked before they are written (none)

README_MAX_LINES = 150

# Where a version after a name may be stated (the name, then the number: "Debian 12", "clang-14",
# "mitsuba==3.9.1", "find_package(embree 3").
VERSION_SOURCES = ["run.sh", "scripts/bootstrap.sh", "python/requirements.txt", "pyproject.toml",
                   "CMakeLists.txt", "apps/scene/CMakeLists.txt", "tests/CMakeLists.txt"]

NUMBER = re.compile(r"(?<![\w.])(?<!\w-)(?<!\^)[-+]?\d[\d.,]*(?:[eE][-+]?\d+)?(?:\^[-+]?\d+)?")


# ---- Markdown: headings, links, prose ----

def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation but '-' and '_' dropped, spaces to '-'."""
    text = re.sub(r"`|\*\*|\*", "", heading.strip()).lower()
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    seen, out = {}, set()
    in_code = False
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("```"):
            in_code = not in_code
        elif not in_code and re.match(r"#{1,6} ", line):
            s = slug(line.lstrip("#"))
            n = seen.get(s, 0)
            seen[s] = n + 1
            out.add(s if n == 0 else f"{s}-{n}")
    return out


def without_code(text):
    """text with its inline code spans' digits taken out (a span is what the user types, not a claim; the
    words stay, so that a version after a package's name is still read as one)."""
    return re.sub(r"`[^`]*`", lambda m: re.sub(r"\d", "", m.group(0)), text)


def prose_lines(path):
    """(line number, text) of a Markdown file, without the digits of inline code spans (one may continue on
    the next line); of a fenced block only its comments (after '#' or inside '/* */'), without the code
    they name (calls and subscripts)."""
    in_code, span_open = False, False
    for no, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if line.startswith("```"):
            in_code = not in_code
            continue
        if in_code:
            comments = re.findall(r"/\*(.*?)\*/", line) + re.findall(r"(?<![\w\"'])#(?![\w\"']*[\"'])\s(.*)$", line)
            for c in comments:
                yield no, re.sub(r"\w+(\([^)]*\)|\[[^\]]*\])", " ", without_code(c))
            continue
        if span_open:  # the span begun on an earlier line ends at this line's first backtick
            head, tick, rest = line.partition("`")
            line = re.sub(r"\d", "", head) + tick + tick + rest if tick else re.sub(r"\d", "", line)
        span_open = line.count("`") % 2 == 1
        if span_open:
            k = line.rindex("`")
            line = line[:k] + "``" + re.sub(r"\d", "", line[k + 1:])
        yield no, without_code(line)


LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def links(path):
    for no, text in prose_lines(path):
        for target in LINK.findall(text):
            yield no, target


def markdown_files():
    files = [README, BENCHMARKS, ROOT / "TESTING.md"] + sorted((ROOT / "docs").rglob("*.md"))
    return [f for f in files if f.exists()]


def link_problem(source, target):
    """None if target (a link in source) resolves, else what is wrong."""
    if re.match(r"[a-z]+:", target):  # http:, https:, mailto:
        return None
    path, _, anchor = target.partition("#")
    dest = source if not path else (source.parent / path).resolve()
    rel = dest.relative_to(ROOT).as_posix() if dest.is_relative_to(ROOT) else str(dest)
    if not dest.exists():
        return None if rel in PAGES_PENDING else f"{target}: no file {rel}"
    if anchor and dest.suffix == ".md" and anchor not in anchors(dest):
        return f"{target}: no heading #{anchor} in {rel}"
    return None


# ---- the README's numbers ----

def benchmark_sections():
    """Slug of each BENCHMARKS.md heading -> the text under it (its subsections included)."""
    lines = BENCHMARKS.read_text(encoding="utf-8").splitlines()
    heads = [(i, len(m.group(1)), slug(m.group(2))) for i, l in enumerate(lines)
             if (m := re.match(r"(#{1,6}) (.*)", l))]
    out = {}
    for k, (i, level, s) in enumerate(heads):
        end = next((j for j, lv, _ in heads[k + 1:] if lv <= level), len(lines))
        out[s] = "\n".join(lines[i + 1:end])
    return out


def version_stated(name, number):
    pattern = re.compile(re.escape(name) + r"[\s\-=_(]*" + re.escape(number) + r"(?![\d])", re.IGNORECASE)
    texts = [(ROOT / f).read_text(encoding="utf-8") for f in VERSION_SOURCES if (ROOT / f).exists()]
    machine = BENCHMARKS.read_text(encoding="utf-8").split("\n## ", 1)[0]  # the machine line
    return any(pattern.search(t) for t in texts + [machine])


def header_text():
    return "\n".join(p.read_text(encoding="utf-8") for p in sorted((ROOT / "libudm1/include/udm1").glob("*.h")))


def digest_draws():
    m = re.search(r"set\(UDM1_DIGEST_DRAWS (\d+)", (ROOT / "tests/CMakeLists.txt").read_text(encoding="utf-8"))
    return int(m.group(1)) if m else None


def unattributed_numbers(path=README):
    sections = benchmark_sections()
    headers = None
    problems = []
    for no, text in prose_lines(path):
        quoted = [sections.get(a, "") for p, a in
                  (t.partition("#")[::2] for t in LINK.findall(text)) if p.endswith("BENCHMARKS.md") and a]
        plain = LINK.sub(lambda m: m.group(0).split("](")[0] + "]", text)  # link targets are paths
        for m in NUMBER.finditer(plain):
            token = m.group(0).rstrip(".,")
            before = plain[:m.start()].rstrip()
            name = re.search(r"([A-Za-z][\w+]*)[\s\-=`]*$", plain[:m.start()])
            if any(re.search(r"(?<![\d.])" + re.escape(token) + r"(?![\d])", s) for s in quoted):
                continue  # a figure of the BENCHMARKS.md section linked on the same line
            if name and plain[:m.start()].endswith((" ", "-")) and version_stated(name.group(1), token) \
                    and not before.endswith(("x", "X")):
                continue  # a version after its name
            if re.fullmatch(r"2\^-?\d+", token):
                headers = headers if headers is not None else header_text()
                if token in headers:
                    continue  # a power of two the public headers state
            if re.fullmatch(r"10\^\d+", token) and digest_draws() == 10 ** int(token.split("^")[1]) \
                    and re.match(r"\s*random draws", plain[m.end():]):
                continue  # the cross-build comparison's draws (tests/CMakeLists.txt)
            problems.append(f"{path.name}:{no}: {token!r} has no source: {text.strip()[:100]}")
    return problems


# ---- the tests ----

def test_readme_is_short():
    n = len(README.read_text(encoding="utf-8").splitlines())
    assert n <= README_MAX_LINES, f"README.md has {n} lines: at most {README_MAX_LINES} (move the rest to docs/)"


def test_every_readme_number_has_a_source():
    assert unattributed_numbers() == []


def test_benchmarks_summary_figures_are_in_their_sections():
    text = BENCHMARKS.read_text(encoding="utf-8")
    summary = text.split("## Summary", 1)[1].split("\n## ", 1)[0]
    sections = benchmark_sections()
    rows = [l for l in summary.splitlines() if l.startswith("| ") and "](#" in l]
    assert len(rows) >= 10, "BENCHMARKS.md's summary table is missing"
    problems = []
    for row in rows:
        cells = [c.strip() for c in row.strip("|").split("|")]
        anchor = re.search(r"\]\(#([^)]+)\)", cells[-1]).group(1)
        assert anchor in sections, f"summary row links to no section: {row[:80]}"
        body = sections[anchor]
        for m in NUMBER.finditer(re.sub(r"`[^`]*`", " ", cells[1])):
            token = m.group(0).rstrip(".,")
            if not re.search(r"(?<![\d.])" + re.escape(token) + r"(?![\d])", body):
                problems.append(f"{token} (row {cells[0]!r}) is not in section #{anchor}")
    assert problems == []


@pytest.mark.parametrize("path", markdown_files(), ids=lambda p: p.relative_to(ROOT).as_posix())
def test_relative_links_resolve(path):
    problems = [f"{path.relative_to(ROOT)}:{no}: {p}" for no, t in links(path) if (p := link_problem(path, t))]
    assert problems == []


def top_level_folders():
    """The project's top-level folders: those git tracks files in, or outside a git checkout every folder
    but the build outputs and the environment (.gitignore)."""
    try:
        files = subprocess.run(["git", "-C", str(ROOT), "ls-files"], capture_output=True, text=True,
                               check=True, timeout=60).stdout.splitlines()
        return {f.split("/", 1)[0] for f in files if "/" in f}
    except (OSError, subprocess.SubprocessError):
        ignored = {"build", "dist", "report", ".venv", ".git", ".pytest_cache", "__pycache__"}
        return {p.name for p in ROOT.iterdir() if p.is_dir() and not p.is_symlink() and p.name not in ignored
                and not p.name.startswith("build-")}


def test_folder_table_lists_every_top_level_folder():
    text = README.read_text(encoding="utf-8")
    table = text.split("## Folders", 1)[1].split("\n## ", 1)[0]
    listed = set(re.findall(r"^\| `([^`]+)/` \|", table, re.MULTILINE))
    present = top_level_folders()
    assert listed == present, f"folders without a row: {sorted(present - listed)}; rows without a folder: {sorted(listed - present)}"


# ---- the checks themselves, on planted faults ----

def test_a_stray_figure_fails(tmp_path):
    page = tmp_path / "README.md"
    page.write_text("# udm1\n\nFast: 4.5e9 values/s, 11 minutes for the report, 9-17x faster than pbrt-v4.\n\n"
                    "On Debian 12 with Clang 14; AVX2, x86-64 and C11 are names; `--spp 64` is code.\n"
                    "Exact below 2^64 ([BENCHMARKS.md](BENCHMARKS.md#sequences-throughput): 4.5-5.3e9).\n",
                    encoding="utf-8")
    found = unattributed_numbers(page)
    assert [p.split(": ")[1] for p in found] == ["'4.5e9' has no source", "'11' has no source", "'9' has no source"], found


def test_a_broken_link_fails(tmp_path):
    page = tmp_path / "x.md"
    page.write_text("# x\n", encoding="utf-8")
    assert link_problem(page, "no-such-page.md") is not None
    assert link_problem(README, "docs/no-such-page.md") is not None
    assert link_problem(README, "BENCHMARKS.md#no-such-heading") is not None
    assert link_problem(README, "BENCHMARKS.md#sequences-throughput") is None
    assert link_problem(README, "#platforms") is None
    assert link_problem(README, "#no-such-heading") is not None
