// scene_export.h - a loaded scene written out for other renderers: one binary PLY per
// triangle shape (world space) and a scene.json with the camera (eye, target, up, fov
// along the shorter axis), the film size, maxdepth, and per shape its file (and whether it has
// vertex normals) or sphere, material (its type and parameters: numbers, strings and booleans as
// they are, a texture as {"texture": name}, a sampled or blackbody spectrum as {"spectrum": numbers})
// and emission (area lights only: a scene with a LightSource is refused). bench/mitsuba_scene.py
// builds the same scene in Mitsuba 3 from it, so that both renderers read one parse.
#pragma once

#include "scene.h"

#include <string>

namespace udm1pt {

// Throws udm1app::Error naming the folder or file on failure.
void export_scene(const udm1scene::Scene &scene, int width, int height, int max_depth, const std::string &dir);

}  // namespace udm1pt
