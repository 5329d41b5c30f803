// spectrum.cpp - see spectrum.h.
#include "spectrum.h"

#include "udm1app/one_line.h"

#include "file_read.h"
#include "spectral_data.h"
#include "scene.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

namespace udm1scene {


namespace {

const int FIRST_NM = 360;

double planck(double nm, double kelvin)
{
    const double c = 299792458.0, h = 6.62606957e-34, kb = 1.3806488e-23;  // pbrt-v4's constants
    double l = nm * 1e-9;
    return 2 * h * c * c / (std::pow(l, 5) * (std::exp(h * c / (l * kb * kelvin)) - 1));
}

const std::map<std::string, Spectrum> &named()
{
    static const std::map<std::string, Spectrum> table = [] {
        std::map<std::string, Spectrum> t;
        for (const spectral_data::NamedData *d = spectral_data::NAMED; d->name; ++d) {
            Spectrum s;
            for (int i = 0; i < d->count; ++i) s.nm.push_back(d->pairs[2 * i]), s.value.push_back(d->pairs[2 * i + 1]);
            t[d->name] = s;
        }
        Spectrum d65;
        for (int i = 0; i < WAVELENGTHS; ++i) d65.nm.push_back(FIRST_NM + i), d65.value.push_back(spectral_data::CIE_D65[i]);
        t["stdillum-D65"] = d65;
        // pbrt-v4's glasses, by their index at 550 nm only: udm1-pt's dielectrics have one index (no
        // dispersion), so nothing else of these spectra is read
        for (const spectral_data::GlassIndex *g = spectral_data::GLASSES; g->name; ++g) t[g->name] = Spectrum::constant(g->eta_550);
        return t;
    }();
    return table;
}

}  // namespace

double Spectrum::at(double lambda) const
{
    if (kelvin > 0) return planck(lambda, kelvin);
    if (nm.empty() || lambda < nm.front() || lambda > nm.back()) return 0;
    size_t i = std::upper_bound(nm.begin(), nm.end(), lambda) - nm.begin();
    if (i >= nm.size()) return value.back();
    double t = (lambda - nm[i - 1]) / (nm[i] - nm[i - 1]);
    return value[i - 1] + t * (value[i] - value[i - 1]);
}

Spectrum Spectrum::blackbody(double k)
{
    Spectrum s;
    s.kelvin = k;
    return s;
}

Spectrum Spectrum::constant(double v)
{
    Spectrum s;
    s.nm = {1.0, 1e6};
    s.value = {v, v};
    return s;
}

Spectrum spectrum_from_pairs(const std::vector<double> &pairs, const std::string &where)
{
    if (pairs.size() < 2 || pairs.size() % 2)
        throw SceneError(where + ": a spectrum needs (wavelength, value) pairs, got " + std::to_string(pairs.size()) +
                         " numbers");
    Spectrum s;
    for (size_t i = 0; i < pairs.size(); i += 2) {
        if (!(pairs[i] > 0) || (i && !(pairs[i] > pairs[i - 2])))
            throw SceneError(where + ": a spectrum's wavelengths must be positive and increasing (" +
                             number_text(pairs[i]) + " nm)");
        s.nm.push_back(pairs[i]), s.value.push_back(pairs[i + 1]);
    }
    return s;
}

const Spectrum *named_spectrum(const std::string &name)
{
    auto it = named().find(name);
    return it == named().end() ? nullptr : &it->second;
}

bool pbrt_v4_named_spectrum(const std::string &name)
{
    static const std::set<std::string> names = [] {
        std::set<std::string> n = {"glass-BK7", "glass-BAF10", "glass-FK51A", "glass-LASF9", "glass-F5", "glass-F10",
                                   "glass-F11", "stdillum-A", "stdillum-D50", "stdillum-D65", "illum-acesD60"};
        for (const char *m : {"Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"})
            for (const char *part : {"-eta", "-k"}) n.insert(std::string("metal-") + m + part);
        for (int f = 1; f <= 12; ++f) n.insert("stdillum-F" + std::to_string(f));
        for (const char *c : {"canon_eos_100d", "canon_eos_1dx_mkii", "canon_eos_200d", "canon_eos_200d_mkii", "canon_eos_5d",
                              "canon_eos_5d_mkii", "canon_eos_5d_mkiii", "canon_eos_5d_mkiv", "canon_eos_5ds", "canon_eos_m",
                              "hasselblad_l1d_20c", "nikon_d810", "nikon_d850", "sony_ilce_6400", "sony_ilce_7m3",
                              "sony_ilce_7rm3", "sony_ilce_9"})
            for (const char *ch : {"_r", "_g", "_b"}) n.insert(std::string(c) + ch);
        return n;
    }();
    return names.count(name) > 0;
}

std::string known_spectra()
{
    std::string s;
    for (const auto &kv : named()) s += (s.empty() ? "" : ", ") + kv.first;
    return s;
}

Spectrum read_spectrum_file(const std::string &path)
{
    std::string text = read_regular_file(path, "spectrum file");
    std::vector<double> v;
    size_t i = 0;
    while (i < text.size()) {
        char c = text[i];
        if (c == '#') {
            while (i < text.size() && text[i] != '\n') ++i;
            continue;
        }
        if (std::isspace((unsigned char)c) || c == ',') {
            ++i;
            continue;
        }
        const char *begin = text.c_str() + i;
        char *end = nullptr;
        errno = 0;
        double x = std::strtod(begin, &end);
        if (end == begin || errno == ERANGE || !std::isfinite(x))
            throw SceneError(path + ": not a spectrum file (a number was expected, found '" +
                             udm1app::quote_raw(text.substr(i, text.find('\n', i) - i), 12) + "')");
        v.push_back(x);
        i += (size_t)(end - begin);
    }
    return spectrum_from_pairs(v, path);
}

Vec3 cie_xyz_at(int nm)
{
    int i = nm - FIRST_NM;
    return Vec3(spectral_data::CIE_X[i], spectral_data::CIE_Y[i], spectral_data::CIE_Z[i]);
}

double cie_d65_at(int nm) { return spectral_data::CIE_D65[nm - FIRST_NM]; }

Vec3 spectrum_xyz(const Spectrum &s, bool under_d65)
{
    Vec3 xyz;
    for (int i = 0; i < WAVELENGTHS; ++i) {
        double v = s.at(FIRST_NM + i) * (under_d65 ? spectral_data::CIE_D65[i] : 1.0);
        xyz = xyz + cie_xyz_at(FIRST_NM + i) * v;
    }
    return xyz;
}

namespace {
struct M3 {
    double m[3][3];
    Vec3 operator*(Vec3 v) const
    {
        return Vec3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z, m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                    m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
    }
    M3 inverse() const
    {
        const double(&a)[3][3] = m;
        double det = a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) - a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
                     a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
        M3 r;
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
                r.m[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
            }
        return r;
    }
};

// linear sRGB from XYZ as pbrt-v4's RGBColorSpace builds it: the Rec. 709 primaries and the white point
// of the D65 table itself, so that D65 is exactly (1, 1, 1)
const M3 &xyz_from_rgb()
{
    static const M3 m = [] {
        Vec3 w;
        for (int i = 0; i < WAVELENGTHS; ++i) w = w + cie_xyz_at(FIRST_NM + i) * spectral_data::CIE_D65[i];
        w = w * (1 / w.y);
        const double xy[3][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}};
        M3 p;
        for (int c = 0; c < 3; ++c) {
            double x = xy[c][0], y = xy[c][1];
            p.m[0][c] = x / y, p.m[1][c] = 1, p.m[2][c] = (1 - x - y) / y;
        }
        Vec3 k = p.inverse() * w;
        for (int r = 0; r < 3; ++r) p.m[r][0] *= k.x, p.m[r][1] *= k.y, p.m[r][2] *= k.z;
        return p;
    }();
    return m;
}

const M3 &rgb_from_xyz()
{
    static const M3 m = xyz_from_rgb().inverse();
    return m;
}
}  // namespace

Vec3 xyz_to_rgb(Vec3 c) { return rgb_from_xyz() * c; }
Vec3 rgb_to_xyz(Vec3 c) { return xyz_from_rgb() * c; }

Vec3 illuminant_rgb(const Spectrum &s, const std::string &where)
{
    Vec3 xyz = spectrum_xyz(s);
    if (!(xyz.y > 0) || !std::isfinite(xyz.y)) throw SceneError(where + ": the spectrum has no visible light (luminance 0)");
    Vec3 rgb = xyz_to_rgb(xyz * (1 / xyz.y));
    return Vec3(std::max(0.0, rgb.x), std::max(0.0, rgb.y), std::max(0.0, rgb.z));
}

Vec3 albedo_rgb(const double *at_each_nm)
{
    Vec3 xyz, white;
    for (int i = 0; i < WAVELENGTHS; ++i) {
        Vec3 w = cie_xyz_at(FIRST_NM + i) * spectral_data::CIE_D65[i];
        xyz = xyz + w * at_each_nm[i];
        white = white + w;
    }
    return xyz_to_rgb(xyz * (1 / white.y));
}

Vec3 albedo_rgb(const Spectrum &s)
{
    double v[WAVELENGTHS];
    for (int i = 0; i < WAVELENGTHS; ++i) v[i] = std::clamp(s.at(FIRST_NM + i), 0.0, 1.0);
    return albedo_rgb(v);
}

}  // namespace udm1scene
