/* main.c - the consumer project's program: prints a few WR points. */
#include <udm1/udm1.h>

#include <stdio.h>

int main(void)
{
    udm1_seq *seq = NULL;
    double pts[8];
    if (udm1_seq_create("wr", 2, 0, 7, &seq) != UDM1_OK) {
        fprintf(stderr, "consumer: %s\n", udm1_last_error());
        return 1;
    }
    if (udm1_seq_fill_f64(seq, 0, 0, 4, 0, 2, pts, 2) != UDM1_OK) return 1;
    for (int i = 0; i < 4; ++i) printf("%.6f %.6f\n", pts[2 * i], pts[2 * i + 1]);
    udm1_seq_destroy(seq);
    printf("consumer ok, udm1 %s\n", udm1_version_string());
    return 0;
}
