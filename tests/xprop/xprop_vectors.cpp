// xprop_vectors: the stimulus and the golden model's expected responses for the 4-state
// X-propagation bench tests/xprop/tb_tex_unit.sv (Icarus Verilog; scripts/xprop.sh,
// docs/verification.md). Only the golden model (texmodel) is used; nothing here simulates the RTL:
// the bench does the handshakes, so the files describe what to offer, not when it is taken.
//
// Writes into DIR:
//   params.txt     MAX_LOG2_W=.., MAX_LOG2_H=.., CW=.., TAG_W=..: the bench's parameters (-P)
//   stimulus.txt   one command per line, in order (numbers decimal unless marked hex):
//     H max_log2_w max_log2_h cw tag_w requests ready_len   header (checked by the bench)
//     C w h last_level wrap_u wrap_v texel_linear mip_mode lod_bias min_lod max_lod mag_linear
//       border(hex, {A, B, G, R} unorm16) reduction compare_op
//                    the cfg pins from now on (only after a drain: nothing in flight)
//     W level x y data(hex)                       one clock with wr_en high
//     I clocks                                    idle clocks (req_valid and wr_en low)
//     R gap u v lod tag(hex) wr level x y data(hex) op component ref
//                    gap idle clocks, then the request offered until taken; wr = 1: the write
//                    (x, y) of `level` <- data (the texel it already holds) in the first of them;
//                    op: req_op (a sample, a gather of `component`, a depth compare with
//                    reference `ref` (Q8.24), or a texel fetch: u, v, lod are i, j, level)
//     Z hold clocks  hold clocks with rsp_ready low and no request, then rst high for `clocks`
//                    clocks: the requests in flight are dropped; the next ones are answered
//     D              drain: no request until every accepted one is answered, then idle clocks
//     E              end (after a drain)
//   expected.txt   per request, in offer order: tag(hex) rgba(hex, {A, B, G, R}, CW bits each)
//   ready.txt      ready_len bits, one a line: rsp_ready in clock n (outside resets) is bit
//                  n mod ready_len (output stalls of 1..6 clocks, now and then 20..80)
//
// Content: textures of several sizes and shapes up to 2^MAX_LOG2_W x 2^MAX_LOG2_H (smaller and
// non-square ones first, so that memory words past the texture are still unwritten, X, while they
// are sampled), random texels, exact or cascade pyramid, loaded through the write port with
// random idle clocks; for each texture all 6 filters x 5 x 5 address modes (a random border colour
// each), half of them with a
// magnification filter apart from the minification filter, plus two cases with the reserved code
// cfg_smp_mip_mode = 3 (random lod bias and clamps), random requests: coordinates far outside [0, 1), near the texel edges and centres of
// every level, any 32-bit value; lambda across every level, on the level and rounding boundaries,
// below 0, past the last level and any 16-bit value; random input gaps; rewrites of texels with
// their own value while requests stream; resets with requests in flight.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "model/error.h"
#include "model/formats.h"
#include "model/image.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "stimulus.h"

namespace {

using namespace tex;

constexpr int kTagBits = 16;  // TAG_W of the bench's tex_unit

struct Options {
  std::string out_dir;
  uint64_t seed = 1;
  int requests = 6000;  // about; at least 4 per filter and wrap pair of each texture
  int max_log2_w = 3, max_log2_h = 3, cw = 8;
  int resets = 3;
  int ready_len = 4099;
};

uint64_t pack_rgba(const Texel& t, int cw) {
  const uint64_t mask = (uint64_t(1) << cw) - 1;
  uint64_t p = 0;
  for (int c = 3; c >= 0; --c) p = p << cw | (t[size_t(c)] & mask);
  return p;
}

struct Gen {
  explicit Gen(const Options& o) : opt(o), rng(o.seed) {}
  const Options& opt;
  std::mt19937_64 rng;
  std::ofstream stim, expect;
  uint64_t issued = 0;

  uint64_t below(uint64_t n) { return n ? rng() % n : 0; }
  int64_t between(int64_t lo, int64_t hi) { return lo + int64_t(below(uint64_t(hi - lo + 1))); }  // [lo, hi]

  // Textures and request fields: tests/common/stimulus.h, as every suite's.
  Image random_texture(int log2_w, int log2_h) {
    return stimulus::random_image(1 << log2_w, 1 << log2_h, opt.cw, rng(), -1);  // any style
  }

  void cfg_line(const Pyramid& p, const SamplerConfig& c) {
    stim << "C " << p.extent0().w << ' ' << p.extent0().h << ' ' << p.last_level() << ' ' << int(c.wrap_u) << ' ' << int(c.wrap_v) << ' '
         << (c.filter.texel == TexelFilter::Linear ? 1 : 0) << ' ' << int(c.filter.mip) << ' ' << c.lod_bias << ' '
         << c.min_lod << ' ' << c.max_lod << ' ' << (c.filter.mag == TexelFilter::Linear ? 1 : 0) << ' ';
    const Texel b = c.border_unorm16();
    char hex[24];
    std::snprintf(hex, sizeof hex, "%llx",
                  static_cast<unsigned long long>(uint64_t(b[0]) | uint64_t(b[1]) << 16 | uint64_t(b[2]) << 32 |
                                                  uint64_t(b[3]) << 48));
    stim << hex << ' ' << int(c.reduction) << ' ' << int(c.compare_op) << '\n';
  }

  void write_line(int level, int x, int y, uint64_t data) {
    char hex[24];
    std::snprintf(hex, sizeof hex, "%llx", static_cast<unsigned long long>(data));
    stim << "W " << level << ' ' << x << ' ' << y << ' ' << hex << '\n';
  }

  // Every texel of every level through the write port, with random idle clocks (pins X).
  void load(const Pyramid& p) {
    for (size_t k = 0; k < p.levels.size(); ++k) {
      const Image& img = p.levels[k];
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          if (below(8) == 0) stim << "I " << 1 + below(3) << '\n';
          write_line(int(k), x, y, pack_rgba(img.at(x, y), opt.cw));
        }
    }
  }

  // `n` random requests with this configuration; a reset after request `reset_at` (-1: none).
  void requests(const Pyramid& p, const SamplerConfig& c, int n, int reset_at) {
    Sampler model(p, c);
    const int last = p.last_level();
    for (int i = 0; i < n; ++i) {
      Request r;
      if (below(8) == 0) {
        r = stimulus::random_fetch(rng, p.extent0());
      } else if (below(8) == 0) {
        r = stimulus::random_gather(rng, p.extent0());
      } else {
        r.u = stimulus::random_coordinate(rng, p.extent0().w, last);
        r.v = stimulus::random_coordinate(rng, p.extent0().h, last);
        r.lod = stimulus::random_lod(rng, last);
        if (below(8) == 0 && c.compare_problem().empty()) {  // a depth compare, its reference in [-1/8, 9/8]
          r.op = Op::Compare;
          r.ref = int32_t(between(-(1 << 21), (1 << 24) + (1 << 21)));
        }
      }
      const uint64_t tag = issued++ & ((uint64_t(1) << kTagBits) - 1);
      // Input gaps: none in about 60% of the requests, else 1..3, now and then up to 12.
      const uint64_t g = below(100);
      const uint64_t gap = g < 60 ? 0 : g < 95 ? 1 + below(3) : 4 + below(9);
      // Now and then a texel of the texture rewritten with its own value while requests stream.
      int wr = 0, wl = 0, wx = 0, wy = 0;
      uint64_t wd = 0;
      if (below(20) == 0) {
        wr = 1;
        wl = int(below(p.levels.size()));
        const Image& img = p.levels[size_t(wl)];
        wx = int(below(uint64_t(img.width)));
        wy = int(below(uint64_t(img.height)));
        wd = pack_rgba(img.at(wx, wy), opt.cw);
      }
      char line[192];
      std::snprintf(line, sizeof line, "R %llu %d %d %d %llx %d %d %d %d %llx %d %d %d\n", static_cast<unsigned long long>(gap),
                    r.u, r.v, int(r.lod), static_cast<unsigned long long>(tag), wr, wl, wx, wy,
                    static_cast<unsigned long long>(wd), int(r.op), int(r.component), r.ref);
      stim << line;
      std::snprintf(line, sizeof line, "%llx %llx\n", static_cast<unsigned long long>(tag),
                    static_cast<unsigned long long>(pack_rgba(model.sample(r), opt.cw)));
      expect << line;
      if (i == reset_at) stim << "Z " << below(14) << ' ' << 1 + below(4) << '\n';
    }
  }
};

int run(const Options& opt) {
  if (opt.max_log2_w < 0 || opt.max_log2_w > kMaxLog2Size || opt.max_log2_h < 0 || opt.max_log2_h > kMaxLog2Size)
    throw Error("--max-log2-w/--max-log2-h must be in 0.." + std::to_string(kMaxLog2Size));
  if (opt.cw < 1 || opt.cw > kMaxChannelBits) throw Error("--cw must be in 1.." + std::to_string(kMaxChannelBits));
  std::filesystem::create_directories(opt.out_dir);
  const std::filesystem::path dir(opt.out_dir);
  Gen g(opt);
  g.stim.open(dir / "stimulus.txt");
  g.expect.open(dir / "expected.txt");
  std::ofstream params(dir / "params.txt"), ready(dir / "ready.txt");
  if (!g.stim || !g.expect || !params || !ready) throw Error("cannot write into " + opt.out_dir);
  params << "MAX_LOG2_W=" << opt.max_log2_w << "\nMAX_LOG2_H=" << opt.max_log2_h << "\nCW=" << opt.cw
         << "\nTAG_W=" << kTagBits << '\n';

  // Textures: the smaller and non-square ones first (their memories keep unwritten words around
  // them), the full size last. Each is distinct and fits the unit.
  const int mw = opt.max_log2_w, mh = opt.max_log2_h;
  std::vector<std::pair<int, int>> sizes = {{mw, std::max(0, mh - 2)}, {std::max(0, mw - 3), mh}, {0, 0}, {mw, mh}};
  std::vector<std::pair<int, int>> textures;
  for (const auto& s : sizes)
    if (std::find(textures.begin(), textures.end(), s) == textures.end()) textures.push_back(s);

  std::vector<Filter> filters;
  for (TexelFilter t : {TexelFilter::Nearest, TexelFilter::Linear})
    for (MipMode m : {MipMode::None, MipMode::Nearest, MipMode::Linear}) filters.push_back({t, m});
  struct Case {
    Filter filter;
    Wrap wu, wv;
  };
  std::vector<Case> cases;
  for (const Filter& f : filters)
    for (int wu = 0; wu < kWrapModes; ++wu)
      for (int wv = 0; wv < kWrapModes; ++wv) {
        cases.push_back({f, Wrap(wu), Wrap(wv)});
        if ((wu + wv) % 2) cases.back().filter.mag = TexelFilter(1 - int(f.texel));  // magnifies apart
      }
  // Plus two cases per texture with the reserved code (docs/rtl.md: cfg_smp_mip_mode = 3 acts as
  // linear, as the model's code does); drawn per texture.
  constexpr size_t kReservedCases = 2;
  const size_t cases_per_texture = cases.size() + kReservedCases;
  const int per_case = std::max(4, opt.requests / int(textures.size() * cases_per_texture));
  const uint64_t total = uint64_t(per_case) * textures.size() * cases_per_texture;

  // Resets mid-traffic: in distinct random cases, after a random request past the pipeline fill.
  const size_t ncases = textures.size() * cases_per_texture;
  std::vector<size_t> reset_cases;
  while (reset_cases.size() < std::min<size_t>(size_t(std::max(opt.resets, 0)), ncases)) {
    const size_t c = size_t(g.below(ncases));
    if (std::find(reset_cases.begin(), reset_cases.end(), c) == reset_cases.end()) reset_cases.push_back(c);
  }

  g.stim << "H " << mw << ' ' << mh << ' ' << opt.cw << ' ' << kTagBits << ' ' << total << ' ' << opt.ready_len << '\n';
  size_t case_index = 0;
  for (size_t t = 0; t < textures.size(); ++t) {
    const Pyramid pyr = build_pyramid(g.random_texture(textures[t].first, textures[t].second),
                                      t % 2 ? PyramidMode::Cascade : PyramidMode::Exact);
    SamplerConfig c;
    g.stim << "D\n";
    g.cfg_line(pyr, c);
    g.load(pyr);
    std::vector<Case> list = cases;
    list.push_back({{TexelFilter(g.below(2)), MipMode(3)}, Wrap(g.below(kWrapModes)), Wrap(g.below(kWrapModes))});
    list.push_back({{TexelFilter(g.below(2)), MipMode(3)}, Wrap(g.below(kWrapModes)), Wrap(g.below(kWrapModes))});
    list.back().filter.mag = TexelFilter(g.below(2));
    std::shuffle(list.begin(), list.end(), g.rng);
    for (const Case& k : list) {
      c.filter = k.filter;
      c.wrap_u = k.wu;
      c.wrap_v = k.wv;
      stimulus::randomize_border(g.rng, c);
      stimulus::randomize_lod_controls(g.rng, c);
      stimulus::randomize_reduction(g.rng, c);
      c.compare_op = CompareOp(g.below(kCompareOps));
      g.stim << "D\n";
      g.cfg_line(pyr, c);
      const bool reset_here = std::find(reset_cases.begin(), reset_cases.end(), case_index) != reset_cases.end();
      const int reset_at = reset_here && per_case >= 4 ? int(g.between(std::min(12, per_case - 2), per_case - 2)) : -1;
      g.requests(pyr, c, per_case, reset_at);
      ++case_index;
    }
  }
  g.stim << "D\nE\n";

  // rsp_ready: runs of ready clocks, stalls of 1..6 clocks, now and then a long one of 20..80
  // (the skid buffer fills and req_ready falls).
  for (int n = 0; n < opt.ready_len;) {
    const uint64_t k = g.below(1000);
    const int run = k < 8 ? int(g.between(20, 80)) : k < 250 ? int(g.between(1, 6)) : 0;
    for (int i = 0; i < run && n < opt.ready_len; ++i, ++n) ready << "0\n";
    for (int i = int(g.between(1, 8)); i > 0 && n < opt.ready_len; --i, ++n) ready << "1\n";
  }
  g.stim.close();
  g.expect.close();
  ready.close();
  if (!g.stim || !g.expect || !ready) throw Error("writing into " + opt.out_dir + " failed");
  std::cout << "xprop_vectors: " << total << " requests, " << textures.size() << " textures, " << cases.size()
            << " filter and wrap pairs each (+" << kReservedCases << " with reserved codes), " << reset_cases.size() << " resets, seed " << opt.seed << " -> "
            << opt.out_dir << '\n';
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  CLI::App app{
      "xprop_vectors: stimulus and expected responses (golden model) for the 4-state X-propagation bench "
      "tests/xprop/tb_tex_unit.sv (scripts/xprop.sh)"};
  app.add_option("out_dir", opt.out_dir, "directory for params.txt, stimulus.txt, expected.txt, ready.txt")->required();
  app.add_option("--seed,-s", opt.seed, "random seed")->capture_default_str();
  app.add_option("--requests,-n", opt.requests, "number of requests, about (at least 4 per filter and wrap pair of each texture)")
      ->capture_default_str()
      ->check(CLI::Range(1, 10000000));
  app.add_option("--max-log2-w", opt.max_log2_w, "MAX_LOG2_W of the bench's tex_unit")->capture_default_str();
  app.add_option("--max-log2-h", opt.max_log2_h, "MAX_LOG2_H of the bench's tex_unit")->capture_default_str();
  app.add_option("--cw", opt.cw, "CW: bits per channel")->capture_default_str();
  app.add_option("--resets", opt.resets, "resets with requests in flight")->capture_default_str()->check(CLI::Range(0, 1000));
  app.add_option("--ready-len", opt.ready_len, "length of the rsp_ready schedule, clocks")
      ->capture_default_str()
      ->check(CLI::Range(1, 65536));
  CLI11_PARSE(app, argc, argv);
  try {
    return run(opt);
  } catch (const std::exception& e) {
    std::cerr << "xprop_vectors: " << e.what() << '\n';
    return 1;
  }
}
