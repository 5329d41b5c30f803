#!/usr/bin/env bash
# scripts/anchors.sh - builds the systems udm1 is measured against from the source snapshots in
# ../shared/anchors/ (never from a copy in this tree) into build/anchors/. Benchmarks only: the test
# command never builds an anchor.
#
#   scripts/anchors.sh pbrt-v4     -> build/anchors/pbrt-v4-build/pbrt, with udm1's sampler (about 8-10
#                                     minutes on two cores)
#   scripts/anchors.sh openqmc     -> build/anchors/openqmc/include (header-only)
#
# Prints the path of what it built on stdout. Exits 3 with a one-line message on stderr when the
# snapshot folder is absent (callers skip the comparison and say so), 1 on a failed build.
# UDM1_ANCHORS overrides the snapshot folder. A finished build is reused (a stamp records the archive).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
SRC="${UDM1_ANCHORS:-$ROOT/../shared/anchors}"
OUT="$ROOT/build/anchors"
log() { printf '[anchors] %s\n' "$*" >&2; }

archive() { # archive <prefix>: the one snapshot archive of that name
    local a
    a=$(ls "$SRC"/"$1"-*.tar.gz 2>/dev/null | head -n 1 || true)
    if [ -z "$a" ]; then
        log "no $1 snapshot in $SRC (the anchors folder is absent): skipped"
        exit 3
    fi
    printf '%s' "$a"
}

unpack() { # unpack <archive> <folder name>: extract once per archive
    local a="$1" name="$2" stamp="$OUT/.$2.unpacked"
    if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$(basename "$a")" ] && [ -d "$OUT/$name" ]; then return 0; fi
    log "unpacking $(basename "$a")"
    mkdir -p "$OUT"
    rm -rf "${OUT:?}/$name"
    tar -xzf "$a" -C "$OUT"
    basename "$a" >"$stamp"
}

case "${1:-}" in
pbrt-v4)
    # pbrt-v4 with udm1's sampler added (integrations/pbrt-v4/udm1-sampler.patch: Sampler "udm1"; the
    # patch adds that sampler and touches nothing else, so pbrt-v4's own samplers are upstream's), linked
    # to this tree's libudm1 installed into build/anchors/udm1-install
    a=$(archive pbrt-v4)
    bin="$OUT/pbrt-v4-build/pbrt"
    stamp="$OUT/.pbrt-v4.built"
    patch_file="$ROOT/integrations/pbrt-v4/udm1-sampler.patch"
    [ -d "$ROOT/build/libudm1" ] || { log "build udm1 first (cmake --build build): pbrt-v4 links its libudm1"; exit 1; }
    cmake --install "$ROOT/build" --prefix "$OUT/udm1-install" >/dev/null
    want="$(basename "$a") $(cat "$patch_file" "$ROOT/integrations/pbrt-v4/udm1_pbrt_sampler.h" | sha256sum | cut -c1-16)"
    if [ -x "$bin" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
        echo "$bin"
        exit 0
    fi
    source "$ROOT/scripts/bootstrap.sh"
    UDM1_DEBIAN_PACKAGES=(libgl-dev libopenexr-dev libxcursor-dev libxi-dev libxinerama-dev libxrandr-dev)
    udm1_bootstrap_debian
    rm -f "$OUT/.pbrt-v4.unpacked"  # a fresh tree for the patch
    unpack "$a" pbrt-v4
    (cd "$OUT/pbrt-v4" && patch -p1 --quiet <"$patch_file") || { log "udm1-sampler.patch does not apply to $(basename "$a")"; exit 1; }
    log "building pbrt-v4 with udm1's sampler (CPU only; about 8-10 minutes on two cores) into $OUT/pbrt-v4-build"
    cmake -S "$OUT/pbrt-v4" -B "$OUT/pbrt-v4-build" -DCMAKE_BUILD_TYPE=Release \
        -DPBRT_BUILD_GPU_RENDERER=OFF -DGLFW_BUILD_WAYLAND=OFF \
        -Dudm1_DIR="$OUT/udm1-install/lib/cmake/udm1" -DUDM1_PBRT_INTEGRATION_DIR="$ROOT/integrations/pbrt-v4" \
        >"$OUT/pbrt-v4-cmake.log" 2>&1 ||
        { log "pbrt-v4 configure failed: $OUT/pbrt-v4-cmake.log"; exit 1; }
    cmake --build "$OUT/pbrt-v4-build" -j "$(nproc)" --target pbrt_exe >"$OUT/pbrt-v4-build.log" 2>&1 ||
        { log "pbrt-v4 build failed: $OUT/pbrt-v4-build.log"; exit 1; }
    echo "$want" >"$stamp"
    echo "$bin"
    ;;
openqmc)
    a=$(archive openqmc)
    unpack "$a" openqmc
    echo "$OUT/openqmc/include"
    ;;
*)
    echo "usage: scripts/anchors.sh pbrt-v4|openqmc" >&2
    exit 2
    ;;
esac
