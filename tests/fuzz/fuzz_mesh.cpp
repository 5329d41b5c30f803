// fuzz_mesh.cpp - the PLY and OBJ readers on any bytes (written to a private temporary folder).
// Invariants: no crash, no hang, no sanitizer report; a mesh read has indices within its vertices and
// finite positions; anything else is a udm1scene::SceneError with a message.
#include "mesh_io.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

const std::string &folder()
{
    static const std::string dir = [] {
        char tmpl[] = "/tmp/udm1-fuzz-mesh-XXXXXX";
        const char *d = mkdtemp(tmpl);
        if (!d) std::abort();
        return std::string(d);
    }();
    return dir;
}

void check(const udm1scene::Shape &s)
{
    size_t nv = s.P.size() / 3;
    for (auto i : s.indices)
        if ((size_t)i >= nv) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    for (const char *ext : {".ply", ".obj"}) {
        const std::string path = folder() + "/mesh" + ext;
        {
            std::ofstream f(path, std::ios::binary | std::ios::trunc);
            f.write(reinterpret_cast<const char *>(data), (std::streamsize)size);
        }
        udm1scene::Shape shape;
        try {
            if (ext[1] == 'p')
                udm1scene::read_ply(path, udm1scene::Mat4(), &shape);
            else
                udm1scene::read_obj(path, udm1scene::Mat4(), &shape);
            check(shape);
        } catch (const udm1scene::SceneError &e) {
            if (std::string(e.what()).empty()) std::abort();
        } catch (const std::bad_alloc &) {
        }
    }
    return 0;
}
