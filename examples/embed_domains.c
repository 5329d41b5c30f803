/* embed_domains.c - udm1 inside a renderer: one stream per pixel, a domain per sub-problem.
 *
 * A toy path "renderer" estimates, for every pixel of a small image, an integral over the pixel's area and
 * over two scattering events, each with a 2D light sample and a 2D direction. Nothing here counts
 * dimensions: the camera draws from the pixel's root domain, each event from the child domain of its
 * depth. The stream is filled once per pixel; every draw is inline arithmetic (udm1/stream.h,
 * udm1/domain.h). It prints the mean absolute error against the exact integral for udm1's R_d and for a
 * sampler whose every draw is independent, so the two can be compared.
 *
 * Build: cc embed_domains.c $(pkg-config --cflags --libs udm1) -lm
 */
#include <udm1/udm1.h>

#include <math.h>
#include <stdio.h>

#define W 16
#define H 16
#define SPP 64
#define EVENTS 2

/* g(u, v) = (1 + cos(2 pi u) / 2)(1 + v^2): mean over [0,1]^2 is 4/3 */
static double g(double u, double v) { return (1.0 + 0.5 * cos(6.283185307179586 * u)) * (1.0 + v * v); }

/* the integrand: a pixel-dependent film weight times each event's light and direction terms */
static double f(double x, double y, double u[EVENTS][4])
{
    double w = 1.0 + 0.5 * x * y;
    for (int e = 0; e < EVENTS; ++e) w *= g(u[e][0], u[e][1]) * g(u[e][2], u[e][3]) / (16.0 / 9.0);
    return w;
}

static double exact_pixel(int px, int py)
{
    double mx = (px + 0.5) / W, my = (py + 0.5) / H; /* x y is bilinear: its pixel mean is mx my */
    return 1.0 + 0.5 * mx * my;
}

static double render(const udm1_seq *seq)
{
    double err = 0.0;
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            udm1_stream pixel; /* once per pixel: its randomization, ready for inline draws */
            if (udm1_stream_init(&pixel, seq, ((uint64_t)py << 32) | (uint32_t)px, 0, 4) != UDM1_OK) {
                fprintf(stderr, "embed_domains: %s\n", udm1_last_error());
                return -1.0;
            }
            double sum = 0.0;
            for (int s = 0; s < SPP; ++s) {
                udm1_domain root = udm1_domain_root(&pixel, (uint64_t)s);
                double film[2], u[EVENTS][4];
                udm1_domain_draw_f64(root, 2, film); /* the camera */
                for (int e = 0; e < EVENTS; ++e)     /* each event its own domain: light and direction */
                    udm1_domain_draw_f64(udm1_domain_child(root, 1 + (uint64_t)e), 4, u[e]);
                sum += f((px + film[0]) / W, (py + film[1]) / H, u);
            }
            err += fabs(sum / SPP - exact_pixel(px, py));
        }
    return err / (W * H);
}

int main(void)
{
    printf("udm1 %s, kernels %s\n", udm1_version_string(), udm1_isa());
    udm1_seq *rd = NULL, *rnd = NULL;
    if (udm1_seq_create("rd", 4, 0, 1234, &rd) != UDM1_OK || udm1_seq_create("pcg32", 4, 0, 1234, &rnd) != UDM1_OK) {
        fprintf(stderr, "embed_domains: %s\n", udm1_last_error());
        udm1_seq_destroy(rd);
        return 1;
    }
    double e_rd = render(rd), e_rnd = render(rnd);
    printf("mean abs error per pixel, %d spp, %d dimensions: rd %.3e, pcg32 (independent) %.3e\n", SPP,
           2 + 4 * EVENTS, e_rd, e_rnd);
    udm1_seq_destroy(rd);
    udm1_seq_destroy(rnd);
    return (e_rd >= 0.0 && e_rnd >= 0.0 && e_rd < e_rnd) ? 0 : 1;
}
