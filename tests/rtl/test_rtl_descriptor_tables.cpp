// tex_unit_cached's descriptor and sampler tables in lockstep with the golden model
// (cached_lockstep.h): many textures of every format, size, layer count and cube map at once,
// random samplers, requests interleaving them at 1 sample per clock; and the checkers shown to
// fire on planted bugs in the tables and in cube maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "cached_lockstep.h"
#include "lockstep.h"
#include "model/image.h"
#include "model/srgb.h"

using namespace tex;
using namespace tex::rtltest;

namespace {

const std::vector<TexelFormat> kBlockFormats = {TexelFormat::Bc1,     TexelFormat::Bc2,       TexelFormat::Bc3,
                                                TexelFormat::Bc4,     TexelFormat::Bc5,       TexelFormat::Bc7,
                                                TexelFormat::Etc2Rgb, TexelFormat::Etc2RgbA1, TexelFormat::Etc2Rgba,
                                                TexelFormat::EacR11,  TexelFormat::EacR11Snorm, TexelFormat::EacRg11,
                                                TexelFormat::EacRg11Snorm,
                                                TexelFormat::Astc4x4, TexelFormat::Astc6x5,   TexelFormat::Astc8x8,
                                                TexelFormat::Astc10x6, TexelFormat::Astc12x12};

// The descriptor table: 2 to 16 textures of random sizes, wrap modes and formats (RGBA8 and block
// formats mixed; with the sRGB tables, half of them sRGB) in memory at once, a random texture in
// every request (consecutive requests interleave textures at 1 sample per clock, no flush), under
// random caches, memory timing and stalls; samples, miss streams and response clocks against the
// model.
void run_descriptor_tables(const std::string& config, int cases) {
  const rtl::RtlConfig& rc = config_named(config);
  const uint64_t base = mix64(seed_base() ^ 0xDE5C ^ std::hash<std::string>{}(config));
  const std::optional<uint64_t> only = env_u64("TEX_SEED");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  uint64_t samples = 0, switches = 0, sampler_switches = 0, reads = 0, flagged = 0;
  int full_tables = 0, full_samplers = 0, failures = 0, block_textures = 0, srgb_textures = 0, array_textures = 0;
  int cube_textures = 0;
  std::map<std::string, uint64_t> layer_cases, cube_cases;
  for (int ci = 0; ci < cases * scale(); ++ci) {
    const uint64_t seed = mix64(base + uint64_t(ci));
    if (only && *only != seed) continue;
    std::mt19937_64 rng(seed);
    const int n = ci % 4 == 0 ? kMaxTextures : 2 + int(rng() % (kMaxTextures - 1));
    full_tables += n == kMaxTextures;
    std::vector<std::vector<Pyramid>> arrays(static_cast<size_t>(n));  // each texture's layers
    TextureTable table;
    for (int t = 0; t < n; ++t) {
      std::vector<Pyramid>& pyramids = arrays[size_t(t)];
      // Up to the configuration's 64x8, half of them of powers of two; half of the textures in a
      // block format (sides >= 4).
      // With CUBE_MAPS, one in 4 a cube map of n x n RGBA faces (n + 2 <= the smaller side), one in
      // 3 of those a cube array of 2 or 3 cubes.
      const bool cube = rc.cube_maps && rng() % 4 == 0;
      const TexelFormat format =
          cube || !rc.formats || rng() % 2 ? TexelFormat::Rgba8 : kBlockFormats[rng() % kBlockFormats.size()];
      const bool blocks = is_compressed(format), srgb = rng() % 2;
      Extent size;
      if (rng() % 2)
        size = {1 << (blocks ? 2 + int(rng() % 5) : int(rng() % 7)), 1 << (blocks ? 2 + int(rng() % 2) : int(rng() % 4))};
      else
        size = {blocks ? 4 + int(rng() % 61) : 1 + int(rng() % 64), blocks ? 4 + int(rng() % 5) : 1 + int(rng() % 8)};
      // A third of them arrays of 2 to 8 layers, now and then of 256 (each layer its own texels).
      int layers = rng() % 3 ? 1 : rng() % 8 == 0 ? kMaxLayers : 2 + int(rng() % 7);
      if (cube) {
        const int face = 1 + int(rng() % uint64_t(std::min(rc.max_cube_face(), 40)));
        size = {face, face};
        layers = 6 * (rng() % 3 ? 1 : 2 + int(rng() % 2));
      }
      const bool view = !cube && rng() % 4 == 0;  // a view: levels b..b+0..3 (the descriptor's last level)
      const uint64_t b = rng(), span = rng() % 4;
      for (int l = 0; l < layers; ++l) {
        pyramids.push_back(random_pyramid(rc, format, size, srgb, rng()));
        if (view) {
          const int first = int(b % uint64_t(pyramids.back().levels.size()));
          pyramids.back() = view_pyramid(pyramids.back(), first, first + int(span));
        }
      }
      block_textures += blocks;
      srgb_textures += pyramids.back().srgb;
      array_textures += !cube && layers > 1;
      cube_textures += cube;
      BoundTexture bound{&pyramids[0], {}, cube ? TextureKind::Cube : TextureKind::Texture2D};
      for (int l = 1; l < layers; ++l) bound.more_layers.push_back(&pyramids[size_t(l)]);
      table.push_back(bound);
    }
    // The sampler table: 1 to 16 entries (a quarter full), every field random.
    const int ns = ci % 4 == 1 ? kMaxSamplers : 1 + int(rng() % kMaxSamplers);
    full_samplers += ns == kMaxSamplers;
    SamplerTable samplers;
    for (int k = 0; k < ns; ++k) samplers.push_back(random_sampler(rng, 6));  // 1 in 6 unnormalized
    const LayoutParams layout = random_layout(rng, rc);
    const CacheParams cache = random_cache(rng, rc);
    std::string memory_name, timing_name;
    const rtl::MemoryTiming memory = random_memory(rng, rc, memory_name);
    const rtl::Timing stim = random_stalls(rng, timing_name);
    std::vector<Request> requests = random_requests(rng, 6, 3, 4000);  // (cube maps': below)
    for (size_t i = 0; i < requests.size(); ++i) {
      requests[i].texture = uint8_t(rng() % uint64_t(n));
      requests[i].sampler = uint8_t(rng() % uint64_t(ns));
      switches += i > 0 && requests[i].texture != requests[i - 1].texture;
      sampler_switches += i > 0 && requests[i].sampler != requests[i - 1].sampler;
    }
    texel_coordinates_where_unnormalized(rng, requests, samplers, [&](int t) { return table[size_t(t)].pyramid->extent0(); });
    fetches_and_gathers_among(rng, requests, 16, [&](int t) { return table[size_t(t)].pyramid->extent0(); });
    layers_among(rng, requests, [&](int t) { return table[size_t(t)].layers(); });
    compares_among(rng, requests, 16, samplers, [&](int t) { return table[size_t(t)].pyramid->depth_problem().empty(); });
    // A cube map's requests: cube_request's, through a sampler a cube takes (normalized; a
    // compare's, one that compares): sampler 0 is made one.
    if (cube_textures) samplers[0].unnormalized = false;
    for (Request& q : requests) {
      const BoundTexture& t = table[q.texture];
      if (t.kind != TextureKind::Cube) continue;
      q = cube_request(rng, q, t.pyramid->extent0().w, t.pyramid->last_level(), t.layers());
      auto takes = [&](const SamplerConfig& c) {
        return !c.unnormalized && (q.op != Op::Compare || c.compare_problem().empty());
      };
      if (!takes(samplers[q.sampler])) q.sampler = 0;
      if (q.op == Op::Compare && (!takes(samplers[q.sampler]) || t.pyramid->srgb)) q.op = Op::Sample;
      const int layer_of = q.op == Op::Fetch ? q.layer : -1;
      ++cube_cases[q.op == Op::Fetch ? (layer_of >= 0 && layer_of < t.layers() ? "a face's texel fetch" : "a fetch outside the faces")
                   : q.op == Op::Gather ? "a gather"
                   : q.op == Op::Compare ? "a depth compare"
                   : q.has_derivatives ? "derivatives" : "a lod"];
      if (q.op != Op::Fetch) {
        const stage::CubeFace f = stage::cube_face(q.u, q.v, q.w);
        const int32_t n = t.pyramid->extent0().w, edge = (1 << kCoordFracBits) / n;
        const bool near_s = f.s < edge || f.s > (1 << kCoordFracBits) - edge, near_t = f.t < edge || f.t > (1 << kCoordFracBits) - edge;
        ++cube_cases[near_s && near_t ? "at a corner" : near_s || near_t ? "at an edge" : "inside a face"];
        ++cube_cases["face " + std::to_string(f.face)];
        if (q.has_derivatives) {  // anisotropic probes beyond the face (tex_cube_seam moves them)
          int face = 0;
          const Probes p = tex_probe(cube_face_request(q, face), samplers[q.sampler], t.pyramid->extent0());
          for (int i = 0; i < p.n; ++i) {
            Request probe = p.at[size_t(i)];
            if (cube_probe(face, probe) != face) ++cube_cases["a probe moved to another face"];
          }
        }
      }
    }
    for (const Request& q : requests) {  // the layer cases of arrays, counted
      const int nl = table[q.texture].layers();
      if (nl == 1 || table[q.texture].kind == TextureKind::Cube) continue;
      const int64_t whole = q.layer >> 16;
      if (q.op == Op::Fetch) ++layer_cases[stage::fetch_layer_inside(q.layer, nl) ? "fetch inside the layers" : "fetch outside the layers"];
      else if (q.layer < 0) ++layer_cases["below layer 0"];
      else if (whole >= nl) ++layer_cases["beyond the last layer"];
      else if ((q.layer & 0xFFFF) == 0x8000) ++layer_cases[whole % 2 ? "a tie, rounded up to even" : "a tie, rounded down to even"];
      else ++layer_cases["between two layers"];
    }
    const std::vector<uint64_t> errors = random_error_reads(rng, ci);
    const CaseResult r = run_case(*unit, table, samplers, layout, cache, memory, requests, stim, rng(), nullptr, nullptr,
                                  -1, 0, nullptr, errors);
    samples += r.samples;
    reads += r.reads;
    flagged += r.flagged;
    if (!r.failure.empty()) {
      ADD_FAILURE() << "case " << ci << " (replay: TEX_SEED=" << seed << "): " << n << " textures, " << ns
                    << " samplers (0: " << describe(samplers[0]) << "), " << cache.size_bytes << " B x " << cache.ways << " ways, " << memory_name << ", stimulus "
                    << timing_name << ": " << r.failure << "; the textures:" << [&] {
                         std::string list;
                         for (size_t t = 0; t < table.size(); ++t) {
                           const Pyramid& p = *table[t].pyramid;
                           list += " " + std::to_string(t) + " " + format_info(p.format).name + (p.srgb ? " sRGB " : " ") +
                                   std::to_string(p.extent0().w) + "x" + std::to_string(p.extent0().h);
                         }
                         for (size_t t = 0; t < samplers.size(); ++t) list += "; sampler " + std::to_string(t) + ": " + describe(samplers[t]);
                         return list;
                       }();
      unit->reset();
      if (++failures >= 3) break;
    }
  }
  std::printf("[ cached   ] descriptor and sampler tables: %llu samples (%llu flagged by memory errors), %llu "
              "texture and %llu sampler switches between consecutive requests, %llu lines read, %d full descriptor "
              "tables of %d, %d full sampler tables of %d, %d block-format textures, %d sRGB, %d arrays (%s)\n",
              (unsigned long long)samples, (unsigned long long)flagged, (unsigned long long)switches,
              (unsigned long long)sampler_switches, (unsigned long long)reads, full_tables, kMaxTextures,
              full_samplers, kMaxSamplers, block_textures, srgb_textures, array_textures, config.c_str());
  if (rc.cube_maps) {
    std::printf("[ cached   ] %d cube maps:", cube_textures);
    for (const auto& [c, k] : cube_cases) std::printf(" %s %llu;", c.c_str(), (unsigned long long)k);
    std::printf("\n");
  }
  if (only) return;
  EXPECT_GT(full_tables, 0);
  EXPECT_GT(full_samplers, 0);
  EXPECT_GT(array_textures, 0);
  EXPECT_EQ(cube_textures > 0, rc.cube_maps);
  if (rc.cube_maps) {
    for (const char* c : {"a face's texel fetch", "a fetch outside the faces", "a gather", "a depth compare", "derivatives",
                          "a lod", "at a corner", "at an edge", "inside a face", "face 0", "face 1", "face 2", "face 3",
                          "face 4", "face 5", "a probe moved to another face"})
      EXPECT_GT(cube_cases[c], 0u) << "cube requests: " << c;
  }
  for (const char* c : {"fetch inside the layers", "fetch outside the layers", "below layer 0", "beyond the last layer",
                        "a tie, rounded up to even", "a tie, rounded down to even", "between two layers"})
    EXPECT_GT(layer_cases[c], 0u) << "array requests: " << c;
  EXPECT_GT(sampler_switches, samples / 2);
  EXPECT_GT(flagged, 0u);
  EXPECT_EQ(block_textures > 0, rc.formats);
  EXPECT_EQ(srgb_textures > 0, rc.formats);
  EXPECT_GT(switches, samples / 2);
}

}  // namespace

TEST(RtlCached, DescriptorAndSamplerTablesInterleave) { run_descriptor_tables("Vtex_cached_6x3", 40); }

// With the sRGB tables (CW 16 filter, 8-bit memory): sRGB and linear textures of every format mixed
// in one table; a model that filters an sRGB texture's codes as linear values is caught.
TEST(RtlCached, DescriptorTableMixesSrgbAndLinear) {
  run_descriptor_tables("Vtex_cached_13x13", 24);
  auto unit = rtl::Driver::create(config_named("Vtex_cached_13x13"), {});
  unit->reset();
  std::mt19937_64 rng(8);
  const Pyramid srgb = build_srgb_pyramid(random_image(64, 8, 8, 4), PyramidMode::Exact);
  Pyramid codes = srgb;  // planted: the stored codes, filtered as if linear (16-bit values a * 257)
  for (size_t k = 0; k < codes.levels.size(); ++k) {
    codes.levels[k] = srgb.codes[k];
    codes.levels[k].channel_bits = 16;
    for (Texel& t : codes.levels[k].texels)
      for (uint16_t& c : t) c = uint16_t(c * 257);
  }
  const std::vector<Request> requests = random_requests(rng, 6, 3, 2000);
  const TextureTable table = {{&srgb}}, wrong = {{&codes}};
  const CacheParams cache{2048, 2};
  EXPECT_EQ(run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, {}, requests, {}, 1, nullptr).failure, "");
  const CaseResult planted =
      run_case(*unit, table, SamplerTable{SamplerConfig{}}, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, -1, 0, &wrong);
  EXPECT_EQ(planted.failure.rfind("sample ", 0), 0u) << planted.failure;
}

// Planted bugs: a model whose sampler table has the entries' wrap modes swapped, whose border
// colours differ, whose array has its layers in the other order, or whose descriptor table has its
// entries in the other order (each request then names the other texture), sees other samples.
TEST(RtlCached, DescriptorTableCheckersCatchPlantedBugs) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  std::mt19937_64 rng(3);
  const Pyramid a = build_pyramid(random_image(64, 8, 8, 1), PyramidMode::Exact);
  const Pyramid b = build_pyramid(random_image(32, 4, 8, 2), PyramidMode::Exact);
  std::vector<Request> requests = random_requests(rng, 6, 3, 2000);
  for (Request& q : requests) {
    q.texture = uint8_t(rng() % 2);
    q.sampler = uint8_t(rng() % 2);
  }
  const TextureTable table = {{&a}, {&b}};
  SamplerTable samplers(2);
  samplers[0].wrap_u = Wrap::Repeat;
  samplers[0].wrap_v = Wrap::Clamp;
  samplers[1].wrap_u = Wrap::Mirror;
  samplers[1].wrap_v = Wrap::Border;
  samplers[1].border = BorderColor::FloatOpaqueWhite;
  SamplerTable rewrapped = samplers;
  std::swap(rewrapped[0].wrap_u, rewrapped[1].wrap_u);
  SamplerTable recoloured = samplers;
  recoloured[1].border = BorderColor::FloatOpaqueBlack;
  const CacheParams cache{2048, 2};
  const CaseResult good = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr);
  EXPECT_EQ(good.failure, "");
  const CaseResult wrap = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                   -1, 0, nullptr, {}, nullptr, &rewrapped);
  EXPECT_EQ(wrap.failure.rfind("sample ", 0), 0u) << wrap.failure;
  unit->reset();
  const CaseResult colour = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                     -1, 0, nullptr, {}, nullptr, &recoloured);
  EXPECT_EQ(colour.failure.rfind("sample ", 0), 0u) << colour.failure;
  unit->reset();
  // An array whose model has its layers in the other order.
  const Pyramid c = build_pyramid(random_image(32, 4, 8, 3), PyramidMode::Exact);
  const TextureTable arrays = {{&a}, {&b, {&c}}}, swapped = {{&a}, {&c, {&b}}};
  std::vector<Request> layered = requests;
  for (Request& q : layered) q.layer = q.texture == 1 ? int32_t(rng() % 2) << 16 : 0;
  EXPECT_EQ(run_case(*unit, arrays, samplers, LayoutParams{}, cache, {}, layered, {}, 1, nullptr).failure, "");
  unit->reset();
  const CaseResult layers = run_case(*unit, arrays, samplers, LayoutParams{}, cache, {}, layered, {}, 1, nullptr, nullptr,
                                     -1, 0, &swapped);
  EXPECT_EQ(layers.failure.rfind("sample ", 0), 0u) << layers.failure;
  unit->reset();
  const TextureTable reordered = {table[1], table[0]};
  const CaseResult order = run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr,
                                    -1, 0, &reordered);
  EXPECT_EQ(order.failure.rfind("sample ", 0), 0u) << order.failure;
}

// Cube maps, planted bugs: a skirt corner that is not the average of three (its R flipped in
// memory), a skirt texel across an edge from the wrong face (likewise), a model whose cube has two
// faces swapped, each seen as other samples; the unplanted cube agrees. Lookups at +X's corner
// (s, t near 0) and along its top edge at level 0, and anywhere on the cube.
TEST(RtlCached, CubeCheckersCatchPlantedBugs) {
  const rtl::RtlConfig& rc = config_named("Vtex_cached_6x3");
  auto unit = rtl::Driver::create(rc, {});
  unit->reset();
  std::mt19937_64 rng(35);
  const int n = 4;
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) faces.push_back(build_pyramid(random_image(n, n, 8, 60 + uint64_t(f)), PyramidMode::Exact));
  std::vector<Pyramid> swapped = faces;
  std::swap(swapped[2], swapped[3]);
  auto cube_of = [](const std::vector<Pyramid>& f) {
    const std::vector<const Pyramid*> p = pointers_to(f);
    return TextureTable{BoundTexture(p[0], {p.begin() + 1, p.end()}, TextureKind::Cube)};
  };
  const TextureTable table = cube_of(faces), wrong = cube_of(swapped);
  SamplerConfig bilinear;
  bilinear.filter = Filter{TexelFilter::Linear, MipMode::None};
  std::vector<Request> requests;
  for (int i = 0; i < 3000; ++i) {
    Request q;
    q.tag = uint16_t(i);
    if (i % 3 == 2) {
      q = cube_request(rng, q, n, faces[0].last_level(), 6);
      if (q.op == Op::Fetch) q.op = Op::Sample, q.lod = 0, q.layer = 0;
    } else {  // +X at its corner (s, t < 1 / 2n) or along its top edge (t < 1 / 2n)
      const double s = double(rng() % 1000) / 1000 / (i % 3 == 0 ? 2 * n : 1), t = double(rng() % 1000) / 1000 / (2 * n);
      const std::array<int32_t, 3> d = cube_direction(rng, 0, s, t);
      q.u = d[0], q.v = d[1], q.w = d[2];
    }
    requests.push_back(q);
  }
  const CacheParams cache{2048, 2};
  const SamplerTable samplers{bilinear};
  EXPECT_EQ(run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr).failure, "");
  // (byte 0 of +X's level 0: its skirt's corner texel (0, 0); byte 4: the skirt texel (1, 0) above
  // its texel (0, 0), a texel of +Y)
  for (const int poke : {0, 4}) {
    const CaseResult planted =
        run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, poke);
    EXPECT_EQ(planted.failure.rfind("sample ", 0), 0u) << "byte " << poke << ": " << planted.failure;
  }
  const CaseResult faces_swapped =
      run_case(*unit, table, samplers, LayoutParams{}, cache, {}, requests, {}, 1, nullptr, nullptr, -1, 0, &wrong);
  EXPECT_EQ(faces_swapped.failure.rfind("sample ", 0), 0u) << faces_swapped.failure;
}
