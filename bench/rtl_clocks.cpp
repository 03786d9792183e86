// texunit_rtl_clocks: streams `make bench`'s RTL speed workload (bench_rtl.h) through compiled
// configurations and prints the clocks it took and the rate. Under callgrind (make bench-ir,
// scripts/rtl_instructions.sh) instructions are collected only while requests stream (callgrind
// client requests around it), so the instructions collected over the clocks printed are the
// simulator's instructions per clock: the same on any machine with this compiler, where clocks/s
// moves with the machine's load.
#include <CLI/CLI.hpp>
#include <valgrind/callgrind.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_rtl.h"
#include "engines/rtl/driver.h"
#include "model/error.h"

int main(int argc, char** argv) {
  std::string names;
  for (const tex::rtl::RtlConfig& c : tex::rtl::compiled_configs()) names += (names.empty() ? "" : ", ") + c.name;
  CLI::App app{"texunit_rtl_clocks: clocks and clocks/s of the Verilated RTL on make bench's random trilinear "
               "workload (instructions per clock: make bench-ir)"};
  std::vector<std::string> configs;
  int repeat = 4;
  std::string texture_name = "rgba8";
  app.add_option("configs", configs, "configurations (default: all): " + names);
  app.add_option("--texture", texture_name,
                 std::string("the texture: ") + bench::kRtlTextureNames +
                     " (all but rgba8: configurations with the block decoders and sRGB tables only)")
      ->capture_default_str();
  app.add_option("--repeat", repeat, "passes over the 65536 requests")->check(CLI::Range(1, 1000));
  bool list = false;
  app.add_flag("--list", list,
               "print the compiled configurations, one per line with the textures each takes, and exit");
  CLI11_PARSE(app, argc, argv);
  if (list) {
    for (const tex::rtl::RtlConfig& c : tex::rtl::compiled_configs()) {
      std::printf("%s", c.name.c_str());
      for (bench::RtlTexture t : bench::kRtlTextures)
        if (bench::config_takes(c, t)) std::printf(" %s", bench::rtl_texture_name(t));
      std::printf("\n");
    }
    return 0;
  }
  try {
    bench::RtlTexture texture;
    if (!bench::parse_rtl_texture(texture_name, texture))
      throw tex::Error("unknown --texture '" + texture_name + "' (" + bench::kRtlTextureNames + ")");
    for (const std::string& n : configs) {
      bool known = false;
      for (const tex::rtl::RtlConfig& c : tex::rtl::compiled_configs()) known |= n == c.name;
      if (!known) throw tex::Error("unknown configuration '" + n + "' (compiled: " + names + ")");
    }
    for (const tex::rtl::RtlConfig& c : tex::rtl::compiled_configs()) {
      bool wanted = configs.empty();
      for (const std::string& n : configs) wanted |= n == c.name;
      if (!wanted || (configs.empty() && !bench::config_takes(c, texture))) continue;
      bench::RtlWorkload work = bench::make_rtl_workload(c, texture);
      uint64_t clocks = 0, samples = 0, sink = 0;
      const auto start = std::chrono::steady_clock::now();
      CALLGRIND_TOGGLE_COLLECT;
      for (int i = 0; i < repeat; ++i) {
        const tex::rtl::StreamStats st =
            tex::rtl::stream(*work.unit, work.requests.data(), work.requests.size(), tex::rtl::Timing{}, 7,
                             [&](size_t, uint64_t rgba) { sink += rgba; });
        clocks += st.cycles();
        samples += st.samples();
      }
      CALLGRIND_TOGGLE_COLLECT;
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("%s %s: %llu samples in %llu clocks, %.3f M clocks/s (checksum %llx)\n", c.name.c_str(),
                  bench::rtl_texture_name(texture),
                  (unsigned long long)samples, (unsigned long long)clocks, double(clocks) / seconds / 1e6,
                  (unsigned long long)sink);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texunit_rtl_clocks: %s\n", e.what());
    return 1;
  }
  return 0;
}
