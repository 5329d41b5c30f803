#!/usr/bin/env bash
# check_patch.sh - udm1's pbrt-v4 patch against the pbrt-v4 snapshot in ../shared/anchors: it applies, the
# patched sampler header compiles, and pbrt::UDM1Sampler gives udm1's values (test_pbrt_sampler.cpp built
# against the patched pbrt-v4 sources; pbrt's sampler class is header code, so nothing of pbrt is built
# or linked). Exits 77 (a CTest skip) with a message where the snapshot is absent.
#
#   check_patch.sh SOURCE_DIR WORK_DIR CXX UDM1_INCLUDE UDM1_LIB_DIR
set -euo pipefail
src="$1" work="$2" cxx="$3" inc="$4" libdir="$5"
anchors="${UDM1_ANCHORS:-$src/../shared/anchors}"
archive=$(ls "$anchors"/pbrt-v4-*.tar.gz 2>/dev/null | head -n 1 || true)
if [ -z "$archive" ]; then
    echo "check_patch: skipped: no pbrt-v4 snapshot in $anchors"
    exit 77
fi
rm -rf "$work" && mkdir -p "$work"
tar -xzf "$archive" -C "$work" pbrt-v4/CMakeLists.txt pbrt-v4/src/pbrt pbrt-v4/src/ext/openvdb/nanovdb \
    2>/dev/null || tar -xzf "$archive" -C "$work"
(cd "$work/pbrt-v4" && patch -p1 --quiet <"$src/integrations/pbrt-v4/udm1-sampler.patch") ||
    { echo "check_patch: udm1-sampler.patch does not apply to $(basename "$archive")" >&2; exit 1; }
grep -q 'name == "udm1"' "$work/pbrt-v4/src/pbrt/samplers.cpp" || { echo "check_patch: no udm1 sampler in samplers.cpp" >&2; exit 1; }
"$cxx" -std=c++17 -O1 -g -DUDM1_TEST_PATCHED_PBRT -DPBRT_IS_LINUX $CHECK_PATCH_FLAGS \
    -I "$work/pbrt-v4/src" -I "$work/pbrt-v4/src/ext" -I "$work/pbrt-v4/src/ext/openvdb/nanovdb" \
    -I "$inc" -I "$src/integrations/pbrt-v4" "$src/tests/pbrt/test_pbrt_sampler.cpp" \
    -o "$work/test_pbrt_patched" -L "$libdir" -ludm1 -Wl,-rpath,"$libdir"
"$work/test_pbrt_patched"
