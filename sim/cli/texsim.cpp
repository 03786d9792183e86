// texsim: the command-line tool. Sample query traces, build and dump pyramids, render scenes.
#include <CLI/CLI.hpp>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <sstream>

#include "cli/frame_store.h"
#include "cli/render_batch.h"
#include "cli/render_model.h"
#include "cli/sampling.h"
#include "engines/engine.h"
#include "model/error.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "reports/explore.h"
#include "reports/figures.h"
#include "workloads/limits.h"
#include "workloads/query_trace.h"
#include "workloads/scenes.h"
#include "workloads/output_files.h"
#include "workloads/texture_io.h"
#include "workloads/texture_list.h"

namespace {

using namespace tex;

// A cube map's texel fetches checked as they are read: the layer must be one of its faces.
class CubeFetchCheck final : public RequestSource {
 public:
  CubeFetchCheck(RequestSource& inner, const TextureTable& table, std::string name)
      : inner_(inner), table_(table), name_(std::move(name)) {}
  size_t read(Request* out, size_t max) override {
    const size_t n = inner_.read(out, max);
    for (size_t i = 0; i < n; ++i) {
      const Request& r = out[i];
      if (r.op != Op::Fetch || r.texture >= table_.size() || table_[r.texture].kind != TextureKind::Cube) continue;
      const int layers = table_[r.texture].layers();
      if (r.layer < 0 || r.layer >= layers)
        throw Error(name_ + ": query " + std::to_string(count_ + i) + ": layer " + std::to_string(r.layer) +
                    " is not a face of the cube map (0.." + std::to_string(layers - 1) + ": face + 6 x cube)");
    }
    count_ += n;
    return n;
  }

 private:
  RequestSource& inner_;
  const TextureTable& table_;
  std::string name_;
  size_t count_ = 0;
};

// The filter as the summary line names it, with a reduction other than the weighted average.
std::string filter_label(const SamplerConfig& c) {
  return filter_name(c.filter) + (c.reduction == Reduction::WeightedAverage ? "" : " " + reduction_name(c.reduction));
}

// What the summary line says was asked: texel fetches, gathers of a component, or the filter.
std::string op_label(Op op, int component, const SamplerConfig& c) {
  if (op == Op::Fetch) return "texel fetches";
  if (op == Op::Gather) return std::string("gathers of ") + "RGBA"[component];
  if (op == Op::Compare) return "depth compares (" + compare_op_name(c.compare_op) + ", " + filter_label(c) + ")";
  return filter_label(c);
}

int cmd_sample(const SamplingOptions& o, const std::string& queries_path, const std::string& textures_path,
               const std::string& texture_layers, const std::string& cube_faces, const std::string& out_path,
               const std::string& op_option, const std::string& component_option, bool depth) {
  const auto t0 = std::chrono::steady_clock::now();
  // Everything is checked before the work: options, engine, outputs, texture, every query.
  Op op{};
  if (!parse_op(op_option, op)) throw Error("--op " + quote_clipped(op_option) + " is not sample, gather, compare or fetch");
  int component = -1;  // 0..3, or r g b a in either case
  for (int c = 0; c < 4; ++c)
    if (component_option == std::to_string(c) ||
        (component_option.size() == 1 && std::tolower(static_cast<unsigned char>(component_option[0])) == "rgba"[c]))
      component = c;
  if (component < 0) throw Error("--component " + quote_clipped(component_option) + " is not 0, 1, 2, 3 (r, g, b, a)");
  if (component != 0 && op != Op::Gather) throw Error("--component is a gather's (--op gather)");
  const SamplerConfig cfg = o.config();
  const TextureOptions topts = o.texture_options();
  EngineOptions eo = o.engine_options();
  OutputSet outputs;
  std::vector<TextureListEntry> list;
  // --texture-layers: an array of those images, in place of --texture; --cube: a cube map (or cube
  // array) of those faces.
  std::vector<std::string> layer_paths;
  const std::string& layers_option = cube_faces.empty() ? texture_layers : cube_faces;
  const char* layers_name = cube_faces.empty() ? "--texture-layers" : "--cube";
  if (!layers_option.empty()) {
    if (o.texture_opt->count() || !textures_path.empty() || (!texture_layers.empty() && !cube_faces.empty()))
      throw Error("sample: give one of --texture, --texture-layers, --cube and --textures");
    layer_paths = split_commas(layers_option);
    for (const std::string& p : layer_paths)
      if (p.empty()) throw Error(std::string(layers_name) + " " + quote_clipped(layers_option) + ": an empty path");
    for (const std::string& p : layer_paths) outputs.add_input(p, layers_name);
  }
  if (!textures_path.empty()) {
    if (o.texture_opt->count()) throw Error("sample: give --texture or --textures, not both");
    list = read_texture_list(textures_path, cfg);
    outputs.add_input(textures_path, "--textures");
    for (const TextureListEntry& e : list) outputs.add_input(e.path, "--textures");
  } else if (layer_paths.empty()) {
    o.add_inputs(outputs);
    list.push_back({o.texture, cfg, false, {}, {}, ""});
  } else {
    list.push_back({layer_paths[0], cfg, false, {}, {}, ""});
  }
  outputs.add_input(queries_path, "--queries");
  OutputFile& result = outputs.declare(out_path, "--out");
  OutputFile* stats_out = o.stats_output(outputs);
  OutputFile* trace = o.trace_output(outputs);
  OutputFile* miss_out = o.miss_trace_output(outputs);
  OutputFile* clocks_out = o.response_clocks_output(outputs);
  if (list.size() > 1 && eo.memory != Memory::Cached)
    throw Error(textures_path + ": " + std::to_string(list.size()) +
                " textures; the on-chip unit holds one (the paper's design): use --memory cached");
  // A query file is checked whole by threads of its own while the textures load (a pipe is
  // checked as it streams); a bad texture is still the error reported first. A file of modest size
  // is parsed only there: the engine reads the requests the threads keep. The cycle engines wait
  // for the whole check before their work; the model, faster than the parse, starts on the first
  // requests, and a bad line stops it as soon as the threads find it (no output is written).
  SamplerTable samplers;  // entry i: list line i's
  for (const TextureListEntry& e : list) samplers.push_back(e.sampler);
  const uint32_t unnormalized = unnormalized_samplers(samplers);  // their queries give texel coordinates
  QueryForm form{unnormalized, uint8_t(component)};
  for (size_t s = 0; s < samplers.size(); ++s) form.no_compare |= uint32_t(!samplers[s].compare_problem().empty()) << s;
  std::optional<QueryReader> reader;
  std::optional<QueryFileParser> parser;
  std::exception_ptr query_error;
  try {
    reader.emplace(queries_path);
    if (reader->op() != op)  // (the header names what the queries carry)
      throw Error(reader->name() + ": header " + reader->header() + " is a " + op_name(reader->op()) + "'s" +
                  (op == Op::Sample ? ": give --op " + op_name(reader->op())
                                    : "; --op " + op_name(op) + " takes " +
                                          (op == Op::Fetch    ? "[tex,[smp,]]i,j[,layer],level"
                                           : op == Op::Gather ? "[tex,[smp,]]u,v[,layer]"
                                                              : "[tex,[smp,]]u,v[,layer],ref,...")));
    if (reader->rewindable()) parser.emplace(queries_path, 2, true, form);
  } catch (...) {
    query_error = std::current_exception();
  }
  std::vector<std::vector<Pyramid>> arrays;  // each texture's layers (a 2D texture: one)
  arrays.reserve(list.size());
  TextureTable table;
  for (const TextureListEntry& e : list) {
    TextureOptions entry = topts;
    entry.srgb = entry.srgb || e.srgb;
    entry.base_level = e.base_level.value_or(entry.base_level);
    entry.max_level = e.max_level.value_or(entry.max_level);
    if (e.base_level || e.max_level)
      entry.view_given_by = e.at + "base=" + std::to_string(entry.base_level) + " max=" + std::to_string(entry.max_level);
    TextureKind kind = cube_faces.empty() ? TextureKind::Texture2D : TextureKind::Cube;
    const std::vector<Pyramid>& layers =
        arrays.emplace_back(load_array(layer_paths.empty() ? std::vector<std::string>{e.path} : layer_paths, entry, &kind));
    BoundTexture bound(&layers[0], {}, kind);
    for (size_t l = 1; l < layers.size(); ++l) bound.more_layers.push_back(&layers[l]);
    table.push_back(bound);
  }
  if (query_error) std::rethrow_exception(query_error);
  check_tables(table, samplers, eo.memory);  // (before any output: an array needs the cached unit)
  if (reader && !query_error && op != Op::Fetch)  // the header's coordinates are the textures' kind's
    for (size_t t = 0; t < table.size(); ++t)
      if ((table[t].kind == TextureKind::Cube) != reader->cube())
        throw Error(reader->name() + ": header " + reader->header() + (reader->cube() ? " is a cube map's; " : " is a 2D texture's; ") +
                    (list.size() > 1 ? list[t].at : "") + list[t].path +
                    (table[t].kind == TextureKind::Cube ? " is a cube map (its queries: x,y,z,...)" : " is not a cube map (its queries: u,v,...)"));
  // A depth compare reads a depth texture's R (Vulkan: compareEnable with a depth format's view): a
  // texture declared one (--depth, a list line's `depth`), never an sRGB (colour) one.
  for (size_t t = 0; t < table.size(); ++t) {
    const bool is_depth = depth || list[t].depth;
    const std::string& at = list[t].at;  // ("" for --texture)
    if (is_depth && !table[t].pyramid->depth_problem().empty())
      throw Error(at + "a depth texture (" + list[t].path + ") that is " + table[t].pyramid->depth_problem());
    if (op == Op::Compare && !is_depth)
      throw Error(at + "--op compare of a colour texture (" + list[t].path + "): a depth compare reads a depth "
                  "texture's R as its depth; declare the texture one (--depth, or `depth` on its --textures line)");
  }
  const bool kept = parser && parser->kept();
  if (parser && (!kept || o.engine != "model")) parser->wait();
  const Pyramid& pyr = arrays[0][0];
  if (trace) eo.trace_path = trace->write_path();

  std::optional<MissTraceWriter> misses;
  if (miss_out) misses.emplace(*miss_out);
  LineSet lines(misses ? &*misses : nullptr);  // texture bytes touched
  if (eo.memory == Memory::Cached) eo.miss_sink = &lines;
  std::optional<ClockWriter> clocks;
  if (clocks_out) eo.clock_sink = &clocks.emplace(*clocks_out);

  // One helper thread beside the engine: it parses a trace that streams, or else writes the results.
  QuerySource streamed(*reader, form);
  std::optional<ReadAheadSource> ahead;
  RequestSource& queries = kept ? static_cast<RequestSource&>(*parser) : ahead.emplace(streamed);
  // A texel fetch of a cube map names a face (face + 6 x cube) as its layer: one outside the faces
  // is a bad query here (the hardware answers 0, Vulkan's robust access to the faces' array view).
  std::optional<CubeFetchCheck> faces;
  const bool any_cube = std::any_of(table.begin(), table.end(), [](const BoundTexture& t) { return t.kind == TextureKind::Cube; });
  RequestSource& source = op == Op::Fetch && any_cube ? faces.emplace(queries, table, reader->name()) : queries;
  bool wide = false;  // sRGB textures give linear unorm16 results, EAC ones its 16-bit channels
  for (const BoundTexture& t : table) wide = wide || t.pyramid->srgb || is_eac(t.pyramid->format);
  CsvTexelWriter writer(result.open(), wide ? "r16,g16,b16,a16" : "r,g,b,a");
  std::optional<WriteBehindSink> behind;
  TexelSink& sink = kept ? static_cast<TexelSink&>(behind.emplace(writer)) : writer;
  EngineStats stats = run_engine(o, eo, outputs, trace, table, samplers, source, sink);
  if (behind) {
    behind->finish();
    stats.write_seconds = behind->busy_seconds();
  }
  if (kept) parser->wait();
  stats.parse_seconds = kept ? parser->parse_seconds() : ahead->busy_seconds();
  const size_t count = kept ? parser->count() : streamed.count();
  const QueryCounts& counts = kept ? parser->counts() : streamed.counts();
  if (misses) misses->close();
  if (clocks) clocks->close();
  if (count == 0)
    std::fprintf(stderr, "texsim: %s has no queries (only a header): the result has only its header\n",
                 reader->name().c_str());
  // A frame's trace (--textures): the figures texsim render gives for the frame.
  std::optional<FrameFigures> frame;
  if (!textures_path.empty())
    frame = frame_figures(counts, stats, texture_bytes_resident(table, eo),
                          lines.bytes(line_bytes(table, eo)));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(stats_out, stats, eo, secs, frame ? frame->to_json() : nlohmann::json::object());
  outputs.commit();
  // The summary goes to stderr when the result itself is on standard output.
  std::FILE* report = result.path() == "-" || result.path() == "/dev/stdout" ? stderr : stdout;
  if (report == stdout) {
    print_cycle_stats(stats, eo);
    print_cache_stats(stats);
    print_probe_stats(stats);
  }
  if (frame) std::fprintf(report, "  %s\n", frame->summary().c_str());
  if (table.size() > 1)
    std::fprintf(report, "texsim sample: %zu queries, %s, %zu textures, engine %s -> %s (%.2f s)\n", count,
                 op_label(op, component, cfg).c_str(), table.size(), o.engine.c_str(), out_path.c_str(), secs);
  else
    std::fprintf(report, "texsim sample: %zu queries, %s, %s/%s, %dx%d%s, engine %s -> %s (%.2f s)\n",
                 count, op_label(op, component, cfg).c_str(), wrap_name(samplers[0].wrap_u).c_str(),
                 wrap_name(samplers[0].wrap_v).c_str(), pyr.levels[0].width, pyr.levels[0].height,
                 (table[0].kind == TextureKind::Cube
                      ? (table[0].layers() == 6 ? std::string(" cube map") : " cube map x " + std::to_string(table[0].layers() / 6) + " cubes")
                  : table[0].layers() > 1 ? " texture x " + std::to_string(table[0].layers()) + " layers"
                                          : std::string(" texture")).c_str(),
                 o.engine.c_str(), out_path.c_str(), secs);
  return 0;
}

// The memory image options of `mip` (docs/memory.md §1).
struct ImageOptions {
  std::string path, block = "4x4", order = "row-major", base = "0";
  LayoutParams layout() const {
    LayoutParams p;
    parse_block(block, p);
    if (!parse_block_order(order, p.order)) throw Error("unknown --block-order " + quote_clipped(order) + " (row-major, morton)");
    const uint64_t b = parse_unsigned(base, "--mem-base");
    if (b > 0xFFFFFFFFull) throw Error("--mem-base " + base + " is beyond the 32-bit address space");
    p.base = uint32_t(b);
    return p;
  }
};

int cmd_mip(const std::string& texture, const std::string& mode_name, bool resize, const std::string& format_name,
            bool format_given, bool srgb, const std::string& dump_dir, const std::string& layout_path,
            const ImageOptions& image) {
  if (dump_dir.empty() && layout_path.empty() && image.path.empty())
    throw Error("mip: give --dump-levels DIR, --layout FILE and/or --memory-image FILE");
  const LayoutParams memory_layout = image.layout();
  TextureOptions topts;
  topts.resize = resize;
  if (!parse_pyramid_mode(mode_name, topts.mode))
    throw Error("unknown pyramid mode " + quote_clipped(mode_name) + " (exact, cascade)");
  topts.format = parse_encodable_format(format_name);
  topts.format_given = format_given;
  topts.srgb = srgb;
  OutputSet outputs;
  outputs.add_input(texture, "--texture");
  if (!layout_path.empty()) check_image_path(layout_path);
  OutputFile* layout = layout_path.empty() ? nullptr : &outputs.declare(layout_path, "--layout", OutputSet::Kind::File);
  OutputFile* image_out = image.path.empty() ? nullptr : &outputs.declare(image.path, "--memory-image");
  const Pyramid pyr = load_pyramid(texture, topts);
  std::vector<uint8_t> image_bytes;
  if (image_out)  // (the layout checks the block, base and size before anything is written)
    image_bytes = memory_image_file(
        pyr, layout_of(pyr, memory_layout));
  if (!dump_dir.empty()) {
    outputs.make_directory(dump_dir, "--dump-levels");
    std::vector<OutputFile*> levels;
    for (size_t k = 0; k < pyr.levels.size(); ++k) {
      char name[32];
      std::snprintf(name, sizeof name, "level%02zu.png", k);
      levels.push_back(&outputs.declare((std::filesystem::path(dump_dir) / name).string(), "--dump-levels",
                                        OutputSet::Kind::File));
    }
    // (an sRGB texture's levels as stored, sRGB codes: what a viewer shows right)
    for (size_t k = 0; k < pyr.levels.size(); ++k) save_image(pyr.srgb ? pyr.codes[k] : pyr.levels[k], *levels[k]);
  }
  if (layout) {
    Pyramid shown;  // the levels as stored
    shown.levels = pyr.srgb ? pyr.codes : pyr.levels;
    save_image(mip_layout(shown), *layout);
  }
  if (image_out) {
    std::FILE* f = image_out->open();
    if (std::fwrite(image_bytes.data(), 1, image_bytes.size(), f) != image_bytes.size())
      throw Error("cannot write " + image_out->path());
    image_out->close();
  }
  outputs.commit();
  std::printf("texsim mip: %dx%d %s%s texture, %zu levels (%s)%s%s%s%s%s%s\n", pyr.levels[0].width,
              pyr.levels[0].height, format_info(pyr.format).name, pyr.srgb ? " sRGB" : "", pyr.levels.size(),
              mode_name.c_str(), dump_dir.empty() ? "" : ", levels in ", dump_dir.c_str(),
              layout_path.empty() ? "" : ", layout in ", layout_path.c_str(),
              image.path.empty() ? "" : ", memory image in ", image.path.c_str());
  return 0;
}

// Renders one frame of a scene, or with --frames M and no --frame every frame to OUT_000.png ...
// A scene with its own map (reflect, mesh) rejects --texture; one whose map is not periodic
// (reflect, mesh) samples with clamp-to-edge unless a --wrap option is given.
int cmd_render(const SamplingOptions& o, const std::string& scene, SceneOptions so, bool all_frames,
               bool texture_given, bool wrap_given, const std::string& out, FrameStore* store) {
  const auto t0 = std::chrono::steady_clock::now();
  SamplerConfig cfg = o.config();
  const TextureOptions topts = o.texture_options();
  EngineOptions eo = o.engine_options();
  make_scene(scene, so);  // checks the scene name, size and frame numbers before any work
  check_image_path(out);
  const int first = all_frames ? 0 : so.frame, last = all_frames ? so.frames - 1 : so.frame;
  OutputSet outputs;
  if (texture_given) o.add_inputs(outputs);
  std::vector<OutputFile*> images;
  for (int f = first; f <= last; ++f) {
    std::string path = out;
    if (all_frames) {
      const std::filesystem::path p(out);
      char num[16];
      std::snprintf(num, sizeof num, "_%03d", f);
      path = (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
    }
    images.push_back(&outputs.declare(path, "--out", OutputSet::Kind::File));
  }
  OutputFile* stats_out = o.stats_output(outputs);
  OutputFile* trace = o.trace_output(outputs);
  if (trace) eo.trace_path = trace->write_path();
  std::optional<MissTraceWriter> misses;  // every frame's, in order
  if (OutputFile* miss_out = o.miss_trace_output(outputs)) eo.miss_sink = &misses.emplace(*miss_out);
  std::optional<ClockWriter> clocks;  // every frame's, each counted from its first request
  if (OutputFile* clocks_out = o.response_clocks_output(outputs)) eo.clock_sink = &clocks.emplace(*clocks_out);

  size_t samples = 0;
  EngineStats last_stats;
  for (int f = first; f <= last; ++f) {
    so.frame = f;
    const SceneFrame frame = make_scene(scene, so);
    const Pyramid pyr = scene_pyramid(frame, texture_given ? o.texture : "", topts);
    if (frame.clamp_edges && !wrap_given) cfg.wrap_u = cfg.wrap_v = Wrap::Clamp;
    const SamplerTable samplers{cfg};
    const uint32_t unnormalized = unnormalized_samplers(samplers);
    std::vector<Query> in_texels;  // (the frame's queries are copied only for an unnormalized sampler)
    const std::vector<Query>& queries =
        unnormalized ? (in_texels = in_sampler_coordinates(frame.queries, samplers, {pyr.extent0()})) : frame.queries;
    const auto requests = to_requests(queries, "scene " + scene, QueryForm{unnormalized});
    if (store) {  // (one frame, no traces: checked by the caller)
      store->set_inputs(requests, {{&pyr}}, samplers);
      if (store->reuse(*images[0], stats_out)) {
        outputs.commit();
        std::printf("texsim render: scene %s, frame %d of %d: reused from the store %s -> %s\n", scene.c_str(), f,
                    so.frames, store->dir().c_str(), out.c_str());
        return 0;
      }
    }
    VectorSource source(requests);
    VectorSink texels;
    last_stats = run_engine(o, eo, outputs, trace, {{&pyr}}, samplers, source, texels);
    if (pyr.srgb) {  // linear results back to sRGB codes for the picture, as a display expects
      for (Texel& t : texels.texels) t = encode_srgb_texel(t);
      save_image(compose(frame, texels.texels, 8), *images[size_t(f - first)]);
    } else {
      save_image(compose(frame, texels.texels, pyr.levels[0].channel_bits), *images[size_t(f - first)]);
    }
    samples += requests.size();
  }
  if (misses) misses->close();
  if (clocks) clocks->close();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_stats(stats_out, last_stats, eo, secs);  // counters of the last frame, time of them all
  outputs.commit();
  if (store) store->keep(images[0]->path(), o.stats_path);
  print_cycle_stats(last_stats, eo);
  print_cache_stats(last_stats);
  print_probe_stats(last_stats);
  std::printf("texsim render: scene %s, %dx%d, frame%s %d..%d of %d, %zu samples, %s, engine %s -> %s (%.2f s)\n",
              scene.c_str(), so.width, so.height, all_frames ? "s" : "", first, last, so.frames, samples,
              filter_label(cfg).c_str(), o.engine.c_str(), out.c_str(), secs);
  return 0;
}

}  // namespace

// --max-memory, --import-memory and --import-timeout (workloads/limits.h), on every command that
// reads files (the import's on those that read models).
struct RunLimits {
  std::string max_memory, import_memory;
  double import_seconds = 0;
  void add_to(CLI::App& cmd, bool models) {
    cmd.add_option("--max-memory", max_memory,
                   "the memory this run may take (e.g. 512M, 8G; default " + memory_words(default_memory_limit()) +
                       ": half the machine's, or an inherited lower data limit); a file whose header asks for more "
                       "is refused in one line, and any allocation past it fails");
    if (models)
      cmd.add_option("--import-memory", import_memory,
                     "the memory a model file's import (Assimp) may take (default 256 MiB plus 64 times the bytes it "
                     "reads, at most --max-memory); past it the import stops with one line");
    if (models)
      cmd.add_option("--import-timeout", import_seconds,
                     "seconds a model file's import may take (default 30 plus 1 per MiB of the file); past it the "
                     "run stops")
          ->check(CLI::PositiveNumber);
  }
  void apply() const {
    set_memory_limit(max_memory.empty() ? default_memory_limit() : parse_memory_size(max_memory, "--max-memory"));
    if (!import_memory.empty()) set_import_memory(parse_memory_size(import_memory, "--import-memory"));
    if (import_seconds > 0) set_import_timeout(import_seconds);
  }
};

int main(int argc, char** argv) {
  CLI::App app{"texsim: cycle-accurate mip-mapping texture unit (Williams 1983) - model, RTL and SystemC"};
  // 0..1 plus the check after parse: CLI11 reports a missing subcommand before an unexpected
  // word, so `texsim smaple ...` would not name the typo.
  app.require_subcommand(0, 1);

  RunLimits limits;
  SamplingOptions sample_opts;
  std::string queries, out;
  CLI::App* sample = app.add_subcommand("sample", "sample a query trace (CSV) and write one RGBA line per query");
  sample_opts.add_to(*sample);
  limits.add_to(*sample, false);
  sample->add_option("--queries,-q", queries,
                     "CSV: header u,v,lod or u,v,dudx,dvdx,dudy,dvdy, either with a leading tex column, or "
                     "tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper; with --op gather u,v, with --op fetch i,j,level, "
                     "with --op compare a ref column after u,v (u,v,ref,lod, ...); an array's layer as a column after "
                     "u,v (i,j): u,v,layer,lod, i,j,layer,level, ...; a cube map's direction x,y,z for u,v: x,y,z,lod, "
                     "x,y,z,dxdx,dydx,dzdx,dxdy,dydy,dzdy[,bias], x,y,z,layer,ref,lod, ... (- = standard input)")
      ->required();
  std::string sample_op = "sample", sample_component = "0";
  sample->add_option("--op", sample_op,
                     "sample | gather | compare | fetch: what each query asks; gather: textureGather, one component of "
                     "the four texels a linear filter weighs at the base level (header u,v); compare: a depth compare "
                     "(shadow lookup): each texel's R, the depth, tested `ref OP depth` (--compare-op) and the tests "
                     "filtered (header u,v,ref,lod or u,v,ref,dudx,...; result R, 0, 0, 1); fetch: texelFetch of "
                     "texel (i, j) of a level, no filter, 0 outside the texture (Vulkan robust image access; header "
                     "i,j,level)")
      ->capture_default_str();
  sample->add_option("--component", sample_component, "the component a gather gathers: 0 1 2 3 or r g b a (R G B A)")
      ->capture_default_str();
  bool sample_depth = false;
  sample->add_flag("--depth", sample_depth,
                   "the texture is a depth texture: its R channel is the depth (16-bit units: D16; 8-bit units: D8), "
                   "what --op compare reads; --op compare takes only depth textures (a --textures line: `depth`)");
  sample->add_option("--out,-o", out, "result CSV: header r,g,b,a (- = standard output)")->required();
  std::string textures_list, texture_layers, cube_faces;
  sample->add_option("--texture-layers", texture_layers,
                     "an array texture, in place of --texture: its layers' image files A,B,C,... (1 to 256 of one size; "
                     "each gets its own pyramid); --texture also takes DDS/KTX/KTX2 array files. A query's layer "
                     "is rounded to the nearest (a tie to the even) and clamped to the layers; a fetch's outside "
                     "them answers 0");
  sample->add_option("--cube", cube_faces,
                     "a cube map, in place of --texture: its faces' image files +X,-X,+Y,-Y,+Z,-Z (square, of one "
                     "size; six more for each further cube of a cube array); --texture also takes DDS/KTX/KTX2 cube "
                     "files. Queries give a direction: x,y,z,lod or x,y,z,dxdx,dydx,dzdx,dxdy,dydy,dzdy (with "
                     "--memory cached; the model engine)");
  sample->add_option("--textures", textures_list,
                     "a descriptor table instead of --texture: one `id path [wrap_u [wrap_v]]` per line, ids 0, 1, ... "
                     "(what render --trace-queries writes); the trace's tex column names the entry");

  std::string mip_texture = "testcard", mip_mode = "exact", mip_format = "rgba8", dump_dir, layout;
  bool mip_resize = false, mip_srgb = false;
  CLI::App* mip = app.add_subcommand("mip", "build a pyramid; dump its levels or the paper's Figure 1 layout");
  mip->add_option("--texture,-t", mip_texture, "image file, DDS/KTX/KTX2/.astc texture file, or pattern NAME[:WxH]")
      ->capture_default_str();
  mip->add_option("--pyramid", mip_mode, "exact | cascade")->capture_default_str();
  limits.add_to(*mip, false);
  mip->add_flag("--resize", mip_resize, "resample a texture whose sides are not powers of two to the nearest ones (no longer needed: every engine samples any size)");
  mip->add_flag("--srgb", mip_srgb, "the texture's R, G, B are sRGB codes: the pyramid averaged in linear space, "
                "levels and memory image in sRGB codes");
  CLI::Option* mip_format_opt = mip->add_option("--format", mip_format,
                                                texel_format_names() + ": how memory holds an image file or pattern "
                                                "(libsquish, Mesa for bc7, ours for etc2 and eac, astcenc for astc; a DDS/KTX/.astc file keeps its own)")
                                    ->capture_default_str();
  mip->add_option("--dump-levels", dump_dir, "write DIR/level00.png, level01.png, ...");
  mip->add_option("--layout", layout, "write the packed R/G/B memory layout (paper Figure 1)");
  ImageOptions image;
  mip->add_option("--memory-image", image.path,
                  "write the pyramid as the cached unit's external memory holds it (header: docs/memory.md)");
  mip->add_option("--block", image.block, "memory image: texels per block WxH, each 2 | 4 | 8")->capture_default_str();
  mip->add_option("--block-order", image.order, "memory image: row-major | morton")->capture_default_str();
  mip->add_option("--mem-base", image.base, "memory image: byte address of level 0 (a multiple of the line)")
      ->capture_default_str();

  SamplingOptions render_opts;
  std::string scene = "plane", render_out;
  int width = 640, height = 480;
  CLI::App* render = app.add_subcommand(
      "render", "render a scene of the paper, or frames of a textured 3D model (--model, --scene-file), through an engine");
  render_opts.add_to(*render);
  limits.add_to(*render, true);
  ModelRenderArgs model_args;
  CLI::Option* scene_opt = nullptr;
  CLI::Option* model_opt = render->add_option(
      "--model", model_args.model,
      "a textured 3D model Assimp reads (glTF/GLB, OBJ+MTL, COLLADA, MD2, MS3D, IQM, 3DS, X, ...) instead of a scene");
  CLI::Option* scene_file_opt = render->add_option(
      "--scene-file", model_args.scene_file,
      "JSON placing several models: {\"models\": [{\"file\", \"translation\", \"rotation\", \"scale\"}, ...]}");
  CLI::Option* camera_opt = render->add_option(
      "--camera", model_args.camera, "models: one view ex,ey,ez,tx,ty,tz,fovy (eye, target, degrees; up = +y)");
  CLI::Option* camera_path_opt = render->add_option(
      "--camera-path", model_args.camera_path,
      "models: JSON {\"keyframes\": [{\"eye\", \"target\", \"fovy\"}, ...]} interpolated over --frames");
  render->add_option("--envmap", model_args.envmap,
                     "models: the paper's reflection mapping: --model drawn as a mirror of this environment, a cube "
                     "map (a DDS/KTX/KTX2 cube file, or six images +X,-X,+Y,-Y,+Z,-Z) or one equirectangular image or "
                     "pattern (converted once), which also fills the background; each pixel samples it along the "
                     "reflected view ray, derivatives from its quad (the model engine, cached memory)");
  CLI::Option* trace_queries_opt = render->add_option(
      "--trace-queries", model_args.trace_queries,
      "models: write the frames' requests (tex,u,v,dudx,dvdx,dudy,dvdy,quad,x,y,helper) to this CSV, and its "
      "textures next to it (STEM.textures.txt, STEM.texNN.png) for texsim sample --textures");
  std::string scene_list;
  for (const std::string& n : scene_names()) scene_list += n + " | ";
  scene_list += "mesh16 (the mesh with 16-bit X, Y, Z; model engines)";
  scene_opt = render->add_option("--scene,-s", scene, scene_list)->capture_default_str();
  render->add_option("--width", width, "image width")->capture_default_str();
  render->add_option("--height", height, "image height")->capture_default_str();
  CLI::Option* render_out_opt = render->add_option("--out,-o", render_out, "output image (PNG, TIFF, EXR, ...)");
  int frame = 0, frames = 1;
  CLI::Option* frame_opt = render->add_option("--frame", frame, "animation frame to render (0-based)");
  render->add_option("--frames", frames, "frames of the animation; without --frame renders all to OUT_000.png ...")
      ->capture_default_str();
  RenderBatchArgs batch;
  std::vector<std::string> render_emit;
  std::string render_collect;
  render->add_option("--emit", render_emit,
                     "slurm DIR | parallel DIR: write the --frames as tasks for a scheduler instead of rendering them "
                     "(DIR/sweep.sbatch, a Slurm job array, or DIR/run-parallel.sh, GNU parallel, resumable): each "
                     "frame's picture and --stats in DIR/frames/; then render --collect DIR")
      ->expected(2);
  render->add_option("--frames-per-task", batch.frames_per_task, "--emit: frames each task renders")->capture_default_str();
  render->add_option("--throttle", batch.throttle, "--emit slurm: at most this many tasks at once (0: no limit)")
      ->capture_default_str();
  render->add_option("--sshloginfile", batch.sshloginfile, "--emit parallel: run the tasks on these hosts (a shared file system)");
  std::string render_store;
  CLI::Option* render_store_opt = render->add_option(
      "--store", render_store,
      "keep the frame in this results store, or take it from there if it was rendered before with the same "
      "build, arguments and inputs (one frame; no traces); --emit passes it to every frame (default there: "
      "$TEXSIM_STORE, else ~/.cache/texsim/results)");
  render->add_option("--collect", render_collect,
                     "check that every frame of an emitted batch is in DIR/frames and merge their statistics into "
                     "DIR/frames.json, or name the tasks that failed or did not run and write DIR/resubmit.sh for them");
  std::string order = "tiled";
  int tile = 8;
  CLI::Option* order_opt = render->add_option("--order", order,
                     "tiled | scanline: the rasterizer's pixel walk (tiles row by row, as GPUs walk; or rows)")
      ->capture_default_str();
  CLI::Option* tile_opt =
      render->add_option("--tile", tile, "tiled order: tile side in pixels, a power of two 2 to 256")->capture_default_str();

  FiguresOptions fig;
  CLI::App* figures = app.add_subcommand("figures", "render every scene's variants, reference, errors and flicker");
  figures->add_option("--out,-o", fig.out_dir, "output directory")->capture_default_str();
  limits.add_to(*figures, false);
  figures->add_option("--engine,-e", fig.engine, "engine of the variants: " + engine_list())->capture_default_str();
  figures->add_option("--width", fig.width, "still image width")->capture_default_str();
  figures->add_option("--height", fig.height, "still image height")->capture_default_str();
  figures->add_option("--frames", fig.frames, "animation frames (flicker)")->capture_default_str();
  figures
      ->add_option("--reference-samples", fig.reference_samples,
                   "reference sub-pixel positions per axis, at least (more where a pixel spans more texels)")
      ->capture_default_str();

  ExploreArgs ex;
  CLI::App* explore = app.add_subcommand(
      "explore", "sweep caches, memory timing and rasterization order over scenes or a query trace (cached memory): "
                 "explore.csv, plots, index.html");
  limits.add_to(*explore, true);
  CLI::Option* ex_scene = explore->add_option("--scene,-s", ex.scenes, "scenes, comma-separated: " + scene_list)
                              ->capture_default_str();
  CLI::Option* ex_queries =
      explore->add_option("--queries,-q", ex.queries, "a query trace (CSV u,v,lod or u,v,dudx,...) instead of scenes");
  CLI::Option* ex_model = explore->add_option(
      "--model", ex.model, "a textured 3D model (render --model) instead of scenes: its first frame, all its textures");
  CLI::Option* ex_scene_file =
      explore->add_option("--scene-file", ex.scene_file, "several models (render --scene-file) instead of scenes");
  explore->add_option("--camera", ex.camera, "models: the view ex,ey,ez,tx,ty,tz,fovy (default: the orbit's first)");
  explore->add_option("--texture,-t", ex.texture, "image file or pattern NAME[:WxH] (scenes with their own map keep it)")
      ->capture_default_str();
  explore->add_option("--filter,-f", ex.filter, "point | bilinear | mip_nearest | trilinear")->capture_default_str();
  explore->add_option("--width", ex.width, "scene width")->capture_default_str();
  explore->add_option("--height", ex.height, "scene height")->capture_default_str();
  explore->add_option("--order", ex.orders, "rasterization orders: scanline,tiled")->capture_default_str();
  explore->add_option("--format", ex.formats,
                      "texture formats, comma-separated: " + texel_format_names() + " (each level compressed: "
                      "libsquish, Mesa for bc7, ours for etc2, astcenc for astc)")
      ->capture_default_str();
  explore->add_option("--tile", ex.tile, "tiled order: tile side in pixels")->capture_default_str();
  explore->add_option("--cache-kib", ex.cache_kib, "sizes of each cache (even, odd levels) in KiB, 1..1024")
      ->capture_default_str();
  explore->add_option("--ways", ex.ways, "associativities: 1 | 2 | 4")->capture_default_str();
  explore->add_option("--block", ex.blocks, "block shapes WxH (= cache lines), each side 2 | 4 | 8")->capture_default_str();
  explore->add_option("--block-order", ex.block_orders, "row-major | morton")->capture_default_str();
  explore->add_option("--mem-latency", ex.latencies, "memory latencies in clocks")->capture_default_str();
  explore->add_option("--mem-bytes-per-clock", ex.bandwidths, "memory bandwidths in bytes per clock")
      ->capture_default_str();
  explore->add_option("--fifo-depth", ex.fifo_depths, "sample FIFO depths; max = the RTL configuration's FIFO_DEPTH")
      ->capture_default_str();
  explore->add_option("--timing", ex.timing,
                      "model | rtl | none: samples/clock from the model's timing layer at every point, or through "
                      "the Verilated RTL where a compiled configuration holds the point (the model elsewhere), or "
                      "hit rates and bytes only")
      ->capture_default_str();
  explore->add_option("--confirm", ex.confirm,
                      "rtl: also run every point a compiled configuration holds through the RTL and fail on any "
                      "difference from the timing model");
  explore->add_option("--out,-o", ex.out_dir, "output directory: explore.csv, *.png, index.html")->capture_default_str();
  explore->add_option("--jobs,-j", ex.jobs, "tasks measured in this many processes at once")->capture_default_str();
  explore->add_option("--store", ex.store_dir,
                      "the results store: every point measured is kept under a key of what determines it (texsim's "
                      "build, the workload's inputs, the point), and a sweep measures only the points it lacks; "
                      "concurrent writers welcome (default: $TEXSIM_STORE, else ~/.cache/texsim/results)");
  std::vector<std::string> ex_emit;
  explore->add_option("--emit", ex_emit,
                      "slurm DIR | parallel DIR: write the tasks of the points the store lacks for a scheduler "
                      "instead of running them: DIR/sweep.sbatch (a Slurm job array) or DIR/run-parallel.sh "
                      "(GNU parallel, resumable), and DIR/sweep.txt for --collect DIR")
      ->expected(2);
  explore->add_option("--throttle", ex.throttle, "--emit slurm: at most this many tasks at once (--array=0-K%T; 0: no limit)")
      ->capture_default_str();
  explore->add_option("--sshloginfile", ex.sshloginfile, "--emit parallel: run the tasks on these hosts (GNU parallel's "
                      "--sshloginfile; the store and DIR on a file system they share)");
  explore->add_option("--collect", ex.collect_dir,
                      "merge an emitted sweep's results from the store into DIR/explore.csv + plots, in sweep order; "
                      "names the tasks that failed or did not run and writes DIR/resubmit.sh for exactly those");
  explore->add_option("--task", ex.task_fingerprint, "(what an emitted task runs) measure into --store only; "
                      "the workload must have this fingerprint");
  bool no_plots = false;
  explore->add_flag("--no-plots", no_plots, "write explore.csv only (no matplotlib needed)");

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
    limits.apply();
    if (*sample)
      return cmd_sample(sample_opts, queries, textures_list, texture_layers, cube_faces, out, sample_op, sample_component,
                        sample_depth);
    if (*mip)
      return cmd_mip(mip_texture, mip_mode, mip_resize, mip_format, mip_format_opt->count() > 0, mip_srgb, dump_dir, layout,
                     image);
    if (*render) {
      if (!render_collect.empty()) {
        if (render->count("--emit") || render_out_opt->count())
          throw tex::Error("render --collect DIR takes no --emit or --out (the batch's manifest names them)");
        return collect_render_batch(render_collect);
      }
      if (!render_out_opt->count()) throw tex::Error("render: --out is required");
      std::vector<std::string> args;  // (render's own, as given)
      for (int i = 1, after = 0; i < argc; ++i) {
        if (after) args.push_back(argv[i]);
        after = after || std::string(argv[i]) == "render";
      }
      if (!render_emit.empty()) {
        if (frame_opt->count()) throw tex::Error("render --emit renders every frame of --frames (no --frame)");
        if (!render_store_opt->count()) {  // every frame kept, in the store the tasks share
          args.push_back("--store");
          args.push_back(std::filesystem::absolute(default_store_dir()).string());
        }
        batch.scheduler = render_emit[0];
        batch.dir = render_emit[1];
        batch.frames = frames;
        batch.out = render_out;
        batch.self = std::filesystem::read_symlink("/proc/self/exe").string();
        batch.args = render_task_arguments(args);
        return emit_render_batch(batch);
      }
      for (const CLI::Option* opt : {render->get_option("--frames-per-task"), render->get_option("--throttle"),
                                     render->get_option("--sshloginfile")})
        if (opt->count()) throw tex::Error(opt->get_name() + " applies to render --emit");
      std::optional<FrameStore> frame_store;
      if (render_store_opt->count()) {
        if (frames > 1 && !frame_opt->count())
          throw tex::Error("render --store keeps one frame: give --frame F (or --emit, whose tasks render one frame each)");
        for (const char* opt : {"--trace", "--miss-trace", "--response-clocks", "--trace-queries"})
          if (render->count(opt)) throw tex::Error(std::string("render --store: ") + opt + " is not kept in the store (drop one of them)");
        frame_store.emplace(render_store, args);
      }
      SceneOptions so;
      so.width = width;
      so.height = height;
      so.frame = frame;
      so.frames = frames;
      so.order = parse_pixel_order(order);
      // The mesh scene samples its vertices in order: the default walk does not apply to it.
      if (!order_opt->count() && scene_samples_vertices(scene)) so.order = PixelOrder::Scanline;
      so.tile = tile;
      if (tile_opt->count() && so.order != PixelOrder::Tiled) throw tex::Error("--tile applies to --order tiled");
      const bool wrap_given = render->count("--wrap") + render->count("--wrap-u") + render->count("--wrap-v") > 0;
      if (model_opt->count() || scene_file_opt->count()) {
        if (scene_opt->count()) throw tex::Error("render: give --scene or --model/--scene-file, not both");
        if (render_opts.texture_opt->count()) throw tex::Error("render: a model samples its own textures (no --texture)");
        model_args.out = render_out;
        model_args.width = width;
        model_args.height = height;
        model_args.frame = frame;
        model_args.frames = frames;
        model_args.all_frames = frames > 1 && frame_opt->count() == 0;
        model_args.wrap_given = wrap_given;
        model_args.filter_given = render->count("--filter") + render->count("--min-filter") +
                                      render->count("--mag-filter") + render->count("--mipmap-mode") > 0;
        model_args.order = so.order;
        model_args.tile = tile;
        model_args.store = frame_store ? &*frame_store : nullptr;
        return cmd_render_model(render_opts, model_args);
      }
      for (const CLI::Option* opt : {camera_opt, camera_path_opt, trace_queries_opt})
        if (opt->count()) throw tex::Error(opt->get_name() + " applies to --model and --scene-file");
      return cmd_render(render_opts, scene, so, frames > 1 && frame_opt->count() == 0,
                        render_opts.texture_opt->count() > 0, wrap_given, render_out, frame_store ? &*frame_store : nullptr);
    }
    if (*figures) return make_figures(fig);
    if (*explore) {
      if (ex_scene->count() && (ex_queries->count() || ex_model->count() || ex_scene_file->count()))
        throw tex::Error("explore: give --scene, --queries, --model or --scene-file, one of them");
      ex.plots = !no_plots;
      if (!ex_emit.empty()) {
        ex.emit_scheduler = ex_emit[0];
        ex.emit_dir = ex_emit[1];
      }
      return run_explore(ex, std::filesystem::read_symlink("/proc/self/exe").string());
    }
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "texsim: error: out of memory: this run needs more than --max-memory allows (%s)\n",
                 memory_words(memory_limit()).c_str());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "texsim: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
