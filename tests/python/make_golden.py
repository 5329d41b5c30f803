"""Writes tests/c/golden_values.h: raw values of every preset, with and without
random shifts, and padded cursor draws, computed by the independent Python
reference (reference.py), never by the library.

These values pin the ABI: udm1.h promises that a (preset, seed, stream, index,
dimension) gives the same value in every 1.x release. test_golden.c checks the
library against them; test_golden_file.py checks this file is what the
reference computes. Regenerate only for a new major version:

    python tests/python/make_golden.py > tests/c/golden_values.h
"""

import reference as ref

CASES = [  # preset, dimensions, point count, seed, randomize
    ("wr", 64, 0, 0, 0), ("wr", 64, 0, 12345, 1), ("wr-ao", 2, 0, 7, 1), ("we", 2, 0, 7, 1),
    ("wgr", 2, 0, 7, 1), ("wmmr", 22, 0, 2**64 - 1, 1), ("hwmmr", 22, 0, 1, 1), ("rd", 2, 0, 0, 0),
    ("rd", 16, 0, 99, 1), ("golden", 1, 0, 0, 0), ("epis", 1, 64, 5, 1), ("episwr", 2, 4096, 5, 1),
]
INDICES = [0, 1, 2, 63, 1000, 2**32 - 1, 2**32 + 1, 2**53, 2**63, 2**64 - 1]
STREAMS = [0, 1, 0x00000005_00000007, 2**64 - 1]


def values():
    rows = []
    for ci, (name, d, k, seed, rnd) in enumerate(CASES):
        fr = ref.preset_fracs(name, d, k)
        for j in sorted({0, 1 % d, d // 2, d - 1}):
            alpha = -(-(1 << 128) // k) if fr[j] is None else ref.round128(fr[j])
            for stream in STREAMS:
                off = ref.shift(seed, stream, j) if rnd else 0
                for n in INDICES:
                    if k and n >= k:
                        continue
                    rows.append((ci, stream, n, j, ref.raw_value(off, alpha, n)))
    return rows


def pads():
    rows = []
    for ci, (name, d, k, seed, rnd) in enumerate(CASES):
        for stream in STREAMS[:2]:
            for n in INDICES[:5]:
                for j in (d, d + 1, d + 1000):
                    if k and n >= k:
                        continue
                    rows.append((ci, stream, n, j, ref.pad(seed, stream, n, j)))
    return rows


def main():
    print("/* golden_values.h - written by tests/python/make_golden.py from the Python reference. Do not edit. */")
    print("static const struct golden_case { const char *preset; uint32_t dims; uint64_t k, seed; int randomize; }")
    print("    GOLDEN_CASES[] = {")
    for name, d, k, seed, rnd in CASES:
        print(f'        {{"{name}", {d}u, {k}u, {seed}ull, {rnd}}},')
    print("};")
    print("struct golden_value { int c; uint64_t stream, index; uint32_t dim; uint64_t raw; };")
    for label, rows in (("GOLDEN_VALUES", values()), ("GOLDEN_PADS", pads())):
        print(f"static const struct golden_value {label}[] = {{")
        for ci, stream, n, j, v in rows:
            print(f"        {{{ci}, 0x{stream:x}ull, 0x{n:x}ull, {j}u, 0x{v:016x}ull}},")
        print("};")


if __name__ == "__main__":
    main()
