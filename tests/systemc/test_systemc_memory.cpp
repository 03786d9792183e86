// Cached memory through SystemC (docs/systemc.md): the texture unit's TLM-2.0 memory socket wired to
// a memory target. Both backends give the golden model's texels and the model's miss stream; the
// RTL behind the socket runs at the Verilator harness's samples/clock under the same memory
// timing; texels really come over the bus (a corrupted byte in the target shows in the samples; an
// error status flags the samples that read the line in the RTL backend, as the model predicts, and
// stops the model backend); the debug transport reads the unit's memory view.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <memory>
#include <random>

#include "engines/engine.h"
#include "engines/rtl/rtl_engine.h"
#include "engines/systemc/memory_target.h"
#include "engines/systemc/stream_initiator.h"
#include "engines/systemc/systemc_engine.h"
#include "engines/systemc/tex_unit_tlm.h"
#include "model/image.h"
#include "model/memory_layout.h"
#include "model/srgb.h"
#include "stimulus.h"
#include "workloads/scenes.h"
#include "workloads/texture_io.h"

using namespace tex;
using namespace tex::systemc;

namespace {

struct Workload {
  Pyramid pyramid;
  SamplerConfig config;
  std::vector<Request> requests;
};

Workload plane(int width, int height, const std::string& texture, PixelOrder order = PixelOrder::Scanline) {
  SceneOptions so;
  so.width = width;
  so.height = height;
  so.order = order;
  const SceneFrame frame = make_scene("plane", so);
  Workload w;
  w.pyramid = build_pyramid(load_texture(texture), PyramidMode::Exact);
  w.requests = to_requests(frame.queries, "plane");
  return w;
}

EngineOptions cached(uint32_t latency, int kib = 2) {
  EngineOptions o;
  o.memory = Memory::Cached;
  o.cache.size_bytes = kib * 1024;
  o.mem_latency = latency;
  return o;
}

struct Misses final : MissSink {
  void write(const uint32_t* a, size_t n) override { lines.insert(lines.end(), a, a + n); }
  std::vector<uint32_t> lines;
};

// The golden model's texels and miss stream.
EngineResult model_run(const Workload& w, EngineOptions o, Misses& misses) {
  o.miss_sink = &misses;
  return run_collected(w.requests, [&](RequestSource& s, TexelSink& t) {
    return run_model(w.pyramid, w.config, s, t, o);
  });
}

// A platform built here: the unit and a memory target whose image `corrupt` may change, at
// `target_base` (the layout's base when equal).
EngineResult custom_platform(Backend backend, const Workload& w, const EngineOptions& o,
                             const std::function<void(std::vector<uint8_t>&)>& corrupt, uint64_t target_base) {
  return run_forked([&] {
    const sc_core::sc_time period(10, sc_core::SC_NS);
    VectorSource source(w.requests);
    VectorSink sink;
    TexUnitTlm unit("unit", backend, w.pyramid, w.config, period, o);
    StreamInitiator bench("bench", source, sink, backend == Backend::Rtl, period, InitiatorTiming{});
    bench.socket.bind(unit.socket);
    const MemoryLayout layout(w.pyramid.extent0(), w.pyramid.levels[0].channel_bits, o.layout);
    std::vector<uint8_t> image = build_memory_image(w.pyramid, layout);
    corrupt(image);
    MemoryTarget memory("memory", image, target_base, period, MemoryTargetTiming{});
    unit.memory_socket.bind(memory.socket);
    run_stream(bench, period, 20000, false, [&unit] { return unit.error(); });
    unit.finish();
    if (!unit.error().empty()) throw SimulationError(unit.error());
    EngineResult r;
    r.texels = sink.texels;
    r.stats.memory_error_samples = bench.flagged();
    return r;
  });
}

struct Debugger : sc_core::sc_module {
  tlm_utils::simple_initiator_socket<Debugger> socket{"socket"};
  explicit Debugger(sc_core::sc_module_name name) : sc_module(name) {}
};

}  // namespace

TEST(SystemcMemory, RtlBehindTheSocketRunsAtTheVerilatorHarnesssSpeed) {
  const Workload w = plane(160, 120, "testcard:256x256");
  for (uint32_t latency : {40u, 300u}) {
    Misses model_misses, rtl_misses, sc_misses;
    const EngineResult model = model_run(w, cached(latency), model_misses);
    EngineOptions o = cached(latency);
    o.miss_sink = &rtl_misses;
    const EngineResult harness = rtl::make_rtl_engine(o)->run(w.pyramid, w.config, w.requests);
    SystemcOptions so;
    so.engine = cached(latency);
    so.engine.miss_sink = &sc_misses;
    const EngineResult sc = run_systemc(Backend::Rtl, w.pyramid, w.config, w.requests, so);
    EXPECT_EQ(sc.texels, model.texels) << "latency " << latency;
    ASSERT_GT(model_misses.lines.size(), 500u);
    EXPECT_EQ(sc_misses.lines, model_misses.lines) << "latency " << latency;
    EXPECT_EQ(rtl_misses.lines, model_misses.lines);
    // The memory target's latency and bandwidth are the harness's: samples/clock within 1 %.
    const double a = harness.stats.samples_per_clock(), b = sc.stats.samples_per_clock();
    EXPECT_LT(b, 0.999) << "the workload must make the memory matter";
    EXPECT_NEAR(b, a, 0.01 * a) << "latency " << latency;
    // While the target's outstanding-read limit does not bind, the same clocks to within one (a
    // response and a clock edge at the same time may run in either order); with it, a read held
    // before END_REQ is already taken from the RTL's point of view: within the 1 %.
    if (latency < 64 * 4) {
      EXPECT_LE(std::llabs(int64_t(sc.stats.cycle->cycles) - int64_t(harness.stats.cycle->cycles)), 1);
    }
    ASSERT_TRUE(sc.stats.cache);
    EXPECT_EQ(sc.stats.cache->misses, model_misses.lines.size());
  }
}

TEST(SystemcMemory, ModelBehindTheSocketReadsTheModelsLines) {
  const Workload w = plane(96, 64, "testcard:128x64", PixelOrder::Tiled);
  Misses model_misses, sc_misses;
  const EngineResult model = model_run(w, cached(100, 1), model_misses);
  SystemcOptions so;
  so.engine = cached(100, 1);
  so.engine.miss_sink = &sc_misses;
  const EngineResult sc = run_systemc(Backend::Model, w.pyramid, w.config, w.requests, so);
  EXPECT_EQ(sc.texels, model.texels);
  ASSERT_GT(model_misses.lines.size(), 100u);
  EXPECT_EQ(sc_misses.lines, model_misses.lines);
}

TEST(SystemcMemory, TexelsComeOverTheBus) {
  const Workload w = plane(96, 64, "testcard:64x64");
  const EngineOptions o = cached(50);
  Misses misses;
  const EngineResult model = model_run(w, o, misses);
  const MemoryLayout layout({64, 64}, 8, o.layout);
  // Planted: every byte of the first line read flipped in the target's memory.
  const uint32_t first = misses.lines.at(0);
  auto corrupt = [&](std::vector<uint8_t>& image) {
    for (int i = 0; i < layout.line_bytes(); ++i) image[first + uint32_t(i)] ^= 0x5A;
  };
  for (Backend b : {Backend::Rtl, Backend::Model}) {
    const EngineResult clean = custom_platform(b, w, o, [](std::vector<uint8_t>&) {}, 0);
    EXPECT_EQ(clean.texels, model.texels);
    const EngineResult bad = custom_platform(b, w, o, corrupt, 0);
    size_t differ = 0;
    for (size_t i = 0; i < bad.texels.size(); ++i) differ += bad.texels[i] != model.texels[i];
    EXPECT_GT(differ, 0u) << (b == Backend::Rtl ? "rtl" : "model") << " does not use the bytes it reads";
    // A target that answers every read with an error status (its memory elsewhere): the RTL flags
    // every sample (TLM_GENERIC_ERROR_RESPONSE, texel 0) and keeps running; the loosely timed model
    // stops the run, naming the line.
    if (b == Backend::Rtl) {
      const EngineResult flagged = custom_platform(b, w, o, [](std::vector<uint8_t>&) {}, uint64_t(1) << 30);
      EXPECT_EQ(flagged.stats.memory_error_samples.size(), w.requests.size());
      EXPECT_EQ(flagged.texels, std::vector<Texel>(w.requests.size(), Texel{}));
      continue;
    }
    try {
      custom_platform(b, w, o, [](std::vector<uint8_t>&) {}, uint64_t(1) << 30);
      ADD_FAILURE() << "an address error was not reported";
    } catch (const SimulationError& e) {
      EXPECT_NE(std::string(e.what()).find("TLM_ADDRESS_ERROR_RESPONSE"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("line " + rtl::hex_address(first)), std::string::npos) << e.what();
    }
  }
}

// --mem-error-at through the socket: the memory target answers its 4th and 30th reads with
// TLM_GENERIC_ERROR_RESPONSE, the RTL flags exactly the samples the golden model flags (its texels
// 0, the others the model's), in order, under random stalls.
TEST(SystemcMemory, ErrorResponsesFlagTheModelsSamples) {
  const Workload w = plane(96, 64, "testcard:128x128", PixelOrder::Tiled);
  EngineOptions o = cached(60);
  o.stalls = Stalls::Random;
  o.mem_error_reads = {4, 30};
  Misses misses;
  const EngineResult model = model_run(w, o, misses);
  ASSERT_GT(model.stats.memory_error_samples.size(), 0u);
  SystemcOptions so;
  so.engine = o;
  const EngineResult sc = run_systemc(Backend::Rtl, w.pyramid, w.config, w.requests, so);
  EXPECT_EQ(sc.stats.memory_error_samples, model.stats.memory_error_samples);
  EXPECT_EQ(sc.texels, model.texels);
}

TEST(SystemcMemory, DebugTransportReadsTheUnitsMemoryView) {
  const Workload w = plane(16, 16, "noise:64x32");
  for (Memory m : {Memory::OnChip, Memory::Cached})
    for (Backend b : {Backend::Rtl, Backend::Model}) {
      EngineOptions o;
      o.memory = m;
      const EngineResult r = run_forked([&] {
        const sc_core::sc_time period(10, sc_core::SC_NS);
        TexUnitTlm unit("unit", b, w.pyramid, w.config, period, o);
        std::unique_ptr<MemoryTarget> memory;
        if (m == Memory::Cached) {
          const MemoryLayout layout({64, 32}, 8, o.layout);
          memory = std::make_unique<MemoryTarget>("memory", build_memory_image(w.pyramid, layout), 0, period,
                                                  MemoryTargetTiming{});
          unit.memory_socket.bind(memory->socket);
        }
        Debugger debugger("debugger");
        debugger.socket.bind(unit.socket);
        sc_core::sc_start(sc_core::SC_ZERO_TIME);
        EngineResult out;
        // Level 1 (32x16), row 5, texels 3..10; then past the row's end (refused: 0 bytes).
        std::vector<uint16_t> data(4 * 8);
        tlm::tlm_generic_payload t;
        t.set_command(tlm::TLM_READ_COMMAND);
        t.set_address(texel_debug_address(1, 3, 5));
        t.set_data_ptr(reinterpret_cast<unsigned char*>(data.data()));
        t.set_data_length(8 * 8);
        out.stats.samples = debugger.socket->transport_dbg(t);
        for (int i = 0; i < 8; ++i) out.texels.push_back({data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]});
        t.set_address(texel_debug_address(1, 30, 5));
        out.stats.texel_reads = debugger.socket->transport_dbg(t);
        return out;
      });
      const std::string what = std::string(m == Memory::Cached ? "cached " : "onchip ") + (b == Backend::Rtl ? "rtl" : "model");
      EXPECT_EQ(r.stats.samples, 64u) << what;
      EXPECT_EQ(r.stats.texel_reads, 0u) << what;
      for (int i = 0; i < 8; ++i) EXPECT_EQ(r.texels.at(size_t(i)), w.pyramid.levels[1].at(3 + i, 5)) << what << " texel " << i;
    }
}

TEST(SystemcMemory, ExamplePlatformRuns) {
  for (const char* args : {"--backend rtl --memory cached", "--backend model --memory cached", "--backend rtl --memory onchip"}) {
    const std::string cmd = std::string(PLATFORM_PATH) + " --width 64 --height 48 " + args + " > platform.txt 2>&1";
    ASSERT_EQ(std::system(cmd.c_str()), 0) << args;
    std::ifstream in("platform.txt");
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("all bit-identical to the golden model"), std::string::npos) << text;
  }
  std::remove("platform.txt");
}

// A frame as a real one binds it: nine textures in the descriptor table (RGBA8 with sides that are
// not powers of two, BC1 sRGB, BC7, RGBA8 sRGB, ETC2 RGBA8, an RGBA8 array of 3 layers, a cube array
// of 2 cubes of 12 x 12 faces, ASTC 6x6 sRGB and ASTC 12x10, EAC RG11 signed and R11) and seven random samplers, random requests over them (tests/common/stimulus.h;
// the cube's: cube_request's directions, a quarter of them with derivatives), the memory jittering.
// Both backends give the golden model's texels and its miss stream, in order.
TEST(SystemcMemory, DescriptorAndSamplerTablesOfMixedFormats) {
  std::vector<Pyramid> pyramids;
  pyramids.push_back(build_pyramid(stimulus::random_image(61, 37, 8, 1), PyramidMode::Exact));
  pyramids.push_back(stimulus::random_block_texture(TexelFormat::Bc1, {64, 32}, 2));
  decode_srgb_levels(pyramids.back());
  pyramids.push_back(stimulus::random_block_texture(TexelFormat::Bc7, {32, 32}, 3));
  pyramids.push_back(build_srgb_pyramid(stimulus::random_image(16, 64, 8, 4), PyramidMode::Exact));
  pyramids.push_back(stimulus::random_block_texture(TexelFormat::Etc2Rgba, {32, 16}, 5));
  TextureTable table;
  std::vector<Extent> sizes;
  for (const Pyramid& p : pyramids) {
    table.push_back({&p});
    sizes.push_back(p.extent0());
  }
  const std::vector<Pyramid> layers = stimulus::random_layers({23, 40}, 3, 6);  // and an array of 3 layers
  std::vector<const Pyramid*> array = stimulus::pointers_to(layers);
  table.push_back({array[0], {array.begin() + 1, array.end()}});
  sizes.push_back(layers[0].extent0());
  const std::vector<Pyramid> faces = stimulus::random_layers({12, 12}, 12, 7);  // and a cube array
  std::vector<const Pyramid*> cube = stimulus::pointers_to(faces);
  table.push_back(BoundTexture(cube[0], {cube.begin() + 1, cube.end()}, TextureKind::Cube));
  sizes.push_back(faces[0].extent0());
  std::vector<Pyramid> astc;  // and ASTC, sRGB and linear, and EAC
  astc.push_back(stimulus::random_block_texture(TexelFormat::Astc6x6, {64, 40}, 8));
  decode_srgb_levels(astc.back());
  astc.push_back(stimulus::random_block_texture(TexelFormat::Astc12x10, {37, 64}, 9));
  astc.push_back(stimulus::random_block_texture(TexelFormat::EacRg11Snorm, {40, 24}, 10));  // (EAC's 16-bit channels)
  astc.push_back(stimulus::random_block_texture(TexelFormat::EacR11, {16, 64}, 11));
  for (const Pyramid& p : astc) {
    table.push_back({&p});
    sizes.push_back(p.extent0());
  }
  std::mt19937_64 rng(5);
  SamplerTable samplers;
  for (int i = 0; i < 7; ++i) samplers.push_back(stimulus::random_sampler(rng));
  samplers[6].unnormalized = false;  // (the cube's requests' sampler)
  std::vector<Request> requests = stimulus::random_requests(rng, sizes, samplers.size(), 3000);
  stimulus::fetches_and_gathers_among(rng, requests, 16, [&](int t) { return sizes[size_t(t)]; });
  stimulus::layers_among(rng, requests, [&](int t) { return table[size_t(t)].layers(); });
  stimulus::compares_among(rng, requests, 16, samplers, [&](int t) { return table[size_t(t)].pyramid->depth_problem().empty(); });
  int cube_requests = 0;
  for (Request& q : requests)
    if (q.texture == 6) {
      q = stimulus::cube_request(rng, q, 12, faces[0].last_level(), 12);
      q.sampler = 6;
      if (q.op == Op::Compare && !samplers[6].compare_problem().empty()) q.op = Op::Sample;
      ++cube_requests;
    }
  ASSERT_GT(cube_requests, 200);  // (3000 requests over 11 textures)
  EngineOptions o = cached(60, 4);
  o.mem_jitter = 40;
  o.seed = 9;
  Misses want_misses;
  o.miss_sink = &want_misses;
  const EngineResult want = run_collected(requests, [&](RequestSource& s, TexelSink& t) {
    return make_engine("model", o)->run(table, samplers, s, t);
  });
  ASSERT_EQ(want.texels.size(), requests.size());
  for (Backend b : {Backend::Rtl, Backend::Model}) {
    const char* name = b == Backend::Rtl ? "systemc" : "systemc-model";
    Misses got_misses;
    SystemcOptions so;
    so.engine = o;
    so.engine.miss_sink = &got_misses;
    const EngineResult got = run_collected(requests, [&](RequestSource& s, TexelSink& t) {
      return run_systemc(b, table, samplers, s, t, so);
    });
    ASSERT_EQ(got.texels.size(), requests.size()) << name;
    size_t bad = 0;
    for (size_t i = 0; i < requests.size(); ++i)
      if (got.texels[i] != want.texels[i] && bad++ < 3)
        ADD_FAILURE() << name << ": request " << i << " (texture " << int(requests[i].texture) << ", sampler "
                      << int(requests[i].sampler) << ") differs from the model";
    EXPECT_EQ(bad, 0u) << name;
    EXPECT_EQ(got_misses.lines, want_misses.lines) << name << ": the lines read, in order";
    if (b == Backend::Rtl) {
      ASSERT_TRUE(got.stats.cycle);
      EXPECT_EQ(got.stats.cycle->configuration, "Vtex_cached_13x13");
    }
  }
}
