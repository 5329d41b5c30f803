// nvdb_write.cpp - writes a NanoVDB test file (nvdb_grids.h) for udm1-pt's tool tests:
//   udm1_test_nvdb_write OUT KIND     KIND one of nvdb_grids::KINDS_LIST
#include "nvdb_grids.h"

#include <cstdio>
#include <exception>

int main(int argc, char **argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: %s OUT KIND (KIND one of:", argv[0]);
        for (const char *k : nvdb_grids::KINDS_LIST) std::fprintf(stderr, " %s", k);
        std::fprintf(stderr, ")\n");
        return 2;
    }
    try {
        nvdb_grids::write(argv[1], argv[2]);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "udm1_test_nvdb_write: %s\n", e.what());
        return 1;
    }
    return 0;
}
