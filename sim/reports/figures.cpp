#include "reports/figures.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "model/error.h"
#include "workloads/texture_io.h"
#include "model/pyramid.h"

namespace tex {

VariantRender render_variant(const std::string& scene, const SceneOptions& options, const std::string& filter,
                             const std::string& engine, int max_aniso) {
  VariantRender r;
  r.frame = make_scene(scene, options);
  const Image texture = scene_texture(r.frame, "");
  SamplerConfig cfg;
  if (!parse_filter(filter, cfg.filter)) throw Error("unknown filter '" + filter + "'");
  cfg.max_aniso = max_aniso;
  cfg.wrap_u = cfg.wrap_v = r.frame.clamp_edges ? Wrap::Clamp : Wrap::Repeat;
  const Pyramid pyr = build_pyramid(texture, PyramidMode::Exact);
  const auto requests = to_requests(r.frame.queries, "scene " + scene);
  r.texels = make_engine(engine, EngineOptions{})->run(pyr, cfg, requests).texels;
  r.channel_bits = texture.channel_bits;
  r.image = render_values(r.frame, texels_to_values(r.texels, r.channel_bits));
  return r;
}

std::vector<Rgba> reference_query_values(const std::string& scene, const SceneOptions& options,
                                         int samples_per_axis) {
  // The mesh's reference surface is the 16-bit map: the 8-bit one's rounding is part of the error.
  const SceneFrame frame = make_scene(scene == "mesh" ? "mesh16" : scene, options);
  const Image texture = scene_texture(frame, "");
  const Wrap wrap = frame.clamp_edges ? Wrap::Clamp : Wrap::Repeat;
  return reference_values(frame, texture, wrap, wrap, samples_per_axis);
}

RgbaImage render_reference(const std::string& scene, const SceneOptions& options, int samples_per_axis) {
  return render_values(make_scene(scene, options), reference_query_values(scene, options, samples_per_axis));
}

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Variant {
  std::string name;    // file-name part
  std::string label;   // caption
  std::string scene;   // scene actually rendered
  std::string filter;
  bool model_only = false;  // rendered by the model whatever the figures' engine
  std::string engine_for(const std::string& figures_engine) const { return model_only ? "model" : figures_engine; }
  // The caption, naming the engine when it is not the figures' own.
  std::string label_for(const std::string& figures_engine) const {
    const std::string e = engine_for(figures_engine);
    return e == figures_engine || label.find("(" + e + ")") != std::string::npos ? label : label + " (" + e + ")";
  }
};

std::vector<Variant> variants_of(const std::string& scene) {
  if (scene == "magnify") return {{"point", "point sampling", scene, "point"}, {"bilinear", "bilinear", scene, "bilinear"}};
  std::vector<Variant> v = {{"point", "point sampling", scene, "point"},
                            {"trilinear", "trilinear mip-map", scene, "trilinear"}};
  if (scene == "mesh") v.push_back({"trilinear16", "trilinear, 16-bit X,Y,Z map (model)", "mesh16", "trilinear", true});
  if (scene == "plane" || scene == "panel")
    v.push_back({"anisotropic", "anisotropic, up to " + std::to_string(kMaxAniso) + " probes", scene, "anisotropic"});
  return v;
}

const char* caption_of(const std::string& scene) {
  if (scene == "magnify") return "Magnification (paper fig. 3, 4): a 16-texel region of the test card blown up 16x.";
  if (scene == "minify") return "Minification (fig. 5, 6): the test card shrunk 6.3x and turned 8 degrees.";
  if (scene == "plane") return "A checkered plane receding to the horizon (fig. 7).";
  if (scene == "panel") return "A textured panel turned 60 degrees towards edge-on (fig. 8-11); the animation turns it 0 to 89 degrees.";
  if (scene == "reflect")
    return "Highlight antialiasing (fig. 17-19): mirror spheres of shrinking radius under a mip-mapped reflectance map "
           "with 9 lights; lambda from the change of the normal across a pixel.";
  if (scene == "mesh")
    return "Levels of detail of the surface (section 5, fig. 20-23): an X,Y,Z map of a face sampled at one vertex per "
           "grid point, grids coarser as the faces shrink; lambda = log2(texels between vertices).";
  return "";
}



std::string fmt(double x, int decimals = 2) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

// Frames side by side (a film strip), 2-pixel gaps.
Image film_strip(const std::vector<RgbaImage>& frames, size_t count) {
  const size_t step = std::max<size_t>(1, frames.size() / count);
  std::vector<Image> picked;
  for (size_t i = 0; i < frames.size() && picked.size() < count; i += step) picked.push_back(to_image8(frames[i]));
  const int w = picked[0].width, h = picked[0].height, gap = 2;
  Image strip(int(picked.size()) * (w + gap) - gap, h, 8);
  for (auto& t : strip.texels) t = {255, 255, 255, 255};
  for (size_t k = 0; k < picked.size(); ++k)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) strip.at(int(k) * (w + gap) + x, y) = picked[k].at(x, y);
  return strip;
}

}  // namespace

int make_figures(const FiguresOptions& o) {
  if (o.frames < 2 || o.frames > 1000) throw Error("figures: --frames " + std::to_string(o.frames) + " is not within 2 to 1000");
  if (o.reference_samples < 1 || o.reference_samples > 32)
    throw Error("figures: --reference-samples " + std::to_string(o.reference_samples) + " is not within 1 to 32");
  make_scene("plane", SceneOptions{o.width, o.height, 0, 1});  // checks the sizes before any work
  make_scene("plane", SceneOptions{o.anim_width, o.anim_height, 0, 1});
  engine_info(o.engine);  // an unknown engine is reported before any file is written
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir(o.out_dir);
  // Every file of the run is written all or nothing (output_files.h).
  OutputSet outputs;
  outputs.make_directory(dir.string(), "--out");
  auto save = [&](const Image& img, const fs::path& path) {
    save_image(img, outputs.declare(path.string(), "--out", OutputSet::Kind::File));
  };
  auto save_text = [&](const fs::path& path, const std::string& text) {
    OutputFile& out = outputs.declare(path.string(), "--out");
    std::fputs(text.c_str(), out.open());
    out.close();
  };
  const double heat_full_scale = 64;  // LSB at white in the heat maps
  json metrics = {{"engine", o.engine},
                  {"width", o.width},
                  {"height", o.height},
                  {"reference_samples_per_axis", o.reference_samples},
                  {"reference_max_samples_per_axis", std::max(o.reference_samples, kReferenceMaxSubPositions)},
                  {"heat_map_full_scale_lsb", heat_full_scale},
                  {"scenes", json::array()},
                  {"flicker", json::array()}};
  std::ostringstream md;
  md << "# The paper's experiments through the simulator\n\n"
     << "Generated by `make figures` (`texsim figures --engine " << o.engine << "` then `scripts/figures.py`). "
     << "Every variant is sampled through the `" << o.engine << "` engine; the reference is real-valued filtering "
     << "of level 0 in double precision (at least " << o.reference_samples << "x" << o.reference_samples
     << " sub-pixel positions through the exact mapping, more where a pixel's footprint is longer, so that a "
     << "sub-pixel spans at most one texel per axis, up to " << kReferenceMaxSubPositions << "x"
     << kReferenceMaxSubPositions << "; each averages its own footprint widened by one texel; docs/scenes.md). "
     << "PSNR over R, G, B of the pixels on the surface; errors in 8-bit steps (LSB). Heat maps: black 0, "
     << "white >= " << fmt(heat_full_scale, 0) << " LSB. Composite figures with captions: [index.html](index.html).\n\n";
  // The filters side by side (scenes with an anisotropic variant): inserted here once measured.
  const size_t summary_at = size_t(md.tellp());
  struct SummaryRow {
    std::string scene, name, label, engine;
    ErrorStats still;
    double flicker_excess = -1;
  };
  std::vector<SummaryRow> summary;

  SceneOptions still;
  still.width = o.width;
  still.height = o.height;
  for (const std::string& scene : scene_names()) {
    const RgbaImage reference = render_reference(scene, still, o.reference_samples);
    save(to_image8(reference), dir / (scene + "_reference.png"));
    json entry = {{"scene", scene}, {"caption", caption_of(scene)}, {"reference", scene + "_reference.png"},
                  {"variants", json::array()}};
    md << "## " << scene << "\n\n" << caption_of(scene) << "\n\n"
       << "| variant | PSNR (dB) | max error (LSB) | mean error (LSB) | image | error |\n|---|---|---|---|---|---|\n";
    // Mesh: also the sampled vertex positions against the reference's (vertex space, texels).
    const bool mesh = scene == "mesh";
    const std::vector<Rgba> reference_vertices = mesh ? reference_query_values(scene, still, o.reference_samples) : std::vector<Rgba>{};
    std::ostringstream vertex_md;
    double texels_per_unit = 0;  // the mesh map's width: X = 1 is that many level-0 texels
    std::string vertex_counts;
    const bool summarized = scene == "plane" || scene == "panel";
    for (const Variant& v : variants_of(scene)) {
      const std::string engine = v.engine_for(o.engine), label = v.label_for(o.engine);
      const VariantRender r = render_variant(v.scene, still, v.filter, engine);
      const ErrorStats e = compare_images(r.image, reference);
      if (mesh) {
        texels_per_unit = r.frame.own_texture->width;
        const VertexErrorStats ve = compare_vertices(r.frame, texels_to_values(r.texels, r.channel_bits),
                                                     reference_vertices, texels_per_unit);
        json parts;
        vertex_md << "| " << label;
        for (const auto& [part_name, part] : {std::pair{"all", ve.all}, {"interior", ve.interior}, {"border", ve.border}}) {
          parts[part_name] = {{"vertices", part.vertices}, {"rms_texels", part.rms_texels}, {"max_texels", part.max_texels}};
          vertex_md << " | " << fmt(part.rms_texels, 2) << " | " << fmt(part.max_texels, 2);
        }
        vertex_md << " |\n";
        parts["name"] = v.name;
        parts["label"] = label;
        entry["vertex_errors"].push_back(parts);
        vertex_counts = "all " + std::to_string(ve.all.vertices) + ", interior " + std::to_string(ve.interior.vertices) +
                        ", border " + std::to_string(ve.border.vertices);
      }
      const std::string image = scene + "_" + v.name + ".png", error = scene + "_" + v.name + "_error.png";
      save(to_image8(r.image), dir / image);
      save(error_heat_map(r.image, reference, heat_full_scale), dir / error);
      if (summarized) summary.push_back({scene, v.name, label, engine, e});
      entry["variants"].push_back({{"name", v.name}, {"label", label}, {"filter", v.filter}, {"engine", engine},
                                   {"image", image}, {"error_image", error}, {"psnr_db", e.psnr_db},
                                   {"max_error_lsb", e.max_error_lsb}, {"mean_error_lsb", e.mean_error_lsb}});
      md << "| " << label << " | " << fmt(e.psnr_db) << " | " << fmt(e.max_error_lsb, 1) << " | "
         << fmt(e.mean_error_lsb) << " | ![](" << image << ") | ![](" << error << ") |\n";
    }
    md << "| reference | | | | ![](" << scene << "_reference.png) | |\n\n";
    if (mesh)
      md << "Vertex space: the distance |P - P_ref| between each sampled vertex position (X, Y, Z) and the "
         << "reference's (the box-filtered 16-bit map at the vertex's (u, v) and footprint), in level-0 texels "
         << "(1 texel = 1/" << texels_per_unit << " of the map's full scale); RMS and max over all vertices ("
         << vertex_counts << "), the interior ones, and those on a face's border (vertices at cell centres: "
         << "docs/scenes.md).\n\n"
         << "| variant | RMS all | max all | RMS interior | max interior | RMS border | max border |\n"
         << "|---|---|---|---|---|---|---|\n"
         << vertex_md.str() << "\n";
    metrics["scenes"].push_back(entry);
    std::fprintf(stderr, "texsim figures: %s done\n", scene.c_str());
  }

  // Temporal aliasing: frame-to-frame change that the reference does not have.
  md << "## Temporal aliasing (flicker)\n\n"
     << "Animations of " << o.frames << " frames at " << o.anim_width << "x" << o.anim_height
     << ". Per frame step: mean |F(t+1) - F(t)| of the variant and of the reference, and the *excess* "
     << "mean |(F(t+1) - F(t)) - (R(t+1) - R(t))|: the change the real-valued reference does not have "
     << "(0 = no flicker). Averages over the steps, in LSB. Plot: flicker.png (index.html).\n\n"
     << "| animation | variant | mean change | reference change | excess (flicker) |\n|---|---|---|---|---|\n";
  std::vector<std::pair<std::string, std::string>> panel_strips;  // name, label
  SceneOptions anim;
  anim.width = o.anim_width;
  anim.height = o.anim_height;
  anim.frames = o.frames;
  for (const std::string scene : {"panel", "plane", "reflect", "mesh"}) {
    std::vector<RgbaImage> reference_frames;
    for (int f = 0; f < o.frames; ++f) {
      anim.frame = f;
      reference_frames.push_back(render_reference(scene, anim, o.reference_samples));
    }
    if (scene == std::string("panel")) save(film_strip(reference_frames, 8), dir / "panel_frames_reference.png");
    for (const Variant& v : variants_of(scene)) {
      if (v.scene != scene) continue;  // mesh16: its surface is compared in vertex space below
      const std::string engine = v.engine_for(o.engine), label = v.label_for(o.engine);
      std::vector<RgbaImage> frames;
      for (int f = 0; f < o.frames; ++f) {
        anim.frame = f;
        frames.push_back(render_variant(scene, anim, v.filter, engine).image);
      }
      if (scene == std::string("panel")) {
        save(film_strip(frames, 8), dir / ("panel_frames_" + v.name + ".png"));
        panel_strips.push_back({v.name, label});
      }
      const FlickerStats s = flicker(frames, reference_frames);
      for (SummaryRow& row : summary)
        if (row.scene == scene && row.name == v.name) row.flicker_excess = s.mean_excess;
      metrics["flicker"].push_back({{"scene", scene}, {"filter", v.filter}, {"name", v.name}, {"label", label},
                                    {"engine", engine}, {"change", s.change},
                                    {"reference_change", s.reference_change}, {"excess", s.excess},
                                    {"mean_change", s.mean_change}, {"mean_reference_change", s.mean_reference_change},
                                    {"mean_excess", s.mean_excess}});
      md << "| " << scene << " | " << label << " | " << fmt(s.mean_change) << " | " << fmt(s.mean_reference_change)
         << " | " << fmt(s.mean_excess) << " |\n";
    }
    std::fprintf(stderr, "texsim figures: %s animation done\n", scene.c_str());
  }
  // The mesh animation in vertex space: how much each variant's surface moves from frame to frame
  // beyond the reference surface's own change (mesh_jitter, docs/scenes.md).
  md << "\nMesh animation in vertex space: each face as the bilinear patch through its vertices, evaluated at "
     << "the same 33x33 (u, v) points in every frame; per frame step the mean distance |S(t+1) - S(t)| the "
     << "variant's surface moves, the reference's, and the excess mean |(S(t+1) - S(t)) - (R(t+1) - R(t))|, "
     << "averaged over the steps, in level-0 texels; over all points, and over the interior points (inside both "
     << "frames' inner quads, clear of the border vertices).\n\n"
     << "| variant | change | reference change | excess (jitter) | interior change | interior reference change "
     << "| interior excess |\n|---|---|---|---|---|---|---|\n";
  {
    std::vector<SceneFrame> mesh_frames;
    std::vector<std::vector<Rgba>> reference_vertices;
    for (int f = 0; f < o.frames; ++f) {
      anim.frame = f;
      mesh_frames.push_back(make_scene("mesh", anim));
      reference_vertices.push_back(reference_query_values("mesh", anim, o.reference_samples));
    }
    const double texels_per_unit = mesh_frames[0].own_texture->width;
    for (const Variant& v : variants_of("mesh")) {
      const std::string engine = v.engine_for(o.engine), label = v.label_for(o.engine);
      std::vector<std::vector<Rgba>> values;
      for (int f = 0; f < o.frames; ++f) {
        anim.frame = f;
        const VariantRender r = render_variant(v.scene, anim, v.filter, engine);
        values.push_back(texels_to_values(r.texels, r.channel_bits));
      }
      const SurfaceJitterStats s = mesh_jitter(mesh_frames, values, reference_vertices, texels_per_unit);
      metrics["mesh_vertex_jitter"].push_back({{"name", v.name}, {"label", label}, {"change", s.change},
                                               {"reference_change", s.reference_change}, {"excess", s.excess},
                                               {"mean_change", s.mean_change},
                                               {"mean_reference_change", s.mean_reference_change},
                                               {"mean_excess", s.mean_excess},
                                               {"mean_interior_change", s.mean_interior_change},
                                               {"mean_interior_reference_change", s.mean_interior_reference_change},
                                               {"mean_interior_excess", s.mean_interior_excess}});
      md << "| " << label << " | " << fmt(s.mean_change, 3) << " | " << fmt(s.mean_reference_change, 3) << " | "
         << fmt(s.mean_excess, 3) << " | " << fmt(s.mean_interior_change, 3) << " | "
         << fmt(s.mean_interior_reference_change, 3) << " | " << fmt(s.mean_interior_excess, 3) << " |\n";
    }
    std::fprintf(stderr, "texsim figures: mesh vertex jitter done\n");
  }
  md << "\nPanel animation, every " << std::max(1, o.frames / 8) << ". frame (";
  for (const auto& [name, label] : panel_strips) md << label << "; ";
  md << "reference):\n\n";
  for (const auto& [name, label] : panel_strips) md << "![](panel_frames_" << name << ".png)\n\n";
  md << "![](panel_frames_reference.png)\n";
  metrics["panel_strips"] = json::array();
  for (const auto& [name, label] : panel_strips)
    metrics["panel_strips"].push_back({{"name", name}, {"label", label}, {"image", "panel_frames_" + name + ".png"}});

  // The filters side by side: still error and flicker excess per variant of plane and panel.
  std::ostringstream sum;
  sum << "## Filters compared: plane and panel\n\n"
      << "Stills " << o.width << "x" << o.height << " against the reference; flicker excess over the " << o.frames
      << "-frame animation at " << o.anim_width << "x" << o.anim_height << " (LSB; details below).\n\n"
      << "| scene | variant | engine | PSNR (dB) | max error (LSB) | mean error (LSB) | flicker excess (LSB) |\n"
      << "|---|---|---|---|---|---|---|\n";
  metrics["filters"] = json::array();
  for (const SummaryRow& row : summary) {
    sum << "| " << row.scene << " | " << row.label << " | " << row.engine << " | " << fmt(row.still.psnr_db) << " | "
        << fmt(row.still.max_error_lsb, 1) << " | " << fmt(row.still.mean_error_lsb) << " | "
        << (row.flicker_excess < 0 ? std::string("") : fmt(row.flicker_excess)) << " |\n";
    metrics["filters"].push_back({{"scene", row.scene}, {"name", row.name}, {"label", row.label},
                                  {"engine", row.engine}, {"psnr_db", row.still.psnr_db},
                                  {"max_error_lsb", row.still.max_error_lsb},
                                  {"mean_error_lsb", row.still.mean_error_lsb},
                                  {"flicker_excess", row.flicker_excess}});
  }
  sum << "\n";

  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  metrics["seconds"] = secs;
  save_text(dir / "metrics.json", metrics.dump(1) + "\n");
  std::string index = md.str();
  index.insert(summary_at, sum.str());
  save_text(dir / "index.md", index);
  outputs.commit();
  std::printf("texsim figures: %zu scenes, engine %s -> %s/index.md, metrics.json (%.1f s)\n", scene_names().size(),
              o.engine.c_str(), o.out_dir.c_str(), secs);
  return 0;
}

}  // namespace tex
