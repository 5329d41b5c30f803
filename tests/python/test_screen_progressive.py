"""Progressive screen-space randomization (UDM1_RANDOMIZE_SCREEN with screen_spp = 0): pixel (x, y),
stream (y << 32) | x, keeps the sequence's own points, shifted by u_j(seed) + x G_j + y H_j (mod 2^64), the
screen generators G, H chosen per dimension pair from the sequence's generators (weyl/screen.c). Pinned:
the values against an independent transcription of the construction (reference.py); every prefix of a
pixel's samples is the same points whatever the render's length; bulk = per-sample = split; each pixel
unbiased over seeds; and the point of it: the error image is blue noise at every sample count, with the
MSE of per-pixel shifts."""

import numpy as np
import pytest

import reference
import udm1
from test_screen_randomization import low_share  # the error image's low-frequency share

M64 = (1 << 64) - 1


def stream(x, y):
    return (y << 32) | x


@pytest.mark.parametrize("preset,d", [("wr", 5), ("rd", 4), ("wopt", 2)])
def test_values_follow_the_contract(preset, d):
    seq = udm1.Sequence(preset, d, seed=9, randomize="screen")
    assert seq.randomization == "screen"
    plain = udm1.Sequence(preset, d, randomize=False)
    gens = reference.screen_generators([seq.alpha(j) >> 64 for j in range(d)])  # an odd d: a lone last dim
    u = [(seq.offset(j, stream(0, 0)) - plain.offset(j)) & M64 for j in range(d)]
    for x, y in [(0, 0), (1, 0), (0, 1), (3, 5), (2**32 - 1, 7), (12345, 2**32 - 1)]:
        for n in (0, 1, 17, 2**40 + 3, 2**64 - 1):
            for j in range(d):
                g, h = gens[j]
                want = (int(plain.sample(n, j, dtype=np.uint64)) + u[j] + x * g + y * h) & M64
                assert int(seq.sample(n, j, stream=stream(x, y), dtype=np.uint64)) == want, (preset, x, y, n, j)


def test_user_generators_take_the_same_construction():
    seq = udm1.Sequence(alphas=[udm1.Sqrt(2), udm1.Sqrt(13), udm1.Sqrt(7)], seed=4, randomize="screen")
    gens = reference.screen_generators([seq.alpha(j) >> 64 for j in range(3)])
    base = [int(seq.sample(0, j, stream=stream(0, 0), dtype=np.uint64)) for j in range(3)]
    for j in range(3):
        assert int(seq.sample(0, j, stream=stream(2, 3), dtype=np.uint64)) == (base[j] + 2 * gens[j][0] + 3 * gens[j][1]) & M64


def test_every_prefix_is_the_same_points_bulk_per_sample_split():
    seq = udm1.Sequence("wopt", 8, seed=3, randomize="screen")
    s = stream(17, 9)
    whole = seq.points(100, stream=s, dtype=np.uint64)
    for k in (1, 2, 7, 64):  # a k-sample render's points are the first k of a longer one's
        assert np.array_equal(seq.points(k, stream=s, dtype=np.uint64), whole[:k])
    parts = np.vstack([seq.points(37, stream=s, dtype=np.uint64), seq.points(63, first=37, stream=s, dtype=np.uint64)])
    assert np.array_equal(whole, parts)
    for n in (0, 1, 50, 99):
        for j in range(8):
            assert whole[n, j] == seq.sample(n, j, stream=s, dtype=np.uint64)
    at = seq.points_at(np.full(100, s, dtype=np.uint64), np.arange(100, dtype=np.uint64))
    assert np.array_equal(at, seq.points(100, stream=s))


@pytest.mark.release_only("a statistical check over many seeds; the other tests of this file run its code under the sanitizers")
def test_each_pixel_unbiased_over_seeds():
    # a pixel's estimate of the area of a disk, 3 samples, over 2000 seeds: mean within 4 standard errors
    est = []
    for seed in range(2000):
        p = udm1.Sequence("wr", 2, seed=seed, randomize="screen").points(3, stream=stream(5, 7))
        est.append(np.mean((p[:, 0] - 0.5) ** 2 + (p[:, 1] - 0.5) ** 2 < 0.09))
    est = np.array(est)
    assert abs(est.mean() - np.pi * 0.09) < 4 * est.std() / np.sqrt(len(est))


SIZE = 48


def disk_truth(cx, cy, r2=0.09, grid=300):
    g = (np.arange(grid) + 0.5) / grid
    gx, gy = np.meshgrid(g, g)
    return np.array([np.mean(((gx - a) % 1 - 0.5) ** 2 + ((gy - b) % 1 - 0.5) ** 2 < r2) for a, b in zip(cx, cy)])


YY, XX = np.indices((SIZE, SIZE))
CX, CY = (0.5 + 0.2 * np.sin(XX / 9)).ravel(), (0.5 + 0.2 * np.cos(YY / 11)).ravel()
TRUTH = disk_truth(CX, CY)
STREAMS = ((YY.astype(np.uint64) << np.uint64(32)) | XX.astype(np.uint64)).ravel()


def error_image(randomize, seed, spp, dims):
    """Per-pixel estimates of a disk's area (periodic, its centre drifting over the image) from dimensions
    `dims` of an 8-dimensional wr, minus the truth."""
    seq = udm1.Sequence("wr", 8, seed=seed, randomize=randomize)
    n = np.tile(np.arange(spp, dtype=np.uint64), len(STREAMS))
    p = seq.points_at(np.repeat(STREAMS, spp), n, dims=range(dims[0], dims[0] + 2)).reshape(len(STREAMS), spp, 2)
    inside = ((p[..., 0] - CX[:, None]) % 1 - 0.5) ** 2 + ((p[..., 1] - CY[:, None]) % 1 - 0.5) ** 2 < 0.09
    return (inside.mean(axis=1) - TRUTH).reshape(SIZE, SIZE)


@pytest.mark.parametrize("dims", [(0, 1), (4, 5)])
def test_error_is_blue_at_every_count_at_no_cost_in_mse(dims):
    for spp in (1, 2, 3, 5, 8, 13, 32):
        shift = [error_image("shift", s, spp, dims) for s in range(1, 6)]
        screen = [error_image("screen", s, spp, dims) for s in range(1, 6)]
        low_shift, low_screen = np.mean([low_share(e) for e in shift]), np.mean([low_share(e) for e in screen])
        assert low_shift > 0.75, (spp, low_shift)  # independent shifts: white noise (1 on average)
        assert low_screen < 0.6 * low_shift, (spp, low_shift, low_screen)
        mse_shift = np.mean([np.mean(e ** 2) for e in shift])
        mse_screen = np.mean([np.mean(e ** 2) for e in screen])
        assert 0.75 < mse_screen / mse_shift < 1.33, (spp, mse_shift, mse_screen)
