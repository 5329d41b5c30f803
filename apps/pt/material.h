// material.h - the scene's materials for the path tracer. Each Material / MakeNamedMaterial of the
// subset (diffuse, coateddiffuse, conductor, dielectric, mix; interface, which only bounds media) becomes a BSDF template plus the
// textures that vary it over the surface (reflectance, roughness, a mix's amount); at a hit, at()
// evaluates them and resolves a mix as pbrt-v4 does: the second material where a hash of the point and
// the outgoing direction falls below the amount. Spectra become RGB as pbrt-v4's film would record
// them (scene/spectrum.h): reflectances under D65, a spectral metal's Fresnel reflectance by channel
// and angle (a table), a dielectric's single index at 550 nm.
#pragma once

#include "bsdf.h"
#include "embree_scene.h"
#include "scene.h"
#include "texture.h"

#include <memory>
#include <vector>

namespace udm1pt {

struct MaterialModel {
    Bsdf base;
    int reflectance_tex = -1;  // diffuse R, or the coated base's R (a spectrum texture)
    int displacement_tex = -1; // bump mapping: a float texture of displacement along the normal
    int roughness_tex = -1;    // conductor, dielectric, coated: a float texture in place of "roughness"
    bool remap = true;         // pbrt's remaproughness: alpha = sqrt(roughness)
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
    // normal: the caller's (interpolated or geometric) on entry, bumped as pbrt-v4's BumpMap if the
    // material has a displacement texture (finite differences of 0.0005 in u and v: udm1-pt has no ray
    // differentials, pbrt-v4's own fallback; the normal's change dn/du is taken as 0).
    // An untextured material's BSDF is returned as it is; a textured one is written to *scratch.
    // Not for the interface material, which has no BSDF (interface()).
    const Bsdf &at(int material, const udm1scene::Shape &shape, const udm1scene::Hit &h, Vec3 wo, Vec3 *ns,
                   Bsdf *scratch) const;
    size_t size() const { return models_.size(); }
    bool interface(int material) const { return models_[material].interface; }

private:
    void refuse_specular(const udm1scene::Scene &scene) const;
    Textures textures_;
    std::vector<MaterialModel> models_;
    std::vector<std::unique_ptr<FresnelTable>> tables_;  // spectral conductors' (their BSDFs point here)
};

// pbrt-v4's default material, that of a shape with no Material or NamedMaterial before it (area
// lights' shapes often have none: their back reflects): diffuse, reflectance 0.5.
Bsdf default_material();

// The texture coordinates of a hit: the mesh's per-vertex uv interpolated, else pbrt-v4's defaults
// ((0,0), (1,0), (1,1) per triangle; spheres by longitude and colatitude in their object space).
void hit_uv(const udm1scene::Shape &shape, const udm1scene::Hit &h, double *u, double *v);

}  // namespace udm1pt
