"""UDM1_RANDOMIZE_SCREEN with screen_spp = N, the fixed scheme (test_screen_progressive.py has N = 0):
pixel (x, y) takes points m N + n of one randomly shifted sequence, m its Morton index and N the samples
per pixel. Pinned: the Morton layout and the segments; each pixel unbiased over
seeds; bulk = per-sample = split; Weyl sequences only; and the point of it: the error image of a
per-pixel integral is blue noise (low screen frequencies carry less energy than white noise) at no cost
in MSE."""

import functools

import numpy as np
import pytest

import udm1


def stream(x, y):
    return (y << 32) | x


def test_pixel_takes_its_morton_segment_of_one_sequence():
    n_spp = 16
    seq = udm1.Sequence("wr", 2, seed=5, randomize="screen", screen_spp=n_spp)
    plain = udm1.Sequence("wr", 2, randomize=False)
    u = [int(seq.sample(0, j, stream=stream(0, 0), dtype=np.uint64)) for j in range(2)]  # pixel (0, 0), point 0
    # Morton: x in the even bits, y in the odd ones
    cases = {(1, 0): 1, (0, 1): 2, (1, 1): 3, (2, 0): 4, (3, 5): 39, (2**32 - 1, 0): 0x5555555555555555}
    for (x, y), m in cases.items():
        for n in (0, 7, 15):
            for j in range(2):
                v = int(seq.sample(n, j, stream=stream(x, y), dtype=np.uint64))
                index = (m * n_spp + n) % 2**64
                assert v == (u[j] + int(plain.sample(index, j, dtype=np.uint64))) % 2**64, (x, y, n, j)
    assert seq.randomization == "screen"


def test_bulk_equals_per_sample_and_split():
    seq = udm1.Sequence("wopt", 8, seed=3, randomize="screen", screen_spp=100)
    s = stream(17, 9)
    whole = seq.points(100, stream=s, dtype=np.uint64)
    parts = np.vstack([seq.points(37, stream=s, dtype=np.uint64), seq.points(63, first=37, stream=s, dtype=np.uint64)])
    assert np.array_equal(whole, parts)
    for n in (0, 1, 50, 99):
        for j in range(8):
            assert whole[n, j] == seq.sample(n, j, stream=s, dtype=np.uint64)


def test_each_pixel_unbiased_over_seeds():
    # a pixel's estimate of the area of a disk, 4 samples, over 4000 seeds: mean within 4 standard errors
    est = []
    for seed in range(2000):
        p = udm1.Sequence("wr", 2, seed=seed, randomize="screen", screen_spp=4).points(4, stream=stream(5, 7))
        est.append(np.mean((p[:, 0] - 0.5) ** 2 + (p[:, 1] - 0.5) ** 2 < 0.09))
    est = np.array(est)
    assert abs(est.mean() - np.pi * 0.09) < 4 * est.std() / np.sqrt(len(est))


def test_weyl_sequences_only_and_spp_only_with_screen():
    with pytest.raises(udm1.UDM1Error, match="Weyl"):
        udm1.Sequence("sobol", 2, randomize="screen", screen_spp=4)
    with pytest.raises(udm1.UDM1Error, match="Weyl"):
        udm1.Sequence("episwr", 2, point_count=4, randomize="screen", screen_spp=4)
    with pytest.raises(udm1.UDM1Error, match="Weyl"):
        udm1.Sequence("sobol", 2, randomize="screen")  # progressive (screen_spp 0): Weyl sequences too
    with pytest.raises(udm1.UDM1Error, match="screen_spp"):
        udm1.Sequence("wr", 2, randomize="shift", screen_spp=4)


SIZE = 32


def centre(x, y):
    return 0.5 + 0.2 * np.sin(x / 9), 0.5 + 0.2 * np.cos(y / 11)


@functools.lru_cache(maxsize=1)
def truth():
    g = (np.arange(400) + 0.5) / 400
    gx, gy = np.meshgrid(g, g)
    t = np.empty((SIZE, SIZE))
    for y in range(SIZE):
        for x in range(SIZE):
            cx, cy = centre(x, y)
            t[y, x] = np.mean((gx - cx) ** 2 + (gy - cy) ** 2 < 0.09)
    return t


def error_image(preset, randomize, seed, spp=4):
    """Per-pixel estimates of a disk's area whose centre drifts smoothly over the image, minus the truth."""
    seq = udm1.Sequence(preset, 2, seed=seed, randomize=randomize, screen_spp=spp if randomize == "screen" else 0)
    est = np.empty((SIZE, SIZE))
    for y in range(SIZE):
        for x in range(SIZE):
            cx, cy = centre(x, y)
            p = seq.points(spp, stream=stream(x, y))
            est[y, x] = np.mean((p[:, 0] - cx) ** 2 + (p[:, 1] - cy) ** 2 < 0.09)
    return est - truth()


def low_share(err):
    p = np.abs(np.fft.fftshift(np.fft.fft2(err - err.mean()))) ** 2
    n = err.shape[0]
    yy, xx = np.indices(p.shape) - n // 2
    r = np.hypot(xx, yy)
    return p[(r > 0) & (r < n / 8)].mean() / p[r > 0].mean()


@pytest.mark.release_only("a statistical check over many seeds; the other tests of this file run its code under the sanitizers")
@pytest.mark.parametrize("preset", ["wr", "wopt", "rd"])
def test_error_is_blue_noise_at_no_cost_in_mse(preset):
    shift = [error_image(preset, "shift", s) for s in range(1, 7)]
    screen = [error_image(preset, "screen", s) for s in range(1, 7)]
    low_shift, low_screen = np.mean([low_share(e) for e in shift]), np.mean([low_share(e) for e in screen])
    assert low_shift > 0.75  # independent shifts: white noise (1 on average)
    assert low_screen < 0.65 * low_shift, (low_shift, low_screen)
    mse_shift, mse_screen = np.mean([np.mean(e ** 2) for e in shift]), np.mean([np.mean(e ** 2) for e in screen])
    assert 0.8 < mse_screen / mse_shift < 1.25, (mse_shift, mse_screen)
