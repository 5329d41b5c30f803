/* embed_cursor.c - udm1 inside a renderer's pixel loop, pbrt-v4 style.
 *
 * A toy "renderer" estimates, for every pixel of a small image, the integral
 * over the pixel's area and over a 2D "light" domain of a smooth function. Each
 * sample asks the cursor for a 2D pixel offset and a 2D light sample, the way
 * pbrt-v4 calls Sampler::StartPixelSample, Get2D, Get2D. It prints the mean
 * absolute error against the exact integral for udm1's WR sequence and for a
 * plain hash-random sampler, so the two can be compared.
 *
 * Build: cc embed_cursor.c $(pkg-config --cflags --libs udm1) -lm
 */
#include <udm1/udm1.h>

#include <math.h>
#include <stdio.h>

#define W 16
#define H 16
#define SPP 64

/* f(x, y, u, v) = (1 + cos(2 pi u) x) (1 + sin(2 pi v) y) e^{-(u+v)}: exact integrals below. */
static double f(double x, double y, double u, double v)
{
    const double tau = 6.283185307179586;
    return (1.0 + cos(tau * u) * x) * (1.0 + sin(tau * v) * y) * exp(-(u + v));
}

static double exact_pixel(int px, int py)
{
    /* integral over [px/W, (px+1)/W] x [py/H, (py+1)/H] x [0,1]^2, divided by the pixel area */
    const double tau = 6.283185307179586, e1 = 1.0 - exp(-1.0);
    double cu = e1 / (1.0 + tau * tau);       /* int cos(2 pi u) e^-u du */
    double sv = tau * e1 / (1.0 + tau * tau); /* int sin(2 pi v) e^-v dv */
    double mx = (px + 0.5) / W, my = (py + 0.5) / H;
    return (e1 + cu * mx) * (e1 + sv * my);
}

static double render(const udm1_seq *seq)
{
    double err = 0.0;
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            uint64_t pixel = ((uint64_t)py << 32) | (uint32_t)px;
            double sum = 0.0;
            for (int s = 0; s < SPP; ++s) {
                udm1_cursor c;
                if (udm1_cursor_start(&c, seq, pixel, (uint64_t)s, 0) != UDM1_OK) {
                    fprintf(stderr, "embed_cursor: %s\n", udm1_last_error());
                    return -1.0;
                }
                double film[2], light[2];
                udm1_cursor_2d_f64(&c, film);  /* dimensions 0, 1 */
                udm1_cursor_2d_f64(&c, light); /* dimensions 2, 3 */
                sum += f((px + film[0]) / W, (py + film[1]) / H, light[0], light[1]);
            }
            err += fabs(sum / SPP - exact_pixel(px, py));
        }
    return err / (W * H);
}

int main(void)
{
    printf("udm1 %s\n", udm1_version_string());
    udm1_seq *wr = NULL, *pad = NULL;
    /* 4 dimensions of WR with a random shift per pixel */
    if (udm1_seq_create("wr", 4, 0, 1234, &wr) != UDM1_OK) {
        fprintf(stderr, "embed_cursor: %s\n", udm1_last_error());
        return 1;
    }
    /* a 1-dimensional set: the cursor pads dimensions 1..3 with hash-random values */
    if (udm1_seq_create("golden", 1, 0, 1234, &pad) != UDM1_OK) {
        fprintf(stderr, "embed_cursor: %s\n", udm1_last_error());
        udm1_seq_destroy(wr);
        return 1;
    }
    double e_wr = render(wr), e_pad = render(pad);
    printf("mean abs error per pixel, %d spp: wr %.3e, mostly random (padded) %.3e\n", SPP, e_wr, e_pad);
    udm1_seq_destroy(wr);
    udm1_seq_destroy(pad);
    return (e_wr >= 0.0 && e_pad >= 0.0 && e_wr < e_pad) ? 0 : 1;
}
