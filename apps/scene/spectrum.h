// spectrum.h - the spectra of a pbrt-v4 scene and the RGB that udm1's renderers use in their place.
// pbrt-v4 renders spectrally; udm1-pt renders in linear sRGB. A spectrum becomes the RGB that pbrt-v4's
// film (sensor "cie1931") would record for it: a light's spectrum at luminance 1 (pbrt-v4 normalizes a
// light to 1 nit before its "scale"), a reflectance as seen under pbrt-v4's white (D65, the RGB colour
// space's illuminant), and a metal's Fresnel reflectance, per channel and angle, as the spectral
// reflectance projected the same way (pt/material.h, FresnelTable). The CIE 1931 colour matching functions, D65 and the metals'
// measured indices are generated at build time (gen/spectral_data.py, from Mitsuba 3's copies).
#pragma once

#include "math.h"

#include <string>
#include <vector>

namespace udm1scene {

// A spectral distribution as pbrt-v4 evaluates it: (wavelength in nm, value) pairs, linear between them
// and zero outside them (PiecewiseLinearSpectrum), or Planck's law at `kelvin` (BlackbodySpectrum).
struct Spectrum {
    std::vector<double> nm, value;  // increasing wavelengths
    double kelvin = 0;              // > 0: a blackbody (nm and value empty)
    double at(double lambda) const;
    static Spectrum blackbody(double kelvin);
    static Spectrum constant(double v);  // over every wavelength (pbrt-v4's ConstantSpectrum)
};

// (wavelength, value) pairs as a pbrt-v4 "spectrum" parameter or .spd file lists them, checked: an
// even count, wavelengths increasing. Throws SceneError("where: what") otherwise.
Spectrum spectrum_from_pairs(const std::vector<double> &pairs, const std::string &where);

// One of pbrt-v4's named spectra that udm1 knows (the metals' "metal-X-eta" and "metal-X-k", and
// "stdillum-D65"), or nullptr. known_spectra() lists them, for messages.
const Spectrum *named_spectrum(const std::string &name);
std::string known_spectra();
// Whether pbrt-v4 knows a spectrum by this name (its spectrum.cpp: glasses, metals, standard illuminants, the
// cameras' sensor curves), held by udm1 or not: the names it does not hold are refused as such.
bool pbrt_v4_named_spectrum(const std::string &name);

// A spectrum file as pbrt-v4 reads it ("spds/..."): whitespace-separated (wavelength, value) pairs,
// '#' comments. Throws SceneError naming the file.
Spectrum read_spectrum_file(const std::string &path);

// XYZ of a spectrum, the integral of s(lambda) (x, y, z)(lambda) over 360..830 nm in 1 nm steps (as
// pbrt-v4 integrates), optionally weighted by D65.
Vec3 spectrum_xyz(const Spectrum &s, bool under_d65 = false);
// CIE XYZ to linear sRGB (Rec. 709 primaries, D65 white), and back.
Vec3 xyz_to_rgb(Vec3 xyz);
Vec3 rgb_to_xyz(Vec3 rgb);

// A light's spectrum as linear sRGB at luminance Y = 1 (negative components, of colours outside the
// sRGB gamut, clamped to 0). Throws SceneError(where) for a spectrum of no luminance.
Vec3 illuminant_rgb(const Spectrum &s, const std::string &where);
// A reflectance spectrum as the linear sRGB reflectance that pbrt-v4 would record under D65, after
// clamping it to [0, 1] at every wavelength as pbrt-v4's materials clamp a reflectance.
Vec3 albedo_rgb(const Spectrum &s);

// The same (unclamped: a metal's Fresnel reflectance, already in [0, 1]) for a reflectance given at every
// integer wavelength 360..830 nm (WAVELENGTHS values).
constexpr int WAVELENGTHS = 471;
Vec3 albedo_rgb(const double *at_each_nm);

// The RGB conversion's own inputs, for tests: the CIE tables at integer wavelengths (360..830 nm).
Vec3 cie_xyz_at(int nm);
double cie_d65_at(int nm);

}  // namespace udm1scene
