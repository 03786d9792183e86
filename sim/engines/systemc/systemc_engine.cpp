// run_systemc: one SystemC simulation (target + testbench initiator) in a forked child process.
#include "engines/systemc/systemc_engine.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <shared_mutex>
#include <nlohmann/json.hpp>

#include "engines/rtl/driver.h"
#include "engines/systemc/stream_initiator.h"
#include "engines/systemc/memory_target.h"
#include "engines/systemc/tex_unit_tlm.h"
#include "engines/streams.h"
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
EngineStats simulate(Backend backend, const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                     TexelSink& sink, MissSink& misses, ClockSink& clocks, const SystemcOptions& o) {
  const bool at = o.initiator == InitiatorStyle::At || (o.initiator == InitiatorStyle::Auto && backend == Backend::Rtl);
  const sc_time period(o.clock_ns, SC_NS);
  const auto wall0 = std::chrono::steady_clock::now();
  EngineOptions eo = o.engine;
  eo.miss_sink = &misses;
  eo.clock_sink = o.engine.clock_sink ? &clocks : nullptr;  // (the parent's sink, through the pipe)
  TexUnitTlm unit("tex_unit_tlm", backend, textures, samplers, period, eo);
  StreamInitiator bench("testbench", source, sink, at, period, initiator_timing(o.engine));
  bench.socket.bind(unit.socket);
  // Cached: the frame's memory image (every texture at its descriptor's layout) in a TLM memory
  // target with the --mem-* timing.
  std::unique_ptr<MemoryTarget> memory;
  if (eo.memory == Memory::Cached) {
    MemoryTargetTiming timing;
    timing.latency = eo.mem_latency;
    timing.jitter = eo.mem_jitter;
    timing.seed = eo.seed ^ 0x9E3779B97F4A7C15ULL;
    timing.bytes_per_clock = eo.mem_bytes_per_clock;
    timing.max_outstanding = eo.mem_outstanding;
    timing.error_reads = eo.mem_error_reads;
    memory = std::make_unique<MemoryTarget>("memory", frame_memory_image(textures, texture_descriptors(textures, eo)),
                                            eo.layout.base, period, timing);
    unit.memory_socket.bind(memory->socket);
  }
  const auto wall1 = std::chrono::steady_clock::now();

  run_stream(bench, period, o.timeout_cycles, o.engine.show_progress, [&unit] { return unit.error(); });
  unit.finish();
  if (!unit.error().empty()) throw SimulationError(unit.error());
  const auto wall2 = std::chrono::steady_clock::now();
  if (unit.in_flight() != 0) throw SimulationError("SystemC: requests still in flight after the last response");

  EngineStats r;
  r.engine = backend == Backend::Rtl ? "systemc" : "systemc-model";
  r.samples = bench.counters().responses;
  r.load_seconds = std::chrono::duration<double>(wall1 - wall0).count();
  r.sample_seconds = std::chrono::duration<double>(wall2 - wall1).count();
  r.memory_error_samples = bench.flagged();
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
    r.cycle = c;
  }
  if (const TextureCache* cache = unit.cache()) {
    CacheCounters k = cache_counters(*cache);
    if (const rtl::Driver* d = unit.driver()) {
      k.fifo_depth = eo.fifo_depth ? eo.fifo_depth : uint32_t(d->config().fifo_depth);
      k.fifo_max_occupancy = d->memory_counters().fifo_max;
      k.memory_stall_cycles = d->memory_counters().head_wait_cycles;
    }
    r.cache = k;
  }
  return r;
}

// ---------------------------------------------------------------- parent <-> child
// Parent -> child: the requests as raw structs (same binary), then end of file.
// Child -> parent: frames [type][u64 length][bytes]: 'T' texels, 'M' line addresses, 'C' response
// clocks, then one 'S' (stats JSON) or 'E' (error JSON: message, and whether it is a simulation
// failure).

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

bool send_frame(int fd, char type, const void* data, uint64_t n) {
  return write_all(fd, &type, 1) && write_all(fd, &n, sizeof n) && (n == 0 || write_all(fd, data, n));
}

// The child's view of the requests: read from the pipe, whole structs only.
class PipeSource final : public RequestSource {
 public:
  explicit PipeSource(int fd) : fd_(fd) {}
  size_t read(Request* out, size_t max) override {
    char* dst = reinterpret_cast<char*>(out);
    const size_t want = max * sizeof(Request);
    size_t have = 0;
    while (have < sizeof(Request) || have % sizeof(Request) != 0) {
      const ssize_t k = ::read(fd_, dst + have, want - have);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) break;
      have += size_t(k);
    }
    return have / sizeof(Request);
  }

 private:
  int fd_;
};

// The child's sinks: each write is one frame of its type to the parent ('T' texels, 'M' line
// addresses, 'C' response clocks).
template <char Type, class Sink, class T>
class PipeFrames final : public Sink {
 public:
  explicit PipeFrames(int fd) : fd_(fd) {}
  void write(const T* items, size_t n) override {
    if (!send_frame(fd_, Type, items, n * sizeof(T))) throw Error("SystemC: the parent process went away");
  }

 private:
  int fd_;
};
using PipeSink = PipeFrames<'T', TexelSink, Texel>;
using PipeMissSink = PipeFrames<'M', MissSink, uint32_t>;
using PipeClockSink = PipeFrames<'C', ClockSink, uint64_t>;

[[noreturn]] void run_child(int request_fd, int result_fd, const Simulation& simulation) {
  ::setenv("SYSC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  std::signal(SIGPIPE, SIG_IGN);
  PipeSource source(request_fd);
  PipeSink sink(result_fd);
  PipeMissSink misses(result_fd);
  PipeClockSink clocks(result_fd);
  nlohmann::json outcome;
  try {
    outcome["stats"] = simulation(source, sink, misses, clocks).to_json(EngineOptions{});
  } catch (const SimulationError& e) {
    outcome = {{"error", e.what()}, {"simulation", true}};
  } catch (const std::exception& e) {
    outcome = {{"error", e.what()}, {"simulation", false}};
  }
  const std::string text = outcome.dump();
  send_frame(result_fd, outcome.contains("error") ? 'E' : 'S', text.data(), text.size());
  ::close(result_fd);
  std::fflush(nullptr);
#if defined(__SANITIZE_ADDRESS__)
  // (make test-sanitize: ASan's _exit runs LeakSanitizer, which hangs in a child forked from a
  // threaded parent and would count the parent's memory as the child's leaks: the system call.)
  ::syscall(SYS_exit_group, 0);
#endif
  ::_exit(0);  // skip the parent's atexit handlers, destructors and SystemC's teardown
}

class SystemcEngine final : public Engine {
 public:
  SystemcEngine(Backend backend, const EngineOptions& options) : backend_(backend) { options_.engine = options; }

  EngineStats run(const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                  TexelSink& sink) override {
    return run_systemc(backend_, pyramid, config, source, sink, options_);
  }
  EngineStats run(const TextureTable& textures, const SamplerTable& samplers, RequestSource& source,
                  TexelSink& sink) override {
    return run_systemc(backend_, textures, samplers, source, sink, options_);
  }

 private:
  Backend backend_;
  SystemcOptions options_;
};

}  // namespace

std::unique_ptr<Engine> make_systemc_engine(Backend backend, const EngineOptions& options) {
  return std::make_unique<SystemcEngine>(backend, options);
}

EngineStats run_systemc(Backend backend, const TextureTable& textures, const SamplerTable& samplers,
                        RequestSource& source, TexelSink& sink, const SystemcOptions& options) {
  // Input errors are reported here, before any simulation, as one line.
  const EngineOptions& eo = options.engine;
  const bool cached = eo.memory == Memory::Cached;
  check_tables(textures, samplers, eo.memory);
  if (cached) TextureCache(texture_descriptors(textures, eo), eo.cache, samplers);  // the layouts and caches fit
  if (backend == Backend::Rtl) {
    const rtl::RtlConfig& rc = rtl::smallest_config_for(textures, eo.memory, eo.layout.block_w, eo.layout.block_h,
                                                        &eo.cache, eo.fifo_depth);
    for (const BoundTexture& t : textures) rtl::check_inputs(rc, *t.pyramid);
    if (cached) rtl::cache_pins(rc, eo.layout, eo.cache, eo.fifo_depth);
    if (cached && eo.mem_bytes_per_clock > uint32_t(rc.mem_bits / 8))  // as the RTL engine's memory channel
      throw Error("--mem-bytes-per-clock " + std::to_string(eo.mem_bytes_per_clock) + ": " + rc.name +
                  "'s memory port carries 1 to " + std::to_string(rc.mem_bits / 8) + " bytes per clock (one beat)");
  } else if (!options.engine.trace_path.empty()) {
    throw Error("--trace: the model behind the SystemC socket has no waveforms (use --engine systemc)");
  }
  if (!(options.clock_ns > 0)) throw Error("SystemC clock period must be positive");
  // Requests are checked against the tables and the RTL's ports in the parent, as they are read.
  size_t index = 0;
  auto check = [&](const Request* r, size_t n) {
    for (size_t i = 0; i < n; ++i) {
      check_request_tables(r[i], textures.size(), samplers.size());
      if (backend == Backend::Rtl) rtl::check_request(r[i], index + i);
    }
    index += n;
  };
  // The child waits for memory as long as the longest read may take, then some.
  SystemcOptions o = options;
  if (cached) o.timeout_cycles = std::max<uint64_t>(o.timeout_cycles, 10000 + 2 * uint64_t(eo.mem_latency + eo.mem_jitter));
  return run_forked(source, sink, [&](RequestSource& s, TexelSink& t, MissSink& m, ClockSink& c) {
    return simulate(backend, textures, samplers, s, t, m, c, o);
  }, check, eo.miss_sink, eo.clock_sink);
}

EngineStats run_systemc(Backend backend, const Pyramid& pyramid, const SamplerConfig& config, RequestSource& source,
                        TexelSink& sink, const SystemcOptions& options) {
  return run_systemc(backend, TextureTable{{&pyramid}}, SamplerTable{config}, source, sink, options);
}

EngineResult run_systemc(Backend backend, const Pyramid& pyramid, const SamplerConfig& config,
                         const std::vector<Request>& requests, const SystemcOptions& options) {
  return run_collected(requests, [&](RequestSource& s, TexelSink& t) {
    return run_systemc(backend, pyramid, config, s, t, options);
  });
}

EngineStats run_forked(RequestSource& source, TexelSink& sink, const Simulation& simulation,
                       const std::function<void(const Request*, size_t)>& check, MissSink* misses,
                       ClockSink* clocks) {
  int to_child[2], from_child[2];
  if (::pipe(to_child) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  if (::pipe(from_child) != 0) {
    ::close(to_child[0]);
    ::close(to_child[1]);
    throw Error(std::string("pipe: ") + std::strerror(errno));
  }
  std::fflush(nullptr);  // nothing buffered may be written twice
  const pid_t parent = ::getpid();
  std::unique_lock gate(fork_gate());  // (no thread beside the engine inside an allocator)
  const pid_t pid = ::fork();
  gate.unlock();
  if (pid < 0) {
    for (int fd : {to_child[0], to_child[1], from_child[0], from_child[1]}) ::close(fd);
    throw Error(std::string("fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    // The child: a fresh SystemC kernel (the parent never touches SystemC). It ends with its parent.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(1);
    ::close(to_child[1]);
    ::close(from_child[0]);
    run_child(to_child[0], from_child[1], simulation);
  }
  ::close(to_child[0]);
  ::close(from_child[1]);
  int request_fd = to_child[1];
  const int result_fd = from_child[0];
  ::fcntl(request_fd, F_SETFL, O_NONBLOCK);
  struct sigaction ignore {}, old_pipe {};
  ignore.sa_handler = SIG_IGN;
  sigaction(SIGPIPE, &ignore, &old_pipe);  // a child that died shows as EPIPE, not as a signal

  auto finish_child = [&](bool kill_it) {
    if (request_fd >= 0) ::close(request_fd);
    request_fd = -1;
    ::close(result_fd);
    if (kill_it) ::kill(pid, SIGKILL);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    sigaction(SIGPIPE, &old_pipe, nullptr);
    return status;
  };

  std::vector<Request> pending(4096);
  size_t pending_at = 0, pending_end = 0;  // bytes of `pending` not yet written
  std::string in;                          // bytes from the child not yet decoded
  nlohmann::json outcome;
  try {
    char buf[1 << 16];
    for (bool eof = false; !eof;) {
      if (request_fd >= 0 && pending_at == pending_end) {
        const size_t n = source.read(pending.data(), pending.size());
        check(pending.data(), n);
        pending_at = 0;
        pending_end = n * sizeof(Request);
        if (n == 0) {
          ::close(request_fd);
          request_fd = -1;
        }
      }
      pollfd fds[2] = {{result_fd, POLLIN, 0}, {request_fd, POLLOUT, 0}};
      if (::poll(fds, request_fd >= 0 ? 2 : 1, -1) < 0 && errno != EINTR)
        throw Error(std::string("poll: ") + std::strerror(errno));
      if (request_fd >= 0 && (fds[1].revents & (POLLOUT | POLLERR | POLLHUP))) {
        const ssize_t k = ::write(request_fd, reinterpret_cast<const char*>(pending.data()) + pending_at,
                                  pending_end - pending_at);
        if (k > 0) pending_at += size_t(k);
        else if (k < 0 && errno != EAGAIN && errno != EINTR) {  // the child is gone: its result says why
          ::close(request_fd);
          request_fd = -1;
        }
      }
      if (fds[0].revents & (POLLIN | POLLHUP | POLLERR)) {
        const ssize_t k = ::read(result_fd, buf, sizeof buf);
        if (k < 0 && errno == EINTR) continue;
        if (k <= 0) eof = true;
        else in.append(buf, size_t(k));
      }
      // Decode every whole frame.
      size_t at = 0;
      std::vector<Texel> texels;
      std::vector<uint32_t> lines;
      while (in.size() - at >= 9) {
        uint64_t len = 0;
        std::memcpy(&len, in.data() + at + 1, sizeof len);
        if (in.size() - at - 9 < len) break;
        const char type = in[at];
        const char* body = in.data() + at + 9;
        // (A frame's body need not be aligned in `in`: each is copied out before it is read.)
        if (type == 'T') {
          texels.resize(len / sizeof(Texel));
          std::memcpy(texels.data(), body, texels.size() * sizeof(Texel));
          sink.write(texels.data(), texels.size());
        } else if (type == 'M') {
          if (misses) {
            lines.resize(len / sizeof(uint32_t));
            std::memcpy(lines.data(), body, lines.size() * sizeof(uint32_t));
            misses->write(lines.data(), lines.size());
          }
        } else if (type == 'C') {
          if (clocks) {
            std::vector<uint64_t> c(len / sizeof(uint64_t));
            std::memcpy(c.data(), body, c.size() * sizeof(uint64_t));
            clocks->write(c.data(), c.size());
          }
        }
        else outcome = nlohmann::json::parse(std::string(body, len));
        at += 9 + len;
      }
      in.erase(0, at);
    }
  } catch (...) {
    finish_child(true);
    throw;
  }
  const int status = finish_child(false);
  if (outcome.is_null()) {  // the child died (an abort inside SystemC or Verilator)
    if (WIFSIGNALED(status))
      throw Error("the SystemC simulation process died with signal " + std::to_string(WTERMSIG(status)) +
                  " (see the messages above)");
    throw Error("the SystemC simulation process ended without a result (exit status " +
                std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + "; see the messages above)");
  }
  if (outcome.contains("error")) {
    if (outcome.value("simulation", false)) throw SimulationError(outcome["error"].get<std::string>());
    throw Error(outcome["error"].get<std::string>());
  }
  return EngineStats::from_json(outcome["stats"]);
}

EngineResult run_forked(const std::function<EngineResult()>& simulation) {
  VectorSource none(nullptr, 0);
  VectorSink sink;
  EngineResult r;
  r.stats = run_forked(none, sink, [&](RequestSource&, TexelSink& out, MissSink&, ClockSink&) {
    const EngineResult x = simulation();
    out.write(x.texels.data(), x.texels.size());
    return x.stats;
  });
  r.texels = std::move(sink.texels);
  return r;
}

}  // namespace tex::systemc
