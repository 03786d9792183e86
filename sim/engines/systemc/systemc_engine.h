// `texsim --engine systemc` / `--engine systemc-model`: the requests through the SystemC/TLM-2.0
// texture unit (tex_unit_tlm.h) driven by the streaming testbench initiator (stream_initiator.h).
// Plain C++: no SystemC header here, so the C++20 rest of the project can include it (Debian's
// SystemC 2.3.4 links only with C++17; the SystemC translation units are built as C++17).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "engines/engine.h"

namespace tex::systemc {

enum class Backend {
  Rtl,    // the Verilated tex_unit; approximately timed (nb_transport)
  Model,  // the golden model tex::Sampler; loosely timed (b_transport), one clock per sample annotated
};

// How the testbench talks to the socket. Auto = At for the RTL backend, Lt for the model.
// The other combinations go through simple_target_socket's b<->nb adapters (slower, same texels).
enum class InitiatorStyle { Auto, Lt, At };

struct SystemcOptions {
  EngineOptions engine;  // stalls, seed, load method, trace, progress
  InitiatorStyle initiator = InitiatorStyle::Auto;
  double clock_ns = 10.0;           // clock period of the RTL (and the model's per-sample annotation)
  uint64_t timeout_cycles = 20000;  // clocks without a response while some are owed
};

std::unique_ptr<Engine> make_systemc_engine(Backend backend, const EngineOptions& options);

// One SystemC simulation (target + testbench initiator) in a forked child process: SystemC
// elaborates once per process, and the fork lets texsim render several frames and the tests run
// many cases. Texels come back in request order. Throws tex::Error with the simulation's one-line
// error (tag mismatch, time-out, bad input).
// The requests stream from `source` into the child through a pipe and the texels come back through
// another, so memory does not grow with the number of requests.
EngineStats run_systemc(Backend backend, const TextureTable& textures, const SamplerTable& samplers,
                        RequestSource& source, TexelSink& sink, const SystemcOptions& options);
// One texture, one sampler.
EngineStats run_systemc(Backend backend, const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                        TexelSink& sink, const SystemcOptions& options);
EngineResult run_systemc(Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
                         const std::vector<Request>& requests, const SystemcOptions& options);

// Runs `simulation` in a forked child process: requests from `source` (each chunk passed to
// `check` in the parent first) go to the child's source, texels from the child's sink to `sink`.
// An exception in the child becomes a tex::Error (tex::SimulationError if it was one) with its
// message in the parent; the child is killed if the parent fails (a bad request, a sink error).
// The child's `misses` and `clocks` sinks (never null) carry line addresses and response clocks
// back to `misses` and `clocks` in the parent (dropped when those are null).
using Simulation =
    std::function<EngineStats(RequestSource& source, TexelSink& sink, MissSink& misses, ClockSink& clocks)>;
EngineStats run_forked(RequestSource& source, TexelSink& sink, const Simulation& simulation,
                       const std::function<void(const Request*, size_t)>& check = [](const Request*, size_t) {},
                       MissSink* misses = nullptr, ClockSink* clocks = nullptr);
// For tests that build their own platform: no requests in, the result's texels out.
EngineResult run_forked(const std::function<EngineResult()>& simulation);

}  // namespace tex::systemc
