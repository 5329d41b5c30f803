// media.h - participating media for the path tracer, as pbrt-v4's VolPathIntegrator models them, in RGB:
// homogeneous media (scene.h, Medium) inside shapes through their MediumInterface and around the camera,
// the Henyey-Greenstein phase function, and which scenes need the volumetric estimator (estimator.h).
//
// A ray travels in one medium at a time (pbrt-v4's ray medium): the camera's to begin with; a surface whose
// MediumInterface is a transition (inside != outside) puts a ray that leaves it on the side its geometric
// normal faces in the outside medium and on the other side in the inside one; any other surface leaves the
// medium as it was. Surfaces with the "interface" material only bound media: rays and shadow rays pass
// them without scattering and without counting a bounce (pbrt-v4's SkipIntersection).
#pragma once

#include "material.h"
#include "scene.h"

#include <cmath>
#include <vector>

namespace udm1pt {

// Whether Integrator "volpath" renders a medium: the camera is in one or a shape's MediumInterface is a
// transition. (Integrator "path" leaves media out, as pbrt-v4's PathIntegrator does.)
bool uses_media(const udm1scene::Scene &scene);

// Whether a medium that uses_media() renders glows (Medium::emissive): a scene without lights is not black then.
bool emissive_media(const udm1scene::Scene &scene);

// Whether a shape has the "interface" material (or its deprecated names "" and "none"): per shape.
std::vector<char> interface_shapes(const udm1scene::Scene &scene);

// pbrt-v4's Henyey-Greenstein phase function of asymmetry g (clamped to [-0.99, 0.99]) between wo (towards
// where the light goes) and wi (towards where it comes from), both unit: positive g scatters forwards
// (wi near -wo). Normalized over the sphere of wi.
double hg_phase(double cos_wo_wi, double g);
// A direction wi drawn with density hg_phase(dot(wo, wi), g) from (u1, u2) in [0, 1)^2; *pdf that density.
udm1scene::Vec3 sample_hg(udm1scene::Vec3 wo, double g, double u1, double u2, double *pdf);

// The transmittance exp(-sigma_t d) per channel over a distance d (infinite allowed: 0 where sigma_t > 0).
inline udm1scene::Vec3 transmittance(const udm1scene::Medium &m, double d)
{
    udm1scene::Vec3 st = m.sigma_a + m.sigma_s, T;
    for (int k = 0; k < 3; ++k) T[k] = st[k] > 0 ? std::exp(-st[k] * d) : 1.0;
    return T;
}

}  // namespace udm1pt
