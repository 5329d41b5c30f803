// mesh_io.h - triangle meshes from PLY (ASCII and binary, either byte order) and OBJ files.
#pragma once

#include "scene.h"

namespace udm1scene {

// Append the triangles of a PLY file to `shape` (positions, and normals and uv where present),
// transformed by `xf`; polygons are split into fans. Throws SceneError naming the file (a missing or
// truncated file, an index out of range, an unsupported property type).
void read_ply(const std::string &path, const Mat4 &xf, Shape *shape);

// The same for a Wavefront OBJ file (v, vn, vt, f with any of its index forms; other statements are
// skipped). Errors name the file and line.
void read_obj(const std::string &path, const Mat4 &xf, Shape *shape);

}  // namespace udm1scene
