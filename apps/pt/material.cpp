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

// A conductor's index given as a float or a spectrum (absent: pbrt-v4's default, copper's).
udm1scene::Spectrum index_spectrum(const udm1scene::ParamSet &ps, const std::string &name)
{
    const udm1scene::Param *p = ps.find(name);
    if (!p) return *udm1scene::named_spectrum("metal-Cu-" + name);
    if (p->type == "float" && p->numbers.size() == 1) return udm1scene::Spectrum::constant(p->numbers[0]);
    if (p->type == "spectrum") return spectrum_of(*p);
    throw SceneError(p->where + ": '" + name + "' must be a float, an rgb triple, a named spectrum or (lambda, value) pairs");
}

// The Fresnel table of a spectral conductor: its reflectance at each wavelength, projected on RGB as
// pbrt-v4's film records it under D65 (udm1scene::albedo_rgb), at 65 incident angles.
std::unique_ptr<FresnelTable> fresnel_table(const udm1scene::Spectrum &eta, const udm1scene::Spectrum &k,
                                            const std::string &where)
{
    double n[udm1scene::WAVELENGTHS], kk[udm1scene::WAVELENGTHS], r[udm1scene::WAVELENGTHS];
    for (int l = 0; l < udm1scene::WAVELENGTHS; ++l) {
        n[l] = eta.at(360 + l), kk[l] = k.at(360 + l);
        if (!(n[l] > 0) || !(kk[l] >= 0))
            throw SceneError(where + ": conductor: eta must be positive and k not negative at every wavelength (" +
                             std::to_string(360 + l) + " nm)");
    }
    auto t = std::make_unique<FresnelTable>();
    for (int i = 0; i < FresnelTable::N; ++i) {
        double c = (double)i / (FresnelTable::N - 1);
        for (int l = 0; l < udm1scene::WAVELENGTHS; ++l) r[l] = fresnel_complex(c, n[l], kk[l]);
        Vec3 rgb = udm1scene::albedo_rgb(r);
        for (int ch = 0; ch < 3; ++ch) t->r[ch][i] = (float)rgb[ch];
    }
    return t;
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
        if (m.type == "interface" || m.type.empty() || m.type == "none") {  // pbrt-v4: no BSDF (media.h)
            only(ps, {}, "Material \"" + m.type + "\"");
            mm.interface = true;
            models_.push_back(mm);
            continue;
        }
        if (m.type == "diffuse") {
            only(ps, {"reflectance", "displacement"}, "diffuse");
            b.kind = Bsdf::Diffuse;
            mm.reflectance_tex = texture_param(scene, ps, "reflectance", "spectrum");
            if (mm.reflectance_tex < 0) b.diffuse.R = albedo_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
        } else if (m.type == "coateddiffuse") {
            only(ps, {"reflectance", "roughness", "uroughness", "vroughness", "remaproughness", "thickness", "eta",
                      "maxdepth", "nsamples", "albedo", "g", "displacement"},
                 "coateddiffuse");
            b.kind = Bsdf::CoatedDiffuse;
            Coated &c = b.coated;
            mm.reflectance_tex = texture_param(scene, ps, "reflectance", "spectrum");
            if (mm.reflectance_tex < 0) c.bottom.R = albedo_param(ps, "reflectance", Vec3(0.5, 0.5, 0.5));
            roughness(&c.top.mf, "coateddiffuse");
            c.top.eta = ps.get_float("eta", 1.5);
            c.thickness = std::max(ps.get_float("thickness", 0.01), 1e-300);
            c.max_depth = ps.get_int("maxdepth", 10);
            c.samples = ps.get_int("nsamples", 1);
            if (!(c.top.eta > 0)) throw SceneError(ps.where + ": coateddiffuse: eta must be positive");
            if (c.max_depth < 1 || c.max_depth > 100 || c.samples < 1 || c.samples > 100)
                throw SceneError(ps.where + ": coateddiffuse: maxdepth and nsamples must be in 1..100");
            Vec3 albedo = albedo_param(ps, "albedo", Vec3());
            if (nonzero(albedo))
                throw SceneError(ps.where + ": coateddiffuse: a scattering medium between the layers (albedo > 0) "
                                            "is not supported");
        } else if (m.type == "conductor") {
            only(ps, {"eta", "k", "roughness", "uroughness", "vroughness", "remaproughness", "displacement"}, "conductor");
            b.kind = Bsdf::ConductorKind;
            roughness(&b.conductor.mf, "conductor");
            const udm1scene::Param *pe = ps.find("eta"), *pk = ps.find("k");
            if ((pe && pe->type == "rgb") || (pk && pk->type == "rgb")) {  // per channel (pbrt upsamples the rgb)
                b.conductor.eta = spectrum_param(ps, "eta", Vec3());
                b.conductor.k = spectrum_param(ps, "k", Vec3());
                if (!pe || !pk) throw SceneError(ps.where + ": conductor: an rgb eta or k needs the other one too");
                if (!(b.conductor.eta.x > 0 && b.conductor.eta.y > 0 && b.conductor.eta.z > 0) ||
                    !(b.conductor.k.x >= 0 && b.conductor.k.y >= 0 && b.conductor.k.z >= 0))
                    throw SceneError(ps.where + ": conductor: eta must be positive and k not negative");
            } else {  // spectral (pbrt's default: copper): its Fresnel reflectance as pbrt-v4 records it
                tables_.push_back(fresnel_table(index_spectrum(ps, "eta"), index_spectrum(ps, "k"), ps.where));
                b.conductor.table = tables_.back().get();
            }
        } else if (m.type == "dielectric") {
            only(ps, {"eta", "roughness", "uroughness", "vroughness", "remaproughness", "displacement"}, "dielectric");
            b.kind = Bsdf::DielectricKind;
            Vec3 eta = spectrum_param(ps, "eta", Vec3(1.5, 1.5, 1.5));
            b.dielectric.eta = eta.y;  // one index for all channels (no dispersion): 550 nm's
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
        } else {
            throw SceneError(ps.where + ": Material \"" + m.type +
                             "\" is not supported (diffuse, coateddiffuse, conductor, dielectric, mix, interface)");
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
        bool textured = m.roughness_tex >= 0;
        bool specular = m.base.kind == Bsdf::ConductorKind    ? textured || m.base.conductor.specular()
                        : m.base.kind == Bsdf::DielectricKind ? textured || m.base.dielectric.specular()
                        : m.base.kind == Bsdf::CoatedDiffuse
                            ? textured || (m.base.coated.top.mf.smooth() && m.base.coated.top.eta != 1)
                            : false;
        if (specular)
            throw SceneError(scene.integrator_where + ": Integrator samples directions uniformly (randomwalk, or "
                                                      "samplebsdf false), which never finds the specular reflection of "
                                                      "the material at " + scene.materials[i].params.where +
                             ": pbrt-v4's image leaves it out, which udm1-pt does not model");
    }
}

namespace {
// dp/du and dp/dv of a triangle from its uv (pbrt-v4's Triangle), or a frame around n when the uv
// are degenerate; spheres: from the longitude/colatitude parametrization of hit_uv.
void surface_derivatives(const udm1scene::Shape &s, const udm1scene::Hit &h, Vec3 n, Vec3 *dpdu, Vec3 *dpdv)
{
    const double PI = 3.14159265358979323846;
    if (s.kind == udm1scene::Shape::Sphere) {  // in object space (pbrt-v4's Sphere), then to world space
        Vec3 d = udm1scene::sphere_object_point(s, udm1scene::shape_point(h));
        double phi_max = 2 * PI, r = s.object_radius, rho = std::sqrt(d.x * d.x + d.y * d.y);
        *dpdu = Vec3(-phi_max * d.y, phi_max * d.x, 0);
        double cos_phi = rho > 0 ? d.x / rho : 1, sin_phi = rho > 0 ? d.y / rho : 0, theta = std::acos(std::clamp(d.z / r, -1.0, 1.0));
        *dpdv = Vec3(d.z * cos_phi, d.z * sin_phi, -r * std::sin(theta)) * (-PI);  // v = 1 - theta / pi
        *dpdu = udm1scene::world_vector(h, s.world_from_object.vector(*dpdu));
        *dpdv = udm1scene::world_vector(h, s.world_from_object.vector(*dpdv));
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
        *dpdu = udm1scene::world_vector(h, (dp02 * dv12 - dp12 * dv02) * (1 / det));
        *dpdv = udm1scene::world_vector(h, (dp12 * du02 - dp02 * du12) * (1 / det));
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
    if (s.kind == udm1scene::Shape::Sphere) {  // pbrt-v4's, of the point in object space
        Vec3 d = udm1scene::sphere_object_point(s, udm1scene::shape_point(h)) * (1 / s.object_radius);
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
