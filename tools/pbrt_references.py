"""The files a pbrt-v4 scene names, found by reading its text: includes, meshes, images, spectra, grids.

A small tokenizer of the pbrt-v4 format (quoted strings, brackets, comments, bare words) walks a main scene
file and every include it can read, and records each file name a directive or parameter gives:
`Include`/`Import`, `"string filename"` (meshes, image textures, environment maps, grids, measured BSDFs),
`mapname`, `lensfile`, `normalmap`, and spectrum parameters given as a file (a string with a dot or a slash:
pbrt-v4's named spectra have neither). The output image's name (`Film "filename"`) is not a reference.

Names are resolved as pbrt-v4 resolves them: relative to the directory of the main scene file, in every
included file too (pbrt-v4's search directory), never relative to the including file.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

TOKEN = re.compile(r'"(?P<q>[^"]*)"|(?P<open>\[)|(?P<close>\])|(?P<comment>#[^\n]*)|(?P<word>[^\s\[\]"#]+)')
PARAM_TYPES = {"integer", "float", "point2", "vector2", "point3", "vector3", "normal", "normal3", "bool", "string",
               "texture", "spectrum", "rgb", "blackbody", "point", "vector", "color"}
FILE_PARAMS = {"filename", "mapname", "lensfile", "normalmap"}
INCLUDES = {"Include", "Import"}


@dataclass
class Reference:
    """One file name a scene gives: where (file relative to the collection, line), in which directive
    (`Shape "plymesh"`), by which parameter (or the include), and the path pbrt-v4 reads."""
    source: str
    line: int
    directive: str
    param: str
    name: str
    path: Path

    @property
    def include(self) -> bool:
        return self.param == "Include"

    @property
    def normal_map(self) -> bool:
        return self.param == "normalmap"


@dataclass
class SceneFiles:
    """What a main file names, in reading order, which of its includes could not be read as text, and which
    were read from a condensed transcription instead of the full text (by their path in the collection)."""
    main: Path
    references: list[Reference] = field(default_factory=list)
    unreadable_includes: list[Reference] = field(default_factory=list)
    condensed: list[str] = field(default_factory=list)


def tokens(text: str):
    """(kind, value, line) for each token: kind 'q' (quoted), '[' , ']', or 'w' (bare word); comments dropped."""
    line = 1
    pos = 0
    for m in TOKEN.finditer(text):
        line += text.count("\n", pos, m.start())
        pos = m.start()
        if m.group("comment") is not None:
            continue
        if m.group("q") is not None:
            yield "q", m.group("q"), line
        elif m.group("open"):
            yield "[", "[", line
        elif m.group("close"):
            yield "]", "]", line
        else:
            yield "w", m.group("word"), line


def is_directive(word: str) -> bool:
    return word[:1].isalpha() and word[:1].isupper()


def scan(main: Path, root: Path, max_depth: int = 32, condensed: Path | None = None,
         base: Path | None = None, label: str | None = None) -> SceneFiles:
    """Every file name the scene `main` gives, its readable includes followed (each once), resolved by
    pbrt-v4's rule. `root` is the collection's folder, which `source` is given relative to.

    `condensed`, where given, is a folder mirroring the collection with condensed transcriptions of files
    whose full text is absent (every directive kept, long inline mesh arrays cut to a stand-in): an include
    absent from the collection is followed there, and listed in `condensed`. `base` is the folder names are
    resolved against (default: the main file's) and `label` the main file's name in `source` (default: its path
    in the collection): give both where `main` is itself a condensed transcription."""
    found = SceneFiles(main)
    base = base if base is not None else main.parent
    seen: set[Path] = set()

    def resolve(name: str) -> Path:
        p = Path(name)
        return p if p.is_absolute() else base / p

    def rel(p: Path) -> str:
        try:
            return p.resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            return str(p)

    def walk(path: Path, depth: int, source: str | None = None) -> None:
        seen.add(path.resolve())
        source = source or rel(path)
        toks = list(tokens(path.read_text(encoding="utf-8", errors="replace")))
        directive, kind = "", ""
        i = 0
        while i < len(toks):
            t, v, line = toks[i]
            if t == "w" and is_directive(v):
                directive, kind = v, ""
                if v in INCLUDES and i + 1 < len(toks) and toks[i + 1][0] == "q":
                    name = toks[i + 1][1]
                    ref = Reference(source, line, v, "Include", name, resolve(name))
                    found.references.append(ref)
                    target = ref.path
                    inside = not Path(rel(target)).is_absolute()  # a name outside the collection has none
                    short = condensed / rel(target) if condensed is not None and inside else None
                    if target.is_file() and not name.lower().endswith(".gz"):
                        if target.resolve() not in seen and depth < max_depth:
                            walk(target, depth + 1)
                    elif short is not None and not target.exists() and short.is_file():
                        if rel(target) not in found.condensed:
                            found.condensed.append(rel(target))
                        if short.resolve() not in seen and depth < max_depth:
                            walk(short, depth + 1, rel(target))
                    else:
                        found.unreadable_includes.append(ref)
                    i += 2
                    continue
                if i + 1 < len(toks) and toks[i + 1][0] == "q" and not _is_param(toks[i + 1][1]):
                    kind = toks[i + 1][1]
                    # Texture "name" "kind" "class": the class is what says what it reads
                    if v == "Texture" and i + 3 < len(toks) and toks[i + 3][0] == "q":
                        kind = toks[i + 3][1]
                i += 1
                continue
            if t == "q" and _is_param(v):
                ptype, pname = v.split()
                values, j = _values(toks, i + 1)
                if ptype == "string" and pname == "type" and values:
                    kind = values[0]  # MakeNamedMaterial / MakeNamedMedium give their kind this way
                label = f'{directive} "{kind}"' if kind else directive
                if directive != "Film" and ((ptype == "string" and pname in FILE_PARAMS)
                                            or (ptype == "spectrum" and _spectrum_files(values))):
                    for name in (values if ptype == "string" else _spectrum_files(values)):
                        found.references.append(Reference(source, line, label, pname, name, resolve(name)))
                i = j
                continue
            i += 1

    walk(main, 0, label)
    return found


def _is_param(text: str) -> bool:
    parts = text.split()
    return len(parts) == 2 and parts[0] in PARAM_TYPES


def _values(toks, i):
    """The values of a parameter starting at token i (one value, or a bracketed list), and the next index."""
    if i < len(toks) and toks[i][0] == "[":
        vals = []
        i += 1
        while i < len(toks) and toks[i][0] != "]":
            vals.append(toks[i][1])
            i += 1
        return vals, i + 1
    if i < len(toks) and toks[i][0] in ("q", "w") and not (toks[i][0] == "q" and _is_param(toks[i][1])):
        if toks[i][0] == "w" and is_directive(toks[i][1]) and toks[i][1] not in ("true", "false"):
            return [], i
        return [toks[i][1]], i + 1
    return [], i


def _spectrum_files(values) -> list[str]:
    return [v for v in values if not _number(v) and ("." in v or "/" in v)]


def _number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def main_files(root: Path) -> list[Path]:
    """The collection's main files (its scenes): every .pbrt file that holds WorldBegin itself, sorted."""
    out = []
    for p in sorted(root.rglob("*.pbrt")):
        if any(part.startswith(".") for part in p.relative_to(root).parts):
            continue
        if any(k == "w" and v == "WorldBegin" for k, v, _ in tokens(p.read_text(errors="replace"))):
            out.append(p)
    return out
