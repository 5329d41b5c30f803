// pbrt_noise.h - pbrt-v4's solid noise, as its procedural textures ("fbm", "wrinkled", "windy") and its
// "cloud" medium evaluate it: Perlin's improved noise over Ken Perlin's permutation (udm1's "perlin" noise
// table), with pbrt-v4's choice of gradient for a corner's hash (it differs from Perlin's reference in 2
// of its 16 directions, so the values differ from udm1_noise_3d's) and the quintic fade; the octave sums
// FBm and Turbulence with lacunarity 1.99.
// udm1's renderers trace no ray differentials: the sums take every octave up to the given count, where
// pbrt-v4 fades out the octaves finer than a pixel's footprint (and Turbulence counts each as its mean, 0.2).
#pragma once

#include "math.h"

namespace udm1scene {

// pbrt-v4's Noise(p): in [-1, 1], 0 at every lattice point.
double pbrt_noise(Vec3 p);
// pbrt-v4's FBm and Turbulence with a footprint smaller than every octave: octave i at frequency 1.99^i,
// weight omega^i; Turbulence sums |noise| and adds omega^octaves 0.2 for the octaves beyond.
double pbrt_fbm(Vec3 p, double omega, int octaves);
double pbrt_turbulence(Vec3 p, double omega, int octaves);
// pbrt-v4's "windy" texture: |FBm(p / 10, 0.5, 3)| FBm(p, 0.5, 6).
double pbrt_windy(Vec3 p);

}  // namespace udm1scene
