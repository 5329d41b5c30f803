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
    return (x >= 0.0 && x < 1.0) ? 0 : 1;
}
