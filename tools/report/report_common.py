"""Helpers shared by the report scripts: progress lines, Markdown tables, a
small Markdown-to-HTML converter (static pages that open from disk)."""

from __future__ import annotations

import hashlib
import html
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path


def log(msg: str) -> None:
    print(f"[report] {msg}", file=sys.stderr, flush=True)


def writable_folder(path: str, tool: str) -> Path | None:
    """Create the output folder and check it is writable; None (and a one-line error) if not."""
    out = Path(path)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / ".write-test"
        probe.write_text("")
        probe.unlink()
    except OSError as exc:
        print(f"{tool}: cannot write to '{out}': {exc.strerror}", file=sys.stderr)
        return None
    return out


def file_digest(path: str) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def reference_cache(out: Path) -> Path:
    """Where references are kept by content: $UDM1_REPORT_CACHE (the main report sets it, so that its steps share
    them), else OUT/cache."""
    return Path(os.environ.get("UDM1_REPORT_CACHE") or Path(out) / "cache")


def cached_reference(tool: str, args: list[str], exr: Path, png: Path | None, cache: Path) -> str:
    """`tool reference ARGS -o exr [--png png]`, rendered once per content: the key is the tool's own bytes and
    ARGS (scene, size, spp, ...), so any step or later run asking for the same reference reuses the file (the
    renders are deterministic: same inputs, bit-identical output). Returns the tool's first stdout line."""
    h = hashlib.sha256(file_digest(tool).encode())
    h.update("\0".join(args).encode())
    scene = next((args[i + 1] for i, a in enumerate(args[:-1]) if a == "--scene"), "")
    if os.path.isfile(scene):  # a scene file: its content too (what it includes is named by the file)
        h.update(file_digest(scene).encode())
    key = h.hexdigest()[:24]
    cache.mkdir(parents=True, exist_ok=True)
    c_exr, c_png, c_txt = (cache / f"{key}{ext}" for ext in (".exr", ".png", ".txt"))
    if not (c_exr.exists() and c_png.exists() and c_txt.exists()):
        tmp = cache / f"{key}.tmp{os.getpid()}"
        r = subprocess.run([tool, "reference", *args, "-o", f"{tmp}.exr", "--png", f"{tmp}.png"],
                           capture_output=True, text=True)
        if r.returncode != 0:
            for ext in (".exr", ".png"):
                Path(f"{tmp}{ext}").unlink(missing_ok=True)
            raise RuntimeError(f"{Path(tool).name} reference {' '.join(args)}: {r.stderr.strip()}")
        line = (r.stdout.splitlines() or [""])[0]
        Path(f"{tmp}.exr").replace(c_exr)
        Path(f"{tmp}.png").replace(c_png)
        c_txt.write_text(line.replace(f"{tmp}.exr", "<reference>") + "\n")
        log(f"reference rendered and kept as {c_exr.name} in {cache}")
    else:
        log(f"reference reused from {cache / c_exr.name} (same tool, scene and settings)")
    shutil.copyfile(c_exr, exr)
    if png is not None:
        shutil.copyfile(c_png, png)
    return c_txt.read_text().rstrip("\n").replace("<reference>", str(exr))


class RendererTool:
    """udm1-ao or udm1-pt with a report's scene options (`common`): one-shot runs, cached references, and
    batches of renders in one process (`sweep`) whose CSV lines are turned into rows as they arrive,
    with progress on stderr."""

    def __init__(self, path: str, name: str, common: list[str], ms: bool, cache: Path | None = None):
        self.path, self.name, self.common, self.ms = path, name, common, ms  # ms: progress times in ms, else s
        self.cache = cache  # references by content (cached_reference); None: rendered every time

    def run(self, *args: str) -> str:
        r = subprocess.run([self.path, *args], capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{self.name} {' '.join(args)}: {r.stderr.strip()}")
        return r.stdout

    def reference(self, spp: int, path: Path, png: Path) -> str:
        if self.cache is not None:
            return cached_reference(self.path, [*self.common, "--spp", str(spp)], path, png, self.cache)
        return self.run("reference", *self.common, "--spp", str(spp), "-o", str(path), "--png", str(png)).splitlines()[0]

    def sweep(self, samplers, spps, seeds: int, ref: Path, images: Path | None = None, note: str = "",
              extra: tuple[str, ...] = ()) -> list[dict]:
        """Every sampler x spp x seed in one process; extra names integer CSV columns to keep too."""
        args = [self.path, "sweep", *self.common, "--against", str(ref), "--samplers", ",".join(samplers),
                "--spps", ",".join(map(str, spps)), "--seeds", str(seeds)] + (["--images", str(images)] if images else [])
        rows, total = [], len(samplers) * len(spps) * seeds
        with subprocess.Popen(args, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) as p:
            header = p.stdout.readline().strip().split(",")
            for line in p.stdout:
                r = dict(zip(header, line.strip().split(",")))
                rows.append({"sampler": r["sampler"], "spp": int(r["spp"]), "seed": int(r["seed"]),
                             "seconds": float(r["seconds"]), "rmse": float(r["rmse"]), "psnr": float(r["psnr"]),
                             **{k: int(r[k]) for k in extra}})
                if rows[-1]["seed"] == seeds:
                    t = float(r["seconds"])
                    log(f"  {note}[{len(rows)}/{total}] {r['sampler']:12s} {r['spp']:>5s} spp: PSNR {float(r['psnr']):.2f} dB, "
                        + (f"{t * 1e3:.1f} ms" if self.ms else f"{t:.2f} s"))
            err = p.stderr.read()
        if p.returncode != 0:
            raise RuntimeError(f"{self.name} sweep: {err.strip()}")
        return rows


def md_table(header: list[str], rows: list[list]) -> str:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(lines)


def inline(text: str) -> str:
    """Escape text, then turn [label](href), **bold** and `code` into HTML."""
    t = html.escape(text)
    t = re.sub(r"\[([^\]]+)\]\(([^)]+)\)", r'<a href="\2">\1</a>', t)
    t = re.sub(r"\*\*([^*]+)\*\*", r"<b>\1</b>", t)
    return re.sub(r"`([^`]+)`", r"<code>\1</code>", t)


def md_to_html(md: str, title: str = "udm1 report") -> str:
    """A small Markdown subset (headings, tables, images, paragraphs) to static HTML."""
    body, table = [], []

    def flush_table():
        if not table:
            return
        rows = [[c.strip() for c in line.strip("|").split("|")] for line in table if not set(line) <= set("|-")]
        body.append("<table>" + "".join(
            "<tr>" + "".join(f"<{'th' if i == 0 else 'td'}>{inline(c)}</{'th' if i == 0 else 'td'}>" for c in r)
            + "</tr>" for i, r in enumerate(rows)) + "</table>")
        table.clear()

    for line in md.splitlines():
        if line.startswith("|"):
            table.append(line)
            continue
        flush_table()
        if line.startswith("#"):
            level = len(line) - len(line.lstrip("#"))
            body.append(f"<h{level}>{inline(line[level:].strip())}</h{level}>")
        elif line.startswith("!["):
            for part in line.split(") "):
                alt, src = part[2:].split("](")
                body.append(f'<img alt="{html.escape(alt)}" src="{html.escape(src.rstrip(")"))}">')
        elif line.startswith("- "):
            body.append(f"<li>{inline(line[2:])}</li>")
        elif line.strip():
            body.append(f"<p>{inline(line)}</p>")
    flush_table()
    style = ("body{font-family:sans-serif;max-width:1100px;margin:auto;padding:1em}table{border-collapse:collapse}"
             "td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}img{max-width:100%}")
    return f"<!doctype html><html><head><meta charset='utf-8'><title>{title}</title><style>{style}</style></head>" \
           f"<body>{''.join(body)}</body></html>\n"


