// nanovdb_grid.cpp - see nanovdb_grid.h.
#include "nanovdb_grid.h"

#include <stdexcept>

#ifdef UDM1_HAVE_NANOVDB

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridChecksum.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <vector>

namespace udm1scene {

using FloatGrid = nanovdb::NanoGrid<float>;
using Root = FloatGrid::TreeType::RootType;
using Upper = Root::ChildNodeType;
using Lower = Upper::ChildNodeType;
using Leaf = Lower::ChildNodeType;

struct NanoVdbGrid::Impl {
    nanovdb::GridHandle<nanovdb::HostBuffer> handle;
    const FloatGrid *grid = nullptr;
};

namespace {

[[noreturn]] void bad(const std::string &why) { throw std::runtime_error(why); }

// The file's segments and grid records, as nanovdb::io::Segment reads them, checked to lie inside the file
// before NanoVDB's reader trusts their sizes (it reads a name of the size a record gives, and a grid of the
// size it gives, without looking at the file's length).
void check_segments(const std::string &path)
{
    std::ifstream is(path, std::ios::binary);
    if (!is) bad("cannot open the NanoVDB file");
    is.seekg(0, std::ios::end);
    const uint64_t size = (uint64_t)is.tellg();
    is.seekg(0);
    if (size == 0) bad("empty (not a NanoVDB file)");
    uint64_t at = 0;
    for (int segment = 0; at < size; ++segment) {
        nanovdb::io::Header h;
        h.magic = 0;
        is.read(reinterpret_cast<char *>(&h), (std::streamsize)std::min<uint64_t>(sizeof h, size - at));
        if (h.magic != NANOVDB_MAGIC_NUMBER)  // (a short file's first bytes too)
            bad(segment == 0 ? "not a NanoVDB file (it does not begin with NanoVDB's magic number)"
                             : "damaged (a segment does not begin with NanoVDB's magic number)");
        if (size - at < sizeof h) bad("truncated (a segment header is cut off)");
        at += sizeof h;
        if (h.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
            bad("NanoVDB file format " + std::to_string(h.version.getMajor()) + ", this reader reads format " +
                std::to_string(NANOVDB_MAJOR_VERSION_NUMBER) + " (pbrt-v4's)");
        if (h.codec != nanovdb::io::Codec::NONE)
            bad("compressed (ZIP or BLOSC), which pbrt-v4 does not read: write it uncompressed");
        if (h.gridCount == 0) bad("damaged (a segment without grids)");
        uint64_t data = 0;
        for (int g = 0; g < h.gridCount; ++g) {
            nanovdb::io::MetaData m;
            if (size - at < sizeof m) bad("truncated (a grid record is cut off)");
            is.read(reinterpret_cast<char *>(&m), sizeof m);
            at += sizeof m;
            if (m.nameSize == 0 || m.nameSize > size - at) bad("truncated (a grid name is cut off)");
            std::vector<char> name(m.nameSize);
            is.read(name.data(), m.nameSize);
            at += m.nameSize;
            if (name.back() != '\0') bad("damaged (a grid name does not end)");
            if (m.gridSize != m.fileSize) bad("damaged (a grid's size in memory and on disk differ, uncompressed)");
            if (m.gridSize < sizeof(nanovdb::GridData)) bad("damaged (a grid smaller than its header)");
            data += m.fileSize;
            if (data > size - at) bad("truncated (its grids need more bytes than it has)");
        }
        at += data;
        is.seekg((std::streamoff)at);
        if (!is) bad("cannot read the NanoVDB file");
    }
}

bool finite3(const nanovdb::Vec3R &v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// Every node the tree links to inside the buffer, 32-byte aligned, the node counts the tree records, every
// value finite and not negative; *max the largest value.
void check_tree(const FloatGrid &grid, uint64_t size, const std::string &what, float *max)
{
    const uint8_t *begin = reinterpret_cast<const uint8_t *>(&grid), *end = begin + size;
    auto inside = [&](const void *p, size_t bytes) {
        const uint8_t *q = static_cast<const uint8_t *>(p);
        return q >= begin && q <= end && (size_t)(end - q) >= bytes && ((uintptr_t)q & 31) == 0;
    };
    auto value = [&](float v) {
        if (!std::isfinite(v) || v < 0)
            bad(what + " holds a " + (std::isfinite(v) ? "negative" : "non-finite") + " value (" + std::to_string(v) +
                "); densities and temperatures must be finite and not negative");
        if (v > *max) *max = v;
    };
    const auto *tree_data = grid.tree().data();
    if (!inside(tree_data, sizeof *tree_data)) bad("damaged (its tree lies outside the grid)");
    const uint64_t root_offset = tree_data->mNodeOffset[3];
    if (root_offset < sizeof *tree_data || root_offset > size) bad("damaged (its root lies outside the grid)");
    const Root &root = grid.tree().root();
    if (!inside(&root, sizeof(Root))) bad("damaged (its root lies outside the grid)");
    const auto *rd = root.data();
    if ((uint64_t)rd->mTableSize > (size - ((const uint8_t *)rd - begin) - sizeof(Root)) / sizeof(Root::Tile))
        bad("damaged (its root's table lies outside the grid)");
    *max = 0;
    value(rd->mBackground);
    uint64_t counted[3] = {0, 0, 0};  // leaf, lower, upper
    for (uint32_t i = 0; i < rd->mTableSize; ++i) {
        const Root::Tile *tile = rd->tile(i);
        if (!tile->isChild()) {
            value(tile->value);
            continue;
        }
        const int64_t off = tile->child;
        const intptr_t from_begin = (const uint8_t *)rd - begin;
        if (off < -from_begin || off > (int64_t)size - from_begin) bad("damaged (a node lies outside the grid)");
        const Upper *upper = rd->getChild(tile);
        if (!inside(upper, sizeof(Upper))) bad("damaged (a node lies outside the grid)");
        ++counted[2];
        const auto *ud = upper->data();
        for (uint32_t n = 0; n < Upper::SIZE; ++n) {
            if (!ud->isChild(n)) {
                value(ud->getValue(n));
                continue;
            }
            const int64_t uoff = ud->mTable[n].child, ufrom = (const uint8_t *)ud - begin;
            if (uoff < -ufrom || uoff > (int64_t)size - ufrom) bad("damaged (a node lies outside the grid)");
            const Lower *lower = ud->getChild(n);
            if (!inside(lower, sizeof(Lower))) bad("damaged (a node lies outside the grid)");
            ++counted[1];
            const auto *ld = lower->data();
            for (uint32_t k = 0; k < Lower::SIZE; ++k) {
                if (!ld->isChild(k)) {
                    value(ld->getValue(k));
                    continue;
                }
                const int64_t loff = ld->mTable[k].child, lfrom = (const uint8_t *)ld - begin;
                if (loff < -lfrom || loff > (int64_t)size - lfrom) bad("damaged (a node lies outside the grid)");
                const Leaf *leaf = ld->getChild(k);
                if (!inside(leaf, sizeof(Leaf))) bad("damaged (a node lies outside the grid)");
                ++counted[0];
                for (uint32_t v = 0; v < Leaf::SIZE; ++v) value(leaf->data()->getValue(v));
            }
        }
    }
    // (the checksum's node manager takes the recorded counts and, breadth first, the recorded offsets)
    const size_t node_bytes[3] = {sizeof(Leaf), sizeof(Lower), sizeof(Upper)};
    for (int level = 0; level < 3; ++level) {
        if (counted[level] != tree_data->mNodeCount[level]) bad("damaged (its tree's node counts are not its nodes')");
        if (grid.isBreadthFirst() && counted[level] > 0) {
            const uint64_t first = ((const uint8_t *)tree_data - begin) + tree_data->mNodeOffset[level];
            if (tree_data->mNodeOffset[level] > size || first > size || counted[level] > (size - first) / node_bytes[level])
                bad("damaged (its tree's node offsets lie outside the grid)");
        }
    }
}

}  // namespace

bool NanoVdbGrid::available() { return true; }

std::shared_ptr<const NanoVdbGrid> NanoVdbGrid::load(const std::string &path, const std::string &name)
{
    check_segments(path);
    auto impl = std::make_unique<Impl>();
    try {
        impl->handle = nanovdb::io::readGrid<nanovdb::HostBuffer>(path, name);
    } catch (const std::exception &e) {
        std::string why = e.what();
        for (char &c : why)
            if (c == '\n' || c == '\t') c = ' ';
        bad("NanoVDB's reader: " + why);
    }
    if (!impl->handle) return nullptr;
    const uint64_t size = impl->handle.size();
    if (size < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>) + sizeof(Root))
        bad("damaged (grid \"" + name + "\" is smaller than a grid's header)");
    const auto *gd = reinterpret_cast<const nanovdb::GridData *>(impl->handle.data());
    const std::string what = "grid \"" + name + "\"";
    if (gd->mMagic != NANOVDB_MAGIC_NUMBER || gd->mGridSize != size) bad("damaged (" + what + "'s header)");
    if (gd->mVersion.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER) bad("damaged (" + what + "'s version)");
    if (gd->mGridType != nanovdb::GridType::Float)
        bad(what + " of type " +
            (gd->mGridType < nanovdb::GridType::End ? std::string(nanovdb::toStr(gd->mGridType)) : std::string("unknown")) +
            ", not float (pbrt-v4 reads float grids)");
    if (gd->mGridClass != nanovdb::GridClass::FogVolume && gd->mGridClass != nanovdb::GridClass::Unknown)
        bad(what + " of class " +
            (gd->mGridClass < nanovdb::GridClass::End ? std::string(nanovdb::toStr(gd->mGridClass)) : std::string("unknown")) +
            ", not a fog volume (pbrt-v4 refuses it)");
    impl->grid = impl->handle.grid<float>();
    if (!impl->grid) bad("damaged (" + what + " is not a float grid)");
    const FloatGrid &grid = *impl->grid;
    const nanovdb::Map &map = grid.map();
    for (int i = 0; i < 9; ++i)
        if (!std::isfinite(map.mMatF[i]) || !std::isfinite(map.mInvMatF[i])) bad("damaged (" + what + "'s map is not finite)");
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(map.mVecF[i])) bad("damaged (" + what + "'s map is not finite)");
    if (!finite3(grid.worldBBox().min()) || !finite3(grid.worldBBox().max())) bad("damaged (" + what + "'s bounds are not finite)");
    float max = 0;
    check_tree(grid, size, what, &max);
    if (!nanovdb::validateChecksum(grid, nanovdb::ChecksumMode::Full))
        bad("damaged (" + what + "'s checksum is not its data's)");
    std::shared_ptr<NanoVdbGrid> out(new NanoVdbGrid(std::move(impl)));
    const auto &wb = grid.worldBBox();
    const auto &ib = grid.indexBBox();
    out->world_min_ = Vec3(wb.min()[0], wb.min()[1], wb.min()[2]);
    out->world_max_ = Vec3(wb.max()[0], wb.max()[1], wb.max()[2]);
    for (int a = 0; a < 3; ++a) out->index_min_[a] = ib.min()[a], out->index_max_[a] = ib.max()[a];
    out->max_value_ = max;
    return out;
}

NanoVdbGrid::NanoVdbGrid(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
NanoVdbGrid::~NanoVdbGrid() = default;

Vec3 NanoVdbGrid::index_of(Vec3 w) const
{
    nanovdb::Vec3<float> i = impl_->grid->worldToIndexF(nanovdb::Vec3<float>((float)w.x, (float)w.y, (float)w.z));
    return Vec3(i[0], i[1], i[2]);
}

double NanoVdbGrid::value(Vec3 w) const
{
    nanovdb::Vec3<float> i = impl_->grid->worldToIndexF(nanovdb::Vec3<float>((float)w.x, (float)w.y, (float)w.z));
    // (a point beyond 2^30 voxels, or not finite, is looked up at 2^30 voxels: no integer conversion overflows)
    for (int a = 0; a < 3; ++a)
        if (!(std::fabs(i[a]) < 0x1.0p30f)) i[a] = std::isnan(i[a]) ? 0x1.0p30f : std::copysign(0x1.0p30f, i[a]);
    using Sampler = nanovdb::SampleFromVoxels<FloatGrid::TreeType, 1, false>;
    return Sampler(impl_->grid->tree())(i);
}

float NanoVdbGrid::voxel(int x, int y, int z) const { return impl_->grid->tree().getValue(nanovdb::Coord(x, y, z)); }

float NanoVdbGrid::max_voxel(const int lo[3], const int hi[3]) const
{
    auto acc = impl_->grid->getAccessor();  // (a cached walk down the tree: neighbouring voxels share nodes)
    float mx = -INFINITY;
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; ++i) mx = std::max(mx, acc.getValue(nanovdb::Coord(i, j, k)));
    return mx;
}

}  // namespace udm1scene

#else  // no NanoVDB in this build

namespace udm1scene {

struct NanoVdbGrid::Impl {};

bool NanoVdbGrid::available() { return false; }

std::shared_ptr<const NanoVdbGrid> NanoVdbGrid::load(const std::string &, const std::string &)
{
    throw std::runtime_error("needs a NanoVDB reader (Debian's libnanovdb-dev), which this build of udm1 does not have");
}

NanoVdbGrid::NanoVdbGrid(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
NanoVdbGrid::~NanoVdbGrid() = default;
double NanoVdbGrid::value(Vec3) const { return 0; }
float NanoVdbGrid::voxel(int, int, int) const { return 0; }
float NanoVdbGrid::max_voxel(const int *, const int *) const { return 0; }
Vec3 NanoVdbGrid::index_of(Vec3 w) const { return w; }

}  // namespace udm1scene

#endif
