"""The native Mitsuba 3 sampler plugin "udm1" (integrations/mitsuba3): where it is built and how.

``python -m udm1.mitsuba build`` compiles integrations/mitsuba3/udm1_sampler.cpp with CMake and the
system's C++ compiler against the Mitsuba that is installed (its headers and libmitsuba.so, Dr.Jit's CMake
package, nanobind's headers) and libudm1's static library, into a folder of this package:
``udm1/_mitsuba/mitsuba-<version>/plugins/udm1.so``. Mitsuba finds a plugin ``plugins/<name>.so`` in the
folders of its file resolver: ``udm1.mitsuba.register()`` prepends that folder, the mitsuba command line
takes it with ``-a <folder>``.

The plugin is compiled against one Mitsuba version (PINNED_MITSUBA, the version python/requirements.txt
pins): Mitsuba's plugin interface and headers change between versions, so another version is refused.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

PINNED_MITSUBA = "3.9.1"  # python/requirements.txt's mitsuba
PACKAGE = Path(__file__).resolve().parent
REPO = PACKAGE.parent.parent
SOURCE = REPO / "integrations" / "mitsuba3"


class BuildError(RuntimeError):
    """A build refused or failed: its message is one line."""


def plugin_folder(version: str | None = None) -> Path:
    """The folder of the plugin built for a Mitsuba version (the installed one by default): it holds
    plugins/udm1.so."""
    if version is None:
        import mitsuba
        version = mitsuba.__version__
    return PACKAGE / "_mitsuba" / f"mitsuba-{version}"


def built(folder: Path | None = None) -> Path | None:
    """The folder of the native plugin for the installed Mitsuba when it is built, else None."""
    folder = plugin_folder() if folder is None else Path(folder)
    return folder if (folder / "plugins" / "udm1.so").is_file() else None


def _mitsuba_paths() -> tuple[Path, Path, str]:
    try:
        import drjit
        import mitsuba
    except ImportError as exc:
        raise BuildError(f"Mitsuba 3 is not installed ({exc}): pip install mitsuba=={PINNED_MITSUBA}") from None
    mi_dir, dr_dir = Path(mitsuba.__path__[0]), Path(drjit.__path__[0])
    version = mitsuba.__version__
    if version != PINNED_MITSUBA:
        raise BuildError(f"Mitsuba {version} is installed; the plugin is built against Mitsuba {PINNED_MITSUBA} "
                         f"(pip install mitsuba=={PINNED_MITSUBA})")
    header = mi_dir / "include" / "mitsuba" / "mitsuba.h"
    if not header.is_file() or not (mi_dir / "libmitsuba.so").is_file():
        raise BuildError(f"the installed Mitsuba ({mi_dir}) has no headers or no libmitsuba.so: a wheel of "
                         f"Mitsuba {PINNED_MITSUBA} from PyPI has both")
    text = header.read_text()
    parts = [re.search(rf"#define MI_VERSION_{k}\s+(\d+)", text) for k in ("MAJOR", "MINOR", "PATCH")]
    if None in parts or ".".join(p.group(1) for p in parts) != version:
        raise BuildError(f"{header} is not Mitsuba {version}'s (its MI_VERSION differs)")
    return mi_dir, dr_dir, version


def _nanobind_include() -> Path:
    try:
        import nanobind
    except ImportError:
        raise BuildError("nanobind is not installed: Mitsuba's headers include its reference counting, which the "
                         "Mitsuba wheel does not ship (pip install nanobind==3.1.0)") from None
    return Path(nanobind.include_dir())


def _run(cmd: list[str], what: str, verbose: bool):
    r = subprocess.run(cmd, stdout=None if verbose else subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode:
        tail = (r.stdout or "").strip().splitlines()[-20:]
        if tail and not verbose:
            print("\n".join(tail), file=sys.stderr)
        raise BuildError(f"{what} failed (exit {r.returncode}): {' '.join(cmd)}")


def _static_library(work: Path, jobs: int, verbose: bool) -> Path:
    """libudm1.a: UDM1_STATIC_LIBRARY, the checkout's release build (build/libudm1/libudm1.a), or built from
    the checkout into `work`."""
    env = os.environ.get("UDM1_STATIC_LIBRARY")
    if env:
        if not Path(env).is_file():
            raise BuildError(f"UDM1_STATIC_LIBRARY {env} is not a file")
        return Path(env)
    release = REPO / "build" / "libudm1" / "libudm1.a"
    if release.is_file():
        return release
    if not (REPO / "libudm1" / "CMakeLists.txt").is_file():
        raise BuildError(f"no libudm1.a: set UDM1_STATIC_LIBRARY (libudm1's static library), or build from a clone "
                         f"of udm1")
    lib_build = work / "libudm1"
    _run(["cmake", "-S", str(REPO), "-B", str(lib_build), "-DCMAKE_BUILD_TYPE=Release", "-DUDM1_BUILD_TESTS=OFF",
          "-DUDM1_BUILD_TOOLS=OFF", "-DUDM1_BUILD_EXAMPLES=OFF", f"-DUDM1_PYTHON={sys.executable}"],
         "configuring libudm1", verbose)
    _run(["cmake", "--build", str(lib_build), "-j", str(jobs), "--target", "udm1_static"], "building libudm1", verbose)
    return lib_build / "libudm1" / "libudm1.a"


def build(out: Path | str | None = None, jobs: int = 2, test_variants: bool = False, verbose: bool = False) -> Path:
    """Build the plugin; returns the folder that holds plugins/udm1.so (`out`, by default plugin_folder()).
    test_variants: scalar_rgb and llvm_ad_rgb only (a faster build). Raises BuildError (one line)."""
    if not (SOURCE / "udm1_sampler.cpp").is_file():
        raise BuildError(f"the plugin's source is not here ({SOURCE}): build from a clone of udm1")
    mi_dir, dr_dir, version = _mitsuba_paths()
    nanobind = _nanobind_include()
    if shutil.which("cmake") is None:
        raise BuildError("cmake is not installed (the plugin is built with CMake and a C++17 compiler)")
    out = plugin_folder(version) if out is None else Path(out)
    work = out / "build"
    work.mkdir(parents=True, exist_ok=True)
    static = _static_library(work, jobs, verbose)
    generator = ["-G", "Ninja"] if shutil.which("ninja") else []
    _run(["cmake", "-S", str(SOURCE), "-B", str(work / "plugin"), *generator, "-DCMAKE_BUILD_TYPE=Release",
          f"-DMITSUBA_DIR={mi_dir}", f"-DDRJIT_DIR={dr_dir}", f"-DNANOBIND_INCLUDE={nanobind}",
          f"-DUDM1_STATIC_LIBRARY={static}", f"-DUDM1_OUTPUT_DIR={out}",
          f"-DUDM1_MITSUBA_TEST_VARIANTS={'ON' if test_variants else 'OFF'}"], "configuring the plugin (CMake)", verbose)
    _run(["cmake", "--build", str(work / "plugin"), "-j", str(jobs)], "compiling the plugin", verbose)
    if not (out / "plugins" / "udm1.so").is_file():
        raise BuildError(f"the build made no {out / 'plugins' / 'udm1.so'}")
    return out
