// header_cxx.cpp - the public header compiles as C++ (-pedantic -Werror) and links.
#include <udm1/udm1.h>

#include <cstdio>
#include <memory>

int main()
{
    udm1_seq *raw = nullptr;
    if (udm1_seq_create("hwmmr", 22, 0, 3, &raw) != UDM1_OK) return 1;
    std::unique_ptr<udm1_seq, void (*)(udm1_seq *)> seq(raw, udm1_seq_destroy);
    double x = 0.0;
    if (udm1_seq_sample_f64(seq.get(), 0, 1000, 21, &x) != UDM1_OK) return 1;
    std::printf("udm1 %s from C++: %f\n", udm1_version_string(), x);
    // the inline draws of udm1/stream.h and udm1/domain.h, compiled as C++
    udm1_stream st;
    if (udm1_stream_init(&st, seq.get(), 0, 20, 2) != UDM1_OK) return 1;
    double y[2];
    float u[4];
    udm1_stream_draw_f64(&st, 1000, 1, 1, y);
    udm1_domain_draw_f32(udm1_domain_chain(udm1_domain_root(&st, 9), 3, 1), 4, u);
    return (x >= 0.0 && x < 1.0 && y[0] == x && u[0] >= 0.0f && u[3] < 1.0f) ? 0 : 1;
}
