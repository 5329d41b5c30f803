# Cross-compiling for 64-bit Windows with Debian's MinGW-w64 (gcc-mingw-w64-x86-64, g++-mingw-w64-x86-64):
# libudm1.dll, its import library libudm1.dll.a and the static libudm1.a; CTest runs the programs under wine64
# (wine64-run.sh beside this file, with a Wine prefix of its own in the build folder).
#   cmake -S . -B build-windows -DCMAKE_TOOLCHAIN_FILE=cmake/toolchains/x86_64-w64-mingw32.cmake \
#         -DUDM1_PORTABLE_INT128=ON -DUDM1_BUILD_TOOLS=OFF -DUDM1_PYTHON=...
# (UDM1_PORTABLE_INT128: without unsigned __int128, as MSVC builds the library; the Sobol table generator
# runs on the host: UDM1_PYTHON names a host Python with scipy).
set(CMAKE_SYSTEM_NAME Windows)
set(CMAKE_SYSTEM_PROCESSOR AMD64)
set(CMAKE_C_COMPILER x86_64-w64-mingw32-gcc)
set(CMAKE_CXX_COMPILER x86_64-w64-mingw32-g++)
set(CMAKE_RC_COMPILER x86_64-w64-mingw32-windres)
set(CMAKE_FIND_ROOT_PATH /usr/x86_64-w64-mingw32)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
# the test programs with GCC's runtime linked in (libudm1.dll links it in itself: libudm1/CMakeLists.txt)
set(CMAKE_EXE_LINKER_FLAGS_INIT "-static-libgcc -static-libstdc++")
set(CMAKE_CROSSCOMPILING_EMULATOR env "WINEPREFIX=${CMAKE_BINARY_DIR}/wineprefix"
    "${CMAKE_CURRENT_LIST_DIR}/wine64-run.sh")
