// media.cpp - see media.h.
#include "media.h"

#include <algorithm>

namespace udm1pt {

using udm1scene::Vec3;

bool uses_media(const udm1scene::Scene &scene)
{
    if (scene.integrator != "volpath" || scene.media.empty()) return false;
    if (scene.camera.medium >= 0) return true;
    for (const udm1scene::Shape &s : scene.shapes)
        if (s.inside != s.outside) return true;
    return false;
}

bool emissive_media(const udm1scene::Scene &scene)
{
    if (!uses_media(scene)) return false;
    for (const udm1scene::Medium &m : scene.media)
        if (m.emissive()) return true;
    return false;
}

std::vector<char> interface_shapes(const udm1scene::Scene &scene)
{
    std::vector<char> v(scene.shapes.size(), 0);
    for (size_t i = 0; i < scene.shapes.size(); ++i) {
        int m = scene.shapes[i].material;
        if (m < 0) continue;
        const std::string &type = scene.materials[m].type;
        v[i] = type == "interface" || type.empty() || type == "none";
    }
    return v;
}

double hg_phase(double cos_wo_wi, double g)
{
    g = std::clamp(g, -0.99, 0.99);
    double denom = 1 + g * g + 2 * g * cos_wo_wi;
    return (1 - g * g) / (4 * 3.14159265358979323846 * denom * std::sqrt(std::max(denom, 0.0)));
}

Vec3 sample_hg(Vec3 wo, double g, double u1, double u2, double *pdf)
{
    g = std::clamp(g, -0.99, 0.99);
    // nu, the cosine between wi and the direction of propagation -wo, by inverting its distribution
    // (1 - g^2) / (2 (1 + g^2 - 2 g nu)^(3/2)) on [-1, 1]
    double nu;
    if (std::fabs(g) < 1e-3) {
        nu = 2 * u1 - 1;
    } else {
        double s = (1 - g * g) / (1 - g + 2 * g * u1);
        nu = (1 + g * g - s * s) / (2 * g);
    }
    nu = std::clamp(nu, -1.0, 1.0);
    double sin_nu = std::sqrt(std::max(0.0, 1 - nu * nu)), s_phi, c_phi;
    udm1scene::sincos_2pi(u2, &s_phi, &c_phi);
    udm1scene::Frame f(-wo);
    Vec3 wi = f.from_local(Vec3(sin_nu * c_phi, sin_nu * s_phi, nu));
    *pdf = hg_phase(-nu, g);
    return wi;
}

}  // namespace udm1pt
