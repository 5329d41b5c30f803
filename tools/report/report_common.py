"""Helpers shared by the report scripts: progress lines, Markdown tables, a
small Markdown-to-HTML converter (static pages that open from disk)."""

from __future__ import annotations

import html
import re
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


