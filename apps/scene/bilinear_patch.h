// bilinear_patch.h - pbrt-v4's bilinear patches (Shape::Bilinear): patch `prim` of a shape has the
// vertices p00 p10 p01 p11 (its 4 indices, in that order) and the points
//   p(u, v) = (1-u)(1-v) p00 + u(1-v) p10 + (1-u)v p01 + uv p11,  (u, v) in [0, 1]^2,
// a doubly ruled surface, planar only when the four vertices are. Rays meet it exactly (Reshetov's
// solution, as pbrt-v4's IntersectBilinearPatch: a quadratic in u, then v and t), not as two triangles,
// which differ wherever the patch is not planar.
#pragma once

#include "scene.h"

namespace udm1scene {

struct Patch {
    Vec3 p00, p10, p01, p11;
    Vec3 at(double u, double v) const;
    // dp/du and dp/dv of the parametrization above
    void derivatives(double u, double v, Vec3 *dpdu, Vec3 *dpdv) const;
    // pbrt-v4's IsRectangle: no two adjacent vertices equal, planar (to 1e-5) and the four vertices
    // equally far from their centre (to 1e-4 relative)
    bool rectangle() const;
    // pbrt-v4's area of a patch: exact for a rectangle, else the sum over a 3 x 3 grid of quads
    double area() const;
    // The differential areas |dp/du x dp/dv| at the corners: pbrt-v4's weights for sampling a patch
    // nearly uniformly by area (SampleBilinear)
    void corner_weights(double w[4]) const;
};

Patch patch_of(const Shape &s, unsigned prim);

// The hits of o + t d with patch q for t in (tnear, tfar], nearest first (at most two), and each one's
// (u, v). Returns their count.
int patch_hits(const Patch &q, Vec3 o, Vec3 d, double tnear, double tfar, double t[2], double uv[2][2]);

// The unit geometric normal of patch `prim` of s at (u, v), oriented as pbrt-v4 orients it:
// dp/du x dp/dv, towards the interpolated vertex normals if the mesh has them, else flipped by
// ReverseOrientation (and a transform that swaps handedness, folded into Shape::reverse_orientation).
Vec3 patch_normal(const Shape &s, unsigned prim, double u, double v);
// The vertex normals interpolated at (u, v) and normalized (zero if the mesh has none or they cancel).
Vec3 patch_shading_normal(const Shape &s, unsigned prim, double u, double v);
// The texture coordinates at (u, v): the mesh's uv interpolated, else (u, v).
void patch_texture_uv(const Shape &s, unsigned prim, double u, double v, double *su, double *sv);
// dp/ds and dp/dt with respect to those texture coordinates (pbrt-v4's, keeping the orientation of
// dp/du x dp/dv), or dp/du and dp/dv without a mesh uv.
void patch_texture_derivatives(const Shape &s, unsigned prim, double u, double v, Vec3 *dpds, Vec3 *dpdt);

// pbrt-v4's sampling of (u, v) in proportion to the bilinear interpolation of weights w (p00 p10 p01
// p11's), and its density.
void sample_bilinear(double u1, double u2, const double w[4], double *u, double *v);
double bilinear_pdf(double u, double v, const double w[4]);

}  // namespace udm1scene
