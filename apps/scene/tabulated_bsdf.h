// tabulated_bsdf.h - pbrt-v4's measured BSDF files ("string filename" of Material "measured"): RGL's tabulated
// BSDFs (Dupuy and Jakob 2018, "An adaptive parameterization for efficient material acquisition and
// rendering"), stored as a "tensor file": the 12 bytes "tensor_file\0", version 1.0, a field count (uint32),
// then per field its name (uint16 length and bytes), rank (uint16), type (uint8: 1..10 = uint8, int8, uint16,
// int16, uint32, int32, uint64, int64, float16, float32, float64), offset of its data in the file (uint64) and
// its size along each axis (uint64 each), all little-endian; the data C-ordered at the offsets.
//
// The fields pbrt-v4's MeasuredBxDF reads, with the types and shapes it asks for (others, such as "rgb", are
// skipped as it skips them):
//   theta_i, phi_i      float32 [T], [P]: the incident directions' elevation and azimuth (radians) at which the
//                       4D tables are tabulated (increasing); P <= 2 means the material is isotropic
//   ndf, sigma          float32 [h][w]: the microfacet normals' density D and the projected area sigma(w),
//                       over (sqrt(theta / (pi / 2)), phi / (2 pi) + 1/2) in [0, 1]^2 (w along the first)
//   vndf                float32 [P][T][h][w]: the visible normals' density for each incident direction, in the
//                       same coordinates (the azimuth relative to the incident one where isotropic)
//   luminance           float32 [P][T][H][W]: a density over the unit square warped by vndf, for sampling
//   spectra             float32 [P][T][L][H][W]: the BSDF's spectral factor at L wavelengths, over that square
//   wavelengths         float32 [L] (nm, increasing); description uint8 [n]; jacobian uint8 [1]
// Anything else is refused: a file that is not a tensor file, another version, a field missing or of another
// type or shape, data outside the file, a value that is not finite, a density (ndf, vndf, luminance) below 0, a
// slice of vndf or luminance that is 0 everywhere, a projected area (sigma) not above 0, axes not increasing, an
// anisotropic table that does not span the whole circle (pbrt-v4's "reduction"). Spectra may be negative
// (pbrt-v4 clamps the interpolated value at 0; RGB below).
//
// udm1-pt renders in RGB: the spectra become `rgb`, three tables [P][T][H][W] (one per channel), each entry
// the linear sRGB that pbrt-v4's film records under D65 for the spectrum pbrt-v4 interpolates between the
// table's wavelengths (linearly, the end values beyond them), after clamping each tabulated value at 0
// (udm1scene::albedo_rgb, unclamped above: a BSDF value is not a reflectance).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace udm1scene {

struct TabulatedBsdf {
    std::string path;
    std::vector<float> theta_i, phi_i, wavelengths;
    bool isotropic = true;
    // each table row-major, h rows of w values; the 4D and 5D ones slice by slice
    int ndf_w = 0, ndf_h = 0, sigma_w = 0, sigma_h = 0, vndf_w = 0, vndf_h = 0, w = 0, h = 0;  // (w, h: luminance and spectra)
    std::vector<float> ndf, sigma, vndf, luminance, spectra;
    std::vector<float> rgb[3];
    uint64_t digest = 0;  // FNV-1a of the file's bytes (Scene::digest)
};

// Reads and checks the tensor file at path (plain, as pbrt-v4 reads it). Throws SceneError "path: what".
std::shared_ptr<const TabulatedBsdf> read_tabulated_bsdf(const std::string &path);

}  // namespace udm1scene
