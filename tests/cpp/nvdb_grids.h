// nvdb_grids.h - the NanoVDB files of udm1-pt's "nanovdb" medium tests, made with NanoVDB's own builder
// (nanovdb/util/GridBuilder.h, Primitives.h) and written with its own writer (nanovdb/util/IO.h): a fog
// sphere, the same with a temperature field, a smooth density over a shifted and scaled grid, and the
// grids udm1-pt must refuse. Header-only: tests/cpp/test_pt_nanovdb.cpp and the writer tool the Python tests
// run (tests/cpp/nvdb_write.cpp) make the same files.
#pragma once

#include "nvdb_grid_values.h"

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/Primitives.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace nvdb_grids {

using Handle = nanovdb::GridHandle<nanovdb::HostBuffer>;

// A grid of f's values over box (voxels where f is 0 left inactive); its checksum over the grid's headers
// (NanoVDB's default, partial) or over all of it (full).
template <class T, class F>
Handle build(const std::string &name, F f, nanovdb::CoordBBox box, double voxel, nanovdb::Vec3d origin,
             nanovdb::GridClass cls = nanovdb::GridClass::FogVolume, nanovdb::ChecksumMode sum = nanovdb::ChecksumMode::Default)
{
    nanovdb::GridBuilder<T> builder(T(0), cls);
    builder.setChecksum(sum);
    builder([&](const nanovdb::Coord &c) { return (T)f(c[0], c[1], c[2]); }, box);
    return builder.template getHandle<>(voxel, origin, name);
}

// The grids of a file of that kind (nvdb_write's KIND), in file order.
inline std::vector<Handle> grids(const std::string &kind)
{
    using nanovdb::Coord;
    using nanovdb::CoordBBox;
    std::vector<Handle> out;
    const CoordBBox ramp_box(Coord(-12, -6, -9), Coord(11, 13, 9)), fire_box(Coord(7), Coord(33));
    // (the sphere and the fire: full checksums; the others NanoVDB's default, a checksum of the headers only)
    const auto full = nanovdb::ChecksumMode::Full;
    const nanovdb::Vec3d ramp_origin(RAMP_ORIGIN[0], RAMP_ORIGIN[1], RAMP_ORIGIN[2]);
    auto sphere = [&] {
        return nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f((float)SPHERE_CENTRE), SPHERE_VOXEL, 3.0, nanovdb::Vec3d(0), "density",
                                                     nanovdb::StatsMode::Default, full);
    };
    if (kind == "sphere") {
        out.push_back(sphere());
    } else if (kind == "fire") {  // the sphere and a temperature grid
        out.push_back(sphere());
        out.push_back(build<float>("temperature", fire_temperature, fire_box, SPHERE_VOXEL, nanovdb::Vec3d(0), nanovdb::GridClass::FogVolume, full));
    } else if (kind == "ramp") {
        out.push_back(build<float>("density", ramp_density, ramp_box, RAMP_VOXEL, ramp_origin));
    } else if (kind == "named") {  // the sphere under another name, after an unrelated grid
        out.push_back(build<float>("velocity_x", ramp_density, ramp_box, RAMP_VOXEL, ramp_origin));
        out.push_back(nanovdb::createFogVolumeSphere<float>(1.0f, nanovdb::Vec3f((float)SPHERE_CENTRE), SPHERE_VOXEL, 3.0, nanovdb::Vec3d(0), "smoke"));
    } else if (kind == "double") {  // a density that is not float
        out.push_back(build<double>("density", ramp_density, ramp_box, RAMP_VOXEL, ramp_origin));
    } else if (kind == "temperature-double") {
        out.push_back(sphere());
        out.push_back(build<double>("temperature", fire_temperature, fire_box, SPHERE_VOXEL, nanovdb::Vec3d(0)));
    } else if (kind == "level-set") {  // a signed distance, not a fog volume
        out.push_back(nanovdb::createLevelSetSphere<float>(1.0f, nanovdb::Vec3f((float)SPHERE_CENTRE), SPHERE_VOXEL, 3.0, nanovdb::Vec3d(0), "density"));
    } else if (kind == "negative") {
        out.push_back(build<float>("density", [](int i, int j, int k) { return ramp_density(i, j, k) - (i == 3 && j == 4 && k == 5 ? 2 : 0); },
                                   ramp_box, RAMP_VOXEL, ramp_origin));
    } else if (kind == "nan") {
        out.push_back(build<float>("density", [](int i, int j, int k) { return i == 3 && j == 4 && k == 5 ? NAN : ramp_density(i, j, k); },
                                   ramp_box, RAMP_VOXEL, ramp_origin, nanovdb::GridClass::Unknown));
    } else if (kind == "empty") {  // a density grid without active voxels
        out.push_back(build<float>("density", [](int, int, int) { return 0.0f; }, ramp_box, RAMP_VOXEL, ramp_origin));
    } else {
        throw std::runtime_error("unknown kind \"" + kind + "\"");
    }
    return out;
}

// Writes the file of that kind at path (uncompressed, as pbrt-v4 reads them).
inline void write(const std::string &path, const std::string &kind)
{
    std::vector<Handle> g = grids(kind);
    nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(path, g);
}

}  // namespace nvdb_grids
