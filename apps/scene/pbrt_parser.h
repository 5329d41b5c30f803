// pbrt_parser.h - reading the subset of the pbrt-v4 format that udm1's scenes use.
#pragma once

#include "scene.h"

namespace udm1scene {

// Parse a .pbrt file (and its Includes and PLY meshes). Throws SceneError "file:line: ..." on
// malformed input, missing files, and (with Need::Everything) anything outside the supported subset.
Scene parse_pbrt(const std::string &path, Need need = Need::Everything);

}  // namespace udm1scene
