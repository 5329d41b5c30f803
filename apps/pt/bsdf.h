// bsdf.h - the scattering functions the target scenes use, in RGB, in a local
// frame whose z axis is the shading normal (pbrt-v4's conventions):
//   diffuse        Lambertian reflection on both sides (pbrt-v4 DiffuseBxDF)
//   conductor      metal: Trowbridge-Reitz microfacets or a mirror, complex Fresnel per channel
//   dielectric     glass: smooth or rough reflection and refraction (one eta for all channels)
//   diffusetransmission  Lambertian reflection R and transmission T (pbrt-v4 DiffuseTransmissionBxDF)
//   coateddiffuse, coatedconductor  a dielectric coat (Trowbridge-Reitz microfacets, or smooth) over
//                  a diffuse or a conductor base, two-sided, with a homogeneous medium between them
//                  (thickness, albedo, Henyey-Greenstein g; none where the albedo is 0), evaluated
//                  by pbrt-v4's stochastic layered random walk (LayeredBxDF), maxdepth, nsamples.
//   thindielectric a thin glass sheet: specular reflection and straight transmission (pbrt-v4 ThinDielectricBxDF)
//   measured       a tabulated BSDF file (pbrt-v4 MeasuredBxDF): reflection on both sides, from tables of
//                  the microfacet normals' density, the visible normals' and the spectral factor (in RGB)
// f() and pdf() of the coated materials are themselves unbiased random estimates, drawn from a
// generator seeded by a hash of the directions (as pbrt does), so they are deterministic.
#pragma once

#include "bilinear_warp.h"
#include "math.h"
#include "tabulated_bsdf.h"

#include <cstdint>

namespace udm1pt {

using udm1scene::Vec3;
using udm1scene::mul;

enum class Mode { Radiance, Importance };  // which way light is carried (refraction scaling)

struct Sample {
    Vec3 f;            // BSDF value (no cosine)
    Vec3 wi;           // local direction
    double pdf = 0;    // solid-angle density; 0 means no sample
    bool specular = false, reflection = true;
    bool pdf_is_proportional = false;  // layered sampling: use pdf() for MIS weights
    double eta = 1;                    // transmission: the relative index crossed (pbrt's etaScale)
};

// Trowbridge-Reitz (GGX) microfacets with visible-normal sampling.
struct Microfacets {
    double ax = 0, ay = 0;
    bool smooth() const { return ax < 1e-3 && ay < 1e-3; }
    double D(Vec3 wm) const;
    double lambda(Vec3 w) const;
    double G1(Vec3 w) const { return 1 / (1 + lambda(w)); }
    double G(Vec3 wo, Vec3 wi) const { return 1 / (1 + lambda(wo) + lambda(wi)); }
    double pdf(Vec3 w, Vec3 wm) const;  // visible normals
    Vec3 sample_wm(Vec3 w, double u1, double u2) const;
};

// Which lobes a sample may take.
enum Lobes : unsigned { Reflect = 1, Transmit = 2, Both = 3 };

struct Dielectric {
    double eta = 1.5;
    Microfacets mf;
    Vec3 f(Vec3 wo, Vec3 wi, Mode mode) const;
    double pdf(Vec3 wo, Vec3 wi, Mode mode, unsigned lobes) const;
    bool sample(Vec3 wo, double uc, double u1, double u2, Mode mode, unsigned lobes, Sample *s) const;
    bool specular() const { return eta == 1 || mf.smooth(); }
};

// A metal's Fresnel reflectance by RGB channel, tabulated over the cosine of the incident angle: a
// spectral metal's reflectance as pbrt-v4 would record it (material.h builds it; the red channel of gold
// exceeds 1 and falls towards grazing angles: no complex index per channel does that).
struct FresnelTable {
    static constexpr int N = 65;  // cos theta = 0, 1/64, ..., 1
    float r[3][N];
    Vec3 at(double cos_theta) const;  // linear interpolation
};

// A metal: Trowbridge-Reitz microfacets (or a perfect mirror when smooth) with the Fresnel
// reflectance of a conductor of complex index eta + i k, per RGB channel (pbrt-v4 ConductorBxDF), or
// of a spectral one through its table.
struct Conductor {
    Vec3 eta{1, 1, 1}, k{0, 0, 0};
    const FresnelTable *table = nullptr;  // if set, in place of eta and k
    Microfacets mf;
    Vec3 fresnel(double cos_i) const;
    Vec3 f(Vec3 wo, Vec3 wi) const;
    double pdf(Vec3 wo, Vec3 wi) const;
    bool sample(Vec3 wo, double u1, double u2, Sample *s) const;
    bool specular() const { return mf.smooth(); }
};

struct Lambert {
    Vec3 R;
    Vec3 f(Vec3 wo, Vec3 wi) const;
    double pdf(Vec3 wo, Vec3 wi, unsigned lobes) const;
    bool sample(Vec3 wo, double u1, double u2, unsigned lobes, Sample *s) const;
};

// Lambertian reflection R on the side of wo and transmission T to the other side, chosen in proportion to
// their largest components (pbrt-v4's DiffuseTransmissionBxDF).
struct DiffuseTransmission {
    Vec3 R{0.25, 0.25, 0.25}, T{0.25, 0.25, 0.25};
    Vec3 f(Vec3 wo, Vec3 wi) const;
    double pdf(Vec3 wo, Vec3 wi) const;
    bool sample(Vec3 wo, double uc, double u1, double u2, Sample *s) const;
};

// A thin dielectric sheet (pbrt-v4's ThinDielectricBxDF): specular reflection about the normal and transmission
// straight through (no refraction), with the Fresnel reflectance R of one interface summed over the light's
// inner reflections, R' = R + T^2 R / (1 - R^2), T' = 1 - R', chosen in proportion to them.
struct ThinDielectric {
    double eta = 1.5;
    bool sample(Vec3 wo, double uc, Sample *s) const;
};

// pbrt-v4's Henyey-Greenstein phase function p(wo, wi) = HG(wo . wi, g) (wo pointing away), g clamped to
// [-0.99, 0.99], and its sampling.
double henyey_greenstein(double cos_theta, double g);
Vec3 sample_henyey_greenstein(Vec3 wo, double g, double u1, double u2, double *pdf);

// A dielectric coat over a base (diffuse, or a conductor: metal_base), the medium between them of
// thickness `thickness` (sigma_t 1), single-scattering albedo `albedo` (zero: no medium) and
// Henyey-Greenstein asymmetry g.
struct Coated {
    Dielectric top;
    Lambert bottom;
    Conductor metal;
    bool metal_base = false;
    double thickness = 0.01, g = 0;
    Vec3 albedo;
    int max_depth = 10, samples = 1;
    Vec3 f(Vec3 wo, Vec3 wi, Mode mode) const;
    double pdf(Vec3 wo, Vec3 wi, Mode mode) const;
    bool sample(Vec3 wo, double uc, double u1, double u2, Mode mode, Sample *s) const;
};

// A tabulated BSDF file's tables (scene/tabulated_bsdf.h) as functions on the unit square: ndf over the
// normal's (theta, phi), sigma over the outgoing direction's, vndf over the normal's for each outgoing (phi,
// theta) (the azimuth relative to the outgoing one where isotropic), luminance and the RGB factor over the
// square vndf warps, for each outgoing (phi, theta); theta maps to sqrt(theta / (pi / 2)), phi to
// phi / (2 pi) + 1/2.
struct MeasuredTables {
    BilinearWarp ndf, sigma, vndf, luminance, rgb[3];
    bool isotropic = true;
    explicit MeasuredTables(const udm1scene::TabulatedBsdf &b);
};

// pbrt-v4's MeasuredBxDF: f(wo, wi) = rgb(u) D(wm) / (4 sigma(wo) cos theta_i), wm the half vector and u the
// point of the square that vndf (for wo) warps to wm's coordinates; sampled by warping (u1, u2) by luminance,
// then by vndf, to a normal, and reflecting wo about it (none below the horizon). Reflection only, on both
// sides (the directions mirrored where wo is below).
struct Measured {
    const MeasuredTables *t = nullptr;
    Vec3 f(Vec3 wo, Vec3 wi) const;
    double pdf(Vec3 wo, Vec3 wi) const;
    bool sample(Vec3 wo, double u1, double u2, Sample *s) const;
};

// A material at a point: one of the above.
struct Bsdf {
    enum Kind {
        Diffuse, CoatedDiffuse, DielectricKind, ConductorKind, CoatedConductor, DiffuseTransmissionKind, MeasuredKind,
        ThinDielectricKind
    } kind = Diffuse;
    Lambert diffuse;
    Coated coated;  // coateddiffuse and coatedconductor
    Dielectric dielectric;
    Conductor conductor;
    DiffuseTransmission transmission;
    Measured measured;
    ThinDielectric thin;
    Vec3 f(Vec3 wo, Vec3 wi, Mode mode = Mode::Radiance) const;
    double pdf(Vec3 wo, Vec3 wi, Mode mode = Mode::Radiance) const;
    bool sample(Vec3 wo, double uc, double u1, double u2, Sample *s, Mode mode = Mode::Radiance) const;
    // Whether a turn of the frame about the normal changes the BSDF: anisotropic microfacets (uroughness and
    // vroughness differ) and tabulated BSDFs, which pbrt-v4 orients by the surface's dp/du (shading_frame).
    bool oriented() const
    {
        auto aniso = [](const Microfacets &m) { return m.ax != m.ay; };
        switch (kind) {
        case MeasuredKind: return true;
        case DielectricKind: return aniso(dielectric.mf);
        case ConductorKind: return aniso(conductor.mf);
        case CoatedDiffuse: return aniso(coated.top.mf);
        case CoatedConductor: return aniso(coated.top.mf) || aniso(coated.metal.mf);
        default: return false;
        }
    }
    // false for perfect mirrors and smooth glass: next-event estimation cannot reach them
    bool has_non_specular() const
    {
        if (kind == CoatedConductor)  // (pbrt-v4's LayeredBxDF: specular only if both interfaces are and no medium)
            return !(coated.top.specular() && coated.metal.specular() && coated.albedo.x == 0 && coated.albedo.y == 0 &&
                     coated.albedo.z == 0);
        return kind == DielectricKind ? !dielectric.specular()
               : kind == ConductorKind ? !conductor.specular()
                                       : kind != ThinDielectricKind;
    }
};

// Fresnel reflectance of a dielectric interface (cos of the incident angle, relative eta).
double fresnel_dielectric(double cos_i, double eta);
// Fresnel reflectance of a conductor (cos of the incident angle, complex index eta + i k).
double fresnel_complex(double cos_i, double eta, double k);

}  // namespace udm1pt
