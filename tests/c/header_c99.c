/* header_c99.c - the public header compiles as strict C99 (-pedantic -Werror,
 * strict prototypes) and its functions link: built by the tests, then run. */
#include <udm1/udm1.h>

#include <stdio.h>

int main(void)
{
    udm1_seq *seq = NULL;
    udm1_cursor c;
    float v[2];
    if (udm1_seq_create("wr", 2, 0, 1, &seq) != UDM1_OK) return 1;
    if (udm1_cursor_start(&c, seq, 0, 0, 0) != UDM1_OK) return 1;
    udm1_cursor_2d(&c, v);
    printf("udm1 %s from C99: %f %f\n", udm1_version_string(), (double)v[0], (double)v[1]);
    /* the inline draws of udm1/stream.h and udm1/domain.h, compiled as C99 */
    udm1_stream st;
    float w[2], u[4];
    double x;
    if (udm1_stream_init(&st, seq, 0, 0, 2) != UDM1_OK) return 1;
    udm1_stream_draw_f32(&st, 0, 0, 2, w);
    udm1_domain_draw_f32(udm1_domain_child(udm1_domain_root(&st, 5), 1), 4, u);
    udm1_domain_draw_f64(udm1_domain_split(udm1_domain_root(&st, 5), 2, 4, 3), 1, &x);
    udm1_seq_destroy(seq);
    return (v[0] >= 0.0f && v[0] < 1.0f && w[0] == v[0] && w[1] == v[1] && u[3] >= 0.0f && x < 1.0) ? 0 : 1;
}
