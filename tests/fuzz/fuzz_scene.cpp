// fuzz_scene.cpp - the pbrt-v4 scene parser on any bytes.
//
// The input is written to scene.pbrt in a private temporary folder (with a small valid PLY beside it, so
// that plymesh directives reach the PLY reader) and parsed with everything the renderers need.
// Invariants: no crash, no hang, no sanitizer report; the only way out besides a scene is a
// udm1scene::SceneError (or std::bad_alloc) whose message names the file.
#include "pbrt_parser.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

namespace {

const std::string &folder()
{
    static const std::string dir = [] {
        char tmpl[] = "/tmp/udm1-fuzz-scene-XXXXXX";
        const char *d = mkdtemp(tmpl);
        if (!d) std::abort();
        std::ofstream(std::string(d) + "/tri.ply") << "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                                       "property float y\nproperty float z\nelement face 1\n"
                                                       "property list uchar int vertex_indices\nend_header\n"
                                                       "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
        return std::string(d);
    }();
    return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const std::string path = folder() + "/scene.pbrt";
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char *>(data), (std::streamsize)size);
    }
    for (auto need : {udm1scene::Need::Everything, udm1scene::Need::Geometry}) {
        try {
            udm1scene::Scene s = udm1scene::parse_pbrt(path, need);
            (void)s;
        } catch (const udm1scene::SceneError &e) {
            if (std::string(e.what()).empty()) std::abort();  // an error always says what and where
        } catch (const std::bad_alloc &) {
        }
    }
    return 0;
}
