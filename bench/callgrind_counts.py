"""Instructions executed by a command under valgrind's callgrind, function by function: the count behind the
--instructions options of bench/ab_pt.py and bench/bench_mitsuba_sampler.py (differences of a few per cent that
a loaded machine's clock cannot resolve)."""

from __future__ import annotations

import re
import shutil
import subprocess

_LINE = re.compile(r"^\s*([0-9,]+) \(\s*[0-9.]+%\)\s+(\S*?):?(\S.*?)\s+\[(.+)\]\s*$")


def missing_tool() -> str | None:
    """The valgrind tool that is not on PATH, or None."""
    for tool in ("valgrind", "callgrind_annotate"):
        if not shutil.which(tool):
            return tool
    return None


def count(cmd: list[str], out_file: str) -> list[tuple[int, str, str]]:
    """Runs cmd under callgrind (its profile in out_file) and returns (instructions, function, object path) for
    every function it executed; raises RuntimeError with the command's last line of stderr where it fails.
    Code in no file (a JIT's) has the object path "???"."""
    r = subprocess.run(["valgrind", "--tool=callgrind", f"--callgrind-out-file={out_file}", *cmd],
                       capture_output=True, text=True)
    if r.returncode != 0:
        lines = r.stderr.strip().splitlines()
        raise RuntimeError(f"{cmd[0]} under callgrind failed (exit {r.returncode}): {lines[-1] if lines else 'no message'}")
    ann = subprocess.run(["callgrind_annotate", "--threshold=100", out_file], capture_output=True, text=True, check=True)
    rows = []
    for line in ann.stdout.splitlines():
        m = _LINE.match(line)
        if m:
            rows.append((int(m.group(1).replace(",", "")), m.group(3), m.group(4)))
    return rows
