#!/usr/bin/env bash
# abi_dump.sh - write the ABI description of a release of libudm1, which the test command compares
# the library with (tests/check_abi.cmake, libabigail's abidiff; only additions pass).
#
#   scripts/abi_dump.sh [SOURCE_TREE]     default: this checkout
#
# Run it at each release, on the release's tree: it builds that tree's shared library with debug
# information (the types abidw reads), then writes libudm1/abi/udm1-MAJOR.MINOR.PATCH.abi of this
# checkout; commit the file and point UDM1_ABI_BASELINE in tests/CMakeLists.txt at it.
# Needs abigail-tools (Debian), cmake, ninja and a Python with scipy (for the Sobol table), as the build.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SRC="$(cd "${1:-$ROOT}" && pwd)"
PY="${UDM1_PYTHON:-$ROOT/.venv/bin/python}"
header="$SRC/libudm1/include/udm1/core.h"
[[ -f "$header" ]] || header="$SRC/libudm1/include/udm1/udm1.h"   # releases before the header parts
version="$(awk '/^#define UDM1_VERSION_(MAJOR|MINOR|PATCH) /{printf "%s%s", sep, $3; sep="."}' "$header")"
[[ "$version" =~ ^[0-9]+\.[0-9]+\.[0-9]+$ ]] || { echo "abi_dump: no version in $header" >&2; exit 2; }
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cmake -S "$SRC" -B "$work" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_C_FLAGS=-g -DUDM1_BUILD_TOOLS=OFF \
    -DUDM1_BUILD_TESTS=OFF -DUDM1_PYTHON="$PY" >/dev/null
cmake --build "$work" --target udm1 >/dev/null
mkdir -p "$ROOT/libudm1/abi"
out="$ROOT/libudm1/abi/udm1-$version.abi"
abidw --no-corpus-path --no-comp-dir-path --headers-dir "$SRC/libudm1/include/udm1" --out-file "$out" \
    "$work/libudm1/libudm1.so.$version"
echo "abi_dump: wrote $out"
