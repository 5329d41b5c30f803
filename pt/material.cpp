// material.cpp - see material.h.
#include "material.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>

namespace udm1pt {

using udm1scene::SceneError;

namespace {

Vec3 rgb_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    Vec3 v;
    if (!ps.get_rgb(name, &v)) throw SceneError(p->where + ": '" + name + "' must be \"rgb " + name + "\" [r g b]");
    if (v.x < 0 || v.y < 0 || v.z < 0) throw SceneError(p->where + ": '" + name + "' must not be negative");
    return v;
}

void only(const udm1scene::ParamSet &ps, std::initializer_list<const char *> allowed, const std::string &what)
{
    for (const udm1scene::Param &p : ps.params) {
        bool ok = p.name == "type";  // MakeNamedMaterial's own parameter
        for (const char *a : allowed) ok |= p.name == a;
        if (!ok) throw SceneError(p.where + ": " + what + ": unsupported parameter '" + p.name + "'");
    }
}

// RGB stand-ins for pbrt-v4's named spectra (pbrt works spectrally; udm1-pt in RGB): the refractive
// index n + i k of metals at about 650, 550 and 450 nm (the RGB table of Hindefjord, from the same
// measured data pbrt-v4 ships), and the index of glasses at 550 nm.
struct NamedSpectrum {
    const char *name;
    Vec3 value;
};
const NamedSpectrum NAMED_SPECTRA[] = {
    {"metal-Au-eta", Vec3(0.18299, 0.42108, 1.3734)}, {"metal-Au-k", Vec3(3.4242, 2.3459, 1.7704)},
    {"metal-Ag-eta", Vec3(0.15943, 0.14512, 0.13547)}, {"metal-Ag-k", Vec3(3.9291, 3.19, 2.3808)},
    {"metal-Cu-eta", Vec3(0.27105, 0.67693, 1.3164)}, {"metal-Cu-k", Vec3(3.6092, 2.6248, 2.2921)},
    {"metal-Al-eta", Vec3(1.3456, 0.96521, 0.61722)}, {"metal-Al-k", Vec3(7.4746, 6.3995, 5.3031)},
    {"glass-BK7", Vec3(1.5185, 1.5185, 1.5185)}, {"glass-BAF10", Vec3(1.6700, 1.6700, 1.6700)},
    {"glass-F11", Vec3(1.6200, 1.6200, 1.6200)},
};

// A "spectrum" or "rgb" or "float" parameter as RGB: a named spectrum, (lambda, value) pairs
// (piecewise linear, taken at 650/550/450 nm), an rgb triple or one number.
Vec3 spectrum_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    if (p->type == "float" && p->numbers.size() == 1) return Vec3(p->numbers[0], p->numbers[0], p->numbers[0]);
    if (p->type == "rgb" && p->numbers.size() == 3) return Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
    if (p->type == "spectrum" && p->strings.size() == 1) {
        for (const NamedSpectrum &n : NAMED_SPECTRA)
            if (p->strings[0] == n.name) return n.value;
        throw SceneError(p->where + ": '" + name + "': the named spectrum \"" + p->strings[0] + "\" is not known");
    }
    if (p->type == "spectrum" && p->numbers.size() >= 2 && p->numbers.size() % 2 == 0) {
        auto at = [&](double lambda) {
            const std::vector<double> &v = p->numbers;
            if (lambda <= v[0]) return v[1];
            for (size_t i = 2; i < v.size(); i += 2)
                if (lambda <= v[i]) return v[i - 1] + (v[i + 1] - v[i - 1]) * (lambda - v[i - 2]) / (v[i] - v[i - 2]);
            return v[v.size() - 1];
        };
        for (size_t i = 2; i < p->numbers.size(); i += 2)
            if (!(p->numbers[i] > p->numbers[i - 2]))
                throw SceneError(p->where + ": '" + name + "': wavelengths must increase");
        return Vec3(at(650), at(550), at(450));
    }
    throw SceneError(p->where + ": '" + name + "' must be a float, an rgb triple, a named spectrum or (lambda, value) pairs");
}

// pbrt-v4's roughness parameters: roughness or uroughness/vroughness, remapped unless remaproughness false.
udm1pt::Microfacets roughness_param(const udm1scene::ParamSet &ps, const std::string &what)
{
    double r = ps.get_float("roughness", 0.0);
    double ur = ps.get_float("uroughness", r), vr = ps.get_float("vroughness", r);
    if (!(ur >= 0 && vr >= 0)) throw SceneError(ps.where + ": " + what + ": roughness must not be negative");
    if (ps.get_bool("remaproughness", true)) ur = std::sqrt(ur), vr = std::sqrt(vr);  // pbrt's RoughnessToAlpha
    udm1pt::Microfacets mf;
    mf.ax = ur, mf.ay = vr;
    return mf;
}

inline bool nonzero(Vec3 v) { return v.x != 0 || v.y != 0 || v.z != 0; }

// A "texture NAME" parameter: the texture's index (checking its kind), -1 if the parameter is absent
// or is not a texture reference.
int texture_param(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &name,
                  const char *kind)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p || p->type != "texture") return -1;
    if (p->strings.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one texture name");
    for (size_t i = 0; i < scene.textures.size(); ++i)
        if (scene.textures[i].name == p->strings[0]) {
            if (scene.textures[i].kind != kind)
                throw SceneError(p->where + ": '" + name + "' needs a " + kind + " texture, \"" + p->strings[0] +
                                 "\" is a " + scene.textures[i].kind + " texture");
            return (int)i;
        }
    throw SceneError(p->where + ": '" + name + "': texture \"" + p->strings[0] + "\" was not made");
}

uint64_t mix_bits(uint64_t z)
{
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

// A uniform number in [0, 1) from a point and a direction (pbrt-v4's MixMaterial hashes the same).
double hash_unit(Vec3 p, Vec3 w)
{
    uint64_t h = 0x4D495846u;
    for (double x : {p.x, p.y, p.z, w.x, w.y, w.z}) {
        uint64_t b;
        std::memcpy(&b, &x, sizeof b);
        h = mix_bits(h ^ b);
    }
    return (double)(h >> 11) * 0x1.0p-53;
}

}  // namespace

Bsdf default_material()
{
    Bsdf b;
    b.kind = Bsdf::Diffuse;
    b.diffuse.R = Vec3(0.5, 0.5, 0.5);
    return b;
}

Materials::Materials(const udm1scene::Scene &scene) : textures_(scene)
{
    for (const udm1scene::Material &m : scene.materials) {
        MaterialModel mm;
        Bsdf &b = mm.base;
        const udm1scene::ParamSet &ps = m.params;
        mm.remap = ps.get_bool("remaproughness", true);
        auto roughness = [&](Microfacets *mf, const char *what) {
            mm.roughness_tex = texture_param(scene, ps, "roughness", "float");
            if (mm.roughness_tex < 0) *mf = roughness_param(ps, what);
        };
        if (m.type == "diffuse") {
            only(ps, {"reflectance", "displacement"}, "diffuse");
            b.kind = Bsdf::Diffuse;
            mm.reflectance_tex = texture_param(scene, ps, "reflectance", "spectrum");
            if (mm.reflectance_tex < 0) b.diffuse.R = rgb_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
        } else if (m.type == "coateddiffuse") {
            only(ps, {"reflectance", "roughness", "uroughness", "vroughness", "remaproughness", "thickness", "eta",
                      "maxdepth", "nsamples", "albedo", "g", "displacement"},
                 "coateddiffuse");
            b.kind = Bsdf::CoatedDiffuse;
            Coated &c = b.coated;
            mm.reflectance_tex = texture_param(scene, ps, "reflectance", "spectrum");
            if (mm.reflectance_tex < 0) c.bottom.R = rgb_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
            roughness(&c.top.mf, "coateddiffuse");
            c.top.eta = ps.get_float("eta", 1.5);
            c.thickness = std::max(ps.get_float("thickness", 0.01), 1e-300);
            c.max_depth = ps.get_int("maxdepth", 10);
            c.samples = ps.get_int("nsamples", 1);
            if (!(c.top.eta > 0)) throw SceneError(ps.where + ": coateddiffuse: eta must be positive");
            if (c.max_depth < 1 || c.max_depth > 100 || c.samples < 1 || c.samples > 100)
                throw SceneError(ps.where + ": coateddiffuse: maxdepth and nsamples must be in 1..100");
            Vec3 albedo = rgb_param(ps, "albedo", Vec3());
            if (nonzero(albedo))
                throw SceneError(ps.where + ": coateddiffuse: a scattering medium between the layers (albedo > 0) "
                                            "is not supported");
        } else if (m.type == "conductor") {
            only(ps, {"eta", "k", "roughness", "uroughness", "vroughness", "remaproughness", "displacement"}, "conductor");
            b.kind = Bsdf::ConductorKind;
            b.conductor.eta = spectrum_param(ps, "eta", Vec3(0.27105, 0.67693, 1.3164));  // pbrt's default: copper
            b.conductor.k = spectrum_param(ps, "k", Vec3(3.6092, 2.6248, 2.2921));
            roughness(&b.conductor.mf, "conductor");
            if (!(b.conductor.eta.x > 0 && b.conductor.eta.y > 0 && b.conductor.eta.z > 0) ||
                !(b.conductor.k.x >= 0 && b.conductor.k.y >= 0 && b.conductor.k.z >= 0))
                throw SceneError(ps.where + ": conductor: eta must be positive and k not negative");
        } else if (m.type == "dielectric") {
            only(ps, {"eta", "roughness", "uroughness", "vroughness", "remaproughness", "displacement"}, "dielectric");
            b.kind = Bsdf::DielectricKind;
            Vec3 eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5));
            b.dielectric.eta = eta.y;  // one index for all channels (no dispersion): green's, 550 nm
            roughness(&b.dielectric.mf, "dielectric");
            if (!(b.dielectric.eta > 0)) throw SceneError(ps.where + ": dielectric: eta must be positive");
        } else if (m.type == "mix") {
            only(ps, {"materials", "amount"}, "mix");
            const udm1scene::Param *mp = ps.find("materials");
            if (!mp || mp->type != "string" || mp->strings.size() != 2)
                throw SceneError(ps.where + ": mix needs \"string materials\" [ \"a\" \"b\" ]");
            mm.mix = true;
            for (int k = 0; k < 2; ++k) {
                for (size_t i = 0; i < scene.materials.size(); ++i)
                    if (scene.materials[i].name == mp->strings[k]) mm.parts[k] = (int)i;
                if (mm.parts[k] < 0) throw SceneError(mp->where + ": mix: material \"" + mp->strings[k] + "\" was not made");
            }
            mm.amount_tex = texture_param(scene, ps, "amount", "float");
            if (mm.amount_tex < 0) mm.amount = ps.get_float("amount", 0.5);
        } else {
            throw SceneError(ps.where + ": Material \"" + m.type +
                             "\" is not supported (diffuse, coateddiffuse, conductor, dielectric, mix)");
        }
        if (!mm.mix) {
            mm.displacement_tex = texture_param(scene, ps, "displacement", "float");
            if (ps.find("displacement") && mm.displacement_tex < 0)
                throw SceneError(ps.find("displacement")->where + ": 'displacement' must be \"texture displacement\"");
        }
        models_.push_back(mm);
    }
    // a mix must not contain itself
    std::function<void(int, int)> walk = [&](int i, int depth) {
        if (depth > 32)
            throw SceneError(scene.materials[i].params.where + ": mix: the materials contain each other");
        if (models_[i].mix) walk(models_[i].parts[0], depth + 1), walk(models_[i].parts[1], depth + 1);
    };
    for (size_t i = 0; i < models_.size(); ++i) walk((int)i, 0);
}

namespace {
// dp/du and dp/dv of a triangle from its uv (pbrt-v4's Triangle), or a frame around n when the uv
// are degenerate; spheres: from the longitude/colatitude parametrization of hit_uv.
void surface_derivatives(const udm1scene::Shape &s, const udm1scene::Hit &h, Vec3 n, Vec3 *dpdu, Vec3 *dpdv)
{
    const double PI = 3.14159265358979323846;
    if (s.kind == udm1scene::Shape::Sphere) {
        Vec3 d = h.p - s.center;
        double phi_max = 2 * PI, r = s.radius, rho = std::sqrt(d.x * d.x + d.y * d.y);
        *dpdu = Vec3(-phi_max * d.y, phi_max * d.x, 0);
        double cos_phi = rho > 0 ? d.x / rho : 1, sin_phi = rho > 0 ? d.y / rho : 0, theta = std::acos(std::clamp(d.z / r, -1.0, 1.0));
        *dpdv = Vec3(d.z * cos_phi, d.z * sin_phi, -r * std::sin(theta)) * (-PI);  // v = 1 - theta / pi
        return;
    }
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    auto P = [&](uint32_t k) { return Vec3(s.P[3 * k], s.P[3 * k + 1], s.P[3 * k + 2]); };
    double uv[3][2] = {{0, 0}, {1, 0}, {1, 1}};
    if (!s.UV.empty())
        for (int k = 0; k < 3; ++k) uv[k][0] = s.UV[2 * i[k]], uv[k][1] = s.UV[2 * i[k] + 1];
    double du02 = uv[0][0] - uv[2][0], dv02 = uv[0][1] - uv[2][1], du12 = uv[1][0] - uv[2][0], dv12 = uv[1][1] - uv[2][1];
    Vec3 dp02 = P(i[0]) - P(i[2]), dp12 = P(i[1]) - P(i[2]);
    double det = du02 * dv12 - dv02 * du12;
    bool ok = std::fabs(det) >= 1e-12;
    if (ok) {
        *dpdu = (dp02 * dv12 - dp12 * dv02) * (1 / det);
        *dpdv = (dp12 * du02 - dp02 * du12) * (1 / det);
        ok = udm1scene::dot(udm1scene::cross(*dpdu, *dpdv), udm1scene::cross(*dpdu, *dpdv)) > 0;
    }
    if (!ok) {
        udm1scene::Frame f(n);
        *dpdu = f.t, *dpdv = f.b;
    }
}
}  // namespace

const Bsdf &Materials::at(int material, const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 wo, Vec3 *ns,
                          Bsdf *scratch) const
{
    double u = 0, v = 0;  // texture coordinates, computed only if a texture is read
    bool have_uv = false;
    auto need_uv = [&] {
        if (!have_uv) hit_uv(shape, h, &u, &v), have_uv = true;
    };
    const MaterialModel *m = &models_[material];
    while (m->mix) {
        double amount = m->amount;
        if (m->amount_tex >= 0) need_uv(), amount = textures_.value(m->amount_tex, u, v);
        int next = amount <= 0 ? m->parts[0] : amount >= 1 ? m->parts[1]
                                                          : (hash_unit(h.p, wo) < amount ? m->parts[1] : m->parts[0]);
        m = &models_[next];
    }
    if (m->reflectance_tex < 0 && m->roughness_tex < 0 && m->displacement_tex < 0) return m->base;
    need_uv();
    Bsdf &b = *scratch;
    b = m->base;
    if (m->reflectance_tex >= 0) {
        Vec3 r = textures_.rgb(m->reflectance_tex, u, v);
        (b.kind == Bsdf::Diffuse ? b.diffuse.R : b.coated.bottom.R) = r;
    }
    if (m->roughness_tex >= 0) {
        double r = std::max(0.0, textures_.value(m->roughness_tex, u, v));
        double a = m->remap ? std::sqrt(r) : r;
        Microfacets &mf = b.kind == Bsdf::ConductorKind ? b.conductor.mf
                          : b.kind == Bsdf::DielectricKind ? b.dielectric.mf
                                                           : b.coated.top.mf;
        mf.ax = mf.ay = a;
    }
    if (m->displacement_tex >= 0) {  // pbrt-v4's BumpMap
        Vec3 n = *ns, dpdu, dpdv;
        surface_derivatives(shape, h, n, &dpdu, &dpdv);
        if (!shape.N.empty()) {  // shading geometry as pbrt-v4 sets it with vertex normals
            Vec3 ts = udm1scene::cross(n, dpdu);
            if (udm1scene::dot(ts, ts) > 0) dpdu = udm1scene::cross(ts, n), dpdv = ts;
        }
        const double du = 0.0005, dv = 0.0005;
        double d = textures_.value(m->displacement_tex, u, v);
        double d_u = textures_.value(m->displacement_tex, u + du, v), d_v = textures_.value(m->displacement_tex, u, v + dv);
        Vec3 bu = dpdu + n * ((d_u - d) / du), bv = dpdv + n * ((d_v - d) / dv);
        Vec3 bn = udm1scene::cross(bu, bv);
        double len = udm1scene::length(bn);
        if (len > 0 && std::isfinite(len)) {
            bn = bn * (1 / len);
            *ns = udm1scene::dot(bn, n) < 0 ? -bn : bn;
        }
    }
    return b;
}

void hit_uv(const udm1scene::Shape &s, const udm1scene::Hit &h, double *u, double *v)
{
    if (s.kind == udm1scene::Shape::Sphere) {
        Vec3 d = (h.p - s.center) * (1 / s.radius);
        double phi = std::atan2(d.y, d.x);
        if (phi < 0) phi += 2 * 3.14159265358979323846;
        *u = phi / (2 * 3.14159265358979323846);
        *v = 1 - std::acos(std::clamp(d.z, -1.0, 1.0)) / 3.14159265358979323846;
        return;
    }
    double b0 = 1 - h.u - h.v;
    if (s.UV.empty()) {  // pbrt-v4: (0,0), (1,0), (1,1)
        *u = h.u + h.v, *v = h.v;
        return;
    }
    const uint32_t *i = &s.indices[3 * (size_t)h.prim];
    *u = b0 * s.UV[2 * i[0]] + h.u * s.UV[2 * i[1]] + h.v * s.UV[2 * i[2]];
    *v = b0 * s.UV[2 * i[0] + 1] + h.u * s.UV[2 * i[1] + 1] + h.v * s.UV[2 * i[2] + 1];
}

}  // namespace udm1pt
