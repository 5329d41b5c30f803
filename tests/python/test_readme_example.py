"""The README's C example is a program that compiles (C99, pedantic) and runs against this build's library: the
first thing a renderer's author copies must not rot when the API moves."""
import os
import pathlib
import re
import shutil
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
LIBRARY = os.environ.get("UDM1_LIBRARY", "")
CC = shutil.which(os.environ.get("CC", "cc"))

pytestmark = [pytest.mark.skipif(not LIBRARY, reason="UDM1_LIBRARY (this build's libudm1) is not set: run through CTest"),
              pytest.mark.skipif(CC is None, reason="no C compiler (cc) on PATH")]


def c_blocks(text):
    return re.findall(r"^```c\n(.*?)^```", text, re.S | re.M)


def as_program(block):
    """The block's #include lines at file scope, the rest in main() with the names it leaves to the reader."""
    includes = [ln for ln in block.splitlines() if ln.startswith("#include")]
    body = "\n".join(ln for ln in block.splitlines() if not ln.startswith("#include"))
    return ("\n".join(includes) + "\n#include <stdio.h>\n#include <stdlib.h>\n"
            "static void die(const char *why) { fprintf(stderr, \"%s\\n\", why); exit(1); }\n"
            "int main(void)\n{\n    uint32_t x = 3, y = 5;\n    uint64_t spp = 4;\n    int max_depth = 3;\n"
            + body + "\n    puts(\"ok\");\n    return 0;\n}\n")


def test_the_readme_has_its_c_example():
    blocks = c_blocks((ROOT / "README.md").read_text())
    assert blocks and "udm1_stream_init" in blocks[0] and "udm1_domain_draw_f32" in blocks[0], blocks


def test_the_readme_c_example_compiles_and_runs(tmp_path):
    src = tmp_path / "readme_example.c"
    src.write_text(as_program(c_blocks((ROOT / "README.md").read_text())[0]))
    exe = tmp_path / "readme_example"
    lib = pathlib.Path(LIBRARY)
    r = subprocess.run([CC, "-std=c99", "-pedantic-errors", "-Werror=implicit-function-declaration",
                        "-Werror=incompatible-pointer-types", "-Werror=int-conversion", "-I", str(ROOT / "libudm1" / "include"),
                        str(src), str(lib), f"-Wl,-rpath,{lib.parent}", "-o", str(exe)], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr + src.read_text()
    run = subprocess.run([str(exe)], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0 and run.stdout == "ok\n", (run.returncode, run.stdout, run.stderr)


def test_a_broken_call_fails_the_check(tmp_path):
    # the check is not vacuous: the example with a call the library does not have is refused by the compiler
    src = tmp_path / "broken.c"
    src.write_text(as_program(c_blocks((ROOT / "README.md").read_text())[0]).replace("udm1_domain_root", "udm1_domain_rooot"))
    r = subprocess.run([CC, "-std=c99", "-Werror=implicit-function-declaration", "-I", str(ROOT / "libudm1" / "include"),
                        "-c", str(src), "-o", str(tmp_path / "broken.o")], capture_output=True, text=True)
    assert r.returncode != 0
