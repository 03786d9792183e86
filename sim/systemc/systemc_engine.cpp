// run_systemc: one SystemC simulation (target + testbench initiator) in a forked child process.
#include "systemc_engine.h"

#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "model/error.h"
#include "stream_initiator.h"
#include "tex_unit_tlm.h"

// libsystemc.so defines main() and needs sc_main; texsim and the tests have their own main and
// start the simulation themselves, so this one is never called.
int sc_main(int, char*[]) {
  std::fprintf(stderr, "sc_main: not used; run the SystemC engine through tex::systemc::run_systemc\n");
  return 1;
}

namespace tex::systemc {

using namespace sc_core;

namespace {

const char* backend_name(Backend b) { return b == Backend::Rtl ? "rtl" : "model"; }

// CPU seconds of this process: on a shared, loaded machine wall time says little about speed.
double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Outcome {
  std::string error;
  nlohmann::json stats;
  std::vector<Texel> texels;
};

// Runs in the child: elaborate, load, stream, check; never throws.
Outcome simulate(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                 const SystemcOptions& o) {
  Outcome out;
  try {
    const bool at = o.initiator == InitiatorStyle::At ||
                    (o.initiator == InitiatorStyle::Auto && o.backend == Backend::Rtl);
    const sc_time period(o.clock_ns, SC_NS);
    InitiatorTiming timing;
    timing.gap_prob = o.gap_prob;
    timing.max_gap = o.max_gap;
    timing.stall_prob = o.stall_prob;
    timing.max_stall = o.max_stall;
    timing.seed = o.seed;
    if (o.fault == Fault::BadLength) timing.bad_length_index = int64_t(o.fault_index);

    TexUnitTlm unit("tex_unit_tlm", o.backend, pyramid, config, period, o.seed, o.fault, o.fault_index);
    StreamInitiator bench("testbench", requests, at, unit, timing);
    bench.socket.bind(unit.socket);

    // Simulate in slices of clocks: between slices, errors, progress and the time-out are checked.
    const uint64_t slice = 4096;
    const auto wall0 = std::chrono::steady_clock::now();
    while (!unit.loaded() && unit.error().empty()) sc_start(double(slice) * period);
    const auto wall1 = std::chrono::steady_clock::now();
    const double cpu1 = cpu_seconds();
    const sc_time sampling_start = sc_time_stamp();
    uint64_t last_done = 0, idle_clocks = 0;
    while (!bench.done() && unit.error().empty()) {
      sc_start(double(slice) * period);
      const uint64_t done = bench.counters().responses;
      if (done != last_done) {
        last_done = done;
        idle_clocks = 0;
        if (o.show_progress)
          std::fprintf(stderr, "\rsystemc: %llu / %zu samples", (unsigned long long)done, requests.size());
      } else if ((idle_clocks += slice) > o.timeout_cycles) {
        throw Error("SystemC time-out: no response for tag " + std::to_string(done) + " (" +
                    std::to_string(requests.size() - done) + " of " + std::to_string(requests.size()) +
                    " owed) for " + std::to_string(idle_clocks) + " clocks, at " + sc_time_stamp().to_string() +
                    ": a response was lost");
      }
    }
    if (o.show_progress) std::fprintf(stderr, "\r%60s\r", "");
    const auto wall2 = std::chrono::steady_clock::now();
    const double sample_cpu_secs = cpu_seconds() - cpu1;
    const sc_time sampling_end = sc_time_stamp();
    // A few idle clocks more: a response that still comes out is a duplicate.
    if (bench.error().empty() && unit.error().empty() && o.backend == Backend::Rtl) sc_start(64.0 * period);
    if (!unit.error().empty()) throw Error(unit.error());
    if (!bench.error().empty()) throw Error(bench.error());
    if (unit.in_flight() != 0) throw Error("SystemC: requests still in flight after the last response");

    const double sample_secs = std::chrono::duration<double>(wall2 - wall1).count();
    const uint64_t cycles = bench.cycles();
    const uint64_t sim_clocks = uint64_t((sampling_end - sampling_start) / period + 0.5);
    const InitiatorCounters& ic = bench.counters();
    const TargetCounters& tc = unit.counters();
    out.stats = {{"engine", o.backend == Backend::Rtl ? "systemc" : "systemc-model"},
                 {"backend", backend_name(o.backend)},
                 {"initiator", at ? "at (nb_transport, pipelined)" : "lt (b_transport, quantum keeper)"},
                 {"clock_ns", o.clock_ns},
                 {"seed", o.seed},
                 {"random_timing", o.gap_prob > 0 || o.stall_prob > 0},
                 {"samples", ic.responses},
                 {"cycles", cycles},
                 {"samples_per_clock", cycles ? double(ic.responses) / double(cycles) : 0.0},
                 {"input_gap_cycles", ic.gap_cycles},
                 {"response_stall_cycles", ic.stall_cycles},
                 {"load_seconds", std::chrono::duration<double>(wall1 - wall0).count()},
                 {"sample_seconds", sample_secs},
                 {"sample_cpu_seconds", sample_cpu_secs},
                 {"samples_per_second", sample_secs > 0 ? double(ic.responses) / sample_secs : 0.0},
                 {"samples_per_cpu_second", sample_cpu_secs > 0 ? double(ic.responses) / sample_cpu_secs : 0.0}};
    if (o.backend == Backend::Rtl) {
      out.stats["rtl_configuration"] = "Vtex_unit_sc (MAX_LOG2_W = MAX_LOG2_H = 10, CW = 8, TAG_W = 16)";
      out.stats["latency_cycles"] = ic.latency_min;
      out.stats["latency_max_cycles"] = ic.latency_max;
      out.stats["load_cycles"] = tc.load_cycles;
      out.stats["rtl_cycles"] = tc.samples ? tc.last_response_cycle - tc.first_offer_cycle + 1 : 0;
      out.stats["rtl_backpressure_cycles"] = tc.backpressure_cycles;
      out.stats["rtl_response_stall_cycles"] = tc.response_stall_cycles;
      out.stats["simulated_clocks_per_second"] = sample_secs > 0 ? double(sim_clocks) / sample_secs : 0.0;
      out.stats["simulated_clocks_per_cpu_second"] = sample_cpu_secs > 0 ? double(sim_clocks) / sample_cpu_secs : 0.0;
    }
    out.texels = bench.texels();
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

// Child -> parent: [u64 length][JSON {"error"} or {"stats"}][u64 count][count x 4 x u16].
bool write_all(int fd, const void* data, size_t n) {
  const char* p = static_cast<const char*>(data);
  while (n > 0) {
    const ssize_t k = ::write(fd, p, n);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) return false;
    p += k;
    n -= size_t(k);
  }
  return true;
}

void send_outcome(int fd, const Outcome& o) {
  nlohmann::json head = o.error.empty() ? nlohmann::json{{"stats", o.stats}} : nlohmann::json{{"error", o.error}};
  const std::string text = head.dump();
  const uint64_t len = text.size(), count = o.error.empty() ? o.texels.size() : 0;
  bool ok = write_all(fd, &len, sizeof len) && write_all(fd, text.data(), text.size()) &&
            write_all(fd, &count, sizeof count);
  for (uint64_t i = 0; ok && i < count; ++i) ok = write_all(fd, o.texels[i].data(), sizeof(Texel));
}

}  // namespace

bool have_rtl_backend() {
#ifdef TEX_SYSTEMC_HAVE_RTL
  return true;
#else
  return false;
#endif
}

SystemcOptions systemc_options_for(Backend backend, const EngineOptions& options) {
  if (!options.trace_path.empty())
    throw Error("--trace is not supported by the SystemC engines; use --engine rtl --trace");
  SystemcOptions o;
  o.backend = backend;
  o.seed = options.seed;
  o.show_progress = options.show_progress;
  if (options.seed != 0 && backend == Backend::Rtl) {  // as --engine rtl: moderate random gaps and stalls
    o.gap_prob = 0.05;
    o.max_gap = 4;
    o.stall_prob = 0.05;
    o.max_stall = 8;
  }
  return o;
}

EngineResult run_systemc(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests,
                         const SystemcOptions& options) {
  // Input errors are reported here, before any simulation, as one line.
  if (options.backend == Backend::Rtl) {
    if (!have_rtl_backend())
      throw Error("this build has no Verilated RTL for --engine systemc (use --engine systemc-model)");
    if (pyramid.log2_w0() > TexUnitTlm::kRtlMaxLog2W || pyramid.log2_h0() > TexUnitTlm::kRtlMaxLog2H)
      throw Error("texture " + std::to_string(pyramid.levels[0].width) + "x" +
                  std::to_string(pyramid.levels[0].height) + " does not fit the SystemC RTL backend (at most " +
                  std::to_string(1 << TexUnitTlm::kRtlMaxLog2W) + "x" + std::to_string(1 << TexUnitTlm::kRtlMaxLog2H) +
                  "; use --engine systemc-model)");
    if (pyramid.levels[0].channel_bits != 8)
      throw Error("--engine systemc is built for 8-bit channels; this texture has " +
                  std::to_string(pyramid.levels[0].channel_bits) + "-bit channels (use --engine systemc-model)");
    for (size_t i = 0; i < requests.size(); ++i)
      if (requests[i].lod < -32768 || requests[i].lod > 32767)
        throw Error("request " + std::to_string(i) + ": lod " + std::to_string(requests[i].lod) +
                    "/256 is outside the 16-bit Q8.8 port of the RTL");
  }
  if (!(options.clock_ns > 0)) throw Error("SystemC clock period must be positive");

  int fds[2];
  if (::pipe(fds) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered may be written twice
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // The child: a fresh SystemC kernel (the parent never touches SystemC).
    ::close(fds[0]);
    ::setenv("SYSC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    std::signal(SIGPIPE, SIG_IGN);
    const Outcome o = simulate(pyramid, config, requests, options);
    send_outcome(fds[1], o);
    ::close(fds[1]);
    std::fflush(nullptr);
    ::_exit(0);  // skip the parent's atexit handlers and SystemC's teardown
  }

  ::close(fds[1]);
  std::string bytes;
  char buf[1 << 16];
  for (;;) {
    const ssize_t k = ::read(fds[0], buf, sizeof buf);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) break;
    bytes.append(buf, size_t(k));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }

  // Decode; anything short means the child died (an abort inside SystemC or Verilator).
  auto died = [&]() {
    if (WIFSIGNALED(status))
      return Error("the SystemC simulation process died with signal " + std::to_string(WTERMSIG(status)) +
                   " (see the messages above)");
    return Error("the SystemC simulation process ended without a result (exit status " +
                 std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "; see the messages above)");
  };
  size_t at = 0;
  auto take = [&](void* dst, size_t n) {
    if (bytes.size() - at < n) throw died();
    std::memcpy(dst, bytes.data() + at, n);
    at += n;
  };
  uint64_t len = 0, count = 0;
  take(&len, sizeof len);
  if (bytes.size() - at < len) throw died();
  const nlohmann::json head = nlohmann::json::parse(bytes.substr(at, len));
  at += len;
  if (head.contains("error")) throw Error(head["error"].get<std::string>());
  take(&count, sizeof count);
  if (count != requests.size())
    throw Error("SystemC: " + std::to_string(count) + " texels for " + std::to_string(requests.size()) + " requests");
  EngineResult r;
  r.texels.resize(count);
  for (uint64_t i = 0; i < count; ++i) take(r.texels[i].data(), sizeof(Texel));
  r.stats = head["stats"];
  return r;
}

}  // namespace tex::systemc
