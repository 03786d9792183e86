#include "cli/render_model.h"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <vector>
#include <nlohmann/json.hpp>

#include "engines/rtl/driver.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "workloads/camera.h"
#include "workloads/mesh_scene.h"
#include "workloads/rasterizer.h"
#include "workloads/texture_files.h"
#include "workloads/texture_io.h"

namespace tex {

namespace {

// OUT_000.png ... for every frame of an animation, else OUT itself.
std::string frame_path(const std::string& out, int frame, bool numbered) {
  if (!numbered) return out;
  const std::filesystem::path p(out);
  char num[16];
  std::snprintf(num, sizeof num, "_%03d", frame);
  return (p.parent_path() / (p.stem().string() + num + p.extension().string())).string();
}

}  // namespace

int cmd_render_model(const SamplingOptions& o, const ModelRenderArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  // Everything is checked before the work: options, engine, cameras, outputs, the model and its textures.
  const SamplerConfig cfg = o.config();
  if (cfg.unnormalized)
    throw Error("render --model: --unnormalized does not apply (a model's texture coordinates are normalized)");
  EngineOptions eo = o.engine_options();
  if (a.model.empty() == a.scene_file.empty()) throw Error("render: give --model FILE or --scene-file FILE (one of them)");
  if (!a.camera.empty() && !a.camera_path.empty()) throw Error("render: give --camera or --camera-path, not both");
  if (a.frames < 1) throw Error("--frames " + std::to_string(a.frames) + " must be at least 1");
  if (!a.all_frames && (a.frame < 0 || a.frame >= a.frames))
    throw Error("--frame " + std::to_string(a.frame) + " is outside 0.." + std::to_string(a.frames - 1));
  std::optional<Camera> fixed_camera;
  if (!a.camera.empty()) fixed_camera = parse_camera(a.camera);
  std::vector<Camera> path;
  if (!a.camera_path.empty()) path = read_camera_path(a.camera_path);
  check_image_path(a.out);
  if (a.trace_queries == "-") throw Error("--trace-queries needs a file (its textures are written next to it)");

  OutputSet outputs;
  outputs.add_input(a.model.empty() ? a.scene_file : a.model, a.model.empty() ? "--scene-file" : "--model");
  if (!a.camera_path.empty()) outputs.add_input(a.camera_path, "--camera-path");
  const int first = a.all_frames ? 0 : a.frame, last = a.all_frames ? a.frames - 1 : a.frame;
  std::vector<OutputFile*> images;
  for (int f = first; f <= last; ++f)
    images.push_back(&outputs.declare(frame_path(a.out, f, a.all_frames), "--out", OutputSet::Kind::File));
  OutputFile* stats_out = o.stats_output(outputs);
  OutputFile* trace = o.trace_output(outputs);
  if (trace) eo.trace_path = trace->write_path();
  OutputFile* queries_out = a.trace_queries.empty() ? nullptr : &outputs.declare(a.trace_queries, "--trace-queries");

  // --envmap: the model as a mirror of a cube map, the one texture.
  const bool mirror = !a.envmap.empty();
  if (mirror) {
    if (a.model.empty()) throw Error("--envmap takes --model (one model drawn as a mirror)");
    if (!a.trace_queries.empty()) throw Error("--envmap: --trace-queries writes 2D queries; a mirror's are a cube's");
    for (const std::string& face : split_commas(a.envmap)) outputs.add_input(face, "--envmap");  // (six faces: each)
  }

  // The model: its meshes and textures, each texture a descriptor-table entry.
  const MeshScene scene = a.model.empty() ? load_models(read_scene_file(a.scene_file)) : load_model(a.model, mirror);
  if (scene.textures.size() > size_t(kMaxTextures))
    throw Error("the scene has " + std::to_string(scene.textures.size()) + " textures; the descriptor table holds " +
                std::to_string(kMaxTextures));
  std::vector<Pyramid> pyramids;
  pyramids.reserve(scene.textures.size());
  TextureTable table;
  SamplerTable samplers;  // entry i: texture i's (the options' sampler with its file's filters and wrap modes)
  std::string envmap_how;
  if (mirror) {
    pyramids = load_envmap(a.envmap, o.texture_options(), envmap_how);
    std::vector<const Pyramid*> faces;
    for (const Pyramid& p : pyramids) faces.push_back(&p);
    table.push_back(BoundTexture(faces[0], {faces.begin() + 1, faces.end()}, TextureKind::Cube));
    samplers.push_back(cfg);
  }
  for (const SceneTexture& t : scene.textures) {
    // --format for every texture; sRGB where the file says so (glTF 2 base colour) or --srgb.
    TextureOptions topts = o.texture_options();
    topts.srgb = topts.srgb || t.srgb;
    try {
      pyramids.push_back(make_pyramid(t.image, topts));
    } catch (const Error& e) {
      throw Error(t.source + " (" + t.material + (t.srgb ? ", sRGB base colour" : "") + "): " + e.what());
    }
    table.push_back({&pyramids.back()});
    samplers.push_back(file_sampler(t, cfg, a.filter_given, a.wrap_given));
  }
  // The cached unit, unless --memory says otherwise, for several textures (its descriptor table)
  // or, with an engine that simulates a compiled unit, a texture no compiled on-chip unit holds (an
  // sRGB texture is held as 16-bit channels on chip, and those units are small).
  std::string memory_chosen;
  if (eo.memory != Memory::Cached && !o.memory_opt->count()) {
    if (mirror) {
      memory_chosen = "a cube map";
    } else if (scene.textures.size() > 1) {
      memory_chosen = "the on-chip unit holds one texture";
    } else if (engine_info(o.engine).cycle_accurate) {
      try {
        rtl::smallest_config_for(table, Memory::OnChip, eo.layout.block_w, eo.layout.block_h);
      } catch (const Error&) {
        memory_chosen = "no compiled on-chip unit holds the texture";
      }
    }
  }
  if (!memory_chosen.empty()) {
    const std::string trace_path = eo.trace_path;
    eo = o.engine_options(Memory::Cached);
    eo.trace_path = trace_path;
  }
  if (scene.textures.size() > 1 && eo.memory != Memory::Cached)
    throw Error("the scene has " + std::to_string(scene.textures.size()) +
                " textures; the on-chip unit holds one (the paper's design): use --memory cached");
  const uint64_t resident = texture_bytes_resident(table, eo);  // also checks the table fits the memory

  // --trace-queries: the frame's requests, and the textures they name (as loaded: of the file's size,
  // RGBA8) with their wrap modes, so that `texsim sample --textures` replays the frame exactly.
  std::vector<OutputFile*> texture_files;
  OutputFile* list_out = nullptr;
  std::optional<QueryTraceWriter> query_writer;
  if (queries_out) {
    const std::filesystem::path q(a.trace_queries);
    const std::string stem = (q.parent_path() / q.stem()).string();
    for (size_t t = 0; t < scene.textures.size(); ++t) {
      char name[32];
      std::snprintf(name, sizeof name, ".tex%02zu.png", t);
      texture_files.push_back(&outputs.declare(stem + name, "--trace-queries", OutputSet::Kind::File));
    }
    list_out = &outputs.declare(stem + ".textures.txt", "--trace-queries");
    query_writer.emplace(queries_out->open());
  }

  std::optional<MissTraceWriter> misses;
  if (OutputFile* miss_out = o.miss_trace_output(outputs)) misses.emplace(*miss_out);
  std::optional<ClockWriter> clocks;  // every frame's, each counted from its first request
  if (OutputFile* clocks_out = o.response_clocks_output(outputs)) eo.clock_sink = &clocks.emplace(*clocks_out);
  // Every input is checked: the notes on what was skipped or resampled, then the work.
  for (const std::string& note : scene.notes) std::fprintf(stderr, "texsim: note: %s\n", note.c_str());
  LineSet all_lines(misses ? &*misses : nullptr);

  FrameFigures total;
  EngineStats last_stats;
  nlohmann::json per_frame = nlohmann::json::array();
  const double aspect = double(a.width) / a.height;
  RasterOptions ro;
  ro.width = a.width;
  ro.height = a.height;
  ro.order = a.order;
  ro.tile = a.tile;
  ro.reflect = mirror;
  for (int f = first; f <= last; ++f) {
    const Camera cam = fixed_camera ? *fixed_camera
                       : !path.empty() ? camera_on_path(path, f, a.frames)
                                       : orbit_camera(scene.bounds_min, scene.bounds_max, aspect, f, a.frames);
    const RasterFrame frame = rasterize(scene, cam, ro);
    const std::string name = "frame " + std::to_string(f);
    const std::vector<Request> requests = to_requests(frame.queries, name);
    QueryCounts counts;
    for (const Query& q : frame.queries) counts.add(q);
    if (query_writer) {
      query_writer->comment(name);
      for (const Query& q : frame.queries) query_writer->write(q);
    }
    if (a.store) {  // (one frame, no traces: checked by the caller)
      a.store->set_inputs(requests, table, samplers);
      if (a.store->reuse(*images[0], stats_out)) {
        outputs.commit();
        std::printf("texsim render: %s, frame %d of %d: reused from the store %s -> %s\n",
                    a.model.empty() ? a.scene_file.c_str() : a.model.c_str(), f, a.frames, a.store->dir().c_str(),
                    a.out.c_str());
        return 0;
      }
    }
    LineSet lines(&all_lines);
    if (eo.memory == Memory::Cached) eo.miss_sink = &lines;
    VectorSource source(requests);
    VectorSink texels;
    last_stats = run_engine(o, eo, outputs, trace, table, samplers, source, texels);
    for (size_t i = 0; i < texels.texels.size(); ++i)  // an sRGB texture's linear results back to codes
      if (table[requests[i].texture].pyramid->srgb) texels.texels[i] = encode_srgb_texel(texels.texels[i]);
    save_image(compose_frame(frame, texels.texels, 8, Texel{48, 48, 56, 255}), *images[size_t(f - first)]);
    const FrameFigures fig = frame_figures(counts, last_stats, resident, lines.bytes(line_bytes(table, eo)));
    total.add(fig);
    nlohmann::json j = fig.to_json();
    j["frame"] = f;
    per_frame.push_back(j);
    if (first != last) std::printf("  frame %d: %s\n", f, fig.summary().c_str());
  }
  total.texture_bytes_touched = all_lines.bytes(line_bytes(table, eo));
  if (misses) misses->close();
  if (clocks) clocks->close();
  if (query_writer) queries_out->close();
  if (list_out) {
    std::FILE* list = list_out->open();
    std::fprintf(list, "# texture list of %s: id file wrap_u wrap_v [srgb] min= mag= mip= [base= max=] (texsim sample --textures)\n",
                 a.trace_queries.c_str());
    const TextureOptions topts = o.texture_options();  // the view, the same for every texture
    const std::string view = topts.base_level == 0 && topts.max_level >= kMaxLevels - 1
                                 ? std::string()
                                 : " base=" + std::to_string(topts.base_level) + " max=" + std::to_string(topts.max_level);
    for (size_t t = 0; t < scene.textures.size(); ++t) {
      save_image(scene.textures[t].image, *texture_files[t]);
      const Filter& fl = samplers[t].filter;
      std::fprintf(list, "%zu %s %s %s%s min=%s mag=%s mip=%s%s\n", t,
                   std::filesystem::path(texture_files[t]->path()).filename().c_str(),
                   wrap_name(samplers[t].wrap_u).c_str(), wrap_name(samplers[t].wrap_v).c_str(),
                   table[t].pyramid->srgb ? " srgb" : "", texel_filter_name(fl.texel).c_str(),
                   texel_filter_name(fl.mag).c_str(), mip_mode_name(fl.mip).c_str(), view.c_str());
    }
    list_out->close();
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  nlohmann::json extra = total.to_json();
  extra["frames"] = per_frame;
  extra["textures"] = scene.textures.size();
  write_stats(stats_out, last_stats, eo, secs, extra);  // engine counters of the last frame; figures of all
  outputs.commit();
  if (a.store) a.store->keep(images[0]->path(), o.stats_path);
  print_cycle_stats(last_stats, eo);
  print_probe_stats(last_stats);
  std::printf("  %s%s\n", first == last ? "" : "total: ", total.summary().c_str());
  std::vector<std::string> names;  // the samplers' filters, each once (a glTF file may give each texture its own)
  for (const SamplerConfig& smp : samplers)
    if (const std::string n = filter_name(smp.filter); std::find(names.begin(), names.end(), n) == names.end())
      names.push_back(n);
  std::string filters;
  for (const std::string& n : names) filters += (filters.empty() ? "" : ", ") + n;
  std::printf("texsim render: %s, %zu meshes, %s, %dx%d, frame%s %d..%d of %d, %s, %s order, engine %s, "
              "%s memory%s -> %s (%.2f s)\n",
              a.model.empty() ? a.scene_file.c_str() : a.model.c_str(), scene.meshes.size(),
              mirror ? ("a mirror of " + a.envmap + " (" + envmap_how + ")").c_str()
                     : (std::to_string(scene.textures.size()) + " textures").c_str(),
              a.width, a.height, first == last ? "" : "s", first, last, a.frames, filters.c_str(),
              a.order == PixelOrder::Tiled ? "tiled" : "scanline", o.engine.c_str(), memory_name(eo.memory).c_str(),
              memory_chosen.empty() ? "" : (" (chosen: " + memory_chosen + ")").c_str(), a.out.c_str(), secs);
  return 0;
}

}  // namespace tex
