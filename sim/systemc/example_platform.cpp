// A minimal SystemC virtual platform with the texture unit (docs/systemc.md): an initiator that
// streams sample requests, the texture unit (RTL or golden model behind a TLM-2.0 target socket)
// and, in cached mode, a memory target that holds the texture and answers the unit's cache-line
// reads on its TLM-2.0 initiator socket:
//
//   StreamInitiator --socket--> TexUnitTlm --memory_socket--> MemoryTarget (latency, bandwidth)
//
// Build: part of `make build` (build/texsim_platform). Run: build/texsim_platform --help.
// Every sample is checked against the golden model; the summary gives samples per clock and what
// the caches did.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <memory>

#include "engines/engine.h"
#include "engines/systemc/memory_target.h"
#include "engines/systemc/stream_initiator.h"
#include "engines/systemc/systemc_engine.h"
#include "engines/systemc/tex_unit_tlm.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "workloads/scenes.h"
#include "workloads/texture_io.h"

using namespace tex;
using namespace tex::systemc;

int main(int argc, char** argv) {
  CLI::App app{"texsim_platform: the texture unit in a minimal SystemC/TLM-2.0 platform (docs/systemc.md)"};
  std::string scene = "plane", texture = "testcard:256x256", backend_name = "rtl", memory_name = "cached";
  int width = 320, height = 240;
  uint32_t latency = 200, bytes_per_clock = 16, cache_kib = 8;
  app.add_option("--scene", scene, "scene whose pixels make the requests (texsim render --help lists them)")
      ->capture_default_str();
  app.add_option("--texture", texture, "image file or pattern NAME[:WxH]")->capture_default_str();
  app.add_option("--width", width, "scene width")->capture_default_str();
  app.add_option("--height", height, "scene height")->capture_default_str();
  app.add_option("--backend", backend_name, "rtl | model: what sits behind the unit's socket")->capture_default_str();
  app.add_option("--memory", memory_name, "onchip | cached: with cached, the unit reads a memory target")
      ->capture_default_str();
  app.add_option("--mem-latency", latency, "memory target: clocks from a read to its response")->capture_default_str();
  app.add_option("--mem-bytes-per-clock", bytes_per_clock, "memory target: bandwidth")->capture_default_str();
  app.add_option("--cache-kib", cache_kib, "size of each cache in KiB")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  try {
    if (backend_name != "rtl" && backend_name != "model") throw Error("--backend " + backend_name + " is not rtl or model");
    const Backend backend = backend_name == "rtl" ? Backend::Rtl : Backend::Model;
    EngineOptions options;
    if (!parse_memory(memory_name, options.memory)) throw Error("--memory " + memory_name + " is not onchip or cached");
    options.cache.size_bytes = int(cache_kib) * 1024;

    // The workload: one request per pixel of the scene, and the texture's pyramid.
    SceneOptions so;
    so.width = width;
    so.height = height;
    const SceneFrame frame = make_scene(scene, so);
    const Pyramid pyramid = build_pyramid(scene_texture(frame, texture), PyramidMode::Exact);
    SamplerConfig config;
    config.wrap_u = config.wrap_v = frame.clamp_edges ? Wrap::Clamp : Wrap::Repeat;
    const std::vector<Request> requests = to_requests(frame.queries, scene);

    // SystemC elaborates once per process: the platform runs in a child process (run_forked),
    // which also keeps a failure inside the simulation from taking this process down.
    const EngineResult result = run_forked([&] {
      const sc_core::sc_time period(10, sc_core::SC_NS);  // 100 MHz
      VectorSource source(requests);
      VectorSink sink;
      TexUnitTlm unit("texture_unit", backend, pyramid, config, period, options);
      StreamInitiator initiator("initiator", source, sink, /*approximately_timed=*/backend == Backend::Rtl, period,
                                InitiatorTiming{});
      initiator.socket.bind(unit.socket);
      std::unique_ptr<MemoryTarget> memory;
      if (options.memory == Memory::Cached) {
        const MemoryLayout layout = layout_of(pyramid, options.layout);
        MemoryTargetTiming timing;
        timing.latency = latency;
        timing.bytes_per_clock = bytes_per_clock;
        memory = std::make_unique<MemoryTarget>("memory", build_memory_image(pyramid, layout), options.layout.base,
                                                period, timing);
        unit.memory_socket.bind(memory->socket);
      }
      run_stream(initiator, period, 100000, false, [&unit] { return unit.error(); });
      unit.finish();
      if (!unit.error().empty()) throw SimulationError(unit.error());
      EngineResult r;
      r.texels = sink.texels;
      r.stats.engine = backend_name;
      r.stats.samples = initiator.counters().responses;
      if (const rtl::Driver* d = unit.driver()) {
        CycleStats c;
        c.cycles = d->counters().cycles();
        c.latency_cycles = d->counters().latency_min;
        r.stats.cycle = c;
      }
      if (const TextureCache* cache = unit.cache()) r.stats.cache = cache_counters(*cache);
      return r;
    });

    // Every sample against the golden model.
    const EngineResult model = run_model(pyramid, config, requests);
    size_t differ = 0;
    for (size_t i = 0; i < requests.size(); ++i) differ += result.texels.at(i) != model.texels[i];
    if (differ) throw Error(std::to_string(differ) + " samples differ from the golden model");
    std::printf("texsim_platform: %zu samples of scene %s through the %s backend, %s memory, all bit-identical to the "
                "golden model",
                requests.size(), scene.c_str(), backend_name.c_str(), memory_name.c_str());
    if (result.stats.cycle) std::printf(", %.4f samples/clock", result.stats.samples_per_clock());
    if (result.stats.cache)
      std::printf(", %.2f%% cache hits, %.2f bytes/sample from the memory target",
                  100.0 * double(result.stats.cache->hits) / double(result.stats.cache->lookups),
                  double(result.stats.cache->memory_read_bytes) / double(requests.size()));
    std::printf("\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texsim_platform: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
