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
    udm1_seq_destroy(seq);
    return (v[0] >= 0.0f && v[0] < 1.0f) ? 0 : 1;
}
