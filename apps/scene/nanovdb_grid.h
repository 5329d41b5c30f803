// nanovdb_grid.h - one float grid of a NanoVDB file (.nvdb), read with NanoVDB's own reader (nanovdb::io of
// Debian's libnanovdb-dev) as pbrt-v4's "nanovdb" medium reads its "density" and "temperature" grids, and
// looked up as pbrt-v4 looks it up: a point of the grid's world space mapped to index space by the grid's
// single-precision map, trilinear between the voxels (nanovdb::SampleFromVoxels of order 1; voxel centres at
// integer indices, the tree's background value where no voxel is stored).
//
// Before a grid is used it is checked, so that a bad file is refused and never read out of bounds: every
// segment's header and grid records lie inside the file (its grid names end inside it), the file is not
// compressed (pbrt-v4 reads uncompressed files), the grid's buffer holds the grid its header describes
// (size, magic, version, type float, class fog volume or unknown as pbrt-v4 accepts), its map and bounds are
// finite, every node the tree links to lies inside the buffer, the checksum the file records (if any) is the
// data's, and every value (voxels, tiles, background) is finite and not negative. Where the build has no
// NanoVDB (the headers absent when it was configured), load() refuses every file with that reason.
#pragma once

#include "math.h"

#include <memory>
#include <string>

namespace udm1scene {

class NanoVdbGrid {
public:
    // Whether this build reads NanoVDB files at all.
    static bool available();
    // The grid named `name` of the file at `path`; nullptr where the file holds no grid of that name. Throws
    // std::runtime_error with a one-line reason (not naming the file: the caller says where) for a file that
    // cannot be opened, is not NanoVDB, is truncated or damaged, or whose grid fails the checks above.
    static std::shared_ptr<const NanoVdbGrid> load(const std::string &path, const std::string &name);
    ~NanoVdbGrid();
    NanoVdbGrid(const NanoVdbGrid &) = delete;
    NanoVdbGrid &operator=(const NanoVdbGrid &) = delete;

    // The trilinear value at a point of the grid's world space (pbrt-v4's lookup, in single precision).
    double value(Vec3 world) const;
    // The value of the voxel at integer index (x, y, z) (the background outside the tree).
    float voxel(int x, int y, int z) const;
    // The largest voxel value of the inclusive index box lo..hi (-infinity where it is empty).
    float max_voxel(const int lo[3], const int hi[3]) const;
    // A point of world space in index space (the grid's single-precision map, as pbrt-v4 maps it).
    Vec3 index_of(Vec3 world) const;
    // The world-space box of the active voxels the file records (pbrt-v4's worldBBox) and the inclusive
    // index box of the tree.
    Vec3 world_min() const { return world_min_; }
    Vec3 world_max() const { return world_max_; }
    int index_min(int axis) const { return index_min_[axis]; }
    int index_max(int axis) const { return index_max_[axis]; }
    // The largest value stored anywhere in the tree (voxels, tiles, background).
    float max_value() const { return max_value_; }

private:
    struct Impl;
    explicit NanoVdbGrid(std::unique_ptr<Impl> impl);
    std::unique_ptr<Impl> impl_;
    Vec3 world_min_, world_max_;
    int index_min_[3] = {0, 0, 0}, index_max_[3] = {0, 0, 0};
    float max_value_ = 0;
};

}  // namespace udm1scene
