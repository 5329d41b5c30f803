// surface.h - what a hit knows of the surface it is on, for every kind of shape: pbrt-v4's texture
// coordinates, the shading normal (interpolated vertex normals where the mesh has them), dp/du and dp/dv
// (for bump and normal maps), and the point at which textures are looked up. A hit through an object
// instance (Hit::instance) is read in its shape's space and answered in the world's.
#pragma once

#include "embree_scene.h"
#include "scene.h"
#include "textures.h"

namespace udm1scene {

// The texture coordinates of a hit: a mesh's per-vertex uv interpolated, else pbrt-v4's defaults
// ((0,0), (1,0), (1,1) per triangle; a bilinear patch's (u, v); quadrics by their parametrization in
// their object space, quadrics.h).
void hit_uv(const Shape &shape, const Hit &h, double *u, double *v);

// The unit shading normal: vertex normals interpolated where the mesh has them, else the geometric one.
Vec3 interpolated_normal(const Shape &shape, const Hit &h);
inline Vec3 shading_normal(const Shape &shape, const Hit &h) { return shape.N.empty() ? h.ng : interpolated_normal(shape, h); }

// dp/du and dp/dv of the texture coordinates at the hit (pbrt-v4's: a triangle's from its uv, or a frame
// around n where the uv are degenerate; a patch's with respect to its texture coordinates; a quadric's).
void surface_derivatives(const Shape &shape, const Hit &h, Vec3 n, Vec3 *dpdu, Vec3 *dpdv);

// Where textures are looked up at the hit: its point, geometric normal and texture coordinates.
TexturePoint texture_point(const Shape &shape, const Hit &h);

}  // namespace udm1scene
