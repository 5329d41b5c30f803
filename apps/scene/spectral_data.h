// spectral_data.h - the tables that gen/spectral_data.py writes at build time (spectral_data.cpp in the
// build tree): CIE 1931 colour matching functions and D65 at 1 nm over 360..830 nm, and pbrt-v4's named
// metal spectra and glasses' indices. Read through spectrum.h.
#pragma once

namespace udm1scene {
namespace spectral_data {

struct NamedData {
    const char *name;
    const double *pairs;  // (wavelength nm, value), count of them
    int count;
};
extern const double CIE_X[471], CIE_Y[471], CIE_Z[471], CIE_D65[471];
extern const NamedData NAMED[];  // ends with a null name
struct GlassIndex {
    const char *name;
    double eta_550;  // the index at 550 nm
};
extern const GlassIndex GLASSES[];  // ends with a null name

}  // namespace spectral_data
}  // namespace udm1scene
