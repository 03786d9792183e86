#include "reports/explore.h"

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
#include "reports/result_store.h"
#include "reports/sweep_tasks.h"
#include "workloads/camera.h"
#include "workloads/mesh_scene.h"
#include "workloads/output_files.h"
#include "workloads/query_trace.h"
#include "workloads/rasterizer.h"
#include "workloads/scenes.h"
#include "workloads/texture_files.h"
#include "workloads/texture_io.h"

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
  std::vector<std::string> fingerprints;  // each workload's (workload_fingerprint)
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
  return r;
}

// ------------------------------------------------------------------------------ CSV

// The columns that name a point (what --collect knows without the workloads), then those measured
// (the results store's result). No wall time: a sweep's CSV is the same bytes whoever measured it.
const char* kCsvHeader =
    "workload,order,texture,format,width,height,filter,cache_kib,ways,block,block_order,mem_latency,mem_bytes_per_clock,"
    "fifo_depth,samples,cache_lookups,cache_hits,cache_misses,hit_rate,memory_read_bytes,bytes_per_sample,"
    "timing_engine,samples_per_clock,cycles,memory_stall_cycles,fifo_max_occupancy,confirmed";

// A CSV field: quoted when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// workload .. mem_bytes_per_clock, with the comma after it.
std::string csv_prefix(const Sweep& s, const Point& p) {
  const Workload& w = s.workloads[p.workload];
  char buf[512];
  std::string line = csv_field(w.name) + "," + w.order + "," + csv_field(w.texture) + "," + format_info(w.format).name + ",";
  if (s.trace) line += ",,";
  else line += std::to_string(s.args.width) + "," + std::to_string(s.args.height) + ",";
  std::snprintf(buf, sizeof buf, "%s,%d,%d,%s,%s,%u,%u,", filter_name(w.config.filter).c_str(), p.cache_kib, p.ways,
                block_size_name(p.layout).c_str(), block_order_name(p.layout.order).c_str(), p.latency, p.bandwidth);
  return line + buf;
}

// fifo_depth .. confirmed: what the store keeps.
std::string csv_measured(const Row& r) {
  const CacheCounters& k = r.cache;
  char buf[512];
  std::string line = r.fifo_depth ? std::to_string(r.fifo_depth) : "";
  std::snprintf(buf, sizeof buf, ",%llu,%llu,%llu,%llu,%.6f,%llu,%.4f,", (unsigned long long)r.samples,
                (unsigned long long)k.lookups, (unsigned long long)k.hits, (unsigned long long)k.misses,
                k.lookups ? double(k.hits) / double(k.lookups) : 0.0, (unsigned long long)k.memory_read_bytes,
                r.samples ? double(k.memory_read_bytes) / double(r.samples) : 0.0);
  line += buf;
  if (!r.timing_engine.empty())
    std::snprintf(buf, sizeof buf, "%s,%.5f,%llu,%llu,%u,%s", r.timing_engine.c_str(), r.samples_per_clock,
                  (unsigned long long)r.cycles, (unsigned long long)k.memory_stall_cycles, k.fifo_max_occupancy,
                  r.confirmed ? "rtl" : "");
  else
    std::snprintf(buf, sizeof buf, ",,,,,");
  return line + buf;
}

// ------------------------------------------------------------------------------ keys

// What a workload's results depend on besides the point: its requests, textures (every level's
// texels and blocks, the format), wrap modes and filter. Two runs that load the same inputs give
// the same fingerprint; a changed file, pattern, scene or model gives another.
std::string workload_fingerprint(const Workload& w) {
  Fingerprint f;
  f.text(filter_name(w.config.filter)).number(int(w.format)).number(int64_t(w.pyramids.size()));
  for (size_t i = 0; i < w.pyramids.size(); ++i) {
    add_pyramid(f, w.pyramids[i]);
    f.number(int(w.wraps[i].first)).number(int(w.wraps[i].second));
  }
  add_requests(f, w.requests);
  return f.hex();
}

// A point's key in the results store: texsim's executable, the workload, the timing asked for and
// every parameter of the point.
std::string point_key(const Sweep& s, const Point& p) {
  return "explore/1 texsim=" + executable_fingerprint() + " workload=" + s.fingerprints[p.workload] +
         " timing=" + s.args.timing + " confirm=" + s.args.confirm + " cache_kib=" + std::to_string(p.cache_kib) +
         " ways=" + std::to_string(p.ways) + " block=" + block_size_name(p.layout) + " block_order=" +
         block_order_name(p.layout.order) + " latency=" + std::to_string(p.latency) + " bandwidth=" +
         std::to_string(p.bandwidth) + " fifo=" + (p.fifo ? std::to_string(p.fifo) : std::string("max"));
}

// ------------------------------------------------------------------------------ tasks

// Points of one workload and block shape and order form a task: one process builds the texture
// and the scene once (a compressed texture's encoding takes seconds), runs the model's caches once
// per cache geometry, and times every latency, bandwidth and FIFO depth of each.
struct Task {
  std::vector<size_t> points;  // indices into Sweep::points, in sweep order
};

std::tuple<size_t, int, int, int> task_key(const Point& p) {
  return {p.workload, p.layout.block_w, p.layout.block_h, int(p.layout.order)};
}

// Every task of the sweep, in the order of their first points.
std::vector<Task> tasks_of(const Sweep& s) {
  std::vector<Task> tasks;
  std::map<std::tuple<size_t, int, int, int>, size_t> index;
  for (size_t i = 0; i < s.points.size(); ++i) {
    const auto [it, fresh] = index.try_emplace(task_key(s.points[i]), tasks.size());
    if (fresh) tasks.emplace_back();
    tasks[it->second].points.push_back(i);
  }
  return tasks;
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

// The command line of one task (argv): its sub-sweep, measured into the store.
std::vector<std::string> task_command(const Sweep& s, const Task& task, const std::string& self, const std::string& store) {
  const Point& p = s.points[task.points.front()];
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
                     "--filter", s.args.filter, "--cache-kib", s.args.cache_kib, "--ways", s.args.ways,
                     "--block", block_size_name(p.layout), "--block-order",
                     block_order_name(p.layout.order), "--mem-latency", join_numbers(s.latencies),
                     "--mem-bytes-per-clock", join_numbers(s.bandwidths), "--fifo-depth", join_numbers(s.fifos, true),
                     "--timing", s.args.timing, "--store", store, "--task", s.fingerprints[p.workload]});
  if (s.confirm) c.insert(c.end(), {"--confirm", "rtl"});
  return c;
}

// Measures the points of `wanted` (indices into Sweep::points) here, each into the store.
void measure_here(const Sweep& s, const std::vector<size_t>& wanted, const ResultStore& store, bool progress) {
  std::map<ModelKey, ModelRun> memo;
  for (size_t i = 0; i < wanted.size(); ++i) {
    const Point& p = s.points[wanted[i]];
    store.put(point_key(s, p), csv_measured(measure(s, p, memo)));
    if (progress) std::fprintf(stderr, "\rexplore: %zu/%zu points", i + 1, wanted.size());
  }
  if (progress) std::fprintf(stderr, "\r%40s\r", "");
}

// ------------------------------------------------------------------------------ the manifest

// An emitted sweep's DIR/sweep.txt: what --collect needs without the workloads. Line 1 names it,
// then `store DIR`, `scheduler NAME`, `tasks N`, `points N`, then one line per point in sweep
// order: its task, its key and its CSV columns up to mem_bytes_per_clock, tab-separated.
constexpr const char* kManifestMagic = "texsim explore sweep 1";

struct ManifestPoint {
  size_t task = 0;
  std::string key, prefix;
};
struct Manifest {
  std::string store;
  Scheduler scheduler = Scheduler::Slurm;
  size_t tasks = 0;
  std::vector<ManifestPoint> points;
};

Manifest read_manifest(const std::string& dir) {
  const fs::path path = fs::path(dir) / "sweep.txt";
  std::ifstream in(path);
  if (!in) throw Error("--collect: " + path.string() + " does not exist (emit the sweep with --emit slurm|parallel " + dir + " first)");
  Manifest m;
  std::string line;
  size_t n = 0, count = 0;
  auto bad = [&](const std::string& why) { throw Error("--collect: " + path.string() + " line " + std::to_string(n) + ": " + why); };
  auto field = [&](const std::string& name) {
    ++n;
    if (!std::getline(in, line) || line.rfind(name + " ", 0) != 0) bad("expected `" + name + " ...`");
    return line.substr(name.size() + 1);
  };
  ++n;
  if (!std::getline(in, line) || line != kManifestMagic) bad(std::string("not a texsim explore sweep (\"") + kManifestMagic + "\")");
  m.store = field("store");
  m.scheduler = parse_scheduler(field("scheduler"));
  m.tasks = parse_bounded(field("tasks"), "--collect: task count", 0, 1u << 30);
  count = parse_bounded(field("points"), "--collect: point count", 1, 1u << 30);
  while (std::getline(in, line)) {
    ++n;
    const size_t a = line.find('\t'), b = a == std::string::npos ? a : line.find('\t', a + 1);
    if (b == std::string::npos) bad("not task<TAB>key<TAB>columns");
    ManifestPoint p;
    p.task = parse_bounded(line.substr(0, a), "--collect: task", 0, uint32_t(m.tasks ? m.tasks - 1 : 0));
    p.key = line.substr(a + 1, b - a - 1);
    p.prefix = line.substr(b + 1);
    m.points.push_back(std::move(p));
  }
  if (m.points.size() != count)
    bad("ends after " + std::to_string(m.points.size()) + " of " + std::to_string(count) + " points");
  return m;
}

// ------------------------------------------------------------------------------ outputs

fs::path scripts_dir() {
  if (const char* env = std::getenv("TEXSIM_SCRIPTS_DIR")) return env;
  return TEXSIM_SCRIPTS_DIR;
}

void run_plots(const std::string& out_dir) {
  const std::string script = (scripts_dir() / "explore_plots.py").string();
  if (run_command({"/usr/bin/python3", script, out_dir}) != 0)
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

// --collect DIR: the emitted sweep's rows from the store, in sweep order, into DIR/explore.csv;
// or, where points are missing, each of their tasks' fate and DIR/resubmit.sh, and an error.
int collect(const ExploreArgs& a) {
  const Manifest m = read_manifest(a.collect_dir);
  const ResultStore store(m.store);
  std::string rows;
  std::map<size_t, size_t> missing;  // task -> points missing
  for (const ManifestPoint& p : m.points) {
    if (const std::optional<std::string> r = store.get(p.key)) rows += p.prefix + *r + "\n";
    else ++missing[p.task];
  }
  if (!missing.empty())
    fail_collect(a.collect_dir, m.scheduler, missing, m.points.size(), m.tasks, "points",
                 "texsim explore --collect " + a.collect_dir);
  write_results(a.collect_dir, rows, {}, a.plots);
  std::printf("texsim explore: collected %zu points of %zu tasks from %s into %s/explore.csv%s\n", m.points.size(),
              m.tasks, m.store.c_str(), a.collect_dir.c_str(),
              a.plots ? (", index in " + a.collect_dir + "/index.html").c_str() : "");
  return 0;
}

// --emit slurm|parallel DIR: the tasks of the points the store lacks, and the manifest.
int emit(const Sweep& s, const std::vector<Task>& tasks, const std::vector<size_t>& task_of, const std::string& self,
         const ResultStore& store, size_t reused) {
  EmitOptions o;
  o.scheduler = parse_scheduler(s.args.emit_scheduler);
  o.dir = fs::absolute(s.args.emit_dir).string();
  o.throttle = s.args.throttle;
  o.sshloginfile = s.args.sshloginfile;
  o.job_name = "texsim-explore";
  o.collect = "texsim explore --collect " + shell_quote(o.dir);
  std::vector<std::vector<std::string>> commands;
  for (const Task& t : tasks) commands.push_back(task_command(s, t, self, store.dir()));
  o.manifest_name = "sweep.txt";
  o.manifest = std::string(kManifestMagic) + "\nstore " + store.dir() + "\nscheduler " + scheduler_name(o.scheduler) +
               "\ntasks " + std::to_string(tasks.size()) + "\npoints " + std::to_string(s.points.size()) + "\n";
  for (size_t i = 0; i < s.points.size(); ++i) {
    std::string prefix = csv_prefix(s, s.points[i]);
    if (prefix.find_first_of("\t\n") != std::string::npos)
      throw Error("--emit: a workload name with a tab or a line break: " + quote_clipped(s.workloads[s.points[i].workload].name));
    o.manifest += std::to_string(task_of[i]) + "\t" + point_key(s, s.points[i]) + "\t" + prefix + "\n";
  }
  emit_tasks(o, commands);
  const std::string run = commands.empty() ? "nothing to run" : emit_hint(o);
  std::printf("texsim explore: %zu points, %zu in the store already, %zu to measure in %zu tasks -> %s (%s); then "
              "texsim explore --collect %s\n",
              s.points.size(), reused, s.points.size() - reused, commands.size(), o.dir.c_str(), run.c_str(),
              s.args.emit_dir.c_str());
  return 0;
}

}  // namespace

int run_explore(const ExploreArgs& a, const std::string& self) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!a.collect_dir.empty()) return collect(a);
  const bool emitting = !a.emit_scheduler.empty();
  if (emitting && !a.task_fingerprint.empty()) throw Error("explore: --emit and --task exclude each other");
  if (emitting) parse_scheduler(a.emit_scheduler);
  {
    EmitOptions o;
    o.throttle = a.throttle;
    o.sshloginfile = a.sshloginfile;
    check_emit_options(o);
  }
  Sweep s = parse_sweep(a);
  if (emitting) prepare_emit_dir(a.emit_dir);  // (before the work: another directory of the user's is refused)
  const ResultStore store(a.store_dir.empty() ? default_store_dir() : a.store_dir);
  load_workloads(s);
  expand_points(s);
  for (const Workload& w : s.workloads) s.fingerprints.push_back(workload_fingerprint(w));

  // Which points the store lacks, and their tasks.
  std::vector<std::optional<std::string>> stored(s.points.size());  // (each point's result, read once)
  std::vector<size_t> wanted;
  for (size_t i = 0; i < s.points.size(); ++i)
    if (!(stored[i] = store.get(point_key(s, s.points[i])))) wanted.push_back(i);
  const size_t reused = s.points.size() - wanted.size();

  if (!a.task_fingerprint.empty()) {  // a task: measure into the store, nothing else
    for (const std::string& f : s.fingerprints)
      if (f != a.task_fingerprint)
        throw Error("explore --task: the workload's fingerprint is " + f + ", the sweep's " + a.task_fingerprint +
                    ": an input changed since the sweep was emitted (emit it again)");
    measure_here(s, wanted, store, false);
    std::printf("texsim explore --task: %zu points measured, %zu in the store already\n", wanted.size(), reused);
    return 0;
  }
  const std::vector<Task> all = tasks_of(s);
  std::vector<size_t> task_of(s.points.size());
  std::vector<Task> todo;  // the tasks with points to measure, each with all of its points
  {
    std::set<size_t> wanted_set(wanted.begin(), wanted.end());
    for (const Task& t : all) {
      bool needed = false;
      for (size_t i : t.points) needed = needed || wanted_set.count(i);
      if (!needed) continue;
      for (size_t i : t.points) task_of[i] = todo.size();
      todo.push_back(t);
    }
  }
  if (emitting) return emit(s, todo, task_of, self, store, reused);

  // Here: the outputs checked before the work, then the tasks, then the rows from the store.
  std::vector<std::string> inputs = {a.texture};
  if (s.trace) inputs.push_back(a.queries);
  {
    OutputSet check;
    for (const std::string& in : inputs) check.add_input(in, "--texture/--queries");
    check.make_directory(a.out_dir, "--out");
    check.declare((fs::path(a.out_dir) / "explore.csv").string(), "--out");
  }
  std::map<std::string, size_t> no_rtl;  // why the RTL could not run a point -> points
  size_t rtl_points = 0;
  for (const Point& p : s.points)
    if (const std::string why = rtl_unavailable(s, p); !why.empty()) ++no_rtl[why];
    else ++rtl_points;
  const bool progress = isatty(STDERR_FILENO);
  if (a.jobs > 1 && todo.size() > 1) {
    std::vector<std::vector<std::string>> commands;
    for (const Task& t : todo) commands.push_back(task_command(s, t, self, store.dir()));
    run_tasks_here(commands, a.jobs, progress);
  } else {
    measure_here(s, wanted, store, progress);
  }
  for (size_t i : wanted)
    if (!(stored[i] = store.get(point_key(s, s.points[i]))))
      throw Error("explore: " + point_name(s, s.points[i]) + ": measured, but not in the store " + store.dir());
  std::string rows;
  for (size_t i = 0; i < s.points.size(); ++i) rows += csv_prefix(s, s.points[i]) + *stored[i] + "\n";
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
  std::printf("texsim explore: %zu points (%zu measured, %zu reused from %s; %s), %zu workloads, %.1f s -> %s/explore.csv%s\n",
              s.points.size(), wanted.size(), reused, store.dir().c_str(), timing.c_str(), s.workloads.size(), secs,
              a.out_dir.c_str(), a.plots ? (", index in " + a.out_dir + "/index.html").c_str() : "");
  return 0;
}

}  // namespace tex
