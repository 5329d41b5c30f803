// builtin.h - scenes built in code, so the renderers run with no files:
//   cornell  the Cornell box of ../shared/scenes/cornell-box (same numbers, same camera)
//   plane    a large floor seen from above, nothing else (ambient occlusion = 1)
//   box      a closed box with the camera inside (ambient occlusion = 0)
//   wall     a floor meeting a tall, wide wall (ambient occlusion 1/2 at the wall's foot)
//   furnace      the inside of a sphere that emits L = 1 (both sides) and reflects 0.5: radiance
//                L / (1 - a) = 2 everywhere (the path tracer's furnace test; no edges, so light
//                sampling has finite variance)
//   furnace-box  the same with a closed box (edges: light sampling converges slowly there)
#pragma once

#include "scene.h"

namespace udm1scene {

Scene builtin_scene(const std::string &name);
std::vector<std::string> builtin_names();

// A scene around one mesh file (.ply/.obj): a grey diffuse material and a camera that frames it.
Scene mesh_scene(const std::string &path);

}  // namespace udm1scene
