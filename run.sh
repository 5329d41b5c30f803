#!/usr/bin/env bash
# run.sh - the project's entry point (see README.md).
#
#   ./run.sh [--full] the main job: build, then write report/index.html: speed against error for every
#                     sampler in every application (tools/report/main_report.py; --quick, --full, --fresh)
#   ./run.sh test     every test: build, CTest (C, ABI, install, Python), then the C and C++ tests again
#                     under AddressSanitizer + UndefinedBehaviorSanitizer, the package's Python tests against
#                     that sanitized library, and the tools' and reports' tests against the sanitized tools
#   ./run.sh bench    the benchmarks recorded in BENCHMARKS.md
#   ./run.sh wheel    the Python wheel, libudm1 inside it (scikit-build-core), into dist/ (manylinux tag)
#   ./run.sh fuzz [S] every libFuzzer target for S seconds (default 60), clang + ASan + UBSan (TESTING.md)
#   ./run.sh arm64    the library and every C test cross-built for 64-bit Arm Linux, run under qemu-user
#   ./run.sh windows  the DLL and every C test cross-built with MinGW-w64 (no unsigned __int128, as MSVC
#                     builds it), run under wine64; the DLL's exports; a consumer project's find_package
#
# ./run.sh test also builds the library without unsigned __int128 (build-portable/) and for 64-bit Arm
# (build-arm64/) and runs a part of their tests beside the sanitizer runs (README.md, "Platforms").
#
# Each command installs what is missing (Debian packages, Python packages into
# .venv) and skips what is there.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
cd "$ROOT"
# shellcheck source=scripts/bootstrap.sh
source scripts/bootstrap.sh

JOBS="$(nproc 2>/dev/null || echo 2)"
PY="$ROOT/.venv/bin/python"

build() { # build <dir> [cmake options...]
    local dir="$1"
    shift
    cmake -S . -B "$dir" -G Ninja -DUDM1_PYTHON="$PY" "$@" >/dev/null
    cmake --build "$dir" -j "$JOBS"
}

build_targets() { # build_targets <dir> "<targets>" [cmake options...]: only those targets
    local dir="$1" targets="$2"
    shift 2
    cmake -S . -B "$dir" -G Ninja -DUDM1_PYTHON="$PY" "$@" >/dev/null
    # shellcheck disable=SC2086
    cmake --build "$dir" -j "$JOBS" --target $targets
}

# ---- the platforms (README.md, "Platforms") ----
# The host build's test_draw_digest: the reference the other builds' values at random draws are compared with.
DIGEST_REFERENCE="$ROOT/build/tests/test_draw_digest"
ARM64=(-DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/toolchains/aarch64-linux-gnu.cmake" -DCMAKE_BUILD_TYPE=Release
       -DUDM1_BUILD_TOOLS=OFF -DUDM1_DIGEST_REFERENCE="$DIGEST_REFERENCE" -DUDM1_DIGEST_DRAWS=1000000)
WINDOWS=(-DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/toolchains/x86_64-w64-mingw32.cmake" -DUDM1_PORTABLE_INT128=ON
         -DCMAKE_BUILD_TYPE=Release -DUDM1_BUILD_TOOLS=OFF -DUDM1_DIGEST_REFERENCE="$DIGEST_REFERENCE")
HEADER_TESTS="test_header_c99 test_header_cxx test_header_c99_no128_vector test_header_c99_no128_scalar
              test_header_cxx_no128_vector test_header_cxx_no128_scalar"

# The part of ./run.sh test run beside the Python tests under the sanitizers (with one build and test job),
# its output into the file $1:
#  - build-portable/: the library and its value tests without unsigned __int128 (UDM1_PORTABLE_INT128, as
#    MSVC builds it): golden values, the 128-bit arithmetic and the radical inverses' divisions built on it,
#    fills against per-sample values (a sampled eighth of the matrix), streams and domains (the inline code
#    too), API errors, the headers compiled without __int128, and 10^7 random draws against the __int128
#    build's (test_draw_digest);
#  - build-arm64/: the library cross-built for 64-bit Arm and its quick subset under qemu-user (label
#    quick: golden values, fills, streams, NEON noise and cellular against the scalar references, API
#    errors, the NEON kernels in use, random draws against the host build's) and the headers as C99 and
#    C++ for AArch64.
platform_checks() {
    local log="$1" JOBS=1 # (one job: the sanitized tests run beside it)
    {
        build_targets build-portable "test_golden test_golden_static test_u128 test_radical_inverse test_fill test_stream
            test_stream_scalar test_api_errors test_draw_digest $HEADER_TESTS" -DCMAKE_BUILD_TYPE=Release -DUDM1_PORTABLE_INT128=ON \
            -DUDM1_BUILD_TOOLS=OFF -DUDM1_DIGEST_REFERENCE="$DIGEST_REFERENCE" &&
        UDM1_TEST_SAMPLE=8 ctest --test-dir build-portable -j "$JOBS" --output-on-failure \
            -R '^c[.](golden|golden_static|u128|radical_inverse|fill|stream|stream_inline_scalar|api_errors|draw_digest_reference|draw_digest|header_.*)$' &&
        build_targets build-arm64 "test_golden test_api_errors test_fill test_stream test_noise_eval test_cellular
            test_isa test_draw_digest $HEADER_TESTS" "${ARM64[@]}" &&
        ctest --test-dir build-arm64 -j "$JOBS" --output-on-failure -L '^quick$' &&
        ctest --test-dir build-arm64 -j "$JOBS" --output-on-failure -R '^c[.]header_'
    } >"$log" 2>&1
}

cmd="${1:-report}"
case "$cmd" in
report | --*)
    if [[ $# -gt 0 && "$1" == report ]]; then shift; fi
    udm1_bootstrap "$ROOT"
    udm1_bootstrap_fastnoisesimd "$ROOT" || udm1_log "pyfastnoisesimd could not be installed: the noise speeds are measured against FastNoise Lite"
    build build -DCMAKE_BUILD_TYPE=Release
    export PYTHONPATH="$ROOT/python" UDM1_LIBRARY="$ROOT/build/libudm1/libudm1.so.1"
    udm1_log "the Mitsuba 3 sampler plugin (python -m udm1.mitsuba build; up to date in a second once built)"
    "$PY" -m udm1.mitsuba build || udm1_log "the Mitsuba plugin could not be built: the report's Mitsuba step uses the Python sampler"
    udm1_log "writing report/: the best sampler per application, then every detail (tools/report/main_report.py; its"
    udm1_log "time: BENCHMARKS.md, \"The main report\"; finished steps are reused on the next run; --full for the shared scenes)"
    "$PY" tools/report/main_report.py --build "$ROOT/build" --out "$ROOT/report" "$@"
    ;;
test)
    udm1_bootstrap_debian
    udm1_bootstrap_python "$ROOT" background
    build build -DCMAKE_BUILD_TYPE=Release
    udm1_bootstrap_python_wait
    udm1_log "running every test (ctest in build/; the report steps' tests run once, below, against the sanitized tools)"
    # The test files that run again below, against the sanitized tools or the sanitized library: here only their
    # release_only tests (tests/python/conftest.py). The package's tests that drive the tools (distributed renders,
    # the census) run here whole: the sanitized library's run below has no tools.
    SANITIZED_TOOL_TESTS="test_tool_seq.py test_tool_noise.py test_tool_ao.py test_tool_pt.py test_tool_pt_nanovdb.py test_hardening.py"
    PACKAGE_TESTS="$(cd tests/python && ls test_*.py |
        grep -v -E 'test_(tool_|reports|main_report|hardening|package_wheel|mitsuba|kronecker_bayes_study|readme_example)')"
    later="$SANITIZED_TOOL_TESTS $(echo "$PACKAGE_TESTS" | grep -v -E '^test_(distributed|scene_census)[.]py$')"
    UDM1_SANITIZED_LATER="$(echo $later | tr ' ' ',')" \
        ctest --test-dir build -j "$JOBS" --output-on-failure -E '^python[.]test_reports$' -LE '^long$'
    udm1_log "building and running the C and C++ tests under AddressSanitizer + UndefinedBehaviorSanitizer (build-asan/)"
    nvdb_writer=()  # the NanoVDB test-file writer: the release build's (NanoVDB's builder, not udm1's code)
    [[ -x build/bin/udm1_test_nvdb_write ]] && nvdb_writer=(-DUDM1_TEST_NVDB_WRITER="$ROOT/build/bin/udm1_test_nvdb_write")
    build build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUDM1_SANITIZE=ON "${nvdb_writer[@]}"
    ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
        ctest --test-dir build-asan -j "$JOBS" -L "^(c|cpp)$" --output-on-failure
    udm1_log "beside what follows: the build without unsigned __int128 (build-portable/) and the arm64 build's quick"
    udm1_log "subset under qemu-user (build-arm64/), their results printed at the end"
    platform_log="$(mktemp)"
    platform_checks "$platform_log" &
    platform_pid=$!
    udm1_log "the Python tests of the package against the sanitized library (libasan and libubsan preloaded;"
    udm1_log "leak detection off there: the interpreter itself keeps memory until exit)"
    (cd tests/python && LD_PRELOAD="$(gcc -print-file-name=libasan.so):$(gcc -print-file-name=libubsan.so)" \
        ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 UDM1_SANITIZED=1 \
        UDM1_LIBRARY="$ROOT/build-asan/libudm1/libudm1.so.1" PYTHONPATH="$ROOT/python" \
        "$PY" -m pytest -q -p no:cacheprovider -n "$JOBS" --dist loadfile $PACKAGE_TESTS)
    udm1_log "the tools' tests again and the report steps' tests, against the sanitized tools and benchmarks of build-asan"
    udm1_log "(ASan, LSan, UBSan; the reports' own Python runs on the release library; two pytest runs side by side)"
    asan_tools_pytest() { # asan_tools_pytest <log> <test files...>: one pytest run, its own temporary folder
        local log="$1"
        shift
        (cd tests/python && UDM1_SANITIZED=1 ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
            UDM1_LIBRARY="$ROOT/build/libudm1/libudm1.so.1" PYTHONPATH="$ROOT/python" \
            UDM1_SEQ_TOOL="$ROOT/build-asan/bin/udm1-seq" UDM1_NOISE_TOOL="$ROOT/build-asan/bin/udm1-noise" \
            UDM1_AO_TOOL="$ROOT/build-asan/bin/udm1-ao" UDM1_PT_TOOL="$ROOT/build-asan/bin/udm1-pt" \
            UDM1_BENCH_SAMPLERS="$ROOT/build-asan/bin/udm1_bench_samplers" \
            UDM1_BENCH_NOISE="$ROOT/build-asan/bin/udm1_bench_noise" UDM1_BUILD_DIR="$ROOT/build-asan" \
            "$PY" -m pytest -q -p no:cacheprovider -n "$JOBS" --basetemp="$(mktemp -d)" "$@") >"$log" 2>&1
    }
    logs="$(mktemp -d)"
    asan_tools_pytest "$logs/reports" test_reports.py &
    reports_pid=$!
    tools_status=0 reports_status=0
    asan_tools_pytest "$logs/tools" $SANITIZED_TOOL_TESTS || tools_status=$?
    wait "$reports_pid" || reports_status=$?
    cat "$logs/tools" "$logs/reports"
    rm -rf "$logs"
    platform_status=0
    wait "$platform_pid" || platform_status=$?
    udm1_log "the build without unsigned __int128 and the arm64 build's quick subset (started before the Python tests):"
    cat "$platform_log"
    rm -f "$platform_log"
    if [[ $tools_status -ne 0 || $reports_status -ne 0 || $platform_status -ne 0 ]]; then
        udm1_log "tests failed (tools: exit $tools_status, reports: exit $reports_status, platforms: exit $platform_status)"
        exit 1
    fi
    udm1_log "all tests passed"
    ;;
bench)
    shift || true
    udm1_bootstrap "$ROOT"
    udm1_bootstrap_fastnoisesimd "$ROOT"
    build build -DCMAKE_BUILD_TYPE=Release
    udm1_log "the long statistical tests (CTest label long: the Crown's lights one by one, about 2 minutes)"
    ctest --test-dir build -L '^long$' --output-on-failure
    udm1_log "C throughput (bench/bench_seq.c)"
    ./build/bin/udm1_bench_seq "$@"
    udm1_log "Python throughput against numpy and scipy (bench/bench_python.py)"
    PYTHONPATH="$ROOT/python" UDM1_LIBRARY="$ROOT/build/libudm1/libudm1.so.1" "$PY" bench/bench_python.py
    udm1_log "per-sample draws (streams, domains, cursor) against OpenQMC at -O3 -march=native, x86-64-v3 and the baseline (bench/bench_per_sample.py)"
    "$PY" bench/bench_per_sample.py --build "$ROOT/build" --out "$ROOT/build/bench_per_sample"
    udm1_log "every sampler's throughput (bench/bench_samplers.c)"
    ./build/bin/udm1_bench_samplers throughput
    udm1_log "noise against libnoise (bench/bench_noise.cpp), FastNoiseSIMD and FastNoise Lite (bench/bench_noise.py)"
    ./build/bin/udm1_bench_noise
    PYTHONPATH="$ROOT/python" UDM1_LIBRARY="$ROOT/build/libudm1/libudm1.so.1" "$PY" bench/bench_noise.py
    udm1_log "udm1-ao against a bare Embree loop over the same rays, and each sampler's cost (bench/bench_ao.cpp)"
    ./build/bin/udm1_bench_ao
    udm1_log "udm1-pt's scalar loop against a bare Embree replay of its own rays: Embree's share of its time (bench/bench_pt_embree.cpp)"
    ./build/bin/udm1_bench_pt_embree --spp 64
    ./build/bin/udm1_bench_pt_embree --spp 64 --sampler sobol-owen
    udm1_log "udm1-pt against Mitsuba 3 scalar_rgb and llvm_ad_rgb: throughput, equal spp, equal error (bench/bench_pt.py, about 17 minutes)"
    "$PY" bench/bench_pt.py --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/bench_pt"
    udm1_log "udm1-pt's estimator choices: roulette depth, solid-angle light sampling (bench/bench_pt.py --estimators)"
    "$PY" bench/bench_pt.py --estimators --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/bench_pt"
    udm1_log "udm1-pt against pbrt-v4 on every shared and test scene (bench/bench_accuracy.py; pbrt-v4 is built once"
    udm1_log "from ../shared/anchors into build/anchors, about 10 minutes; skipped with a message where it is absent)"
    "$PY" bench/bench_accuracy.py --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/accuracy"
    udm1_log "udm1-pt on every scene of the public pbrt-v4 collection: renders or its first refusal (bench/bench_scene_census.py;"
    udm1_log "about a minute; skipped with a message where the collection's text, \$UDM1_PBRT_SCENES or ../pbrt-v4-scenes, is absent)"
    "$PY" bench/bench_scene_census.py --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/census"
    udm1_log "the same with each absent .pbrt include an empty file, the rest of each scene judged (--absent-includes empty)"
    "$PY" bench/bench_scene_census.py --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/census-empty" \
        --absent-includes empty
    udm1_log "udm1-pt against pbrt-v4 and Mitsuba 3 at equal error on the shared scenes, each against its own reference"
    udm1_log "(bench/bench_pt_scenes.py, about 45 minutes; skipped with a message where ../shared is absent)"
    "$PY" bench/bench_pt_scenes.py --tool "$ROOT/build/bin/udm1-pt" --out "$ROOT/build/bench_pt_scenes"
    udm1_log "the paper's experiment inside pbrt-v4: its samplers and udm1's (Sampler \"udm1\") on the Crown and veach-mis"
    udm1_log "(bench/bench_pbrt_samplers.py, about 20 minutes; skipped with a message where ../shared is absent)"
    "$PY" bench/bench_pbrt_samplers.py --out "$ROOT/build/bench_pbrt"
    udm1_log "udm1's samplers inside Mitsuba 3 (the native plugin, built first: python -m udm1.mitsuba build) against Mitsuba's own,"
    udm1_log "llvm_ad_rgb and scalar_rgb"
    udm1_log "(bench/bench_mitsuba_sampler.py, about 10 minutes)"
    "$PY" bench/bench_mitsuba_sampler.py --out "$ROOT/build/bench_mitsuba_sampler"
    udm1_log "the same on veach-mis given to Mitsuba (udm1-pt export; skipped with a message where ../shared is absent)"
    "$PY" bench/bench_mitsuba_sampler.py --scene veach-mis --size 192 --scalar-size 96 --tool "$ROOT/build/bin/udm1-pt" \
        --out "$ROOT/build/bench_mitsuba_sampler"
    udm1_log "the native plugin's render time against Mitsuba's independent sampler (bench/bench_mitsuba_sampler.py --speed)"
    "$PY" bench/bench_mitsuba_sampler.py --speed --out "$ROOT/build/bench_mitsuba_sampler"
    udm1_log "integration to a tolerance: udm1.integrate against QMCPy and scipy on Genz's six families (bench/bench_integrate.py;"
    udm1_log "1000 trials per case: hours; --trials N for fewer)"
    "$PY" bench/bench_integrate.py --out "$ROOT/build/bench_integrate"
    udm1_log "scale-out: udm1.distributed on 1 and 2 local Dask workers against the tools alone (bench/bench_distributed.py)"
    UDM1_LIBRARY="$ROOT/build/libudm1/libudm1.so.1" "$PY" bench/bench_distributed.py --tool "$ROOT/build/bin/udm1-pt" \
        --out "$ROOT/build/bench_distributed"
    ;;
wheel)
    udm1_bootstrap "$ROOT"
    udm1_log "building the Python wheel (pyproject.toml: scikit-build-core builds libudm1 into the package) into dist/"
    rm -rf build/wheel
    "$PY" -m pip wheel . --no-deps -q -w build/wheel
    udm1_log "auditwheel repair: the manylinux tag the wheel is compatible with (it needs no other library)"
    PATH="$ROOT/.venv/bin:$PATH" "$PY" -m auditwheel repair build/wheel/udm1-*.whl -w dist
    udm1_log "install it with: pip install $(ls -t dist/udm1-*.whl | head -1)"
    ;;
fuzz)
    shift || true
    UDM1_DEBIAN_PACKAGES+=(clang-14 libclang-rt-14-dev)
    udm1_bootstrap "$ROOT"
    udm1_log "building the libFuzzer targets with clang, ASan and UBSan (build-fuzz/)"
    CC=clang-14 CXX=clang++-14 build build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DUDM1_FUZZ=ON \
        -DUDM1_MULTIVERSION=ON -DUDM1_PYTHON="$PY"
    udm1_log "fuzzing every target (tools/fuzz_run.py; ${1:-60} s each)"
    "$PY" tools/fuzz_run.py --build "$ROOT/build-fuzz" --seconds "${1:-60}" "${@:2}"
    ;;
arm64)
    udm1_bootstrap "$ROOT"
    udm1_log "the host build's test_draw_digest (build/), the reference of the values at random draws"
    build_targets build test_draw_digest -DCMAKE_BUILD_TYPE=Release
    udm1_log "the library and every C test cross-built for 64-bit Arm Linux (build-arm64/, gcc-aarch64-linux-gnu)"
    build build-arm64 "${ARM64[@]}"
    udm1_log "every C test under qemu-user, and the exported symbols (about 10 minutes on 2 cores)"
    ctest --test-dir build-arm64 -j "$JOBS" --output-on-failure -L '^(c|abi)$'
    ;;
windows)
    UDM1_DEBIAN_PACKAGES+=(gcc-mingw-w64-x86-64 g++-mingw-w64-x86-64 wine64)
    udm1_bootstrap "$ROOT"
    udm1_log "the host build's test_draw_digest (build/), the reference of the values at random draws"
    build_targets build test_draw_digest -DCMAKE_BUILD_TYPE=Release
    udm1_log "the DLL and every C test cross-built with MinGW-w64 without unsigned __int128 (build-windows/)"
    build build-windows "${WINDOWS[@]}"
    udm1_log "a Wine prefix of its own (build-windows/wineprefix), then every C test under wine64, the DLL's"
    udm1_log "exports against libudm1/udm1.symbols, and a consumer project's find_package(udm1) with the import library"
    # one Wine server for the whole run (-p: persistent, started before anything else of the prefix): without it
    # the server exits whenever no test runs, and a test that starts just then loses its connection ("wine client
    # error: recvmsg")
    export WINEPREFIX="$ROOT/build-windows/wineprefix"
    wineserver="$(command -v wineserver || echo /usr/lib/wine/wineserver)"
    "$wineserver" -k 2>/dev/null || true
    "$wineserver" -p
    trap '"$wineserver" -k 2>/dev/null || true' EXIT
    WINEDEBUG=-all cmake/toolchains/wine64-run.sh wineboot --init
    ctest --test-dir build-windows -j "$JOBS" --output-on-failure -L '^(c|abi|install)$'
    ;;
*)
    echo "run.sh: unknown command '$cmd' (use: ./run.sh [report|test|bench|wheel|fuzz|arm64|windows])" >&2
    exit 2
    ;;
esac
