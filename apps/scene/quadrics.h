// quadrics.h - pbrt-v4's quadrics (sphere, disk, cylinder; Shape::quadric()) met in their object space:
// a ray is taken to object space by the shape's affine object_from_world (t is the same parameter in
// both spaces) and solved there in double precision, so that any affine transform (a non-uniform scale,
// a shear, a reflection) places the quadric as pbrt-v4 places it. Normals go to world space by the
// inverse transpose; (u, v) and dp/du, dp/dv are pbrt-v4's parametrizations of each quadric.
#pragma once

#include "scene.h"

namespace udm1scene {

// The hits of o + t d with quadric s for t in (tnear, tfar], nearest first: at most two (a sphere's and a
// cylinder's two roots, a disk's one), each inside the shape's clipping (a disk's radii and phi_max, a
// cylinder's z range and phi_max). Returns their count.
int quadric_hits(const Shape &s, Vec3 o, Vec3 d, double tnear, double tfar, double t[2]);

// The unit outward normal in world space at world point p on quadric s (before any flip for orientation):
// the object-space normal by the inverse transpose.
Vec3 quadric_normal(const Shape &s, Vec3 p);

// pbrt-v4's (u, v) at world point p on quadric s: the sphere's (phi / 2 pi, 1 - theta / pi), the disk's
// (phi / phi_max, (radius - r) / (radius - inner_radius)), the cylinder's (phi / phi_max,
// (z - zmin) / (zmax - zmin)).
void quadric_uv(const Shape &s, Vec3 p, double *u, double *v);

// dp/du and dp/dv in world space at world point p on quadric s (pbrt-v4's, by world_from_object).
void quadric_derivatives(const Shape &s, Vec3 p, Vec3 *dpdu, Vec3 *dpdv);

// A quadric's area in its object space (pbrt-v4's Area(), which its area lights use).
double quadric_area(const Shape &s);

// pbrt-v4's area sampling of a disk or cylinder from (u1, u2): the world point and the unit world normal
// (outward, before any flip for orientation). A disk is sampled over its
// whole radius and 2 pi (pbrt-v4's Disk::Sample), a cylinder over its z range and phi_max.
void quadric_sample_area(const Shape &s, double u1, double u2, Vec3 *p, Vec3 *n);

}  // namespace udm1scene
