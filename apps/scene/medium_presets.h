// medium_presets.h - pbrt-v4's named scattering media ("string preset" of MakeNamedMedium): measured
// absorption and (reduced) scattering coefficients in mm^-1, in RGB, from Jensen, Marschner, Levoy and
// Hanrahan, "A Practical Model for Subsurface Light Transport" (SIGGRAPH 2001) and Narasimhan, Gupta,
// Donner, Ramamoorthi, Nayar and Jensen, "Acquiring Scattering Properties of Participating Media by
// Dilution" (SIGGRAPH 2006), as pbrt-v4 lists them (src/pbrt/media.cpp, GetMediumScatteringProperties).
#pragma once

#include "math.h"

#include <string>

namespace udm1scene {

// The preset of that name (pbrt-v4's spelling, case and spaces included): false if there is none.
// pbrt-v4 takes the reduced scattering coefficient sigma'_s as sigma_s; so does this.
bool medium_preset(const std::string &name, Vec3 *sigma_a, Vec3 *sigma_s);

// The presets' names, for messages ("Apple, Chicken1, ...").
std::string medium_preset_names();

}  // namespace udm1scene
