// material.cpp - see material.h.
#include "material.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <set>

#include "spectrum.h"
#include "surface.h"

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

// A "spectrum" parameter as a spectrum: (wavelength, value) pairs (the parser has read spectrum files
// into pairs) or one of the named spectra udm1 knows.
udm1scene::Spectrum spectrum_of(const udm1scene::Param &p)
{
    if (p.strings.size() == 1) {
        if (const udm1scene::Spectrum *s = udm1scene::named_spectrum(p.strings[0])) return *s;
        throw SceneError(p.where + ": '" + p.name + "': the named spectrum \"" + p.strings[0] +
                         "\" is not known (udm1 knows " + udm1scene::known_spectra() + ")");
    }
    return udm1scene::spectrum_from_pairs(p.numbers, p.where);
}

// An albedo (a reflectance of at most 1): "rgb" (refused with a component above 1, as pbrt-v4 refuses it)
// or "spectrum" (its RGB under D65, udm1scene::albedo_rgb).
Vec3 albedo_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    if (p->type == "spectrum") return udm1scene::albedo_rgb(spectrum_of(*p));
    Vec3 v = rgb_param(ps, name, fallback);
    if (v.x > 1 || v.y > 1 || v.z > 1)
        throw SceneError(p->where + ": RGB parameter '" + name + "' is an albedo and has a component above 1 (" +
                         udm1scene::number_text(v.x) + " " + udm1scene::number_text(v.y) + " " +
                         udm1scene::number_text(v.z) + "), which pbrt-v4 refuses too");
    return v;
}

// Every parameter a material of the subset takes (an Attribute "material" default that a material does not
// take is ignored if another takes it, as pbrt-v4 ignores it; else refused: pbrt-v4 might read it there).
const std::set<std::string> &material_parameters()
{
    static const std::set<std::string> all = {"reflectance", "displacement", "roughness", "uroughness", "vroughness",
                                              "remaproughness", "thickness", "eta", "maxdepth", "nsamples", "albedo",
                                              "g", "k", "materials", "amount"};
    return all;
}

void only(const udm1scene::ParamSet &ps, std::initializer_list<const char *> allowed, const std::string &what)
{
    for (const udm1scene::Param &p : ps.params) {
        bool ok = p.name == "type";  // MakeNamedMaterial's own parameter
        for (const char *a : allowed) ok |= p.name == a;
        if (ok || (p.attribute && material_parameters().count(p.name))) continue;
        if (p.attribute) throw SceneError(p.where + ": Attribute: parameter '" + p.name + "' is not modelled (" + what + ")");
        throw SceneError(p.where + ": " + what + ": unsupported parameter '" + p.name + "'");
    }
}

// A parameter that is a float, an rgb triple or a spectrum, as RGB: a spectrum's values at about 650,
// 550 and 450 nm (a conductor given partly as rgb, a dielectric's index: its green value).
Vec3 spectrum_param(const udm1scene::ParamSet &ps, const std::string &name, Vec3 fallback)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return fallback;
    if (p->type == "float" && p->numbers.size() == 1) return Vec3(p->numbers[0], p->numbers[0], p->numbers[0]);
    if (p->type == "rgb" && p->numbers.size() == 3) return Vec3(p->numbers[0], p->numbers[1], p->numbers[2]);
    if (p->type == "spectrum") {
        udm1scene::Spectrum s = spectrum_of(*p);
        return Vec3(s.at(650), s.at(550), s.at(450));
    }
    throw SceneError(p->where + ": '" + name + "' must be a float, an rgb triple, a named spectrum or (lambda, value) pairs");
}

// pbrt-v4's wavelengths of one camera sample (SampledWavelengths::SampleVisible): four, a quarter apart in its
// distribution of visible wavelengths (pdf proportional to 1 / cosh^2(0.0072 (lambda - 538)) over 360..830 nm).
// The others of the four that come with `lambda`.
void companions(double lambda, double out[3])
{
    double u = (0.85691062 - std::tanh((538 - lambda) / 138.888889)) / 1.82750197;  // (its place in the distribution)
    for (int i = 1; i < 4; ++i) {
        double up = u + i / 4.0;
        if (up > 1) up -= 1;
        out[i - 1] = 538 - 138.888889 * std::atanh(0.85691062 - 1.82750197 * up);
    }
}

// The Fresnel table of a spectral conductor of index eta + i k (each divided by `relative`: a coated
// conductor's index is relative to its coat's): its reflectance at each wavelength, projected on RGB as
// pbrt-v4's film records it under D65 (udm1scene::albedo_rgb), at 65 incident angles. pbrt-v4 takes a
// spectrum given as pairs or read from a file as 0 outside its wavelengths (PiecewiseLinearSpectrum); where
// both eta and k are 0 its Fresnel term is not a number, and pbrt-v4 zeroes the radiance of every camera sample
// one of whose four wavelengths falls there: the table keeps a wavelength's reflectance only where it and its
// three companions (above) have an index, which is the conductor's reflection as pbrt-v4 renders it (the light a
// zeroed sample gathered at its other vertices is not modelled). Negative values are refused.
std::unique_ptr<FresnelTable> fresnel_table(const udm1scene::Spectrum &eta, const udm1scene::Spectrum &k,
                                            const std::string &where, double relative = 1)
{
    double n[udm1scene::WAVELENGTHS], kk[udm1scene::WAVELENGTHS], r[udm1scene::WAVELENGTHS];
    double kept[udm1scene::WAVELENGTHS];  // the part of the nanometre around each wavelength that is kept
    auto defined = [&](double lambda) { return eta.at(lambda) != 0 || k.at(lambda) != 0; };
    for (int l = 0; l < udm1scene::WAVELENGTHS; ++l) {
        n[l] = eta.at(360 + l) / relative, kk[l] = k.at(360 + l) / relative;
        if (!(n[l] >= 0) || !(kk[l] >= 0))
            throw SceneError(where + ": conductor: eta and k must not be negative (at " + std::to_string(360 + l) + " nm)");
        constexpr int SUB = 32;  // (the kept bands can be a few nanometres wide: their edges to 1/32 nm)
        int in = 0;
        for (int j = 0; j < SUB; ++j) {
            double lambda = 360 + l + (j + 0.5) / SUB - 0.5, others[3];
            companions(lambda, others);
            in += defined(lambda) && defined(others[0]) && defined(others[1]) && defined(others[2]);
        }
        kept[l] = (double)in / SUB;
    }
    auto t = std::make_unique<FresnelTable>();
    for (int i = 0; i < FresnelTable::N; ++i) {
        double c = (double)i / (FresnelTable::N - 1);
        for (int l = 0; l < udm1scene::WAVELENGTHS; ++l) r[l] = kept[l] > 0 ? kept[l] * fresnel_complex(c, n[l], kk[l]) : 0;
        Vec3 rgb = udm1scene::albedo_rgb(r);
        for (int ch = 0; ch < 3; ++ch) t->r[ch][i] = (float)rgb[ch];
    }
    return t;
}

// pbrt-v4's conductor "reflectance" r as a complex index: eta 1, k = 2 sqrt(r) / sqrt(1 - r), r clamped
// to [0, 0.9999].
inline double reflectance_k(double r)
{
    r = std::clamp(r, 0.0, 0.9999);
    return 2 * std::sqrt(r) / std::sqrt(1 - r);
}

inline bool nonzero(Vec3 v) { return v.x != 0 || v.y != 0 || v.z != 0; }

// A "texture NAME" parameter: the texture's index (the last texture of that name and kind), -1 if the
// parameter is absent or is not a texture reference.
int texture_param(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &name,
                  const char *kind)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p || p->type != "texture") return -1;
    if (p->strings.size() != 1) throw SceneError(p->where + ": '" + name + "' needs one texture name");
    int other = -1;  // (float and spectrum textures have names of their own, as in pbrt-v4)
    for (size_t i = 0; i < scene.textures.size(); ++i)
        if (scene.textures[i].name == p->strings[0]) {
            if (scene.textures[i].kind == kind) return (int)i;
            other = (int)i;
        }
    if (other >= 0)
        throw SceneError(p->where + ": '" + name + "' needs a " + kind + " texture, \"" + p->strings[0] + "\" is a " +
                         scene.textures[other].kind + " texture");
    throw SceneError(p->where + ": '" + name + "': texture \"" + p->strings[0] + "\" was not made");
}

// A float parameter that pbrt-v4 reads as a float texture: a texture (*tex its index) or a constant.
double float_param(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &name,
                   double fallback, int *tex)
{
    *tex = texture_param(scene, ps, name, "float");
    return *tex >= 0 ? fallback : ps.get_float(name, fallback);
}

// An albedo that pbrt-v4 reads as a spectrum texture: a texture (*tex) or a constant (albedo_param).
Vec3 albedo_texture_param(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &name,
                          Vec3 fallback, int *tex)
{
    *tex = texture_param(scene, ps, name, "spectrum");
    return *tex >= 0 ? fallback : albedo_param(ps, name, fallback);
}

// pbrt-v4's roughness parameters with a prefix ("", "interface.", "conductor."): P + "uroughness" and P +
// "vroughness", each P + "roughness" where absent, each a constant or a float texture (bound to the two
// slots), remapped unless remaproughness is false.
void roughness_params(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &prefix,
                      MaterialModel *mm, Microfacets *mf, MaterialModel::Slot uslot, MaterialModel::Slot vslot,
                      const std::string &what)
{
    int rt, ut, vt;
    double r = float_param(scene, ps, prefix + "roughness", 0.0, &rt);
    double ur = ps.find(prefix + "uroughness") ? float_param(scene, ps, prefix + "uroughness", 0.0, &ut) : (ut = rt, r);
    double vr = ps.find(prefix + "vroughness") ? float_param(scene, ps, prefix + "vroughness", 0.0, &vt) : (vt = rt, r);
    if (!(ur >= 0 && vr >= 0)) throw SceneError(ps.where + ": " + what + ": roughness must not be negative");
    if (mm->remap) ur = std::sqrt(ur), vr = std::sqrt(vr);  // pbrt's RoughnessToAlpha
    mf->ax = ur, mf->ay = vr;
    if (ut >= 0) mm->bindings.push_back({uslot, ut});
    if (vt >= 0) mm->bindings.push_back({vslot, vt});
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

// A conductor's index (eta, k: spectra, rgb triples, or "reflectance"), relative to `relative` (a coat's
// index), into *c: per channel, or its spectral Fresnel table (kept in *tables). Prefix "conductor." for
// a coated conductor's base. A textured reflectance is bound to its slot.
void conductor_index(const udm1scene::Scene &scene, const udm1scene::ParamSet &ps, const std::string &prefix,
                     double relative, const std::string &what, MaterialModel *mm, Conductor *c,
                     std::vector<std::unique_ptr<FresnelTable>> *tables)
{
    const udm1scene::Param *pe = ps.find(prefix + "eta"), *pk = ps.find(prefix + "k"), *pr = ps.find("reflectance");
    for (const udm1scene::Param *p : {pe, pk})
        if (p && p->type == "texture")
            throw SceneError(p->where + ": " + what + ": a textured '" + p->name + "' is not supported (a spectrum or rgb)");
    if (pr) {
        if (pe || pk)
            throw SceneError(pr->where + ": " + what + ": both \"reflectance\" and \"eta\" and \"k\" given (pbrt-v4 "
                                         "refuses that too)");
        int tex = texture_param(scene, ps, "reflectance", "spectrum");
        if (tex >= 0) {
            mm->bindings.push_back({MaterialModel::Slot::ConductorReflectance, tex});
            c->eta = Vec3(1, 1, 1) * (1 / relative), c->k = Vec3(0, 0, 0);
            return;
        }
        if (pr->type == "spectrum") {  // per wavelength, as pbrt-v4 computes it
            udm1scene::Spectrum r = spectrum_of(*pr), eta = udm1scene::Spectrum::constant(1), k;
            for (int l = 0; l < udm1scene::WAVELENGTHS; ++l)
                k.nm.push_back(360 + l), k.value.push_back(reflectance_k(r.at(360 + l)));
            tables->push_back(fresnel_table(eta, k, ps.where, relative));
            c->table = tables->back().get();
            return;
        }
        Vec3 r = albedo_param(ps, "reflectance", Vec3());
        c->eta = Vec3(1, 1, 1) * (1 / relative);
        c->k = Vec3(reflectance_k(r.x), reflectance_k(r.y), reflectance_k(r.z)) * (1 / relative);
        return;
    }
    if ((pe && pe->type == "rgb") || (pk && pk->type == "rgb")) {  // per channel (pbrt upsamples the rgb)
        c->eta = spectrum_param(ps, prefix + "eta", Vec3()) * (1 / relative);
        c->k = spectrum_param(ps, prefix + "k", Vec3()) * (1 / relative);
        if (!pe || !pk) throw SceneError(ps.where + ": " + what + ": an rgb eta or k needs the other one too");
        if (!(c->eta.x > 0 && c->eta.y > 0 && c->eta.z > 0) || !(c->k.x >= 0 && c->k.y >= 0 && c->k.z >= 0))
            throw SceneError(ps.where + ": " + what + ": eta must be positive and k not negative");
        return;
    }
    // spectral (pbrt's default: copper): its Fresnel reflectance as pbrt-v4 records it
    auto index = [&](const std::string &name, const std::string &cu) {
        const udm1scene::Param *p = ps.find(name);
        if (!p) return *udm1scene::named_spectrum(cu);
        if (p->type == "float" && p->numbers.size() == 1) return udm1scene::Spectrum::constant(p->numbers[0]);
        if (p->type == "spectrum") return spectrum_of(*p);
        throw SceneError(p->where + ": '" + name + "' must be a float, an rgb triple, a named spectrum or (lambda, value) pairs");
    };
    tables->push_back(fresnel_table(index(prefix + "eta", "metal-Cu-eta"), index(prefix + "k", "metal-Cu-k"), ps.where, relative));
    c->table = tables->back().get();
}

}  // namespace

udm1scene::Frame oriented_frame(const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 ns)
{
    udm1scene::Frame f(ns);
    Vec3 dpdu, dpdv;
    udm1scene::surface_derivatives(shape, h, ns, &dpdu, &dpdv);
    Vec3 x = dpdu - ns * udm1scene::dot(dpdu, ns);
    double len = udm1scene::length(x);
    if (!(len > 0) || !std::isfinite(len)) return f;  // (pbrt-v4 then takes CoordinateSystem(ns), which f is)
    f.t = x * (1 / len), f.b = udm1scene::cross(ns, f.t);
    return f;
}

Bsdf default_material()
{
    Bsdf b;
    b.kind = Bsdf::Diffuse;
    b.diffuse.R = Vec3(0.5, 0.5, 0.5);
    return b;
}

Materials::Materials(const udm1scene::Scene &scene) : textures_(scene)
{
    using Slot = MaterialModel::Slot;
    for (const udm1scene::Material &m : scene.materials) {
        MaterialModel mm;
        Bsdf &b = mm.base;
        const udm1scene::ParamSet &ps = m.params;
        mm.remap = ps.get_bool("remaproughness", true);
        // the layers' medium and walk (coateddiffuse, coatedconductor)
        auto layers = [&](Coated &c, const std::string &what) {
            int tex;
            c.thickness = std::max(float_param(scene, ps, "thickness", 0.01, &tex), 1e-300);
            if (tex >= 0) mm.bindings.push_back({Slot::Thickness, tex});
            c.g = std::clamp(float_param(scene, ps, "g", 0.0, &tex), -1.0, 1.0);
            if (tex >= 0) mm.bindings.push_back({Slot::G, tex});
            c.albedo = albedo_texture_param(scene, ps, "albedo", Vec3(), &tex);
            if (tex >= 0) mm.bindings.push_back({Slot::Albedo, tex});
            c.max_depth = ps.get_int("maxdepth", 10);
            c.samples = ps.get_int("nsamples", 1);
            if (c.max_depth < 1 || c.max_depth > 100 || c.samples < 1 || c.samples > 100)
                throw SceneError(ps.where + ": " + what + ": maxdepth and nsamples must be in 1..100");
        };
        if (m.type == "interface" || m.type.empty() || m.type == "none") {  // pbrt-v4: no BSDF (media.h)
            only(ps, {}, "Material \"" + m.type + "\"");
            mm.interface = true;
            models_.push_back(mm);
            continue;
        }
        if (m.type == "diffuse") {
            only(ps, {"reflectance", "displacement", "normalmap"}, "diffuse");
            b.kind = Bsdf::Diffuse;
            int tex;
            b.diffuse.R = albedo_texture_param(scene, ps, "reflectance", Vec3(0.5, 0.5, 0.5), &tex);
            if (tex >= 0) mm.bindings.push_back({Slot::Reflectance, tex});
        } else if (m.type == "coateddiffuse") {
            only(ps, {"reflectance", "roughness", "uroughness", "vroughness", "remaproughness", "thickness", "eta",
                      "maxdepth", "nsamples", "albedo", "g", "displacement", "normalmap"},
                 "coateddiffuse");
            b.kind = Bsdf::CoatedDiffuse;
            Coated &c = b.coated;
            int tex;
            c.bottom.R = albedo_texture_param(scene, ps, "reflectance", Vec3(0.5, 0.5, 0.5), &tex);
            if (tex >= 0) mm.bindings.push_back({Slot::Reflectance, tex});
            roughness_params(scene, ps, "", &mm, &c.top.mf, Slot::URoughness, Slot::VRoughness, "coateddiffuse");
            c.top.eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5)).y;  // (one index: 550 nm's)
            if (c.top.eta == 0) c.top.eta = 1;                                // (pbrt-v4 takes 0 as 1)
            if (!(c.top.eta > 0)) throw SceneError(ps.where + ": coateddiffuse: eta must be positive");
            layers(c, "coateddiffuse");
        } else if (m.type == "coatedconductor") {
            only(ps, {"interface.roughness", "interface.uroughness", "interface.vroughness", "interface.eta", "thickness",
                      "conductor.eta", "conductor.k", "reflectance", "conductor.roughness", "conductor.uroughness",
                      "conductor.vroughness", "remaproughness", "maxdepth", "nsamples", "albedo", "g", "displacement",
                      "normalmap"},
                 "coatedconductor");
            b.kind = Bsdf::CoatedConductor;
            Coated &c = b.coated;
            c.metal_base = true;
            roughness_params(scene, ps, "interface.", &mm, &c.top.mf, Slot::URoughness, Slot::VRoughness, "coatedconductor");
            roughness_params(scene, ps, "conductor.", &mm, &c.metal.mf, Slot::ConductorURoughness,
                             Slot::ConductorVRoughness, "coatedconductor");
            c.top.eta = spectrum_param(ps, "interface.eta", Vec3(1.5, 1.5, 1.5)).y;  // (one index: 550 nm's)
            if (c.top.eta == 0) c.top.eta = 1;                                          // (pbrt-v4 takes 0 as 1)
            if (!(c.top.eta > 0)) throw SceneError(ps.where + ": coatedconductor: interface.eta must be positive");
            mm.interface_eta = c.top.eta;
            conductor_index(scene, ps, "conductor.", c.top.eta, "coatedconductor", &mm, &c.metal, &tables_);
            layers(c, "coatedconductor");
        } else if (m.type == "conductor") {
            only(ps, {"eta", "k", "reflectance", "roughness", "uroughness", "vroughness", "remaproughness", "displacement",
                      "normalmap"},
                 "conductor");
            b.kind = Bsdf::ConductorKind;
            roughness_params(scene, ps, "", &mm, &b.conductor.mf, Slot::URoughness, Slot::VRoughness, "conductor");
            conductor_index(scene, ps, "", 1, "conductor", &mm, &b.conductor, &tables_);
        } else if (m.type == "dielectric") {
            only(ps, {"eta", "roughness", "uroughness", "vroughness", "remaproughness", "displacement", "normalmap"},
                 "dielectric");
            b.kind = Bsdf::DielectricKind;
            Vec3 eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5));
            b.dielectric.eta = eta.y;  // one index for all channels (no dispersion): 550 nm's
            roughness_params(scene, ps, "", &mm, &b.dielectric.mf, Slot::URoughness, Slot::VRoughness, "dielectric");
            if (!(b.dielectric.eta > 0)) throw SceneError(ps.where + ": dielectric: eta must be positive");
        } else if (m.type == "thindielectric") {
            only(ps, {"eta", "displacement", "normalmap"}, "thindielectric");
            b.kind = Bsdf::ThinDielectricKind;
            b.thin.eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5)).y;  // (one index for all channels, as dielectric)
            if (!(b.thin.eta > 0) || !std::isfinite(b.thin.eta)) throw SceneError(ps.where + ": thindielectric: eta must be positive");
        } else if (m.type == "diffusetransmission") {
            only(ps, {"reflectance", "transmittance", "scale", "displacement", "normalmap"}, "diffusetransmission");
            b.kind = Bsdf::DiffuseTransmissionKind;
            mm.scale = ps.get_float("scale", 1.0);
            if (!(mm.scale >= 0) || !std::isfinite(mm.scale))
                throw SceneError(ps.where + ": diffusetransmission: scale must not be negative");
            auto scaled = [&](Vec3 v) {  // (pbrt-v4: clamp(scale x, 0, 1))
                v = v * mm.scale;
                return Vec3(std::min(v.x, 1.0), std::min(v.y, 1.0), std::min(v.z, 1.0));
            };
            int tex;
            b.transmission.R = scaled(albedo_texture_param(scene, ps, "reflectance", Vec3(0.25, 0.25, 0.25), &tex));
            if (tex >= 0) mm.bindings.push_back({Slot::Reflectance, tex});
            b.transmission.T = scaled(albedo_texture_param(scene, ps, "transmittance", Vec3(0.25, 0.25, 0.25), &tex));
            if (tex >= 0) mm.bindings.push_back({Slot::Transmittance, tex});
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
                const std::string &type = scene.materials[mm.parts[k]].type;
                if (type == "interface" || type.empty() || type == "none")
                    throw SceneError(mp->where + ": mix: a mix of the \"interface\" material (\"" + mp->strings[k] +
                                     "\") is not modelled");
                // pbrt-v4 makes the named materials in order, then the others: a named mix takes only named
                // materials made before it
                if (!m.name.empty() && mm.parts[k] > (int)(&m - scene.materials.data()))
                    throw SceneError(mp->where + ": mix: material \"" + mp->strings[k] + "\" is made after this named mix (at " +
                                     scene.materials[mm.parts[k]].params.where + "), which pbrt-v4 refuses");
            }
            mm.amount_tex = texture_param(scene, ps, "amount", "float");
            if (mm.amount_tex < 0) mm.amount = ps.get_float("amount", 0.5);
        } else if (m.type == "measured") {
            only(ps, {"filename", "displacement", "normalmap"}, "measured");
            const udm1scene::Param *file = ps.find("filename");
            if (!m.tabulated || !file)  // (the parser reads the file)
                throw SceneError(ps.where + ": Material \"measured\": no tabulated BSDF file read");
            b.kind = Bsdf::MeasuredKind;
            auto it = measured_.find(m.tabulated.get());
            if (it == measured_.end())
                it = measured_.emplace(m.tabulated.get(), std::make_shared<const MeasuredTables>(*m.tabulated)).first;
            b.measured.t = it->second.get();
        } else {
            throw SceneError(ps.where + ": Material \"" + m.type +
                             "\" is not supported (diffuse, coateddiffuse, coatedconductor, conductor, dielectric, thindielectric, "
                             "diffusetransmission, measured, mix, interface)");
        }
        if (!mm.mix) {
            mm.displacement_tex = texture_param(scene, ps, "displacement", "float");
            if (ps.find("displacement") && mm.displacement_tex < 0)
                throw SceneError(ps.find("displacement")->where + ": 'displacement' must be \"texture displacement\"");
            std::string nm = ps.get_string("normalmap", "");
            if (!nm.empty()) mm.normal_map = textures_.add_normal_map(nm, ps.find("normalmap")->where);
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
    if (!scene.bsdf_sampling) refuse_specular(scene);
}

void Materials::refuse_specular(const udm1scene::Scene &scene) const
{
    std::vector<char> used(models_.size(), 0);  // the materials of shapes, and the parts of their mixes
    std::function<void(int)> use = [&](int i) {
        if (i < 0 || used[i]) return;
        used[i] = 1;
        if (models_[i].mix) use(models_[i].parts[0]), use(models_[i].parts[1]);
    };
    for (const udm1scene::Shape &s : scene.shapes) use(s.material);
    for (size_t i = 0; i < models_.size(); ++i) {
        const MaterialModel &m = models_[i];
        if (!used[i] || m.mix) continue;
        // smooth (or, with a roughness texture, maybe smooth somewhere) metal and glass, a smooth coat
        bool textured = false, base_textured = false;
        for (const MaterialModel::Binding &bd : m.bindings) {
            textured |= bd.slot == MaterialModel::Slot::URoughness || bd.slot == MaterialModel::Slot::VRoughness;
            base_textured |= bd.slot == MaterialModel::Slot::ConductorURoughness ||
                             bd.slot == MaterialModel::Slot::ConductorVRoughness;
        }
        const Coated &c = m.base.coated;
        bool specular = m.base.kind == Bsdf::ConductorKind    ? textured || m.base.conductor.specular()
                        : m.base.kind == Bsdf::DielectricKind ? textured || m.base.dielectric.specular()
                        : m.base.kind == Bsdf::ThinDielectricKind ? true
                        : m.base.kind == Bsdf::CoatedDiffuse  ? textured || (c.top.mf.smooth() && c.top.eta != 1)
                        : m.base.kind == Bsdf::CoatedConductor
                            ? textured || (c.top.mf.smooth() && (c.top.eta != 1 || base_textured || c.metal.specular()))
                            : false;
        if (specular)
            throw SceneError(scene.integrator_where + ": Integrator samples directions uniformly (randomwalk, or "
                                                      "samplebsdf false), which never finds the specular reflection of "
                                                      "the material at " + scene.materials[i].params.where +
                             ": pbrt-v4's image leaves it out, which udm1-pt does not model");
    }
}

namespace {

// pbrt-v4's RotateFromTo(a, b) applied to v (a, b unit).
Vec3 rotate_from_to(Vec3 a, Vec3 b, Vec3 v)
{
    Vec3 c = udm1scene::cross(a, b);
    double cs = udm1scene::dot(a, b);
    if (cs < -1 + 1e-12) return -v;  // (opposite: any half turn)
    // Rodrigues: v cos + (c x v) + c (c . v) / (1 + cos)
    return v * cs + udm1scene::cross(c, v) + c * (udm1scene::dot(c, v) / (1 + cs));
}

}  // namespace

const Bsdf &Materials::at(int material, const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 wo, Vec3 *ns,
                          Bsdf *scratch) const
{
    using Slot = MaterialModel::Slot;
    udm1scene::TexturePoint tp;  // where textures are looked up, made only if one is read
    bool have_tp = false;
    auto need_tp = [&] {
        if (!have_tp) tp = udm1scene::texture_point(shape, h), have_tp = true;
    };
    const MaterialModel *m = &models_[material];
    while (m->mix) {
        double amount = m->amount;
        if (m->amount_tex >= 0) need_tp(), amount = textures_.value(m->amount_tex, tp);
        int next = amount <= 0 ? m->parts[0] : amount >= 1 ? m->parts[1]
                                                          : (hash_unit(h.p, wo) < amount ? m->parts[1] : m->parts[0]);
        m = &models_[next];
    }
    if (m->bindings.empty() && m->displacement_tex < 0 && m->normal_map < 0) return m->base;
    need_tp();
    Bsdf &b = *scratch;
    b = m->base;
    auto alpha = [&](int tex) {
        double r = std::max(0.0, textures_.value(tex, tp));
        return m->remap ? std::sqrt(r) : r;
    };
    Microfacets &mf = b.kind == Bsdf::ConductorKind    ? b.conductor.mf
                      : b.kind == Bsdf::DielectricKind ? b.dielectric.mf
                                                       : b.coated.top.mf;
    for (const MaterialModel::Binding &bd : m->bindings) {
        switch (bd.slot) {
        case Slot::Reflectance: {
            Vec3 r = textures_.rgb(bd.tex, tp);
            if (b.kind == Bsdf::DiffuseTransmissionKind) {
                r = r * m->scale;
                b.transmission.R = Vec3(std::min(r.x, 1.0), std::min(r.y, 1.0), std::min(r.z, 1.0));
            } else {
                (b.kind == Bsdf::Diffuse ? b.diffuse.R : b.coated.bottom.R) = r;
            }
            break;
        }
        case Slot::Transmittance: {
            Vec3 t = textures_.rgb(bd.tex, tp) * m->scale;
            b.transmission.T = Vec3(std::min(t.x, 1.0), std::min(t.y, 1.0), std::min(t.z, 1.0));
            break;
        }
        case Slot::Albedo: b.coated.albedo = textures_.rgb(bd.tex, tp); break;
        case Slot::G: b.coated.g = std::clamp(textures_.value(bd.tex, tp), -1.0, 1.0); break;
        case Slot::Thickness: b.coated.thickness = std::max(textures_.value(bd.tex, tp), 1e-300); break;
        case Slot::URoughness: mf.ax = alpha(bd.tex); break;
        case Slot::VRoughness: mf.ay = alpha(bd.tex); break;
        case Slot::ConductorURoughness: b.coated.metal.mf.ax = alpha(bd.tex); break;
        case Slot::ConductorVRoughness: b.coated.metal.mf.ay = alpha(bd.tex); break;
        case Slot::ConductorReflectance: {
            Vec3 r = textures_.rgb(bd.tex, tp);
            Conductor &c = b.kind == Bsdf::ConductorKind ? b.conductor : b.coated.metal;
            c.table = nullptr;
            c.eta = Vec3(1, 1, 1) * (1 / m->interface_eta);
            c.k = Vec3(reflectance_k(r.x), reflectance_k(r.y), reflectance_k(r.z)) * (1 / m->interface_eta);
            break;
        }
        }
    }
    if (m->displacement_tex >= 0 || m->normal_map >= 0) {
        // shading dp/du and dp/dv, as pbrt-v4 sets them: with vertex normals, turned into the shading plane
        Vec3 n = *ns, dpdu, dpdv;
        udm1scene::surface_derivatives(shape, h, n, &dpdu, &dpdv);
        if (!shape.N.empty() && shape.kind == udm1scene::Shape::Bilinear) {  // (pbrt-v4: rotated from ng to ns)
            dpdu = rotate_from_to(h.ng, n, dpdu), dpdv = rotate_from_to(h.ng, n, dpdv);
        } else if (!shape.N.empty()) {
            Vec3 ts = udm1scene::cross(n, dpdu);
            if (udm1scene::dot(ts, ts) > 0) dpdu = udm1scene::cross(ts, n), dpdv = ts;
        }
        if (m->normal_map >= 0) {  // pbrt-v4's NormalMap: the map's normal in the frame (dp/du, n)
            Vec3 x = dpdu - n * udm1scene::dot(dpdu, n);
            double len = udm1scene::length(x);
            x = len > 0 ? x * (1 / len) : udm1scene::Frame(n).t;
            Vec3 y = udm1scene::cross(n, x), t = textures_.normal_map(m->normal_map, tp.u, tp.v);
            Vec3 bn = x * t.x + y * t.y + n * t.z;
            double bl = udm1scene::length(bn);
            if (bl > 0 && std::isfinite(bl)) {
                bn = bn * (1 / bl);
                *ns = udm1scene::dot(bn, h.ng) < 0 ? -bn : bn;  // (faced to the geometric normal)
            }
        } else {  // pbrt-v4's BumpMap
            const double du = 0.0005, dv = 0.0005;
            double d = textures_.value(m->displacement_tex, tp);
            udm1scene::TexturePoint tu = tp, tv = tp;
            tu.u += du, tu.p = tu.p + dpdu * du;
            tv.v += dv, tv.p = tv.p + dpdv * dv;
            double d_u = textures_.value(m->displacement_tex, tu), d_v = textures_.value(m->displacement_tex, tv);
            Vec3 bu = dpdu + n * ((d_u - d) / du), bv = dpdv + n * ((d_v - d) / dv);
            Vec3 bn = udm1scene::cross(bu, bv);
            double len = udm1scene::length(bn);
            if (len > 0 && std::isfinite(len)) {
                bn = bn * (1 / len);
                *ns = udm1scene::dot(bn, n) < 0 ? -bn : bn;
            }
        }
    }
    return b;
}

}  // namespace udm1pt
