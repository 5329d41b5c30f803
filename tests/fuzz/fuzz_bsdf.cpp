// fuzz_bsdf.cpp - the tabulated BSDF reader (Material "measured") on any bytes (written to a private temporary
// folder), and, where it accepts them, the measured BSDF made from them. Invariants: no crash, no hang, no
// sanitizer report; a file read has f and pdf finite and not negative in every direction tried, and samples with
// finite f and a positive finite density; anything else is a udm1scene::SceneError with a message.
#include "bsdf.h"
#include "scene.h"
#include "tabulated_bsdf.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <new>
#include <string>

#include <unistd.h>

namespace {

const std::string &folder()
{
    static const std::string dir = [] {
        char tmpl[] = "/tmp/udm1-fuzz-bsdf-XXXXXX";
        const char *d = mkdtemp(tmpl);
        if (!d) std::abort();
        return std::string(d);
    }();
    return dir;
}

bool finite_non_negative(udm1pt::Vec3 v)
{
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

void check(const udm1scene::TabulatedBsdf &tab)
{
    udm1pt::MeasuredTables tables(tab);
    udm1pt::Measured m;
    m.t = &tables;
    const udm1pt::Vec3 dirs[] = {{0, 0, 1}, {0.6, 0, 0.8}, {-0.3, 0.4, 0.866}, {0.99, 0.1, 0.0995}, {0.2, -0.5, -0.84}};
    for (udm1pt::Vec3 wo : dirs) {
        for (udm1pt::Vec3 wi : dirs) {
            wi = udm1scene::normalize(wi), wo = udm1scene::normalize(wo);
            double p = m.pdf(wo, wi);
            if (!finite_non_negative(m.f(wo, wi)) || !std::isfinite(p) || p < 0) std::abort();
        }
        for (double u : {0.0, 0.3, 0.77, 0.999999}) {
            udm1pt::Sample s;
            if (m.sample(udm1scene::normalize(wo), u, 1 - u, &s) && (!finite_non_negative(s.f) || !(s.pdf > 0) || !std::isfinite(s.pdf)))
                std::abort();
        }
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const std::string path = folder() + "/t.bsdf";
    {
        std::ofstream f(path, std::ios::binary | std::ios::trunc);
        f.write(reinterpret_cast<const char *>(data), (std::streamsize)size);
    }
    try {
        check(*udm1scene::read_tabulated_bsdf(path));
    } catch (const udm1scene::SceneError &e) {
        if (std::string(e.what()).empty()) std::abort();
    } catch (const std::bad_alloc &) {
    }
    return 0;
}
