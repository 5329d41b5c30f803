// grid_medium.cpp - see grid_medium.h.
#include "grid_medium.h"

#include "pbrt_noise.h"
#include "spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace udm1pt {

MajorantIterator::MajorantIterator(Vec3 o, Vec3 d, double t_min, double t_max, const MajorantGrid *grid, Vec3 sigma_t)
    : t_min_(t_min), t_max_(t_max), grid_(grid), sigma_t_(sigma_t)
{
    if (!grid) return;
    for (int a = 0; a < 3; ++a) {  // (pbrt-v4's DDA set-up, axis by axis)
        const int res = grid->res[a];
        double entry = o[a] + d[a] * t_min;
        voxel_[a] = (int)std::clamp(entry * res, 0.0, (double)(res - 1));
        delta_t_[a] = 1 / (std::fabs(d[a]) * res);
        double da = d[a] == 0 ? 0.0 : d[a];  // (-0: as +0)
        if (da >= 0) {
            next_t_[a] = t_min + ((double)(voxel_[a] + 1) / res - entry) / da;
            step_[a] = 1, limit_[a] = res;
        } else {
            next_t_[a] = t_min + ((double)voxel_[a] / res - entry) / da;
            step_[a] = -1, limit_[a] = -1;
        }
    }
}

bool MajorantIterator::next(MajorantSegment *seg)
{
    if (!(t_min_ < t_max_)) return false;
    if (!grid_) {
        *seg = {t_min_, t_max_, sigma_t_};
        t_min_ = t_max_;
        return true;
    }
    // the axis whose cell boundary comes first
    int axis = next_t_[0] < next_t_[1] ? (next_t_[0] < next_t_[2] ? 0 : 2) : (next_t_[1] < next_t_[2] ? 1 : 2);
    double exit = std::min(t_max_, next_t_[axis]);
    *seg = {t_min_, exit, sigma_t_ * grid_->at(voxel_[0], voxel_[1], voxel_[2])};
    t_min_ = exit;
    if (next_t_[axis] > t_max_) t_min_ = t_max_;
    voxel_[axis] += step_[axis];
    if (voxel_[axis] == limit_[axis]) t_min_ = t_max_;
    next_t_[axis] += delta_t_[axis];
    return true;
}

namespace {

const double FIRST_KELVIN = 100;  // pbrt-v4's grid emits nothing at or below it

// pbrt-v4's BlackbodySpectrum at kelvin: Planck's law normalized to 1 at its peak (Wien's law), as linear sRGB
// of its XYZ (the film's record of it, not normalized to luminance 1).
Vec3 blackbody_rgb(double kelvin)
{
    udm1scene::Spectrum b = udm1scene::Spectrum::blackbody(kelvin);
    double peak = b.at(2.8977721e6 / kelvin);
    return udm1scene::xyz_to_rgb(udm1scene::spectrum_xyz(b) * (1 / peak));
}

}  // namespace

GridMedium::GridMedium(const udm1scene::Medium &m) : m_(m), extent_(m.p1 - m.p0), sigma_t_(m.sigma_a + m.sigma_s)
{
    if (m.kind == udm1scene::Medium::Cloud) return;  // (its density is pbrt_noise.h's, no grid)
    emissive_ = m.emissive();
    if (m.kind == udm1scene::Medium::NanoVDB) {
        nanovdb_majorants();
        if (emissive_) blackbody_table(0, m.vdb_temperature->max_value());  // (its values are not negative)
        return;
    }
    const int res = MajorantGrid::RES;
    grid_.max.resize((size_t)res * res * res);
    for (int z = 0; z < res; ++z)
        for (int y = 0; y < res; ++y)
            for (int x = 0; x < res; ++x)
                grid_.max[(size_t)x + res * ((size_t)y + res * (size_t)z)] = (float)max_value(
                    m.density, Vec3((double)x / res, (double)y / res, (double)z / res),
                    Vec3((double)(x + 1) / res, (double)(y + 1) / res, (double)(z + 1) / res));
    if (!m.temperature.empty()) {  // the blackbody's RGB over the temperatures the grid holds
        auto [lo, hi] = std::minmax_element(m.temperature.begin(), m.temperature.end());
        blackbody_table(*lo, *hi);
    }
}

// The blackbody's RGB from FIRST_KELVIN to the hottest temperature grid values in [lo, top] give (either end:
// the map to kelvin is linear, its scale of either sign); above 1e6 K no table: blackbody() computes it exactly.
void GridMedium::blackbody_table(double lo, double top)
{
    double hi = FIRST_KELVIN;
    for (double t : {lo, top}) hi = std::max(hi, (t - m_.temperature_offset) * m_.temperature_scale);
    hi = std::min(hi, 1e6);
    bb_step_ = std::max(1.0, (hi - FIRST_KELVIN) / 16384);
    int n = (int)std::ceil((hi - FIRST_KELVIN) / bb_step_) + 2;
    blackbody_.resize(n);
    for (int i = 0; i < n; ++i) blackbody_[i] = blackbody_rgb(FIRST_KELVIN + i * bb_step_);
}

void GridMedium::nanovdb_majorants()
{
    const udm1scene::NanoVdbGrid &g = *m_.vdb_density;
    const int res = MajorantGrid::NANOVDB_RES;
    grid_.res[0] = grid_.res[1] = grid_.res[2] = res;
    grid_.max.assign((size_t)res * res * res, 0.0f);
    // each cell's box in the medium's space, in the grid's index space, widened by one voxel for the
    // trilinear lookups (truncated as pbrt-v4 truncates it) and clipped to the tree's index box; the cell's
    // majorant the largest voxel there (at least 0). The cells are independent: any split gives the same grid.
    tbb::parallel_for(tbb::blocked_range<int>(0, res * res), [&](const tbb::blocked_range<int> &r) {
        for (int yz = r.begin(); yz < r.end(); ++yz) {
            const int y = yz % res, z = yz / res;
            for (int x = 0; x < res; ++x) {
                Vec3 lo, hi;
                const int c[3] = {x, y, z};
                for (int a = 0; a < 3; ++a) {
                    lo[a] = m_.p0[a] + (m_.p1[a] - m_.p0[a]) * ((double)c[a] / res);
                    hi[a] = m_.p0[a] + (m_.p1[a] - m_.p0[a]) * ((double)(c[a] + 1) / res);
                }
                Vec3 i0 = g.index_of(lo), i1 = g.index_of(hi);
                int n0[3], n1[3];
                for (int a = 0; a < 3; ++a) {
                    double a0 = std::min(i0[a], i1[a]) - 1, a1 = std::max(i0[a], i1[a]) + 1;  // (a map may flip an axis)
                    if (!(a0 <= a1)) a0 = g.index_min(a), a1 = g.index_max(a);  // (not finite: the whole tree)
                    n0[a] = (int)std::clamp(std::trunc(a0), (double)g.index_min(a), (double)g.index_max(a) + 1);
                    n1[a] = (int)std::clamp(std::trunc(a1), (double)g.index_min(a) - 1, (double)g.index_max(a));
                }
                grid_.max[(size_t)x + res * ((size_t)y + res * (size_t)z)] = std::max(0.0f, g.max_voxel(n0, n1));
            }
        }
    });
}

GridMedium::~GridMedium() = default;

Vec3 GridMedium::blackbody(double kelvin) const
{
    double x = (kelvin - FIRST_KELVIN) / bb_step_;
    if (!(x >= 0)) return Vec3();
    size_t i = (size_t)x;
    if (i + 1 >= blackbody_.size()) return blackbody_rgb(kelvin);  // (past the table: exactly)
    double f = x - (double)i;
    return blackbody_[i] * (1 - f) + blackbody_[i + 1] * f;
}

double GridMedium::lookup(const std::vector<float> &v, Vec3 u) const
{
    // (a grid of one value is pbrt-v4's 1 x 1 x 1 grid: one sample at the box's centre)
    const int nx = v.size() == 1 ? 1 : m_.nx, ny = v.size() == 1 ? 1 : m_.ny, nz = v.size() == 1 ? 1 : m_.nz;
    double s[3] = {u.x * nx - 0.5, u.y * ny - 0.5, u.z * nz - 0.5};
    int i[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
        double fl = std::floor(s[a]);
        if (!(fl > -2 && fl < 2147483000.0)) return 0;  // (far outside: no sample near)
        i[a] = (int)fl, f[a] = s[a] - fl;
    }
    auto at = [&](int x, int y, int z) -> double {
        if (x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz) return 0;
        return v[((size_t)z * ny + y) * nx + x];
    };
    auto lerp = [](double t, double a, double b) { return (1 - t) * a + t * b; };
    double d00 = lerp(f[0], at(i[0], i[1], i[2]), at(i[0] + 1, i[1], i[2]));
    double d10 = lerp(f[0], at(i[0], i[1] + 1, i[2]), at(i[0] + 1, i[1] + 1, i[2]));
    double d01 = lerp(f[0], at(i[0], i[1], i[2] + 1), at(i[0] + 1, i[1], i[2] + 1));
    double d11 = lerp(f[0], at(i[0], i[1] + 1, i[2] + 1), at(i[0] + 1, i[1] + 1, i[2] + 1));
    return lerp(f[2], lerp(f[1], d00, d10), lerp(f[1], d01, d11));
}

// pbrt-v4's SampledGrid::MaxValue: the largest sample whose trilinear support meets the box lo..hi.
double GridMedium::max_value(const std::vector<float> &v, Vec3 lo, Vec3 hi) const
{
    const int n[3] = {m_.nx, m_.ny, m_.nz};
    int a0[3], a1[3];
    for (int a = 0; a < 3; ++a) {
        a0[a] = std::max((int)std::floor(lo[a] * n[a] - 0.5), 0);
        a1[a] = std::min((int)std::floor(hi[a] * n[a] - 0.5) + 1, n[a] - 1);
    }
    double mx = 0;
    for (int z = a0[2]; z <= a1[2]; ++z)
        for (int y = a0[1]; y <= a1[1]; ++y)
            for (int x = a0[0]; x <= a1[0]; ++x) mx = std::max(mx, (double)v[((size_t)z * n[1] + y) * n[0] + x]);
    return mx;
}

double GridMedium::grid_density(Vec3 unit) const { return lookup(m_.density, unit); }

double GridMedium::cloud_density(Vec3 p) const
{
    auto noise = [](Vec3 q) { return udm1scene::pbrt_noise(q); };
    Vec3 pp = p * m_.frequency;
    if (m_.wispiness > 0) {  // the point perturbed by the noise's gradient (finite differences, as pbrt-v4's DNoise)
        double vomega = 0.05 * m_.wispiness, vlambda = 10;
        for (int i = 0; i < 2; ++i) {
            Vec3 q = pp * vlambda;
            const double delta = 0.01;
            double n0 = noise(q);
            Vec3 dn((noise(q + Vec3(delta, 0, 0)) - n0) / delta, (noise(q + Vec3(0, delta, 0)) - n0) / delta,
                    (noise(q + Vec3(0, 0, delta)) - n0) / delta);
            pp = pp + dn * vomega;
            vomega *= 0.5, vlambda *= 1.99;
        }
    }
    double d = 0, omega = 0.5, lambda = 1;
    for (int i = 0; i < 5; ++i) {  // octaves of noise
        d += omega * noise(pp * lambda);
        omega *= 0.5, lambda *= 1.99;
    }
    d = std::clamp((1 - p.y) * 4.5 * m_.cloud_density * d, 0.0, 1.0);  // thinner with altitude
    d += 2 * std::max(0.0, 0.5 - p.y);
    return std::clamp(d, 0.0, 1.0);
}

GridMedium::Point GridMedium::at(Vec3 p) const
{
    Point out;
    Vec3 pm = m_.medium_from_world.point(p);
    if (m_.kind == udm1scene::Medium::Cloud) {
        double d = cloud_density(pm);
        out.sigma_a = m_.sigma_a * d, out.sigma_s = m_.sigma_s * d;
        return out;
    }
    if (m_.kind == udm1scene::Medium::NanoVDB) {  // (pbrt-v4's NanoVDBMedium::SamplePoint)
        double d = m_.vdb_density->value(pm);
        out.sigma_a = m_.sigma_a * d, out.sigma_s = m_.sigma_s * d;
        if (emissive_) {
            double kelvin = (m_.vdb_temperature->value(pm) - m_.temperature_offset) * m_.temperature_scale;
            if (kelvin > FIRST_KELVIN) out.Le = blackbody(kelvin) * m_.le_scale[0];
        }
        return out;
    }
    Vec3 u((pm.x - m_.p0.x) / extent_.x, (pm.y - m_.p0.y) / extent_.y, (pm.z - m_.p0.z) / extent_.z);
    double d = lookup(m_.density, u);
    out.sigma_a = m_.sigma_a * d, out.sigma_s = m_.sigma_s * d;
    if (emissive_) {
        double scale = lookup(m_.le_scale, u);
        if (scale > 0) {
            if (!m_.temperature.empty()) {
                double kelvin = (lookup(m_.temperature, u) - m_.temperature_offset) * m_.temperature_scale;
                if (kelvin > FIRST_KELVIN) out.Le = blackbody(kelvin) * scale;
            } else {
                out.Le = m_.Le * scale;
            }
        }
    }
    return out;
}

MajorantIterator GridMedium::majorants(Vec3 o, Vec3 d, double t_max) const
{
    // the ray in the unit box's coordinates (the same t: an affine map), clipped to the box (pbrt-v4's slab test)
    Vec3 om = m_.medium_from_world.point(o), dm = m_.medium_from_world.vector(d);
    Vec3 ou((om.x - m_.p0.x) / extent_.x, (om.y - m_.p0.y) / extent_.y, (om.z - m_.p0.z) / extent_.z);
    Vec3 du(dm.x / extent_.x, dm.y / extent_.y, dm.z / extent_.z);
    double t0 = 0, t1 = t_max;
    for (int a = 0; a < 3; ++a) {
        double inv = 1 / du[a];
        double near = (0 - ou[a]) * inv, far = (1 - ou[a]) * inv;
        if (near > far) std::swap(near, far);
        far *= 1 + 2 * 3 * 0x1.0p-53 / (1 - 3 * 0x1.0p-53);  // (pbrt-v4's robust far bound, in double)
        t0 = near > t0 ? near : t0;
        t1 = far < t1 ? far : t1;
        if (t0 > t1) return MajorantIterator();
    }
    return MajorantIterator(ou, du, t0, t1, m_.kind == udm1scene::Medium::Cloud ? nullptr : &grid_, sigma_t_);
}

uint64_t tracking_seed(const double *v, int n)
{
    uint64_t h = 0x243F6A8885A308D3ull;
    for (int i = 0; i < n; ++i) {
        uint64_t b;
        std::memcpy(&b, &v[i], sizeof b);
        h = udm1_mix64(h ^ b) + UDM1_GOLDEN_GAMMA;
    }
    return h;
}

}  // namespace udm1pt
