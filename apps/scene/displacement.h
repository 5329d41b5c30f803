// displacement.h - pbrt-v4's displaced "plymesh" ("texture displacement", "float edgelength"; pbrt-v4's
// TriQuadMesh::Displace), done at load time as pbrt-v4 does it:
//   refine     every triangle's longest edge is split at its midpoint, recursively, until every edge is shorter
//              than edgelength measured in world space; an edge is split once for both its triangles (the mesh
//              stays watertight); the midpoint's normal is the normalized sum of its ends', its uv their mean
//   displace   every vertex moves along its normal by the float texture's value at (its object-space point, its uv)
//   normals    recomputed from the displaced faces: each vertex the normalized sum of its faces' unit normals
// A mesh without vertex normals gets the faces' (the same rule) before refining. Everything is in object space,
// in float as pbrt-v4 keeps it; only the edge lengths are measured after the world transform.
#pragma once

#include "math.h"

#include <cstdint>
#include <functional>
#include <vector>

namespace udm1scene {

struct DisplacedMesh {
    std::vector<float> P, N, UV;    // 3, 3 and 2 per vertex, object space
    std::vector<uint32_t> indices;  // 3 per triangle
};

// Refines and displaces mesh in place. height(p, u, v) is the displacement texture's value at an object-space point
// and its uv. mesh.UV must hold one uv per vertex (pbrt-v4 refuses a displaced mesh without); edgelength > 0.
void displace_mesh(DisplacedMesh &mesh, const Mat4 &world_from_object, double edgelength,
                   const std::function<double(const Vec3 &p, double u, double v)> &height);

// Each vertex's normal: the normalized sum of the unit normals of its faces (degenerate faces add nothing; a vertex
// of none keeps 0). pbrt-v4's TriQuadMesh::ComputeNormals.
void face_normals(DisplacedMesh &mesh);

}  // namespace udm1scene
