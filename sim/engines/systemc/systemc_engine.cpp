// run_systemc: one SystemC simulation (target + testbench initiator) in a forked child process.
#include "engines/systemc/systemc_engine.h"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "engines/rtl/driver.h"
#include "engines/systemc/stream_initiator.h"
#include "engines/systemc/tex_unit_tlm.h"
#include "model/error.h"

// libsystemc.so defines main() and needs sc_main; texsim and the tests have their own main and
// start the simulation themselves, so this one is never called.
int sc_main(int, char*[]) {
  std::fprintf(stderr, "sc_main: not used; run the SystemC engine through tex::systemc::run_systemc\n");
  return 1;
}

namespace tex::systemc {

using namespace sc_core;

namespace {

// The --stalls profile of --engine rtl, applied per request (gap before BEGIN_REQ) and per
// response (END_RESP held); the rare long stalls of `random` are left to the RTL engine.
InitiatorTiming initiator_timing(const EngineOptions& o) {
  const rtl::Timing p = rtl::Timing::of(o.stalls);
  InitiatorTiming t;
  t.seed = o.seed;
  t.gap_prob = p.gap_prob;
  t.max_gap = p.max_gap;
  t.stall_prob = p.stall_prob;
  t.max_stall = p.max_stall;
  return t;
}

// Runs in the child: elaborate, load, stream, check.
EngineResult simulate(Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
                      const std::vector<Request>& requests, const SystemcOptions& o) {
  const bool at = o.initiator == InitiatorStyle::At || (o.initiator == InitiatorStyle::Auto && backend == Backend::Rtl);
  const sc_time period(o.clock_ns, SC_NS);
  const auto wall0 = std::chrono::steady_clock::now();
  TexUnitTlm unit("tex_unit_tlm", backend, pyramid, config, period, o.engine);
  StreamInitiator bench("testbench", requests, at, period, initiator_timing(o.engine));
  bench.socket.bind(unit.socket);
  const auto wall1 = std::chrono::steady_clock::now();

  run_stream(bench, requests.size(), period, o.timeout_cycles, o.engine.show_progress,
             [&unit] { return unit.error(); });
  const auto wall2 = std::chrono::steady_clock::now();
  if (unit.in_flight() != 0) throw Error("SystemC: requests still in flight after the last response");

  EngineResult r;
  r.texels = bench.texels();
  r.stats.engine = backend == Backend::Rtl ? "systemc" : "systemc-model";
  r.stats.samples = bench.counters().responses;
  r.stats.load_seconds = std::chrono::duration<double>(wall1 - wall0).count();
  r.stats.sample_seconds = std::chrono::duration<double>(wall2 - wall1).count();
  if (const rtl::Driver* d = unit.driver()) {
    const rtl::ProtocolCounters& pc = d->counters();
    CycleStats c;
    c.configuration = d->config().name;
    c.cycles = pc.cycles();
    c.latency_cycles = pc.latency_min;
    c.latency_max_cycles = pc.latency_max;
    c.output_stall_cycles = pc.output_stall_cycles;
    c.input_gap_cycles = bench.counters().gap_cycles;
    c.backpressure_cycles = pc.backpressure_cycles;
    c.load_cycles = d->load_cycles();
    r.stats.cycle = c;
  }
  return r;
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

void send_outcome(int fd, const std::string& error, const EngineResult& r) {
  const nlohmann::json head =
      error.empty() ? nlohmann::json{{"stats", r.stats.to_json(EngineOptions{})}} : nlohmann::json{{"error", error}};
  const std::string text = head.dump();
  const uint64_t len = text.size(), count = error.empty() ? r.texels.size() : 0;
  bool ok = write_all(fd, &len, sizeof len) && write_all(fd, text.data(), text.size()) &&
            write_all(fd, &count, sizeof count);
  if (ok && count) write_all(fd, r.texels.data(), count * sizeof(Texel));
}

class SystemcEngine final : public Engine {
 public:
  SystemcEngine(Backend backend, const EngineOptions& options) : backend_(backend) { options_.engine = options; }

  EngineResult run(const Pyramid& pyramid, const SamplerConfig& config, const std::vector<Request>& requests) override {
    return run_systemc(backend_, pyramid, config, requests, options_);
  }

 private:
  Backend backend_;
  SystemcOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_systemc_engine(Backend backend, const EngineOptions& options) {
  return std::make_unique<SystemcEngine>(backend, options);
}

EngineResult run_systemc(Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
                         const std::vector<Request>& requests, const SystemcOptions& options) {
  // Input errors are reported here, before any simulation, as one line.
  if (backend == Backend::Rtl) {
    const rtl::RtlConfig& rc =
        rtl::smallest_config_for(pyramid.log2_w0(), pyramid.log2_h0(), pyramid.levels[0].channel_bits);
    rtl::check_inputs(rc, pyramid, requests);
  } else if (!options.engine.trace_path.empty()) {
    throw Error("--trace: the model behind the SystemC socket has no waveforms (use --engine systemc)");
  }
  if (!(options.clock_ns > 0)) throw Error("SystemC clock period must be positive");
  return run_forked([&] { return simulate(backend, pyramid, config, requests, options); });
}

EngineResult run_forked(const std::function<EngineResult()>& simulation) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  std::fflush(nullptr);  // nothing buffered may be written twice
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw Error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // The child: a fresh SystemC kernel (the parent never touches SystemC). It ends with its parent.
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(1);
    ::close(fds[0]);
    ::setenv("SYSC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
    std::signal(SIGPIPE, SIG_IGN);
    EngineResult r;
    std::string error;
    try {
      r = simulation();
    } catch (const std::exception& e) {
      error = e.what();
    }
    send_outcome(fds[1], error, r);
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
  EngineResult r;
  r.texels.resize(count);
  if (count) take(r.texels.data(), count * sizeof(Texel));
  r.stats = EngineStats::from_json(head["stats"]);
  return r;
}

}  // namespace tex::systemc
