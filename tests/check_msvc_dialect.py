"""The library's sources and public headers as MSVC would see them: no GNU extension left.

MSVC is not available on the machines that run the tests, so this check does what can be done without
it: every library source (C11) and the public headers (as C99 and as C++) are run through the C
preprocessor with the compiler's own macros removed (-undef) and MSVC's defined instead (_MSC_VER,
_WIN32, _WIN64, and _M_X64 or _M_ARM64), system headers replaced by empty files, so that every
#if chooses the branch MSVC would compile. What is left must hold none of the GCC/Clang extensions MSVC
lacks: __attribute__, __builtin_*, __int128, __extension__, typeof, GNU inline assembly, __thread,
statement expressions, #pragma GCC. Together with the MinGW-w64 build of the portable path (no
unsigned __int128: ./run.sh windows) and the portable build the test command makes, this is how the
code MSVC compiles is checked here.

Usage: python check_msvc_dialect.py <source root> [<C compiler>]
"""

import os
import re
import subprocess
import sys
import tempfile

FORBIDDEN = [
    (re.compile(r"\b__attribute__\b"), "__attribute__"),
    (re.compile(r"\b__builtin_\w+"), "a __builtin_ function"),
    (re.compile(r"\b__int128\b"), "__int128"),
    (re.compile(r"\b__extension__\b"), "__extension__"),
    (re.compile(r"\b(__typeof__|__typeof|typeof)\b"), "typeof"),
    (re.compile(r"\b(__asm__|__asm)\b|\basm\s*\("), "GNU inline assembly"),
    (re.compile(r"\b__thread\b"), "__thread"),
    (re.compile(r"\(\s*\{"), "a statement expression"),
    (re.compile(r"^\s*#\s*pragma\s+GCC\b"), "#pragma GCC"),
    (re.compile(r"\bvector_size\b"), "vector_size"),
]
TARGETS = {"x64": ["-D_M_X64=100", "-D_M_AMD64=100"], "ARM64": ["-D_M_ARM64=1"]}
MSVC = ["-D_MSC_VER=1938", "-D_MSC_FULL_VER=193833130", "-D_WIN32=1", "-D_WIN64=1"]
INCLUDE = re.compile(r'^\s*#\s*include\s*<([^>]+)>', re.M)


def sources(root):
    src = os.path.join(root, "libudm1", "src")
    for base, _, files in os.walk(src):
        for f in sorted(files):
            if f.endswith(".c"):
                yield os.path.join(base, f)


def stub_headers(root, stub):
    """Empty files for every system header the library and its public headers include."""
    names = set()
    for base in (os.path.join(root, "libudm1", "src"), os.path.join(root, "libudm1", "include")):
        for d, _, files in os.walk(base):
            for f in files:
                if f.endswith((".c", ".h")):
                    with open(os.path.join(d, f), encoding="utf-8") as fh:
                        names.update(INCLUDE.findall(fh.read()))
    for name in names:
        if os.path.exists(os.path.join(root, "libudm1", "include", name)):
            continue
        path = os.path.join(stub, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        open(path, "w").close()


def scan(text, root):
    """(file, line, what) for every forbidden construct in preprocessed text (line markers kept)."""
    found, origin, line = [], "?", 0
    for raw in text.splitlines():
        m = re.match(r'^# (\d+) "([^"]+)"', raw)
        if m:
            line, origin = int(m.group(1)), m.group(2)
            continue
        for rx, what in FORBIDDEN:
            if rx.search(raw):
                found.append((os.path.relpath(origin, root) if origin.startswith("/") else origin, line, what))
        line += 1
    return found


def preprocess(cc, args, path):
    r = subprocess.run([cc, "-E", "-undef", "-nostdinc", *args, path], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"{path}: the preprocessor failed: {r.stderr.strip().splitlines()[-1]}")
    return r.stdout


def main():
    root = os.path.abspath(sys.argv[1])
    cc = sys.argv[2] if len(sys.argv) > 2 else "cc"
    problems, checked = set(), 0
    with tempfile.TemporaryDirectory() as stub:
        stub_headers(root, stub)
        common = ["-isystem", stub, "-I", os.path.join(root, "libudm1", "include"),
                  "-I", os.path.join(root, "libudm1", "src"), *MSVC]
        header_c = os.path.join(stub, "udm1_public_headers.c")
        with open(header_c, "w") as f:
            f.write("#include <udm1/udm1.h>\n#include <udm1/stream.h>\n#include <udm1/domain.h>\n")
        for target, macros in TARGETS.items():
            for path in sources(root):
                text = preprocess(cc, [*common, *macros, "-DUDM1_BUILDING", "-DUDM1_HAVE_SOBOL_TABLE", "-std=c11", "-x", "c"], path)
                problems.update(scan(text, root))
                checked += 1
            for lang, std in (("c", "-std=c99"), ("c++", "-std=c++11")):
                text = preprocess(cc, [*common, *macros, std, "-x", lang], header_c)
                problems.update(scan(text, root))
                checked += 1
    for origin, line, what in sorted(problems):
        print(f"{origin}:{line}: {what} in the code MSVC compiles (guard it, or use core/bits.h, core/u128.h)")
    print(f"check_msvc_dialect: {checked} translation units (x64 and ARM64), {len(problems)} GNU extensions "
          "in the code MSVC compiles")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
