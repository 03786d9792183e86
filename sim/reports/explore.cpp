#include "reports/explore.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <charconv>
#include <csignal>
#include <cstring>
#include <tuple>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>

#include "engines/engine.h"
#include "engines/rtl/driver.h"
#include "model/error.h"
#include "model/pyramid.h"
#include "workloads/camera.h"
#include "workloads/mesh_scene.h"
#include "workloads/output_files.h"
#include "workloads/query_trace.h"
#include "workloads/rasterizer.h"
#include "workloads/scenes.h"
#include "workloads/texture_files.h"
#include "workloads/texture_io.h"

extern char** environ;

namespace tex {

namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------------------ the sweep

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ','))
    if (item.empty()) throw Error(option + " " + quote_clipped(text) + " has an empty item (a list is A,B,C)");
    else items.push_back(item);
  if (items.empty()) throw Error(option + " is empty (a list is A,B,C)");
  return items;
}

uint32_t parse_bounded(const std::string& text, const std::string& option, uint32_t lo, uint32_t hi) {
  uint64_t v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi)
    throw Error(option + " " + quote_clipped(text) + " is not a whole number from " + std::to_string(lo) + " to " +
                std::to_string(hi));
  return uint32_t(v);
}

std::vector<uint32_t> parse_numbers(const std::string& text, const std::string& option, uint32_t lo, uint32_t hi) {
  std::vector<uint32_t> out;
  for (const std::string& s : split_list(text, option)) out.push_back(parse_bounded(s, option, lo, hi));
  return out;
}

// One measured point.
struct Point {
  size_t workload = 0;  // index into Sweep::workloads
  int cache_kib = 8, ways = 2;
  LayoutParams layout;  // block shape and order (base 0)
  uint32_t latency = 200, bandwidth = 16;
  uint32_t fifo = 0;  // 0 = the RTL configuration's FIFO_DEPTH ("max")
};

// A scene or a model's frame in one rasterization order, or a query trace: the requests and the
// textures they sample (a model's: its descriptor table).
struct Workload {
  std::string name;   // scene name, model file or trace path
  std::string order;  // scanline | tiled | trace
  std::string texture;
  TexelFormat format = TexelFormat::Rgba8;  // every pyramid's, compressed by compress_pyramid
  std::vector<Pyramid> pyramids;            // one per descriptor-table entry
  std::vector<std::pair<Wrap, Wrap>> wraps;  // each entry's wrap modes
  SamplerConfig config;
  std::vector<Request> requests;
  TextureTable table() const {
    TextureTable t;
    for (const Pyramid& p : pyramids) t.push_back({&p});
    return t;
  }
  // The sampler table: entry i samples texture i (config with entry i's wrap modes).
  SamplerTable samplers() const {
    SamplerTable t;
    for (const auto& [u, v] : wraps) {
      SamplerConfig c = config;
      c.wrap_u = u;
      c.wrap_v = v;
      t.push_back(c);
    }
    return t;
  }
};

// Who gives samples/clock: the model's timing layer at every point, the RTL where a compiled
// configuration holds the point (the model elsewhere), or nobody (caches only).
enum class TimingMode { Model, Rtl, None };

struct Sweep {
  ExploreArgs args;
  bool trace = false;
  bool model = false;  // --model or --scene-file
  std::vector<std::string> workload_names, order_names;
  std::vector<TexelFormat> formats;
  std::vector<int> cache_kib, ways;
  std::vector<LayoutParams> blocks;  // shapes
  std::vector<BlockOrder> block_orders;
  std::vector<uint32_t> latencies, bandwidths, fifos;
  TimingMode timing = TimingMode::Model;
  bool confirm = false;  // --confirm rtl
  std::vector<Workload> workloads;
  std::vector<Point> points;  // in CSV order
};

// Everything about the lists, before any texture is built.
Sweep parse_sweep(const ExploreArgs& a) {
  Sweep s;
  s.args = a;
  s.trace = !a.queries.empty();
  s.model = !a.model.empty() || !a.scene_file.empty();
  if (int(s.trace) + int(!a.model.empty()) + int(!a.scene_file.empty()) > 1)
    throw Error("explore: give one of --queries, --model and --scene-file");
  if (!a.camera.empty() && !s.model) throw Error("explore: --camera applies to --model and --scene-file");
  if (s.trace) {
    s.workload_names = {a.queries};
    s.order_names = {"trace"};
  } else if (s.model) {
    s.workload_names = {a.model.empty() ? a.scene_file : a.model};
    s.order_names = split_list(a.orders, "--order");
    for (const std::string& o : s.order_names) parse_pixel_order(o);
    if (!a.camera.empty()) parse_camera(a.camera);
  } else {
    s.workload_names = split_list(a.scenes, "--scene");
    for (const std::string& n : s.workload_names) {
      bool known = n == "mesh16";
      for (const std::string& k : scene_names()) known = known || k == n;
      if (!known) make_scene(n, SceneOptions{});  // throws naming the known scenes
    }
    s.order_names = split_list(a.orders, "--order");
    for (const std::string& o : s.order_names) parse_pixel_order(o);
  }
  for (const std::string& f : split_list(a.formats, "--format")) {
    s.formats.push_back(parse_encodable_format(f));
  }
  for (uint32_t k : parse_numbers(a.cache_kib, "--cache-kib", 1, 1024)) s.cache_kib.push_back(int(k));
  for (const std::string& w : split_list(a.ways, "--ways")) {
    if (w != "1" && w != "2" && w != "4") throw Error("--ways " + quote_clipped(w) + " is not 1, 2 or 4");
    s.ways.push_back(std::stoi(w));
  }
  for (const std::string& b : split_list(a.blocks, "--block")) {
    LayoutParams l;
    if (!parse_block_size(b, l)) throw Error("--block " + quote_clipped(b) + " is not WxH with W and H each 2, 4 or 8");
    s.blocks.push_back(l);
  }
  for (const std::string& o : split_list(a.block_orders, "--block-order")) {
    BlockOrder bo;
    if (!parse_block_order(o, bo)) throw Error("unknown --block-order " + quote_clipped(o) + " (row-major, morton)");
    s.block_orders.push_back(bo);
  }
  s.latencies = parse_numbers(a.latencies, "--mem-latency", 1, 100000);
  s.bandwidths = parse_numbers(a.bandwidths, "--mem-bytes-per-clock", 1, 1024);
  for (const std::string& f : split_list(a.fifo_depths, "--fifo-depth"))
    s.fifos.push_back(f == "max" ? 0 : parse_bounded(f, "--fifo-depth", 1, 1u << 20));
  if (a.timing == "model") s.timing = TimingMode::Model;
  else if (a.timing == "rtl") s.timing = TimingMode::Rtl;
  else if (a.timing == "none") s.timing = TimingMode::None;
  else throw Error("--timing " + quote_clipped(a.timing) + " is not model, rtl or none");
  if (!a.confirm.empty() && a.confirm != "rtl") throw Error("--confirm " + quote_clipped(a.confirm) + " is not rtl");
  s.confirm = a.confirm == "rtl";
  if (s.confirm && s.timing != TimingMode::Model) throw Error("--confirm rtl checks the timing model: it needs --timing model");
  if (a.jobs < 1 || a.jobs > 256) throw Error("--jobs " + std::to_string(a.jobs) + " is outside 1..256");
  return s;
}

void load_rgba8_workloads(Sweep& s) {
  SamplerConfig config;
  if (!parse_filter(s.args.filter, config.filter)) throw Error("unknown --filter " + quote_clipped(s.args.filter));
  if (s.trace) {
    Workload w;
    w.name = s.args.queries;
    w.order = "trace";
    w.texture = s.args.texture;
    w.pyramids.push_back(build_pyramid(load_texture(s.args.texture), PyramidMode::Exact));
    w.wraps.emplace_back(config.wrap_u, config.wrap_v);
    w.config = config;
    QueryReader reader(s.args.queries);
    QuerySource source(reader);
    std::vector<Request> chunk(4096);
    while (const size_t n = source.read(chunk.data(), chunk.size()))
      w.requests.insert(w.requests.end(), chunk.begin(), chunk.begin() + long(n));
    if (w.requests.empty()) throw Error(s.args.queries + " has no queries");
    s.workloads.push_back(std::move(w));
    return;
  }
  if (s.model) {  // the model's first frame: the orbit's first position, or --camera
    const MeshScene scene = s.args.model.empty() ? load_models(read_scene_file(s.args.scene_file)) : load_model(s.args.model);
    if (scene.textures.size() > size_t(kMaxTextures))
      throw Error("the scene has " + std::to_string(scene.textures.size()) + " textures; the descriptor table holds " +
                  std::to_string(kMaxTextures));
    RasterOptions ro;
    ro.width = s.args.width;
    ro.height = s.args.height;
    ro.tile = s.args.tile;
    const Camera camera = s.args.camera.empty() ? orbit_camera(scene.bounds_min, scene.bounds_max,
                                                               double(ro.width) / ro.height, 0, 1)
                                                : parse_camera(s.args.camera);
    for (const std::string& order : s.order_names) {
      ro.order = parse_pixel_order(order);
      Workload w;
      w.name = s.workload_names[0];
      w.order = order;
      w.texture = std::to_string(scene.textures.size()) + " textures";
      for (const SceneTexture& t : scene.textures) {
        w.pyramids.push_back(build_pyramid(t.image, PyramidMode::Exact));
        w.wraps.emplace_back(t.wrap_u, t.wrap_v);
      }
      w.config = config;
      w.requests = to_requests(rasterize(scene, camera, ro).queries, w.name);
      s.workloads.push_back(std::move(w));
    }
    return;
  }
  for (const std::string& name : s.workload_names)
    for (const std::string& order : s.order_names) {
      SceneOptions so;
      so.width = s.args.width;
      so.height = s.args.height;
      so.order = parse_pixel_order(order);
      so.tile = s.args.tile;
      const SceneFrame frame = make_scene(name, so);
      Workload w;
      w.name = name;
      w.order = order;
      w.texture = frame.own_texture ? "own map" : s.args.texture;
      w.pyramids.push_back(build_pyramid(scene_texture(frame, s.args.texture), PyramidMode::Exact));
      w.config = config;
      if (frame.clamp_edges) w.config.wrap_u = w.config.wrap_v = Wrap::Clamp;
      w.wraps.emplace_back(w.config.wrap_u, w.config.wrap_v);
      w.requests = to_requests(frame.queries, "scene " + name);
      s.workloads.push_back(std::move(w));
    }
}

// Every workload once per format, its textures compressed (in the order workload, order, format).
void load_workloads(Sweep& s) {
  load_rgba8_workloads(s);
  if (s.formats.size() == 1 && s.formats[0] == TexelFormat::Rgba8) return;
  std::vector<Workload> all;
  for (Workload& w : s.workloads)
    for (TexelFormat f : s.formats) {
      Workload c = w;
      c.format = f;
      for (Pyramid& p : c.pyramids) p = compress_pyramid(std::move(p), f);
      all.push_back(std::move(c));
    }
  s.workloads = std::move(all);
}

CacheParams cache_of(const Point& p) {
  CacheParams c;
  c.size_bytes = p.cache_kib * 1024;
  c.ways = p.ways;
  return c;
}

EngineOptions engine_options(const Point& p) {
  EngineOptions o;
  o.memory = Memory::Cached;
  o.layout = p.layout;
  o.cache = cache_of(p);
  o.mem_latency = p.latency;
  o.mem_bytes_per_clock = p.bandwidth;
  o.fifo_depth = p.fifo;
  return o;
}

// The cartesian product, in CSV order. A cache geometry the hardware cannot have (fewer than 4
// sets, ...) is left out, and said once on stderr.
void expand_points(Sweep& s) {
  std::set<std::string> said;
  std::vector<std::string> notes;
  for (size_t w = 0; w < s.workloads.size(); ++w) {
    const TextureTable table = s.workloads[w].table();
    for (const LayoutParams& block : s.blocks)
      for (BlockOrder bo : s.block_orders)
        for (int kib : s.cache_kib)
          for (int ways : s.ways) {
            Point p;
            p.workload = w;
            p.cache_kib = kib;
            p.ways = ways;
            p.layout = block;
            p.layout.order = bo;
            try {
              TextureCache(texture_descriptors(table, engine_options(p)), cache_of(p), s.workloads[w].samplers());
            } catch (const Error& e) {
              const std::string what = std::to_string(kib) + " KiB, " + std::to_string(ways) + " ways, " +
                                       block_size_name(block) + " blocks";
              if (said.insert(what).second) notes.push_back("left out " + what + ": " + e.what());
              continue;
            }
            const int cw = s.workloads[w].pyramids[0].levels[0].channel_bits;
            const uint32_t line = uint32_t(block.block_w * block.block_h * (cw > 8 ? 8 : 4));
            for (uint32_t lat : s.latencies)
              for (uint32_t bw : s.bandwidths)
                for (uint32_t fifo : s.fifos) {
                  if (bw > line) {  // the memory port carries one beat, at most a line, per clock
                    const std::string what = std::to_string(bw) + " bytes per clock with " + block_size_name(block) +
                                             " blocks";
                    if (said.insert(what).second)
                      notes.push_back("left out " + what + ": more than one " + std::to_string(line) +
                                      "-byte line per clock");
                    continue;
                  }
                  p.latency = lat;
                  p.bandwidth = bw;
                  p.fifo = fifo;
                  s.points.push_back(p);
                }
          }
  }
  if (s.points.empty())
    throw Error("explore: no point of the sweep has a cache geometry the hardware can have (" + notes.front() + ")");
  for (const std::string& n : notes) std::fprintf(stderr, "explore: %s\n", n.c_str());
}


// Why the RTL cannot measure this point (empty: it can).
std::string rtl_unavailable(const Sweep& s, const Point& p) {
  const Workload& w = s.workloads[p.workload];
  try {
    const CacheParams cache = cache_of(p);
    const rtl::RtlConfig& rc = rtl::smallest_config_for(w.table(), Memory::Cached, p.layout.block_w, p.layout.block_h,
                                                        &cache, p.fifo);
    rtl::cache_pins(rc, p.layout, cache, p.fifo);
    if (p.bandwidth > uint32_t(rc.line_bytes())) throw Error("the bandwidth is more than a line per clock");
    for (const Pyramid& pyramid : w.pyramids) rtl::check_inputs(rc, pyramid);  // (formats it has no decoder for)
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// ------------------------------------------------------------------------------ measuring

struct Row {
  Point point;
  uint64_t samples = 0;
  CacheCounters cache;
  std::string timing_engine;  // model | rtl | "" (not timed)
  bool confirmed = false;     // --confirm rtl: the RTL gave the same figures
  double samples_per_clock = 0;
  uint64_t cycles = 0;
  uint32_t fifo_depth = 0;  // in use (timed rows; else the one asked for, 0 = max)
  double seconds = 0;
};

class NullSink final : public TexelSink {
 public:
  void write(const Texel*, size_t) override {}
};

// Points of one cache geometry share the model's caches: their counters, and each request's probes
// and misses (what the timing layer clocks at every latency, bandwidth and FIFO depth).
using ModelKey = std::tuple<size_t, int, int, int, int, int>;
ModelKey model_key(const Point& p) {
  return {p.workload, p.cache_kib, p.ways, p.layout.block_w, p.layout.block_h, int(p.layout.order)};
}
struct ModelRun {
  CacheCounters cache;
  std::vector<RequestWork> work;
  int line_bytes = 0;
};

std::string point_name(const Sweep& s, const Point& p) {
  const Workload& w = s.workloads[p.workload];
  return w.name + " (" + w.order + "), " + std::to_string(p.cache_kib) + " KiB x " + std::to_string(p.ways) +
         " ways, " + block_size_name(p.layout) + " " + block_order_name(p.layout.order) + ", latency " +
         std::to_string(p.latency) + ", " + std::to_string(p.bandwidth) + " B/clock, FIFO " +
         (p.fifo ? std::to_string(p.fifo) : std::string("max"));
}

Row measure(const Sweep& s, const Point& p, std::map<ModelKey, ModelRun>& model_memo) {
  const auto t0 = std::chrono::steady_clock::now();
  const Workload& w = s.workloads[p.workload];
  Row r;
  r.point = p;
  r.samples = w.requests.size();
  r.fifo_depth = p.fifo;
  const bool rtl_can = rtl_unavailable(s, p).empty();
  std::optional<EngineStats> rtl;
  if (rtl_can && (s.timing == TimingMode::Rtl || s.confirm)) {
    // The RTL engine runs the model's caches beside the RTL and fails on any read they do not predict.
    VectorSource source(w.requests);
    NullSink sink;
    rtl = make_engine("rtl", engine_options(p))->run(w.table(), w.samplers(), source, sink);
  }
  if (rtl && s.timing == TimingMode::Rtl) {
    r.timing_engine = "rtl";
    r.cache = *rtl->cache;
    r.samples_per_clock = rtl->samples_per_clock();
    r.cycles = rtl->cycle->cycles;
    r.fifo_depth = rtl->cache->fifo_depth;
  } else {
    auto [it, fresh] = model_memo.try_emplace(model_key(p));
    ModelRun& m = it->second;
    if (fresh) {
      TextureCache cache(texture_descriptors(w.table(), engine_options(p)), cache_of(p), w.samplers());
      m.work.reserve(w.requests.size());
      for (const Request& q : w.requests) m.work.push_back(cache.lookup_sample(q, nullptr));
      m.cache = cache_counters(cache);
      m.line_bytes = cache.line_bytes();
    }
    r.cache = m.cache;
    if (s.timing != TimingMode::None) {
      std::string configuration;
      const std::unique_ptr<TimedStream> timed = model_timing(w.table(), engine_options(p), m.line_bytes, configuration);
      for (const RequestWork& work : m.work) timed->push(work);
      timed->finish(nullptr);
      const TimingCounters t = timed->counters();
      r.timing_engine = "model";
      r.cycles = t.cycles();
      r.samples_per_clock = r.cycles > t.latency_min ? double(t.samples) / double(r.cycles - t.latency_min) : 0.0;
      r.fifo_depth = timed->fifo_limit();
      r.cache.fifo_depth = r.fifo_depth;
      r.cache.fifo_max_occupancy = t.fifo_max;
      r.cache.memory_stall_cycles = t.head_wait_cycles;
      if (rtl) {  // --confirm rtl: the same figures, or the sweep fails
        const CacheCounters& k = *rtl->cache;
        std::string differ;
        auto check = [&](const char* what, uint64_t model, uint64_t measured) {
          if (model != measured && differ.empty())
            differ = std::string(what) + ": timing model " + std::to_string(model) + ", RTL " + std::to_string(measured);
        };
        check("cycles", r.cycles, rtl->cycle->cycles);
        check("memory_stall_cycles", r.cache.memory_stall_cycles, k.memory_stall_cycles);
        check("fifo_max_occupancy", r.cache.fifo_max_occupancy, k.fifo_max_occupancy);
        check("fifo_depth", r.fifo_depth, k.fifo_depth);
        check("cache_hits", r.cache.hits, k.hits);
        check("cache_misses", r.cache.misses, k.misses);
        if (!differ.empty()) throw SimulationError("--confirm rtl: " + point_name(s, p) + ": " + differ);
        r.confirmed = true;
      }
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

// ------------------------------------------------------------------------------ CSV

const char* kCsvHeader =
    "workload,order,texture,format,width,height,filter,cache_kib,ways,block,block_order,mem_latency,mem_bytes_per_clock,"
    "fifo_depth,samples,cache_lookups,cache_hits,cache_misses,hit_rate,memory_read_bytes,bytes_per_sample,"
    "timing_engine,samples_per_clock,cycles,memory_stall_cycles,fifo_max_occupancy,confirmed,seconds";

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_row(const Sweep& s, const Row& r) {
  const Workload& w = s.workloads[r.point.workload];
  const Point& p = r.point;
  const CacheCounters& k = r.cache;
  char buf[512];
  std::string line = csv_field(w.name) + "," + w.order + "," + csv_field(w.texture) + "," + format_info(w.format).name + ",";
  if (s.trace) line += ",,";
  else line += std::to_string(s.args.width) + "," + std::to_string(s.args.height) + ",";
  std::snprintf(buf, sizeof buf, "%s,%d,%d,%s,%s,%u,%u,", filter_name(w.config.filter).c_str(), p.cache_kib, p.ways,
                block_size_name(p.layout).c_str(), block_order_name(p.layout.order).c_str(), p.latency, p.bandwidth);
  line += buf;
  line += r.fifo_depth ? std::to_string(r.fifo_depth) : "";
  std::snprintf(buf, sizeof buf, ",%llu,%llu,%llu,%llu,%.6f,%llu,%.4f,", (unsigned long long)r.samples,
                (unsigned long long)k.lookups, (unsigned long long)k.hits, (unsigned long long)k.misses,
                k.lookups ? double(k.hits) / double(k.lookups) : 0.0, (unsigned long long)k.memory_read_bytes,
                r.samples ? double(k.memory_read_bytes) / double(r.samples) : 0.0);
  line += buf;
  if (!r.timing_engine.empty())
    std::snprintf(buf, sizeof buf, "%s,%.5f,%llu,%llu,%u,%s,%.3f", r.timing_engine.c_str(), r.samples_per_clock,
                  (unsigned long long)r.cycles, (unsigned long long)k.memory_stall_cycles, k.fifo_max_occupancy,
                  r.confirmed ? "rtl" : "", r.seconds);
  else
    std::snprintf(buf, sizeof buf, ",,,,,,%.3f", r.seconds);
  return line + buf + "\n";
}

// ------------------------------------------------------------------------------ jobs

// Points of one workload and block shape form a job: one process builds the texture and the scene
// once, runs the model's caches once per cache size and ways, and times every latency, bandwidth
// and FIFO depth of each.
struct Job {
  size_t first = 0, count = 0;  // range of Sweep::points
};

std::tuple<size_t, int, int, int> job_key(const Point& p) {
  return {p.workload, p.layout.block_w, p.layout.block_h, int(p.layout.order)};
}

std::vector<Job> jobs_of(const Sweep& s) {
  std::vector<Job> jobs;
  for (size_t i = 0; i < s.points.size(); ++i) {
    if (jobs.empty() || job_key(s.points[i]) != job_key(s.points[jobs.back().first])) jobs.push_back({i, 0});
    ++jobs.back().count;
  }
  return jobs;
}

// A path as a command line of another machine or directory sees it: absolute if it exists here.
std::string portable_path(const std::string& path) {
  std::error_code ec;
  return fs::exists(path, ec) ? fs::absolute(path).string() : path;
}

std::string join_numbers(const std::vector<uint32_t>& v, bool max_for_zero = false) {
  std::string s;
  for (uint32_t x : v) s += (s.empty() ? "" : ",") + (max_for_zero && x == 0 ? std::string("max") : std::to_string(x));
  return s;
}

// The command line of one job (argv), writing its rows to `rows`.
std::vector<std::string> job_command(const Sweep& s, const Job& job, const std::string& self, const std::string& rows) {
  const Point& p = s.points[job.first];
  const Workload& w = s.workloads[p.workload];
  std::vector<std::string> c = {self, "explore"};
  const std::vector<std::string> frame = {"--order", w.order, "--width", std::to_string(s.args.width), "--height",
                                          std::to_string(s.args.height), "--tile", std::to_string(s.args.tile)};
  if (s.trace) {
    c.insert(c.end(), {"--queries", portable_path(w.name)});
  } else if (s.model) {
    c.insert(c.end(), {s.args.model.empty() ? "--scene-file" : "--model", portable_path(w.name)});
    c.insert(c.end(), frame.begin(), frame.end());
    if (!s.args.camera.empty()) c.insert(c.end(), {"--camera", s.args.camera});
  } else {
    c.insert(c.end(), {"--scene", w.name});
    c.insert(c.end(), frame.begin(), frame.end());
  }
  c.insert(c.end(), {"--texture", portable_path(s.args.texture), "--format", format_info(w.format).name,
                     "--filter", s.args.filter, "--cache-kib",
                     s.args.cache_kib, "--ways", s.args.ways, "--block", block_size_name(p.layout),
                     "--block-order", block_order_name(p.layout.order), "--mem-latency", join_numbers(s.latencies),
                     "--mem-bytes-per-clock", join_numbers(s.bandwidths), "--fifo-depth", join_numbers(s.fifos, true),
                     "--timing", s.args.timing, "--rows", rows});
  if (s.confirm) c.insert(c.end(), {"--confirm", "rtl"});
  return c;
}

std::string shell_quote(const std::string& word) {
  if (!word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./:=,+@%") ==
                           std::string::npos)
    return word;
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Starts argv; with an `err_path`, stdout goes to /dev/null and stderr to that file (a job),
// else both are this process's. Returns the pid.
pid_t spawn(const std::vector<std::string>& argv, const std::string& err_path) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (!err_path.empty()) {
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, args[0], &fa, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) throw Error("cannot start " + argv[0] + ": " + std::strerror(rc));
  return pid;
}

// The last non-empty line of a child's stderr (its one-line error).
std::string last_line(const std::string& text) {
  size_t end = text.find_last_not_of("\r\n");
  if (end == std::string::npos) return "(no message)";
  const size_t begin = text.find_last_of("\r\n", end);
  return text.substr(begin == std::string::npos ? 0 : begin + 1, end - (begin == std::string::npos ? 0 : begin + 1) + 1);
}

// Removes a directory tree when it goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string t = (fs::temp_directory_path() / "texsim-explore-XXXXXX").string();
    if (!mkdtemp(t.data())) throw Error("cannot create a temporary directory in " + fs::temp_directory_path().string());
    path = t;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

// Runs every job in up to `parallel` child processes; returns the rows (no header) in sweep order.
std::string run_jobs(const Sweep& s, const std::string& self, int parallel, bool progress) {
  const std::vector<Job> jobs = jobs_of(s);
  TempDir tmp;
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0;
  auto stop_all = [&] {
    for (const auto& [pid, j] : running) kill(pid, SIGTERM);
    for (const auto& [pid, j] : running) waitpid(pid, nullptr, 0);
    running.clear();
  };
  auto name = [&](size_t j, const char* ext) { return (tmp.path / ("job" + std::to_string(j) + ext)).string(); };
  try {
    while (done < jobs.size()) {
      while (next < jobs.size() && running.size() < size_t(parallel)) {
        running[spawn(job_command(s, jobs[next], self, name(next, ".csv")), name(next, ".err"))] = next;
        ++next;
      }
      int status = 0;
      const pid_t pid = waitpid(-1, &status, 0);
      if (pid < 0) throw Error(std::string("waiting for the jobs: ") + std::strerror(errno));
      const auto it = running.find(pid);
      if (it == running.end()) continue;
      const size_t j = it->second;
      running.erase(it);
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::string cmd;
        for (const std::string& a : job_command(s, jobs[j], self, name(j, ".csv"))) cmd += " " + shell_quote(a);
        throw Error("explore: job " + std::to_string(j + 1) + " failed: " + last_line(read_file(name(j, ".err"))) +
                    " (command:" + cmd + ")");
      }
      ++done;
      if (progress) std::fprintf(stderr, "\rexplore: %zu/%zu jobs", done, jobs.size());
    }
  } catch (...) {
    stop_all();
    if (progress) std::fprintf(stderr, "\n");
    throw;
  }
  if (progress) std::fprintf(stderr, "\r%40s\r", "");
  std::string rows;
  for (size_t j = 0; j < jobs.size(); ++j) {
    const std::string text = read_file(name(j, ".csv"));
    const size_t nl = text.find('\n');
    rows += text.substr(nl == std::string::npos ? text.size() : nl + 1);
  }
  return rows;
}

// ------------------------------------------------------------------------------ outputs

fs::path scripts_dir() {
  if (const char* env = std::getenv("TEXSIM_SCRIPTS_DIR")) return env;
  return TEXSIM_SCRIPTS_DIR;
}

void run_plots(const std::string& out_dir) {
  const std::string script = (scripts_dir() / "explore_plots.py").string();
  std::fflush(stdout);
  int status = 0;
  const pid_t pid = spawn({"/usr/bin/python3", script, out_dir}, "");
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw Error("explore: the plots failed (" + script + ", with /usr/bin/python3 and matplotlib); " + out_dir +
                "/explore.csv is complete");
}

// Writes OUT/explore.csv (all or nothing), then the plots and index.html.
void write_results(const std::string& out_dir, const std::string& rows, const std::vector<std::string>& inputs,
                   bool plots) {
  OutputSet outputs;
  for (const std::string& in : inputs) outputs.add_input(in, "--texture/--queries");
  outputs.make_directory(out_dir, "--out");
  OutputFile& csv = outputs.declare((fs::path(out_dir) / "explore.csv").string(), "--out");
  std::FILE* f = csv.open();
  std::fputs(kCsvHeader, f);
  std::fputs("\n", f);
  std::fputs(rows.c_str(), f);
  csv.close();
  outputs.commit();
  if (plots) run_plots(out_dir);
}

size_t count_lines(const std::string& text) {
  size_t n = 0;
  for (char c : text) n += c == '\n';
  return n;
}

// --collect DIR: the row files of an --emit-jobs sweep, in job order, into DIR/explore.csv.
int collect(const ExploreArgs& a) {
  const fs::path points = fs::path(a.collect_dir) / "points";
  const fs::path expected_path = points / "jobs";
  std::error_code ec;
  if (!fs::is_regular_file(expected_path, ec))
    throw Error("--collect: " + expected_path.string() + " does not exist (write the jobs with --emit-jobs --out " +
                a.collect_dir + " first)");
  const std::string count_text = last_line(read_file(expected_path));
  const uint32_t count = parse_bounded(count_text, "--collect: " + expected_path.string() + ": job count", 1, 1u << 30);
  std::string rows;
  size_t missing = 0;
  std::string first_missing;
  for (uint32_t j = 0; j < count; ++j) {
    char name[32];
    std::snprintf(name, sizeof name, "job%06u.csv", j + 1);
    const fs::path p = points / name;
    if (!fs::is_regular_file(p, ec)) {
      if (!missing++) first_missing = p.string();
      continue;
    }
    const std::string text = read_file(p);
    const size_t nl = text.find('\n');
    if (text.substr(0, nl) != kCsvHeader)
      throw Error("--collect: " + p.string() + " line 1 is not the header of texsim explore's rows");
    if (text.back() != '\n') throw Error("--collect: " + p.string() + " ends in the middle of a line");
    rows += text.substr(nl + 1);
  }
  if (missing)
    throw Error("--collect: " + std::to_string(missing) + " of " + std::to_string(count) +
                " jobs have no rows yet (first: " + first_missing + "); run their command lines first");
  write_results(a.collect_dir, rows, {}, a.plots);
  std::printf("texsim explore: collected %zu points of %u jobs into %s/explore.csv%s\n", count_lines(rows), count,
              a.collect_dir.c_str(), a.plots ? (", index in " + a.collect_dir + "/index.html").c_str() : "");
  return 0;
}

// --emit-jobs FILE: one command line per job, each writing OUT/points/jobNNNNNN.csv.
int emit_jobs(const Sweep& s, const std::string& self) {
  const std::vector<Job> jobs = jobs_of(s);
  OutputSet outputs;
  outputs.add_input(s.args.texture, "--texture");
  if (s.trace) outputs.add_input(s.args.queries, "--queries");
  const fs::path points = fs::path(s.args.out_dir) / "points";
  outputs.make_directory(points.string(), "--out");
  OutputFile& file = outputs.declare(s.args.emit_jobs_path, "--emit-jobs");
  OutputFile& count = outputs.declare((points / "jobs").string(), "--out");
  std::FILE* f = file.open();
  for (size_t j = 0; j < jobs.size(); ++j) {
    char name[32];
    std::snprintf(name, sizeof name, "job%06zu.csv", j + 1);
    std::string line;
    for (const std::string& w : job_command(s, jobs[j], self, fs::absolute(points / name).string()))
      line += (line.empty() ? "" : " ") + shell_quote(w);
    std::fprintf(f, "%s\n", line.c_str());
  }
  file.close();
  std::fprintf(count.open(), "%zu\n", jobs.size());
  count.close();
  outputs.commit();
  std::printf("texsim explore: %zu points in %zu jobs -> %s (one command line each, e.g. `parallel < %s`); then "
              "texsim explore --collect %s\n",
              s.points.size(), jobs.size(), s.args.emit_jobs_path.c_str(), s.args.emit_jobs_path.c_str(),
              s.args.out_dir.c_str());
  return 0;
}

}  // namespace

int run_explore(const ExploreArgs& a, const std::string& self) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!a.collect_dir.empty()) return collect(a);
  if (!a.rows_path.empty() && !a.emit_jobs_path.empty()) throw Error("explore: --rows and --emit-jobs exclude each other");
  Sweep s = parse_sweep(a);
  // Check the outputs before the work.
  std::optional<OutputSet> row_outputs;
  OutputFile* rows_file = nullptr;
  if (!a.rows_path.empty()) {
    row_outputs.emplace();
    row_outputs->add_input(a.texture, "--texture");
    if (s.trace) row_outputs->add_input(a.queries, "--queries");
    rows_file = &row_outputs->declare(a.rows_path, "--rows");
  }
  load_workloads(s);
  expand_points(s);
  if (!a.emit_jobs_path.empty()) return emit_jobs(s, self);

  std::map<std::string, size_t> no_rtl;  // why the RTL could not run a point -> points
  size_t rtl_points = 0;
  for (const Point& p : s.points)
    if (const std::string why = rtl_unavailable(s, p); !why.empty()) ++no_rtl[why];
    else ++rtl_points;

  const bool progress = rows_file == nullptr && isatty(STDERR_FILENO);
  std::string rows;
  if (a.jobs > 1 && rows_file == nullptr) {
    rows = run_jobs(s, self, a.jobs, progress);
  } else {
    std::map<ModelKey, ModelRun> memo;
    for (size_t i = 0; i < s.points.size(); ++i) {
      rows += csv_row(s, measure(s, s.points[i], memo));
      if (progress) std::fprintf(stderr, "\rexplore: %zu/%zu points", i + 1, s.points.size());
    }
    if (progress) std::fprintf(stderr, "\r%40s\r", "");
  }
  if (rows_file) {
    std::FILE* f = rows_file->open();
    std::fprintf(f, "%s\n%s", kCsvHeader, rows.c_str());
    rows_file->close();
    row_outputs->commit();
    return 0;
  }
  std::vector<std::string> inputs = {a.texture};
  if (s.trace) inputs.push_back(a.queries);
  write_results(a.out_dir, rows, inputs, a.plots);
  if (s.timing == TimingMode::Rtl || s.confirm)
    for (const auto& [why, n] : no_rtl)
      std::printf("  %s (no RTL configuration): %zu points: %s\n",
                  s.confirm ? "not confirmed" : "timed by the model", n, why.c_str());
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::string timing = s.timing == TimingMode::None ? "none timed"
                             : s.timing == TimingMode::Rtl ? std::to_string(rtl_points) + " timed by the RTL, the rest by the timing model"
                             : s.confirm ? "all timed by the timing model, " + std::to_string(rtl_points) + " confirmed by the RTL"
                                         : "all timed by the timing model";
  std::printf("texsim explore: %zu points (%s), %zu workloads, %.1f s -> %s/explore.csv%s\n", s.points.size(),
              timing.c_str(), s.workloads.size(), secs, a.out_dir.c_str(),
              a.plots ? (", index in " + a.out_dir + "/index.html").c_str() : "");
  return 0;
}

}  // namespace tex
