#!/bin/sh
# wine64-run.sh PROGRAM [ARGUMENTS...] - runs a Windows program under wine64 as CTest's emulator for the
# MinGW-w64 build (x86_64-w64-mingw32.cmake): Wine's own messages off (WINEDEBUG=-all unless set), the
# MinGW-w64 runtime DLLs (libwinpthread-1.dll, which the threaded tests use) on the DLL search path, the
# program's exit status returned. WINEPREFIX: the Wine prefix (default ~/.wine), created on first use.
wine=$(command -v wine64 || command -v wine || echo /usr/lib/wine/wine64)
export WINEDEBUG="${WINEDEBUG:--all}"
runtime=$(printf 'Z:%s' "$(dirname "$(x86_64-w64-mingw32-gcc -print-file-name=libwinpthread-1.dll)")" | tr / '\\')
export WINEPATH="${WINEPATH:+$WINEPATH;}$runtime"
exec "$wine" "$@"
