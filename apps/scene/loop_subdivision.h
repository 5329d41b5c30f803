// loop_subdivision.h - pbrt-v4's "loopsubdiv" shape: a triangle mesh refined `levels` times by Loop's rules
// at load time, then its vertices pushed to their limit positions, with the limit surface's normals as
// vertex normals (pbrt-v4's LoopSubdivide):
//   even (old) vertices   interior: (1 - n beta) p + beta sum(ring), beta = 3/16 for valence n = 3, else
//                         3 / (8 n); boundary: 3/4 p + 1/8 (its two boundary neighbours)
//   odd (edge) vertices   interior: 3/8 (both ends) + 1/8 (the two opposite vertices); boundary: the midpoint
//   limit positions       interior: the one-ring rule with gamma = 1 / (n + 3 / (8 beta)); boundary:
//                         3/5 p + 1/5 (its two boundary neighbours) (pbrt-v4's; not the boundary curve's
//                         own limit, 2/3 p + 1/6 of the neighbours, which refinement approaches)
//   limit normals         S x T, the tangents of the ring (interior: sum cos(2 pi j / n) ring_j and
//                         sum sin(2 pi j / n) ring_j; boundary: pbrt-v4's rules by valence)
// Everything happens in object space; the caller transforms the result.
#pragma once

#include "math.h"

#include <cstdint>
#include <string>
#include <vector>

namespace udm1scene {

struct LoopMesh {
    std::vector<Vec3> P, N;         // limit positions and (unnormalized) limit normals
    std::vector<uint32_t> indices;  // 3 per triangle, the control faces' orientation
};

// Subdivides the mesh (3 indices per face into P). Returns false with *why (one phrase) for a mesh the
// rules do not apply to: a face that repeats a vertex, an edge shared by more than two faces or by two
// faces that traverse it the same way (inconsistent orientation), a vertex whose faces do not form one
// fan. Vertices no face uses are dropped (the others keep their order, and their numbers if none is).
bool loop_subdivide(const std::vector<uint32_t> &indices, const std::vector<Vec3> &P, int levels, LoopMesh *out,
                    std::string *why);

}  // namespace udm1scene
