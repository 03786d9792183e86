// The Verilated RTL's sampling rate per compiled configuration (bench_rtl.cpp), for `make bench`.
#pragma once
#include <string>
#include <vector>

namespace bench {

// Registers one benchmark per configuration: "rtl_sampling/<configuration>". Each streams random
// trilinear requests through rtl::Driver with ideal timing after a backdoor load: the sampling
// phase alone, in samples/s and clocks/s (equal within 0.01% on chip; a cached configuration
// waits for its memory model, default timing, so there clocks/s is the simulator's speed).
std::vector<std::string> register_rtl_benchmarks(double min_time);

}  // namespace bench
