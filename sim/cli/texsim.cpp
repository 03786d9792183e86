// texsim: the command-line tool. Sample query traces, build and dump pyramids, render scenes.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

#include "engines/engine.h"
#include "model/error.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "reports/figures.h"
#include "workloads/query_trace.h"
#include "workloads/scenes.h"
#include "workloads/texture_io.h"

namespace {

using namespace tex;

// Options shared by every command that samples a texture.
struct SamplingOptions {
  std::string texture = "testcard";
  std::string filter = "trilinear";
  std::string wrap = "repeat";
  std::string wrap_u, wrap_v;
  std::string pyramid = "exact";
  std::string engine = "model";
  double lod_bias = 0, min_lod = -128, max_lod = 127.99;
  bool resize = false;
  std::string stalls = "none";
  uint64_t seed = 1;
  std::string load = "backdoor";
  std::string stats_path;
  std::string trace_path;
  std::string trace_window;
  bool verify = false;

  void add_to(CLI::App& cmd) {
    cmd.add_option("--texture,-t", texture, "image file (any OpenImageIO format) or pattern NAME[:WxH]")
        ->capture_default_str();
    cmd.add_option("--filter,-f", filter,
                   "point | bilinear | mip_nearest | trilinear, or a GL name (nearest_mipmap_linear, ...)")
        ->capture_default_str();
    cmd.add_option("--wrap,-w", wrap, "repeat | clamp | mirror, both axes")->capture_default_str();
    cmd.add_option("--wrap-u", wrap_u, "wrap mode of u only (overrides --wrap)");
    cmd.add_option("--wrap-v", wrap_v, "wrap mode of v only (overrides --wrap)");
    cmd.add_option("--pyramid", pyramid, "exact (mean of the level-0 footprint) | cascade")->capture_default_str();
    cmd.add_option("--engine,-e", engine, engine_list())->capture_default_str();
    cmd.add_option("--lod-bias", lod_bias, "added to lambda before the clamp, in levels")->capture_default_str();
    cmd.add_option("--min-lod", min_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_option("--max-lod", max_lod, "lambda clamp, in levels")->capture_default_str();
    cmd.add_flag("--resize", resize, "resample a texture whose sides are not powers of two");
    cmd.add_option("--stalls", stalls,
                   "none | random | heavy: input gaps and output stalls of cycle-accurate engines (none = ideal "
                   "timing, what the hardware sustains)")
        ->capture_default_str();
    cmd.add_option("--seed", seed, "seed of --stalls random|heavy and of the RTL's unreset registers")
        ->capture_default_str();
    cmd.add_option("--load", load,
                   "backdoor | port: fill the RTL's texture memories directly (0 clocks) or through the write "
                   "port (one texel per clock)")
        ->capture_default_str();
    cmd.add_option("--stats", stats_path, "write counters to this JSON file");
    cmd.add_option("--trace", trace_path, "write an FST waveform (engines rtl, systemc)");
    cmd.add_option("--trace-window", trace_window, "cycles FIRST:LAST to trace (default: all)");
    cmd.add_flag("--verify", verify, "also run the golden model and fail unless every sample is bit-identical");
  }

  SamplerConfig config() const {
    SamplerConfig c;
    if (!parse_filter(filter, c.filter)) throw Error("unknown filter '" + filter + "'");
    Wrap w;
    if (!parse_wrap(wrap, w)) throw Error("unknown wrap mode '" + wrap + "' (repeat, clamp, mirror)");
    c.wrap_u = c.wrap_v = w;
    if (!wrap_u.empty() && !parse_wrap(wrap_u, c.wrap_u)) throw Error("unknown wrap mode '" + wrap_u + "'");
    if (!wrap_v.empty() && !parse_wrap(wrap_v, c.wrap_v)) throw Error("unknown wrap mode '" + wrap_v + "'");
    if (!to_lod_fixed(lod_bias, c.lod_bias)) throw Error("--lod-bias " + std::to_string(lod_bias) + " is outside [-128, 128)");
    if (!to_lod_fixed(min_lod, c.min_lod)) throw Error("--min-lod " + std::to_string(min_lod) + " is outside [-128, 128)");
    if (!to_lod_fixed(max_lod, c.max_lod)) throw Error("--max-lod " + std::to_string(max_lod) + " is outside [-128, 128)");
    if (c.min_lod > c.max_lod) throw Error("--min-lod is greater than --max-lod");
    return c;
  }

  PyramidMode pyramid_mode() const {
    PyramidMode m;
    if (!parse_pyramid_mode(pyramid, m)) throw Error("unknown pyramid mode '" + pyramid + "' (exact, cascade)");
    return m;
  }

  EngineOptions engine_options() const {
    EngineOptions o;
    if (!parse_stalls(stalls, o.stalls)) throw Error("unknown --stalls '" + stalls + "' (none, random, heavy)");
    if (!parse_load_method(load, o.load)) throw Error("unknown --load '" + load + "' (backdoor, port)");
    o.seed = seed;
    o.show_progress = isatty(STDERR_FILENO);
    o.trace_path = trace_path;
    if (!trace_window.empty()) {
      unsigned long long a = 0, b = 0;
      char extra = 0;
      if (std::sscanf(trace_window.c_str(), "%llu:%llu%c", &a, &b, &extra) != 2 || b < a)
        throw Error("--trace-window '" + trace_window + "' is not FIRST:LAST with FIRST <= LAST");
      o.trace_begin = a;
      o.trace_end = b;
    }
    return o;
  }
};

// Runs the engine; with --verify also the golden model, and fails on the first differing sample.
EngineResult run_checked(const SamplingOptions& o, Engine& engine, const Pyramid& pyr, const SamplerConfig& cfg,
                         const std::vector<Request>& requests) {
  EngineResult r = engine.run(pyr, cfg, requests);
  if (!o.verify) return r;
  const EngineResult golden = run_model(pyr, cfg, requests);
  for (size_t i = 0; i < requests.size(); ++i)
    if (r.texels[i] != golden.texels[i]) {
      const Texel& a = r.texels[i];
      const Texel& b = golden.texels[i];
      throw Error("verify: sample " + std::to_string(i) + " differs: engine " + o.engine + " gives " +
                  std::to_string(a[0]) + "," + std::to_string(a[1]) + "," + std::to_string(a[2]) + "," +
                  std::to_string(a[3]) + ", model gives " + std::to_string(b[0]) + "," + std::to_string(b[1]) +
                  "," + std::to_string(b[2]) + "," + std::to_string(b[3]));
    }
  std::printf("verify: %zu samples of engine %s are bit-identical to the golden model\n", requests.size(),
              o.engine.c_str());
  return r;
}

// Cycle counters of a cycle-accurate engine, one line (the model has none).
void print_cycle_stats(const EngineStats& stats, const EngineOptions& options) {
  if (!stats.cycle) return;
  const CycleStats& c = *stats.cycle;
  std::printf("  %s (%s): %llu samples in %llu clocks = %.4f samples/clock after the %llu-clock pipeline fill, "
              "stalls %s, %llu output-stall clocks, texture load %s (%llu clocks)\n",
              stats.engine.c_str(), c.configuration.c_str(), (unsigned long long)stats.samples,
              (unsigned long long)c.cycles, stats.samples_per_clock(), (unsigned long long)c.latency_cycles,
              stalls_name(options.stalls).c_str(), (unsigned long long)c.output_stall_cycles,
              load_method_name(options.load).c_str(), (unsigned long long)c.load_cycles);
}

void write_stats(const std::string& path, const EngineStats& stats, const EngineOptions& options, double seconds) {
  if (path.empty()) return;
  nlohmann::json j = stats.to_json(options);
  j["wall_seconds"] = seconds;
  write_file_atomically(path, j.dump(2) + "\n");
}

int cmd_sample(const SamplingOptions& o, const std::string& queries_path, const std::string& out_path) {
  const auto t0 = std::chrono::steady_clock::now();
  const SamplerConfig cfg = o.config();
  const EngineOptions eo = o.engine_options();
  const auto engine = make_engine(o.engine, eo);  // engine errors come before any work
  const Pyramid pyr = build_pyramid(load_texture(o.texture, o.resize), o.pyramid_mode());
  const auto queries = read_queries(queries_path);
  const auto requests = to_requests(queries, pyr.log2_w0(), pyr.log2_h0(), queries_path);
  const EngineResult r = run_checked(o, *engine, pyr, cfg, requests);
  write_file_atomically(out_path, format_results(r.texels));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(o.stats_path, r.stats, eo, secs);
  print_cycle_stats(r.stats, eo);
  std::printf("texsim sample: %zu queries, %s, %s/%s, %dx%d texture, engine %s -> %s (%.2f s)\n", requests.size(),
              filter_name(cfg.filter).c_str(), wrap_name(cfg.wrap_u).c_str(), wrap_name(cfg.wrap_v).c_str(),
              pyr.levels[0].width, pyr.levels[0].height, o.engine.c_str(), out_path.c_str(), secs);
  return 0;
}

int cmd_mip(const std::string& texture, const std::string& mode_name, bool resize, const std::string& dump_dir,
            const std::string& layout_path) {
  if (dump_dir.empty() && layout_path.empty()) throw Error("mip: give --dump-levels DIR and/or --layout FILE");
  PyramidMode mode;
  if (!parse_pyramid_mode(mode_name, mode)) throw Error("unknown pyramid mode '" + mode_name + "' (exact, cascade)");
  const Pyramid pyr = build_pyramid(load_texture(texture, resize), mode);
  if (!dump_dir.empty()) {
    std::filesystem::create_directories(dump_dir);
    for (size_t k = 0; k < pyr.levels.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "level%02zu.png", k);
      save_image(pyr.levels[k], (std::filesystem::path(dump_dir) / name).string());
    }
  }
  if (!layout_path.empty()) save_image(mip_layout(pyr), layout_path);
  std::printf("texsim mip: %dx%d texture, %zu levels (%s)%s%s%s%s\n", pyr.levels[0].width, pyr.levels[0].height,
              pyr.levels.size(), mode_name.c_str(), dump_dir.empty() ? "" : ", levels in ", dump_dir.c_str(),
              layout_path.empty() ? "" : ", layout in ", layout_path.c_str());
  return 0;
}

// Renders one frame of a scene, or with --frames M and no --frame every frame to OUT_000.png ...
// A scene with its own map (reflect, mesh) rejects --texture; one whose map is not periodic
// (reflect, mesh) samples with clamp-to-edge unless a --wrap option is given.
int cmd_render(const SamplingOptions& o, const std::string& scene, SceneOptions so, bool all_frames,
               bool texture_given, bool wrap_given, const std::string& out) {
  const auto t0 = std::chrono::steady_clock::now();
  SamplerConfig cfg = o.config();
  const EngineOptions eo = o.engine_options();
  const auto engine = make_engine(o.engine, eo);  // engine errors come before any work
  make_scene(scene, so);  // checks the scene name, size and frame numbers before any work
  const int first = all_frames ? 0 : so.frame, last = all_frames ? so.frames - 1 : so.frame;
  size_t samples = 0;
  EngineStats last_stats;
  for (int f = first; f <= last; ++f) {
    so.frame = f;
    const SceneFrame frame = make_scene(scene, so);
    const Pyramid pyr = build_pyramid(scene_texture(frame, texture_given ? o.texture : "", o.resize), o.pyramid_mode());
    if (frame.clamp_edges && !wrap_given) cfg.wrap_u = cfg.wrap_v = Wrap::Clamp;
    const auto requests = to_requests(frame.queries, pyr.log2_w0(), pyr.log2_h0(), "scene " + scene);
    const EngineResult r = run_checked(o, *engine, pyr, cfg, requests);
    std::string path = out;
    if (all_frames) {
      const std::filesystem::path p(out);
      char num[16];
      std::snprintf(num, sizeof num, "_%03d", f);
      path = (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
    }
    save_image(compose(frame, r.texels, pyr.levels[0].channel_bits), path);
    samples += requests.size();
    last_stats = r.stats;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(o.stats_path, last_stats, eo, secs);  // counters of the last frame, time of them all
  print_cycle_stats(last_stats, eo);
  std::printf("texsim render: scene %s, %dx%d, frame%s %d..%d of %d, %zu samples, %s, engine %s -> %s (%.2f s)\n",
              scene.c_str(), so.width, so.height, all_frames ? "s" : "", first, last, so.frames, samples,
              filter_name(cfg.filter).c_str(), o.engine.c_str(), out.c_str(), secs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"texsim: cycle-accurate mip-mapping texture unit (Williams 1983) - model, RTL and SystemC"};
  // 0..1 plus the check after parse: CLI11 reports a missing subcommand before an unexpected
  // word, so `texsim smaple ...` would not name the typo.
  app.require_subcommand(0, 1);

  SamplingOptions sample_opts;
  std::string queries, out;
  CLI::App* sample = app.add_subcommand("sample", "sample a query trace (CSV) and write one RGBA line per query");
  sample_opts.add_to(*sample);
  sample->add_option("--queries,-q", queries, "CSV: header u,v,lod or u,v,dudx,dvdx,dudy,dvdy")->required();
  sample->add_option("--out,-o", out, "result CSV: header r,g,b,a")->required();

  std::string mip_texture = "testcard", mip_mode = "exact", dump_dir, layout;
  bool mip_resize = false;
  CLI::App* mip = app.add_subcommand("mip", "build a pyramid; dump its levels or the paper's Figure 1 layout");
  mip->add_option("--texture,-t", mip_texture, "image file or pattern NAME[:WxH]")->capture_default_str();
  mip->add_option("--pyramid", mip_mode, "exact | cascade")->capture_default_str();
  mip->add_flag("--resize", mip_resize, "resample a texture whose sides are not powers of two");
  mip->add_option("--dump-levels", dump_dir, "write DIR/level00.png, level01.png, ...");
  mip->add_option("--layout", layout, "write the packed R/G/B memory layout (paper Figure 1)");

  SamplingOptions render_opts;
  std::string scene = "plane", render_out;
  int width = 640, height = 480;
  CLI::App* render = app.add_subcommand("render", "render a scene of the paper through an engine");
  render_opts.add_to(*render);
  std::string scene_list;
  for (const std::string& n : scene_names()) scene_list += n + " | ";
  scene_list += "mesh16 (the mesh with 16-bit X, Y, Z; model engines)";
  render->add_option("--scene,-s", scene, scene_list)->capture_default_str();
  render->add_option("--width", width, "image width")->capture_default_str();
  render->add_option("--height", height, "image height")->capture_default_str();
  render->add_option("--out,-o", render_out, "output image (PNG, TIFF, EXR, ...)")->required();
  int frame = 0, frames = 1;
  CLI::Option* frame_opt = render->add_option("--frame", frame, "animation frame to render (0-based)");
  render->add_option("--frames", frames, "frames of the animation; without --frame renders all to OUT_000.png ...")
      ->capture_default_str();

  FiguresOptions fig;
  CLI::App* figures = app.add_subcommand("figures", "render every scene's variants, reference, errors and flicker");
  figures->add_option("--out,-o", fig.out_dir, "output directory")->capture_default_str();
  figures->add_option("--engine,-e", fig.engine, "engine of the variants: " + engine_list())->capture_default_str();
  figures->add_option("--width", fig.width, "still image width")->capture_default_str();
  figures->add_option("--height", fig.height, "still image height")->capture_default_str();
  figures->add_option("--frames", fig.frames, "animation frames (flicker)")->capture_default_str();
  figures->add_option("--reference-samples", fig.reference_samples, "reference sub-pixel positions per axis")
      ->capture_default_str();

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "texsim: error: %s (see --help)\n", e.what());
    return 2;
  }
  if (app.get_subcommands().empty()) {
    std::fprintf(stderr, "texsim: error: a command is required (see --help)\n");
    return 2;
  }
  try {
    if (*sample) return cmd_sample(sample_opts, queries, out);
    if (*mip) return cmd_mip(mip_texture, mip_mode, mip_resize, dump_dir, layout);
    if (*render) {
      SceneOptions so;
      so.width = width;
      so.height = height;
      so.frame = frame;
      so.frames = frames;
      const bool wrap_given = render->count("--wrap") + render->count("--wrap-u") + render->count("--wrap-v") > 0;
      return cmd_render(render_opts, scene, so, frames > 1 && frame_opt->count() == 0,
                        render->count("--texture") > 0, wrap_given, render_out);
    }
    if (*figures) return make_figures(fig);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texsim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
