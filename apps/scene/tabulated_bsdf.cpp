// tabulated_bsdf.cpp - see tabulated_bsdf.h.
#include "tabulated_bsdf.h"

#include "file_read.h"
#include "scene.h"
#include "spectrum.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

namespace udm1scene {

namespace {

enum Dtype : uint8_t { UInt8 = 1, Int8, UInt16, Int16, UInt32, Int32, UInt64, Int64, Float16, Float32, Float64 };

const char *dtype_name(int t)
{
    static const char *names[] = {"invalid", "uint8", "int8", "uint16", "int16", "uint32", "int32",
                                  "uint64", "int64", "float16", "float32", "float64"};
    return t >= 0 && t <= Float64 ? names[t] : "unknown";
}

size_t dtype_size(int t)
{
    switch (t) {
    case UInt8: case Int8: return 1;
    case UInt16: case Int16: case Float16: return 2;
    case UInt32: case Int32: case Float32: return 4;
    default: return 8;
    }
}

struct Field {
    int dtype = 0;
    std::vector<uint64_t> shape;
    const unsigned char *data = nullptr;  // into the file's bytes
    size_t count = 0;                     // values
};

// The file's bytes read in order, every read checked against its end.
struct Cursor {
    const std::string &bytes;
    const std::string &path;
    size_t at = 0;
    void need(size_t n, const char *what) const
    {
        if (bytes.size() - at < n)
            throw SceneError(path + ": tabulated BSDF file truncated (in " + what + " at byte " + std::to_string(at) + ")");
    }
    template <class T> T take(const char *what)
    {
        need(sizeof(T), what);
        T v = 0;
        for (size_t i = 0; i < sizeof(T); ++i) v |= (T)((T)(unsigned char)bytes[at + i] << (8 * i));  // little-endian
        at += sizeof(T);
        return v;
    }
};

std::string shape_text(const std::vector<uint64_t> &s)
{
    std::string t = "[";
    for (size_t i = 0; i < s.size(); ++i) t += (i ? ", " : "") + std::to_string(s[i]);
    return t + "]";
}

std::map<std::string, Field> read_fields(const std::string &bytes, const std::string &path)
{
    Cursor c{bytes, path};
    c.need(12 + 2 + 4, "the header");
    if (std::memcmp(bytes.data(), "tensor_file", 12) != 0)
        throw SceneError(path + ": not a tabulated BSDF file (it does not begin with \"tensor_file\")");
    c.at = 12;
    int major = c.take<uint8_t>("the version"), minor = c.take<uint8_t>("the version");
    if (major != 1 || minor != 0)
        throw SceneError(path + ": tensor file version " + std::to_string(major) + "." + std::to_string(minor) +
                         " (pbrt-v4 reads version 1.0)");
    uint32_t n = c.take<uint32_t>("the field count");
    std::map<std::string, Field> fields;
    for (uint32_t i = 0; i < n; ++i) {
        uint16_t name_length = c.take<uint16_t>("a field's name");
        c.need(name_length, "a field's name");
        std::string name = bytes.substr(c.at, name_length);
        c.at += name_length;
        Field f;
        uint16_t rank = c.take<uint16_t>("a field's rank");
        f.dtype = c.take<uint8_t>("a field's type");
        uint64_t offset = c.take<uint64_t>("a field's offset");
        if (f.dtype < UInt8 || f.dtype > Float64)
            throw SceneError(path + ": field " + std::to_string(i) + " has an unknown type (" + std::to_string(f.dtype) + ")");
        uint64_t size = dtype_size(f.dtype), count = 1;
        bool overflow = false;
        for (uint16_t k = 0; k < rank; ++k) {
            uint64_t s = c.take<uint64_t>("a field's shape");
            f.shape.push_back(s);
            if (s != 0 && count > UINT64_MAX / s) overflow = true;
            count *= s;
        }
        if (overflow || count > UINT64_MAX / size || offset > bytes.size() || count * size > bytes.size() - offset)
            throw SceneError(path + ": field \"" + name + "\" (" + dtype_name(f.dtype) + " " + shape_text(f.shape) +
                             " at byte " + std::to_string(offset) + ") lies outside the file, which is truncated or damaged");
        f.data = reinterpret_cast<const unsigned char *>(bytes.data()) + offset;
        f.count = (size_t)count;
        if (!fields.emplace(name, f).second) throw SceneError(path + ": field \"" + name + "\" appears twice");
    }
    return fields;
}

const Field &field(const std::map<std::string, Field> &fields, const std::string &name, int dtype, size_t rank,
                   const std::string &path)
{
    auto it = fields.find(name);
    if (it == fields.end()) throw SceneError(path + ": no field \"" + name + "\" (pbrt-v4's measured BSDF needs it)");
    const Field &f = it->second;
    if (f.dtype != dtype || f.shape.size() != rank)
        throw SceneError(path + ": field \"" + name + "\" is " + dtype_name(f.dtype) + " " + shape_text(f.shape) + ", not " +
                         dtype_name(dtype) + " of rank " + std::to_string(rank));
    return f;
}

// A float32 field's values, each finite (and at least `low`, or above it if `strict`).
std::vector<float> floats(const Field &f, const std::string &name, const std::string &path, double low = -HUGE_VAL,
                          bool strict = false)
{
    std::vector<float> v(f.count);
    if (f.count) std::memcpy(v.data(), f.data, f.count * sizeof(float));  // (little-endian hosts, as pbrt-v4 reads it)
    for (size_t i = 0; i < v.size(); ++i)
        if (!std::isfinite(v[i]) || v[i] < low || (strict && v[i] == low))
            throw SceneError(path + ": field \"" + name + "\" value " + std::to_string(i) + " is " +
                             (std::isfinite(v[i]) ? number_text(v[i]) : std::string("not finite")) +
                             (std::isfinite(v[i]) ? (strict ? " (it must be above " : " (it must be at least ") +
                                                        number_text(low) + ")"
                                                  : ""));
    return v;
}

void increasing(const std::vector<float> &v, const std::string &name, const std::string &path)
{
    for (size_t i = 1; i < v.size(); ++i)
        if (!(v[i] > v[i - 1])) throw SceneError(path + ": field \"" + name + "\" does not increase (value " + std::to_string(i) + ")");
}

// A density's slices (`count` of h x w values each) must each hold some density.
void slices_nonzero(const std::vector<float> &v, size_t count, const std::string &name, const std::string &path)
{
    size_t n = v.size() / count;
    for (size_t s = 0; s < count; ++s) {
        double sum = 0;
        for (size_t i = 0; i < n; ++i) sum += v[s * n + i];
        if (!(sum > 0)) throw SceneError(path + ": field \"" + name + "\" slice " + std::to_string(s) + " is 0 everywhere");
    }
}

// The linear sRGB weight of each tabulated wavelength: the spectrum pbrt-v4 interpolates (linear between the
// wavelengths, the end values beyond) is the sum of the values times hat functions; each hat's RGB under D65.
std::vector<Vec3> wavelength_rgb(const std::vector<float> &nm)
{
    std::vector<Vec3> w(nm.size());
    std::vector<double> delta(WAVELENGTHS, 0.0);
    for (int l = 0; l < WAVELENGTHS; ++l) {
        const double lambda = 360 + l;
        delta[l] = 1;
        Vec3 rgb = albedo_rgb(delta.data());  // (the RGB of 1 at this wavelength alone)
        delta[l] = 0;
        if (nm.size() == 1) {
            w[0] = w[0] + rgb;
            continue;
        }
        size_t i = std::upper_bound(nm.begin(), nm.end(), (float)lambda) - nm.begin();
        i = std::clamp<size_t>(i, 1, nm.size() - 1) - 1;
        double t = std::clamp((lambda - nm[i]) / ((double)nm[i + 1] - nm[i]), 0.0, 1.0);
        w[i] = w[i] + rgb * (1 - t);
        w[i + 1] = w[i + 1] + rgb * t;
    }
    return w;
}

uint64_t fnv1a(const std::string &bytes)
{
    uint64_t h = 0xcbf29ce484222325ull;
    for (unsigned char c : bytes) h = (h ^ c) * 0x100000001b3ull;
    return h;
}

}  // namespace

std::shared_ptr<const TabulatedBsdf> read_tabulated_bsdf(const std::string &path)
{
    const std::string bytes = read_regular_file(path, "tabulated BSDF file");
    const std::map<std::string, Field> fields = read_fields(bytes, path);
    auto b = std::make_shared<TabulatedBsdf>();
    b->path = path;
    b->digest = fnv1a(bytes);
    const Field &theta_i = field(fields, "theta_i", Float32, 1, path), &phi_i = field(fields, "phi_i", Float32, 1, path),
                &wavelengths = field(fields, "wavelengths", Float32, 1, path), &ndf = field(fields, "ndf", Float32, 2, path),
                &sigma = field(fields, "sigma", Float32, 2, path), &vndf = field(fields, "vndf", Float32, 4, path),
                &luminance = field(fields, "luminance", Float32, 4, path),
                &spectra = field(fields, "spectra", Float32, 5, path);
    field(fields, "description", UInt8, 1, path);
    const Field &jacobian = field(fields, "jacobian", UInt8, 1, path);
    const uint64_t P = phi_i.shape[0], T = theta_i.shape[0], L = wavelengths.shape[0];
    auto shape_error = [&](const std::string &what) {
        return SceneError(path + ": " + what + " (theta_i " + shape_text(theta_i.shape) + ", phi_i " + shape_text(phi_i.shape) +
                          ", wavelengths " + shape_text(wavelengths.shape) + ", ndf " + shape_text(ndf.shape) + ", sigma " +
                          shape_text(sigma.shape) + ", vndf " + shape_text(vndf.shape) + ", luminance " +
                          shape_text(luminance.shape) + ", spectra " + shape_text(spectra.shape) + ")");
    };
    if (P < 1 || T < 1 || L < 1) throw shape_error("theta_i, phi_i and wavelengths need a value each at least");
    if (jacobian.shape[0] != 1) throw shape_error("field \"jacobian\" must hold one value");
    if (vndf.shape[0] != P || vndf.shape[1] != T) throw shape_error("vndf's first axes must be phi_i's and theta_i's");
    if (luminance.shape[0] != P || luminance.shape[1] != T || luminance.shape[2] != luminance.shape[3])
        throw shape_error("luminance's first axes must be phi_i's and theta_i's, its last two equal");
    if (spectra.shape[0] != P || spectra.shape[1] != T || spectra.shape[2] != L || spectra.shape[3] != spectra.shape[4])
        throw shape_error("spectra's first axes must be phi_i's, theta_i's and wavelengths', its last two equal");
    if (spectra.shape[3] != luminance.shape[2]) throw shape_error("spectra and luminance must have the same grid");
    for (const Field *f : {&ndf, &sigma, &vndf, &luminance})
        if (f->shape[f->shape.size() - 1] < 2 || f->shape[f->shape.size() - 2] < 2 || f->shape[f->shape.size() - 1] > (1u << 20) ||
            f->shape[f->shape.size() - 2] > (1u << 20))
            throw shape_error("a table's grid needs 2 to 2^20 values along each axis");
    b->theta_i = floats(theta_i, "theta_i", path);
    b->phi_i = floats(phi_i, "phi_i", path);
    b->wavelengths = floats(wavelengths, "wavelengths", path, 0, true);
    increasing(b->theta_i, "theta_i", path);
    increasing(b->phi_i, "phi_i", path);
    increasing(b->wavelengths, "wavelengths", path);
    b->isotropic = P <= 2;
    if (!b->isotropic) {  // pbrt-v4 reads only tables over the whole circle of azimuths
        double span = (double)b->phi_i.back() - b->phi_i.front();
        if (std::rint(2 * M_PI / span) != 1)
            throw SceneError(path + ": phi_i spans " + number_text(span) + " radians: pbrt-v4 reads only anisotropic tables "
                             "over the whole circle (a reduction of 1)");
    }
    b->ndf_w = (int)ndf.shape[1], b->ndf_h = (int)ndf.shape[0];
    b->sigma_w = (int)sigma.shape[1], b->sigma_h = (int)sigma.shape[0];
    b->vndf_w = (int)vndf.shape[3], b->vndf_h = (int)vndf.shape[2];
    b->w = (int)luminance.shape[3], b->h = (int)luminance.shape[2];
    b->ndf = floats(ndf, "ndf", path, 0);
    b->sigma = floats(sigma, "sigma", path, 0, true);
    b->vndf = floats(vndf, "vndf", path, 0);
    b->luminance = floats(luminance, "luminance", path, 0);
    b->spectra = floats(spectra, "spectra", path);
    slices_nonzero(b->vndf, P * T, "vndf", path);
    slices_nonzero(b->luminance, P * T, "luminance", path);
    const std::vector<Vec3> weight = wavelength_rgb(b->wavelengths);
    const size_t n = (size_t)b->w * b->h;
    for (int ch = 0; ch < 3; ++ch) b->rgb[ch].assign(P * T * n, 0.0f);
    std::vector<double> sum(n);
    for (size_t s = 0; s < P * T; ++s)
        for (int ch = 0; ch < 3; ++ch) {
            std::fill(sum.begin(), sum.end(), 0.0);
            for (size_t l = 0; l < L; ++l) {
                const float *v = &b->spectra[(s * L + l) * n];
                const double wl = weight[l][ch];
                for (size_t i = 0; i < n; ++i) sum[i] += wl * std::max(0.0f, v[i]);
            }
            for (size_t i = 0; i < n; ++i) b->rgb[ch][s * n + i] = (float)sum[i];
        }
    return b;
}

}  // namespace udm1scene
