// color.h - the RGB stand-ins for pbrt-v4's spectral quantities that the scenes use.
#pragma once

#include "math.h"

namespace udm1scene {

// Linear sRGB (Rec. 709 primaries, D65 white) of a blackbody at kelvin (1667..25000 K), scaled to
// luminance Y = 1, as pbrt-v4 normalizes "blackbody L" before its scale. The chromaticity comes from
// Kim et al.'s cubic fit of the Planckian locus (2002), the matrix from XYZ to linear sRGB; RGB
// components a saturated colour would make negative are clamped to 0.
Vec3 blackbody_rgb(double kelvin);

}  // namespace udm1scene
