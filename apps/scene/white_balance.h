// white_balance.h - pbrt-v4's white balance of its default film sensor ("cie1931", whose values are CIE XYZ):
// Film "whitebalance" T adapts the colours of an illuminant of temperature T to the RGB colour space's white
// (D65) by the von Kries transform in Bradford's cone space, as pbrt-v4's PixelSensor does. The source white
// is the chromaticity of pbrt-v4's illuminant for T: the CIE daylight locus at the correlated colour temperature
// T * 1.4388 / 1.4380 from 4000 K up (pbrt-v4 builds the CIE D spectrum there, whose chromaticity is that point of
// the locus up to the rounding of the CIE basis tables), Planck's law below (integrated with the CIE 1931 tables
// at 1 nm, as pbrt-v4 integrates it). The target white is that of the D65 table udm1 renders under.
#pragma once

#include "math.h"

namespace udm1scene {

// The chromaticity (x, y) of pbrt-v4's white-balance illuminant of temperature `kelvin` (above).
void white_balance_source(double kelvin, double *x, double *y);

// The white balance for temperature `kelvin` as a matrix on linear sRGB (out[r] = dot(rows[r], rgb)): sRGB from
// XYZ, times the Bradford adaptation, times XYZ from sRGB. False where it is not finite (a temperature so low
// that Planck's law underflows).
bool white_balance_rgb(double kelvin, Vec3 rows[3]);

}  // namespace udm1scene
