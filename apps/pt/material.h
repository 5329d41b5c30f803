// material.h - the scene's materials for the path tracer. Each Material / MakeNamedMaterial of the
// subset (diffuse, coateddiffuse, coatedconductor, conductor, dielectric, diffusetransmission, measured, mix;
// interface, which only bounds media) becomes a BSDF template plus the textures that vary it over the
// surface (any of pbrt-v4's texture-valued parameters of these materials: reflectance, transmittance, the
// medium's albedo, g and thickness, roughnesses, a conductor's reflectance, a mix's amount), a bump map
// ("displacement") or a normal map ("normalmap"); at a hit, at() evaluates them and resolves a mix as
// pbrt-v4 does: the second material where a hash of the point and the outgoing direction falls below the
// amount. Spectra become RGB as pbrt-v4's film would record them (scene/spectrum.h): reflectances under
// D65, a spectral metal's Fresnel reflectance by channel and angle (a table), a dielectric's single index
// at 550 nm, a tabulated BSDF's spectral factor per table entry (scene/tabulated_bsdf.h).
#pragma once

#include "bsdf.h"
#include "embree_scene.h"
#include "scene.h"
#include "surface.h"
#include "textures.h"

#include <map>
#include <memory>
#include <vector>

namespace udm1pt {

struct MaterialModel {
    Bsdf base;
    // A texture evaluated at the hit into one parameter of the BSDF.
    enum class Slot {
        Reflectance, Transmittance, Albedo, G, Thickness,
        URoughness, VRoughness,                    // the material's, or a coated conductor's interface
        ConductorURoughness, ConductorVRoughness,  // a coated conductor's base
        ConductorReflectance                       // a conductor's (or coated conductor's base's) "reflectance"
    };
    struct Binding {
        Slot slot;
        int tex;
    };
    std::vector<Binding> bindings;
    int displacement_tex = -1; // bump mapping: a float texture of displacement along the normal
    int normal_map = -1;       // a normal map (Textures::normal_map), which takes precedence over a bump map
    bool remap = true;         // pbrt's remaproughness: alpha = sqrt(roughness)
    double scale = 1;          // diffusetransmission: scales its (textured) reflectance and transmittance
    double interface_eta = 1;  // coatedconductor: the base's index is relative to the coat's
    bool mix = false;
    bool interface = false;    // "interface" (pbrt-v4's deprecated "" and "none" too): no BSDF, bounds media only
    int parts[2] = {-1, -1};   // mix: the two materials
    double amount = 0.5;
    int amount_tex = -1;
};

class Materials {
public:
    // Validates every material (unknown types and parameters, missing textures and named materials,
    // mixes that contain themselves) with its file:line, and reads the textures' images. With an
    // integrator that samples directions uniformly (Scene::bsdf_sampling false) a material in use that
    // may have a specular lobe is refused: pbrt-v4's image leaves that lobe out.
    explicit Materials(const udm1scene::Scene &scene);
    // The BSDF at hit h of shape (a mix resolved, textures evaluated) and, through *ns, the shading
    // normal: the caller's (interpolated or geometric) on entry, perturbed as pbrt-v4's NormalMap or
    // BumpMap if the material has a normal map or a displacement texture (bump: finite differences of
    // 0.0005 in u and v: udm1-pt has no ray differentials, pbrt-v4's own fallback; the normal's change
    // dn/du is taken as 0).
    // An untextured material's BSDF is returned as it is; a textured one is written to *scratch.
    // Not for the interface material, which has no BSDF (interface()).
    const Bsdf &at(int material, const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 wo, Vec3 *ns,
                   Bsdf *scratch) const;
    size_t size() const { return models_.size(); }
    bool interface(int material) const { return models_[material].interface; }

private:
    void refuse_specular(const udm1scene::Scene &scene) const;
    udm1scene::Textures textures_;
    std::vector<MaterialModel> models_;
    std::vector<std::unique_ptr<FresnelTable>> tables_;  // spectral conductors' (their BSDFs point here)
    std::map<const udm1scene::TabulatedBsdf *, std::shared_ptr<const MeasuredTables>> measured_;  // by file (likewise)
};

// The local frame of the BSDF at hit h (pt/bsdf.h's conventions: z the shading normal ns): a frame around ns; for a
// BSDF that a turn about ns changes (Bsdf::oriented: anisotropic microfacets, tabulated BSDFs), the frame pbrt-v4
// gives every BSDF: x along dp/du (udm1scene::surface_derivatives) made perpendicular to ns, y = ns x x (around ns
// alone where dp/du is along ns).
udm1scene::Frame oriented_frame(const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 ns);
inline udm1scene::Frame shading_frame(const Bsdf &b, const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 ns)
{
    return b.oriented() ? oriented_frame(shape, h, ns) : udm1scene::Frame(ns);  // (isotropic: the same BSDF in any frame about ns)
}

// pbrt-v4's default material, that of a shape with no Material or NamedMaterial before it (area
// lights' shapes often have none: their back reflects): diffuse, reflectance 0.5.
Bsdf default_material();

using udm1scene::hit_uv;

}  // namespace udm1pt
