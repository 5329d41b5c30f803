// test_pt_nanovdb.cpp - udm1-pt's "nanovdb" medium (scene/nanovdb_grid.h, pt/grid_medium.h) on files NanoVDB's
// own builder writes (nvdb_grids.h, through the writer tool udm1_test_nvdb_write) into a temporary folder: the grids read back hold the builder's values
// (voxel by voxel, and trilinear between voxels through the grid's map), the majorant grid bounds the
// density everywhere in the box and along every ray's DDA segments, the medium's transform places it, the
// temperature grid makes it glow, and every damaged file - truncated at any byte, a byte changed anywhere in
// its headers or its data, not NanoVDB at all - and every grid pbrt-v4 cannot use is refused with a reason,
// never read out of bounds (this test runs under the sanitizers too).
#include "../c/check.h"
#include "nvdb_grid_values.h"
#include "scene_text.h"

#include "grid_medium.h"
#include "nanovdb_grid.h"
#include "scene.h"

#include <nanovdb/util/IO.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

using namespace udm1scene;
using namespace udm1pt;

namespace {

std::string g_dir;

std::string write(const std::string &kind)
{
    // the writer (its path from the build: UDM1_NVDB_WRITER) compiles NanoVDB's builder once for every test
    std::string path = g_dir + "/" + kind + ".nvdb";
    std::string cmd = std::string("'") + UDM1_NVDB_WRITER + "' '" + path + "' '" + kind + "'";
    int status = std::system(cmd.c_str());
    if (status != 0) {
        std::fprintf(stderr, "test_pt_nanovdb: %s failed (status %d)\n", cmd.c_str(), status);
        std::exit(1);
    }
    return path;
}

std::vector<char> bytes(const std::string &path)
{
    std::ifstream f(path, std::ios::binary);
    return std::vector<char>(std::istreambuf_iterator<char>(f), {});
}

void put(const std::string &path, const std::vector<char> &b, size_t n)
{
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(b.data(), (std::streamsize)n);
}

// load() refuses the file: the reason contains `want`.
std::string refusal(const std::string &path, const std::string &grid = "density")
{
    try {
        auto g = NanoVdbGrid::load(path, grid);
        return g ? "" : "(no grid)";
    } catch (const std::runtime_error &e) {
        return e.what();
    }
}

void test_values_are_the_builders()
{
    auto g = NanoVdbGrid::load(write("ramp"), "density");
    CHECK(g != nullptr);
    if (!g) return;
    // every voxel of the box (and a margin of background around it)
    int wrong = 0;
    for (int k = -11; k <= 11; ++k)
        for (int j = -8; j <= 15; ++j)
            for (int i = -14; i <= 13; ++i) wrong += g->voxel(i, j, k) != nvdb_grids::ramp_density(i, j, k);
    CHECKF(wrong == 0, "%d voxels differ from the builder's values", wrong);
    CHECK(g->index_min(0) == -12 && g->index_max(0) == 11 && g->index_min(1) == -6 && g->index_max(1) == 13);
    // the world box: voxel centres of the index box, as NanoVDB's builder records it (its corners at least)
    const double *o = nvdb_grids::RAMP_ORIGIN;
    const double h = nvdb_grids::RAMP_VOXEL;
    CHECKF(std::fabs(g->world_min().x - (o[0] - 12 * h)) < 1e-9 && g->world_max().y >= o[1] + 13 * h - 1e-9,
           "world box %g .. %g", g->world_min().x, g->world_max().y);
    // at voxel centres the trilinear value is the voxel's; between them the trilinear blend of the eight
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0, 1);
    double worst_centre = 0, worst = 0;
    for (int n = 0; n < 20000; ++n) {
        int i = -13 + (int)(u(rng) * 26), j = -7 + (int)(u(rng) * 22), k = -10 + (int)(u(rng) * 21);
        Vec3 w(o[0] + h * i, o[1] + h * j, o[2] + h * k);
        worst_centre = std::max(worst_centre, std::fabs(g->value(w) - nvdb_grids::ramp_density(i, j, k)));
        Vec3 p(o[0] + h * (-14 + 28 * u(rng)), o[1] + h * (-8 + 24 * u(rng)), o[2] + h * (-11 + 22 * u(rng)));
        Vec3 x = g->index_of(p);
        double fl[3] = {std::floor(x.x), std::floor(x.y), std::floor(x.z)}, f[3] = {x.x - fl[0], x.y - fl[1], x.z - fl[2]};
        double want = 0;
        for (int c = 0; c < 8; ++c) {
            int d[3] = {c & 1, (c >> 1) & 1, (c >> 2) & 1};
            double wgt = 1;
            for (int a = 0; a < 3; ++a) wgt *= d[a] ? f[a] : 1 - f[a];
            want += wgt * nvdb_grids::ramp_density((int)fl[0] + d[0], (int)fl[1] + d[1], (int)fl[2] + d[2]);
        }
        worst = std::max(worst, std::fabs(g->value(p) - want));
    }
    CHECKF(worst_centre < 1e-5, "at voxel centres: off by %g", worst_centre);
    CHECKF(worst < 1e-5, "trilinear: off by %g", worst);
    // far away (and not finite): what the tree holds there
    CHECK(g->value(Vec3(1e30, 0, 0)) == 0 && g->value(Vec3(NAN, 0, 0)) == 0 && g->value(Vec3(0, -1e9, 0)) == 0);
}

Medium nanovdb_medium(const std::string &kind, Mat4 medium_from_world = Mat4())
{
    Medium m;
    m.kind = Medium::NanoVDB;
    m.sigma_a = Vec3(0.5, 1, 2), m.sigma_s = Vec3(2, 1, 0.5);
    m.vdb_density = NanoVdbGrid::load(write(kind), "density");
    m.vdb_temperature = NanoVdbGrid::load(g_dir + "/" + kind + ".nvdb", "temperature");
    m.p0 = m.vdb_density->world_min(), m.p1 = m.vdb_density->world_max();
    m.medium_from_world = medium_from_world;
    return m;
}

void test_majorants_bound_the_density()
{
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (const char *kind : {"ramp", "sphere"}) {
        Medium m = nanovdb_medium(kind, Mat4::scale(Vec3(1, 2, 0.5)));
        GridMedium g(m);
        const MajorantGrid &mg = g.majorant_grid();
        const int R = MajorantGrid::NANOVDB_RES;
        CHECK(mg.res[0] == R && mg.res[1] == R && mg.res[2] == R && mg.max.size() == (size_t)R * R * R);
        int worse = 0;
        double top = 0, cell_top = 0;
        for (float v : mg.max) cell_top = std::max(cell_top, (double)v);
        for (int i = 0; i < 100000; ++i) {
            Vec3 unit(u(rng), u(rng), u(rng));
            Vec3 pm = m.p0 + Vec3((m.p1.x - m.p0.x) * unit.x, (m.p1.y - m.p0.y) * unit.y, (m.p1.z - m.p0.z) * unit.z);
            double d = m.vdb_density->value(pm);
            top = std::max(top, d);
            if (d > mg.at(std::min(R - 1, (int)(unit.x * R)), std::min(R - 1, (int)(unit.y * R)), std::min(R - 1, (int)(unit.z * R))) * (1 + 1e-6))
                ++worse;
        }
        CHECKF(worse == 0, "%s: %d points above their cell's majorant", kind, worse);
        CHECKF(top > 0.9 && cell_top <= m.vdb_density->max_value() && cell_top > 0.9, "%s: density up to %g, majorants up to %g",
               kind, top, cell_top);
        // along rays (world space: the medium's transform in between): every segment's majorant bounds sigma_t
        int bounds = 0, segments = 0;
        for (int r = 0; r < 2000; ++r) {
            Vec3 o(-3 + 6 * u(rng), -3 + 6 * u(rng), -3 + 6 * u(rng));
            double a = 2 * M_PI * u(rng), z = 2 * u(rng) - 1, s = std::sqrt(1 - z * z);
            Vec3 d(s * std::cos(a), s * std::sin(a), z);
            MajorantIterator it = g.majorants(o, d, 10);
            MajorantSegment seg;
            while (it.next(&seg)) {
                ++segments;
                for (int k = 0; k < 4; ++k) {
                    GridMedium::Point mp = g.at(o + d * (seg.t0 + (seg.t1 - seg.t0) * u(rng)));
                    for (int c = 0; c < 3; ++c) bounds += mp.sigma_a[c] + mp.sigma_s[c] > seg.sigma_maj[c] * (1 + 1e-6) + 1e-12;
                }
            }
        }
        CHECKF(bounds == 0 && segments > 2000, "%s: %d points above their segment's majorant (%d segments)", kind, bounds, segments);
    }
}

void test_transform_and_emission()
{
    // the medium's transform: the density at world p is the grid's at medium_from_world(p)
    Medium m = nanovdb_medium("fire", Mat4::translate(Vec3(-3, 2, 2)));  // (world (5, 0, 0): the sphere's centre)
    GridMedium g(m);
    CHECK(g.emissive() && m.emissive());
    // (away: a corner of the box, outside the sphere)
    GridMedium::Point centre = g.at(Vec3(5, 0, 0)), away = g.at(Vec3(4.05, -0.95, -0.95));
    CHECKF(std::fabs(centre.sigma_a.y - 1) < 1e-6 && std::fabs(centre.sigma_s.x - 2) < 1e-6, "sigma at the centre %g %g",
           centre.sigma_a.y, centre.sigma_s.x);
    CHECK(away.sigma_a.y == 0 && away.Le.x == 0);
    // the glow: pbrt-v4's blackbody at the temperature there, times Lescale; none at or below 100 K
    double kelvin = m.vdb_temperature->value(Vec3(2, 2, 2));
    CHECKF(std::fabs(kelvin - nvdb_grids::fire_temperature(20, 20, 20)) < 1e-3, "temperature %g", kelvin);
    Vec3 want = g.blackbody(kelvin);
    CHECKF(centre.Le.x > 0 && std::fabs(centre.Le.x - want.x) < 1e-9 * want.x && std::fabs(centre.Le.z - want.z) < 1e-9 * std::fabs(want.z) + 1e-12,
           "Le %g %g, blackbody %g %g", centre.Le.x, centre.Le.z, want.x, want.z);
    m.le_scale = {2.5f}, m.temperature_offset = 300, m.temperature_scale = 0.5;
    GridMedium g2(m);
    Vec3 want2 = g2.blackbody((kelvin - 300) * 0.5) * 2.5;
    CHECK(std::fabs(g2.at(Vec3(5, 0, 0)).Le.x - want2.x) < 1e-9 * want2.x);
    m.temperature_offset = kelvin;  // everything at or below 0 K: no glow
    CHECK(GridMedium(m).at(Vec3(5, 0, 0)).Le.x == 0);
    m.le_scale = {0.0f};  // pbrt-v4: not emissive with Lescale 0
    CHECK(!m.emissive());
    Medium plain = nanovdb_medium("sphere");
    CHECK(!plain.emissive() && !plain.vdb_temperature);
}

void test_bad_files_are_refused()
{
    struct Case {
        const char *kind, *grid, *want;
    } cases[] = {
        {"double", "density", "of type double, not float"},
        {"temperature-double", "temperature", "of type double, not float"},
        {"level-set", "density", "not a fog volume"},
        {"negative", "density", "grid \"density\" holds a negative value"},
        {"nan", "density", "grid \"density\" holds a non-finite value"},
    };
    for (const Case &c : cases) {
        std::string why = refusal(write(c.kind), c.grid);
        CHECKF(why.find(c.want) != std::string::npos, "%s: \"%s\"", c.kind, why.c_str());
    }
    CHECK(refusal(write("named")) == "(no grid)");  // (the parser names the missing grid)
    CHECK(NanoVdbGrid::load(g_dir + "/named.nvdb", "smoke") != nullptr);
    CHECK(refusal(g_dir + "/absent.nvdb").find("cannot open the NanoVDB file") != std::string::npos);
    std::string text = g_dir + "/text.nvdb";
    std::ofstream(text) << "#VDB not really\n";
    CHECK(refusal(text).find("not a NanoVDB file") != std::string::npos);
    std::ofstream(g_dir + "/empty.nvdb");
    CHECK(refusal(g_dir + "/empty.nvdb").find("empty") != std::string::npos);

    // truncated at every byte of its headers and at a sample of the rest: refused. A byte changed at a sample
    // of places: in the grids (whose checksums cover all of them here) refused; in the file's segment header
    // and grid records (some fields of which NanoVDB's reader does not use) refused or read, never out of bounds.
    const std::string fire = write("fire"), cut = g_dir + "/cut.nvdb";
    const std::vector<char> b = bytes(fire);
    int accepted = 0, tried = 0;
    for (size_t n = 0; n < b.size(); n += n < 2048 ? 1 : 4099) {
        if (!check_sampled()) continue;
        put(cut, b, n);
        ++tried;
        for (const char *grid : {"density", "temperature"}) {
            std::string why = refusal(cut, grid);
            accepted += why.empty();
        }
    }
    CHECKF(accepted == 0, "%d truncated files of %d accepted", accepted, tried);
    const size_t records = sizeof(nanovdb::io::Header) + 2 * sizeof(nanovdb::io::MetaData) + sizeof("density") + sizeof("temperature");
    std::mt19937_64 rng(9);
    int in_grids = 0, in_grids_read = 0, in_records = 0;
    for (int t = 0; t < 600; ++t) {
        std::vector<char> c = b;
        size_t at = t < 100 ? (size_t)(rng() % records) : t < 350 ? records + (size_t)(rng() % 8192) : (size_t)(rng() % b.size());
        c[at] = (char)(c[at] ^ (1 + rng() % 255));
        put(cut, c, c.size());
        bool refused = false;
        for (const char *grid : {"density", "temperature"}) {
            try {
                auto g = NanoVdbGrid::load(cut, grid);
                if (g) g->value(Vec3(0.1, 0.2, 0.3)), g->voxel(1, 2, 3);  // (read anyway: inside its bounds)
                else refused = true;  // (a name changed: the grid is not found)
            } catch (const std::runtime_error &) {
                refused = true;
            }
        }
        if (at < records) ++in_records;
        else ++in_grids, in_grids_read += !refused;
    }
    CHECKF(in_grids > 0 && in_grids_read == 0 && in_records > 0, "%d of %d files with a byte changed in a grid read",
           in_grids_read, in_grids);
    std::remove(cut.c_str());
}

void test_scene_file()
{
    // through the parser: the medium's grids, its box, the transform in force, the parameters
    std::string path = write("fire");
    Scene s = load_scene_text("Integrator \"volpath\"\nWorldBegin\nAttributeBegin\nTranslate 1 2 3\n"
                              "MakeNamedMedium \"m\" \"string type\" \"nanovdb\" \"string filename\" \"" + path +
                              "\" \"float Lescale\" [ 3 ] \"float temperaturecutoff\" [ 200 ] \"float temperaturescale\" [ 2 ]"
                              " \"rgb sigma_a\" [ 1 2 3 ] \"float scale\" [ 0.5 ] \"float g\" [ 0.3 ]\nAttributeEnd\n"
                              "MediumInterface \"m\" \"\"\nMaterial \"interface\"\nShape \"sphere\" \"float radius\" [ 1 ]\n");
    CHECK(s.media.size() == 1);
    if (s.media.size() != 1) return;
    const Medium &m = s.media[0];
    CHECK(m.kind == Medium::NanoVDB && m.vdb_density && m.vdb_temperature && m.emissive());
    CHECK(m.le_scale.size() == 1 && m.le_scale[0] == 3 && m.temperature_offset == 200 && m.temperature_scale == 2 && m.g == 0.3);
    CHECK(m.sigma_a.z == 1.5 && m.sigma_s.x == 0.5);
    CHECK(m.medium_from_world.point(Vec3(1, 2, 3)).x == 0);
    // the box: the density grid's with the temperature grid's (the builder's boxes differ: voxel corners of
    // the active voxels, the density's 10..30, the temperature's 9..31)
    CHECKF(m.p0.x == std::min(m.vdb_density->world_min().x, m.vdb_temperature->world_min().x) &&
           m.p1.y == std::max(m.vdb_density->world_max().y, m.vdb_temperature->world_max().y) &&
           m.p0.z < m.vdb_density->world_min().z && m.p1.x > m.vdb_density->world_max().x,
           "box %g .. %g", m.p0.x, m.p1.x);
}

}  // namespace

int main()
{
    char dir[] = "/tmp/udm1_test_nanovdb_XXXXXX";
    if (!mkdtemp(dir)) return 1;
    g_dir = dir;
    test_values_are_the_builders();
    test_majorants_bound_the_density();
    test_transform_and_emission();
    test_bad_files_are_refused();
    test_scene_file();
    for (const char *k : nvdb_grids::KINDS_LIST) std::remove((g_dir + "/" + k + ".nvdb").c_str());
    for (const char *k : {"text", "empty"}) std::remove((g_dir + "/" + k + ".nvdb").c_str());
    rmdir(dir);
    CHECK_DONE();
}
