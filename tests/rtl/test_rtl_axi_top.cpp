// tex_unit_axi (rtl/tex_unit_axi.sv) end to end, Verilated with the parameters below
// (tests/rtl/CMakeLists.txt): the test drives every pin itself, no rtl::Driver.
//
// - Programming over AXI4-Lite only (docs/rtl-interface.md, "AXI4-Lite configuration
//   (tex_unit_axi)"): the ID, VERSION and CAPS registers against the build's parameters; with the
//   unit in reset (CONTROL.unit_reset) the cache geometry, FIFO limit, filter and LOD registers;
//   then the unit released, 2 to 4 descriptors staged and committed (RGBA8 pyramids, arrays and cube
//   maps through DESC_ATTR's layers and cube bit, packed in
//   memory by texture_descriptors / build_memory_image), the counters cleared. Refused writes on
//   the way: DESC_COMMIT while the unit is in reset, CACHE while it runs, DESC_COMMIT of an entry
//   beyond TEXTURES, of a base off the line, of a size beyond MAX_LOG2_W (each SLVERR, the
//   register unchanged). CACHE and the release come as close as the slave allows (BREADY high at
//   once). The first case starts from the hardware reset, the others use the documented way to
//   change the geometry (unit_reset 1, CACHE, unit_reset 0, every descriptor again).
// - The test's AXI4 slave memory serves the image: random ARREADY, a latency (and jitter), random
//   gaps between beats, RLAST on each burst's last beat, SLVERR / DECERR on chosen line reads (on
//   every beat of the line or on one beat), junk on R while RVALID is low; every AR's ARLEN,
//   ARSIZE, ARBURST, ARID, ARCACHE, ARPROT and alignment checked, and the addresses against the
//   model's miss stream, in order.
// - Random requests (lambda and derivatives; textures interleaved), random req_valid gaps and
//   rsp_ready stalls, junk on the request payload while req_valid is low: every response against
//   tex::Sampler of its texture (with that texture's wrap modes) bit for bit, and its rsp_error
//   against tex::TextureCache::set_error_reads (a flagged sample answers 0).
// - The counters: read (LO then HI) while the stream runs and after a freeze at the end, each
//   against what the test saw at the pins in the exact window the register map defines (events of
//   a clock counted one clock later, from the clear's edge): CYCLES, SAMPLES, SAMPLE_ERRORS,
//   MEM_BYTES, OUT_STALL, REQ_STALL, MEM_WAIT (tex_cached_fetch's head_waits, public for the
//   harness); LOOKUPS and MISSES against the model's cache statistics, MEM_BYTES = MISSES x line.
// - Planted bugs: a descriptor committed with other wrap modes than the model's table, and a
//   model that expects the memory error 64 reads later, are caught.
// - A descriptor rewritten and requests naming it right after the commit's B handshake.
#include <gtest/gtest.h>
#include <verilated.h>
#include <verilated_syms.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "axi_top.h"
#include "engines/engine.h"
#include "engines/rtl/register_map.h"
#include "model/memory_layout.h"
#include "model/pyramid.h"
#include "model/sampler.h"
#include "model/texture_cache.h"
#include "stimulus.h"

using namespace tex;


using namespace tex::axitest;
using namespace tex::stimulus;

namespace {

// ---------------------------------------------------------------- cases

// One case: textures (the RTL's descriptor table), samplers (its sampler table), the cache
// configuration, the memory, the stimulus, the requests.
struct Case {
  Case() = default;
  Case(Case&&) = default;  // (moves keep the pyramids where the table points)
  Case(const Case&) = delete;
  std::vector<Pyramid> pyramids;
  TextureTable table;
  SamplerTable samplers;
  LayoutParams layout;
  int log2_sets = 4, log2_ways = 1;
  uint32_t fifo_limit = 0;
  MemorySetup memory;
  Stimulus stim;
  std::vector<Request> requests;
};

struct CaseResult {
  std::string first_mismatch;         // the first response unlike the model's (value or rsp_error)
  std::vector<std::string> failures;  // anything else: protocol, registers, miss stream, counters
  uint64_t samples = 0, flagged = 0, reads = 0, clocks = 0;
  uint64_t counter_reads = 0;         // counters read (LO, HI) while the stream ran
  AxiTop::Totals counters{};          // read back after the freeze
};

// The level-0 sizes of a descriptor table's textures.
std::vector<Extent> sizes_of(const TextureTable& table) {
  std::vector<Extent> sizes;
  for (const BoundTexture& t : table) sizes.push_back(t.pyramid->extent0());
  return sizes;
}

// A random case: 2 to 4 textures (the first of the largest size; of the others half any size, half
// powers of two), 1 to 16 random samplers, block
// order, base, cache geometry, FIFO limit, memory and stimulus.
Case random_case(uint64_t seed, size_t requests, bool errors, bool cubes = true) {
  std::mt19937_64 rng(seed);
  Case c;
  const int n = 2 + int(rng() % (kTextures - 1));
  c.pyramids.reserve(size_t(n) * 4);
  for (int i = 0; i < n; ++i) {
    Extent size{1 << kMaxLog2W, 1 << kMaxLog2H};
    if (i > 0 && rng() % 2) size = {1 << (rng() % (kMaxLog2W + 1)), 1 << (rng() % (kMaxLog2H + 1))};
    else if (i > 0) size = {1 + int(rng() % (1u << kMaxLog2W)), 1 + int(rng() % (1u << kMaxLog2H))};
    int layers = i > 0 && rng() % 3 == 0 ? 2 + int(rng() % 3) : 1;  // arrays (DESC_ATTR's layers)
    const bool cube = cubes && i > 0 && rng() % 4 == 0;  // a cube map, now and then an array of 2 (DESC_ATTR's cube)
    if (cube) {
      const int face = 1 + int(rng() % uint64_t((1 << std::min(kMaxLog2W, kMaxLog2H)) - 2));
      size = {face, face};
      layers = rng() % 3 ? 6 : 12;
    }
    const bool view = !cube && i > 0 && rng() % 3 == 0;  // a view: its chain cut (DESC_ATTR's last level)
    const uint64_t b = rng(), span = rng() % 3;
    BoundTexture t(nullptr, {}, cube ? TextureKind::Cube : TextureKind::Texture2D);
    for (int l = 0; l < layers; ++l) {
      c.pyramids.push_back(random_pyramid(size, rng()));
      if (view) {
        const int first = int(b % uint64_t(c.pyramids.back().levels.size()));
        c.pyramids.back() = view_pyramid(c.pyramids.back(), first, first + int(span));
      }
      if (l == 0) t.pyramid = &c.pyramids.back();
      else t.more_layers.push_back(&c.pyramids.back());
    }
    c.table.push_back(t);
  }
  const int ns = rng() % 4 == 0 ? kSamplers : 1 + int(rng() % kSamplers);
  for (int i = 0; i < ns; ++i) c.samplers.push_back(random_sampler(rng, 6));  // 1 in 6 unnormalized
  c.layout.block_w = kBlockW;
  c.layout.block_h = kBlockH;
  c.layout.order = BlockOrder(rng() % 2);
  c.layout.base = uint32_t(rng() % 64) * 4096u + uint32_t(rng() % 64) * kLineBytes;
  c.log2_ways = int(rng() % (log2i(kMaxWays) + 1));
  c.log2_sets = 2 + int(rng() % uint64_t(log2i(kLines) - c.log2_ways - 1));  // 4 sets .. LINES / ways
  c.fifo_limit = rng() % 3 == 0 ? 1 + uint32_t(rng() % kFifoDepth) : 0;
  c.memory.latency = rng() % 2 ? 1 + uint32_t(rng() % 8) : 20 + uint32_t(rng() % 80);
  c.memory.jitter = rng() % 2 ? uint32_t(rng() % 30) : 0;
  c.memory.arready_p = rng() % 2 ? 1.0 : 0.3 + 0.6 * double(rng() % 100) / 100;
  c.memory.rgap_p = rng() % 2 ? 0.0 : 0.4;
  c.memory.max_outstanding = rng() % 3 ? 64 : 1 + uint32_t(rng() % 8);
  if (errors)  // 2 to 6 line reads among the first 1500 answered with an error
    for (int k = 2 + int(rng() % 5); k > 0; --k) c.memory.error_reads.push_back(1 + rng() % 1500);
  std::sort(c.memory.error_reads.begin(), c.memory.error_reads.end());
  c.memory.error_reads.erase(std::unique(c.memory.error_reads.begin(), c.memory.error_reads.end()),
                             c.memory.error_reads.end());
  c.stim.gap_prob = rng() % 2 ? 0.0 : 0.3;
  c.stim.max_gap = 4;
  c.stim.stall_prob = rng() % 2 ? 0.05 : 0.3;
  c.stim.max_stall = 6;
  c.stim.long_stall_prob = 0.002;
  c.stim.long_stall = 50 + int(rng() % 100);
  c.requests = random_requests(rng, sizes_of(c.table), c.samplers.size(), requests);
  texel_coordinates_where_unnormalized(rng, c.requests, c.samplers,
                                       [&](int t) { return c.table[size_t(t)].pyramid->extent0(); });
  fetches_and_gathers_among(rng, c.requests, 16, [&](int t) { return c.table[size_t(t)].pyramid->extent0(); });
  layers_among(rng, c.requests, [&](int t) { return c.table[size_t(t)].layers(); });
  compares_among(rng, c.requests, 16, c.samplers, [](int) { return true; });
  // A cube map's requests: cube_request's, through a normalized sampler (sampler 0 made one).
  if (cubes) c.samplers[0].unnormalized = false;
  for (Request& q : c.requests) {
    const BoundTexture& t = c.table[q.texture];
    if (t.kind != TextureKind::Cube) continue;
    q = cube_request(rng, q, t.pyramid->extent0().w, t.pyramid->last_level(), t.layers());
    const SamplerConfig& s = c.samplers[q.sampler];
    if (s.unnormalized || (q.op == Op::Compare && !s.compare_problem().empty())) q.sampler = 0;
    if (q.op == Op::Compare && !c.samplers[q.sampler].compare_problem().empty()) q.op = Op::Sample;
  }
  return c;
}


// Counter i as the register map defines it, for a read whose AR edge is `ar`: the events of the
// edges from the clear's to the one before the read's (to the freeze's edge, if frozen there).
uint64_t expected_counter(const AxiTop& top, int i, uint64_t clear_edge, uint64_t ar, uint64_t freeze_edge) {
  const uint64_t until = std::min(ar - 1, freeze_edge);
  return top.sums_before(until)[size_t(i)] - top.sums_before(clear_edge)[size_t(i)];
}

// Programs the unit for case `c` over AXI4-Lite: geometry and filter in reset, then the
// descriptors `desc` (wrap modes from `rtl_table`), then the counters cleared (its edge in
// `clear_edge`). Refused writes along the way must answer SLVERR and change nothing.
void program(AxiTop& top, const Case& c, const std::vector<TextureDescriptor>& desc, uint64_t& clear_edge,
             std::vector<std::string>& failures) {
  auto expect_write = [&](uint32_t addr, uint32_t data, uint32_t want, const char* what) {
    const uint32_t got = top.write(addr, data);
    if (got != want)
      failures.push_back(std::string(what) + ": write " + hex(data) + " to " + hex(addr) + " answered " +
                         std::to_string(got) + ", want " + std::to_string(want));
  };
  auto expect_read = [&](uint32_t addr, uint32_t want, const char* what) {
    const auto [data, resp] = top.read(addr);
    if (data != want || resp != kOkay)
      failures.push_back(std::string(what) + ": read " + hex(addr) + " gave " + hex(data) + " resp " +
                         std::to_string(resp) + ", want " + hex(want));
  };
  expect_write(kControl, kUnitReset, kOkay, "CONTROL: hold the unit in reset");
  expect_read(kControl, kUnitReset, "CONTROL");
  expect_read(kId, kIdValue, "ID");
  expect_read(kVersion, kVersionValue, "VERSION");
  expect_read(kCaps0, uint32_t(kMaxLog2W | kMaxLog2H << 4 | kTextures << 8 | 1 << 18 | kSamplers << 20), "CAPS0");  // (CUBE_MAPS: the default)
  expect_read(kCaps1, uint32_t(log2i(kLines) | kMaxWays << 8 | log2i(kFifoDepth) << 16 | log2i(kLineBytes) << 24 |
                               log2i(kBeatBytes) << 28),
              "CAPS1");
  const uint32_t cache = uint32_t(c.log2_ways) << 16 | uint32_t(c.log2_sets) << 8 |
                         uint32_t(c.layout.order == BlockOrder::Morton);
  expect_write(kFifoLimit, c.fifo_limit, kOkay, "FIFO_LIMIT");
  // A commit while the unit is in reset would be lost: refused.
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT in reset");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT in reset");
  // The geometry, then the release as soon as allowed (BREADY high at once: the CONTROL write's
  // edge 2 clocks after the CACHE write's when AW and W come together).
  top.bready_p = 1.0;
  expect_write(kCache, cache, kOkay, "CACHE in reset");
  expect_write(kControl, 0, kOkay, "CONTROL: release the unit");
  top.bready_p = 0.7;
  expect_read(kCache, cache, "CACHE");
  // The geometry is fixed while the unit runs.
  expect_write(kCache, cache ^ 1u, kSlverr, "CACHE while the unit runs");
  expect_read(kCache, cache, "CACHE after the refused write");
  for (size_t i = 0; i < desc.size(); ++i) {
    const MemoryLayout& l = desc[i].layout;
    expect_write(kDescBase, l.params().base, kOkay, "DESC_BASE");
    expect_write(kDescAttr, desc_attr_word(l), kOkay, "DESC_ATTR");
    expect_write(kDescSize, desc_size_word(l.size0()), kOkay, "DESC_SIZE");
    expect_write(kDescCommit, uint32_t(i), kOkay, "DESC_COMMIT");
    expect_read(kDescCommit, uint32_t(i), "DESC_COMMIT");
  }
  // Refused commits: an entry beyond the table, a base off the line, a size beyond MAX_LOG2_W, 0.
  const uint32_t last = uint32_t(desc.size() - 1);
  expect_write(kDescCommit, kTextures, kSlverr, "DESC_COMMIT beyond TEXTURES");
  expect_write(kDescBase, desc.back().layout.params().base + 4, kOkay, "DESC_BASE off the line");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a base off the line");
  expect_write(kDescBase, desc.back().layout.params().base, kOkay, "DESC_BASE");
  expect_write(kDescSize, desc_size_word({(1 << kMaxLog2W) + 1, 1}), kOkay, "DESC_SIZE too wide");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a texture beyond MAX_LOG2_W");
  expect_write(kDescSize, desc_size_word({1, 0}), kOkay, "DESC_SIZE of height 0");
  expect_write(kDescCommit, 0, kSlverr, "DESC_COMMIT of a texture of height 0");
  expect_read(kDescCommit, last, "DESC_COMMIT after the refused commits");
  // The sampler table: each entry staged, committed and read back.
  for (size_t i = 0; i < c.samplers.size(); ++i) {
    const SamplerConfig& s = c.samplers[i];
    expect_write(kFilter, filter_word(s), kOkay, "FILTER");
    expect_write(kLodBias, uint16_t(s.lod_bias), kOkay, "LOD_BIAS");
    expect_write(kMinLod, uint16_t(s.min_lod), kOkay, "MIN_LOD");
    expect_write(kMaxLod, uint16_t(s.max_lod), kOkay, "MAX_LOD");
    expect_write(kBorderRg, border_rg_word(s), kOkay, "BORDER_RG");
    expect_write(kBorderBa, border_ba_word(s), kOkay, "BORDER_BA");
    expect_write(kWrap, wrap_word(s), kOkay, "WRAP");
    expect_read(kFilter, filter_word(s), "FILTER");
    expect_read(kMinLod, uint16_t(s.min_lod), "MIN_LOD");
    expect_read(kBorderBa, border_ba_word(s), "BORDER_BA");
    expect_read(kWrap, wrap_word(s), "WRAP");
    expect_write(kSmpCommit, uint32_t(i), kOkay, "SMP_COMMIT");
    expect_read(kSmpCommit, uint32_t(i), "SMP_COMMIT");
  }
  // Refused sampler commits: an entry beyond the table, an address mode 5..7, mip mode 3. (The
  // staged fields stay: the last sampler's are written back before the next case.)
  const uint32_t last_smp = uint32_t(c.samplers.size() - 1);
  const SamplerConfig& ls = c.samplers.back();
  expect_write(kSmpCommit, kSamplers, kSlverr, "SMP_COMMIT beyond SAMPLERS");
  expect_write(kWrap, 5u | 1u << 4, kOkay, "WRAP with mode 5");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of address mode 5");
  expect_write(kWrap, 7u << 4, kOkay, "WRAP with mode 7");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of address mode 7");
  expect_write(kWrap, wrap_word(ls), kOkay, "WRAP");
  expect_write(kFilter, filter_word(ls) | 3u << 4, kOkay, "FILTER with mip mode 3");
  expect_write(kSmpCommit, 0, kSlverr, "SMP_COMMIT of mip mode 3");
  expect_write(kFilter, filter_word(ls), kOkay, "FILTER");
  expect_read(kSmpCommit, last_smp, "SMP_COMMIT after the refused commits");
  if (top.write(kControl, kClear, &clear_edge) != kOkay) failures.push_back("CONTROL: clear refused");
  expect_read(kControl, 0, "CONTROL after the clear");
}

// One case through the unit: programmed over AXI4-Lite, every response against the model (the
// model's table and error reads: the RTL's unless a test plants others), the lines read against
// the model's misses, the counters against the pins and the model.
CaseResult run_case(AxiTop& top, const Case& c, const SamplerTable* model_samplers_in = nullptr,
                    const std::vector<uint64_t>* model_errors_in = nullptr) {
  CaseResult r;
  const SamplerTable& model_samplers = model_samplers_in ? *model_samplers_in : c.samplers;
  const std::vector<uint64_t>& model_errors = model_errors_in ? *model_errors_in : c.memory.error_reads;
  EngineOptions eo;
  eo.layout = c.layout;
  const std::vector<TextureDescriptor> desc = texture_descriptors(c.table, eo);
  // The memory image: the pyramids packed from the layout's base.
  std::vector<uint8_t> image;
  for (size_t i = 0; i < desc.size(); ++i) {
    const std::vector<uint8_t> bytes = build_memory_image(c.table[i].all_layers(), desc[i].layout);
    const size_t at = desc[i].layout.params().base - c.layout.base;
    if (image.size() < at + bytes.size()) image.resize(at + bytes.size());
    std::copy(bytes.begin(), bytes.end(), image.begin() + std::ptrdiff_t(at));
  }
  top.set_memory(c.layout.base, std::move(image), c.memory);

  // The model: each request's value and flag, the lines it misses.
  SamplerPairs samplers(c.table, model_samplers);
  TextureCache model(texture_descriptors(c.table, eo),
                     CacheParams{(1 << (c.log2_sets + c.log2_ways)) * kLineBytes, 1 << c.log2_ways}, model_samplers);
  model.set_error_reads(model_errors);
  std::vector<uint32_t> predicted;
  std::vector<uint32_t> want(c.requests.size());
  std::vector<uint8_t> want_error(c.requests.size());
  uint64_t want_flagged = 0;
  for (size_t i = 0; i < c.requests.size(); ++i) {
    const Request& q = c.requests[i];
    want_error[i] = model.lookup_sample(q, &predicted).error;
    want[i] = want_error[i] ? 0 : pack_rgba8(samplers.at(q).sample(q));
    want_flagged += want_error[i];
  }

  uint64_t clear_edge = 0;
  if (top.failure().empty()) program(top, c, desc, clear_edge, r.failures);
  if (!top.failure().empty()) {
    r.failures.insert(r.failures.begin(), top.failure());
    return r;
  }

  // The stream, with counter reads (LO, then HI) now and then.
  const uint64_t never = ~uint64_t(0);
  std::vector<std::pair<int, uint64_t>> mid_reads;  // LOOKUPS / MISSES read while running
  auto check_read = [&](int i, uint32_t lo, uint32_t lo_resp, uint64_t lo_edge, uint32_t hi, uint32_t hi_resp,
                        uint64_t freeze_edge) {
    const uint64_t got = uint64_t(hi) << 32 | lo;
    r.counter_reads += freeze_edge == never;
    if (lo_resp != kOkay || hi_resp != kOkay)
      r.failures.push_back(std::string(kCounterNames[i]) + ": read answered " + std::to_string(lo_resp) + "/" +
                           std::to_string(hi_resp));
    if (pin_visible(i)) {
      const uint64_t want_v = expected_counter(top, i, clear_edge, lo_edge, freeze_edge);
      if (got != want_v)
        r.failures.push_back(std::string(kCounterNames[i]) + " read at clock " + std::to_string(lo_edge) + ": " +
                             std::to_string(got) + ", the pins showed " + std::to_string(want_v));
    } else if (hi != 0) {
      r.failures.push_back(std::string(kCounterNames[i]) + ": high word " + std::to_string(hi));
    }
    return got;
  };
  bool counter_read_busy = false;
  auto read_counter = [&](int i, std::function<void(uint64_t)> then, uint64_t freeze_edge) {
    counter_read_busy = true;
    auto lo = std::make_shared<std::array<uint64_t, 3>>();  // data, resp, edge of the LO read
    top.queue_read(kCounterBase + 8 * uint32_t(i),
                   [lo](uint32_t d, uint32_t resp, uint64_t e) { *lo = {d, resp, e}; });
    top.queue_read(kCounterBase + 8 * uint32_t(i) + 4, [&, i, lo, then, freeze_edge](uint32_t d, uint32_t resp, uint64_t) {
      counter_read_busy = false;
      then(check_read(i, uint32_t((*lo)[0]), uint32_t((*lo)[1]), (*lo)[2], d, resp, freeze_edge));
    });
  };

  std::mt19937_64 rng(c.requests.size() * 31 + c.layout.base);
  uint64_t next_counter_read = top.edge() + 50 + rng() % 300;
  const uint64_t t0 = top.edge();
  top.start_stream(c.requests, c.stim, [&](size_t i, uint32_t rgba, bool error) {
    r.flagged += error;
    ++r.samples;
    if (!r.first_mismatch.empty()) return;
    const Request& q = c.requests[i];
    if (error != bool(want_error[i]))
      r.first_mismatch = "sample " + std::to_string(i) + " " + describe(q) + ": RTL rsp_error " +
                         std::to_string(error) + ", model " + std::to_string(want_error[i]);
    else if (rgba != want[i])
      r.first_mismatch = "sample " + std::to_string(i) + " " + describe(q) + ": RTL " + describe(unpack_rgba8(rgba)) +
                         ", model " + describe(unpack_rgba8(want[i])) + (error ? " (flagged: must be 0)" : "");
  });
  const uint64_t limit = 400 * c.requests.size() + 20000;
  while (!top.stream_done() && top.failure().empty()) {
    if (top.edge() - t0 > limit) {
      top.fail("time-out: " + std::to_string(r.samples) + " of " + std::to_string(c.requests.size()) + " answered");
      break;
    }
    if (top.edge() >= next_counter_read && !counter_read_busy) {
      const int i = int(rng() % kCounters);
      read_counter(i, [&, i](uint64_t v) { if (!pin_visible(i)) mid_reads.push_back({i, v}); }, never);
      next_counter_read = top.edge() + 50 + rng() % 300;
    }
    top.clock();
  }
  top.end_stream();
  top.run_until([&] { return top.lite_idle() && top.memory_idle(); }, 2000);
  top.idle(10);
  r.clocks = top.edge() - t0;

  // The lines read: the model's misses, in order.
  const std::vector<uint32_t>& actual = top.ar_log();
  r.reads = actual.size();
  if (actual != predicted) {
    size_t i = 0;
    while (i < actual.size() && i < predicted.size() && actual[i] == predicted[i]) ++i;
    r.failures.push_back("miss stream differs at read " + std::to_string(i) + " of " + std::to_string(actual.size()) +
                         " (model " + std::to_string(predicted.size()) + "): RTL " +
                         (i < actual.size() ? hex(actual[i]) : "none") + ", model " +
                         (i < predicted.size() ? hex(predicted[i]) : "none"));
  }

  // Freeze, then every counter, 64 bits.
  uint64_t freeze_edge = 0;
  if (top.write(kControl, kFreeze, &freeze_edge) != kOkay) r.failures.push_back("CONTROL: freeze refused");
  for (int i = 0; i < kCounters; ++i) {
    read_counter(i, [&, i](uint64_t v) { r.counters[size_t(i)] = v; }, freeze_edge);
    top.run_until([&] { return !counter_read_busy; }, 1000);
  }
  if (!top.failure().empty()) {
    r.failures.push_back(top.failure());
    return r;
  }
  const AxiTop::Totals& k = r.counters;
  auto expect_eq = [&](const char* what, uint64_t got, uint64_t want_v) {
    if (got != want_v)
      r.failures.push_back(std::string(what) + ": " + std::to_string(got) + ", want " + std::to_string(want_v));
  };
  expect_eq("SAMPLES = requests", k[kSamples], c.requests.size());
  expect_eq("SAMPLE_ERRORS = flagged responses", k[kSampleErrors], r.flagged);
  expect_eq("SAMPLE_ERRORS = the model's flagged samples", k[kSampleErrors], want_flagged);
  expect_eq("LOOKUPS = the model's lookups", k[kLookups], model.stats().total_lookups());
  expect_eq("MISSES = the model's misses", k[kMisses], model.stats().total_misses());
  expect_eq("MISSES = AXI reads", k[kMisses], r.reads);
  expect_eq("MEM_BYTES = MISSES x line bytes", k[kMemBytes], k[kMisses] * kLineBytes);
  expect_eq("CYCLES = clocks from the clear to the freeze", k[kCycles], freeze_edge - clear_edge);
  if (k[kMemWait] == 0 && r.reads > 0) r.failures.push_back("MEM_WAIT 0 with " + std::to_string(r.reads) + " reads");
  for (int i : {kSamples, kOutStall, kMemWait, kReqStall})
    if (k[size_t(i)] > k[kCycles]) r.failures.push_back(std::string(kCounterNames[i]) + " above CYCLES");
  for (const auto& [i, v] : mid_reads)
    if (v > k[size_t(i)])
      r.failures.push_back(std::string(kCounterNames[i]) + " read " + std::to_string(v) + " while running, " +
                           std::to_string(k[size_t(i)]) + " at the end");
  return r;
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size() && i < 8; ++i) s += "\n  " + v[i];
  if (v.size() > 8) s += "\n  ... " + std::to_string(v.size()) + " in all";
  return s;
}

}  // namespace

// Random cases end to end: the first from the hardware reset, each next one through the soft
// reset (new geometry, descriptors again); every other case with memory errors.
TEST(RtlAxiTop, EndToEndAgainstModel) {
  const auto t0 = std::chrono::steady_clock::now();
  // TEX_SEED_BASE=N: another set of cases (as the lockstep suites).
  const char* env = std::getenv("TEX_SEED_BASE");
  const uint64_t base = env && *env ? std::strtoull(env, nullptr, 0) : 0xA71;
  AxiTop top(base);
  ASSERT_TRUE(top.head_waits_visible()) << "tex_cached_fetch's head_waits is not public (rtl/tex_unit.vlt)";
  uint64_t samples = 0, flagged = 0, reads = 0, clocks = 0, out_stall = 0, req_stall = 0, mem_wait = 0;
  uint64_t lookups = 0, counter_reads = 0;
  int cubes = 0;  // cube maps through DESC_ATTR's cube bit
  const int cases = 10;
  for (int ci = 0; ci < cases; ++ci) {
    const uint64_t seed = base + uint64_t(ci) * 7919;
    const Case c = random_case(seed, 4000, ci % 2 == 1);
    for (const BoundTexture& t : c.table) cubes += t.kind == TextureKind::Cube;
    const CaseResult r = run_case(top, c);
    EXPECT_EQ(r.first_mismatch, "") << "case " << ci << " (seed " << seed << ")";
    EXPECT_TRUE(r.failures.empty()) << "case " << ci << " (seed " << seed << "):" << join(r.failures);
    if (!r.first_mismatch.empty() || !r.failures.empty()) break;
    samples += r.samples;
    flagged += r.flagged;
    reads += r.reads;
    clocks += r.clocks;
    out_stall += r.counters[kOutStall];
    req_stall += r.counters[kReqStall];
    mem_wait += r.counters[kMemWait];
    lookups += r.counters[kLookups];
    counter_reads += r.counter_reads;
  }
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("[ axi top  ] %d cases: %llu samples (%llu flagged by memory errors), %llu lines read, %llu lookups, "
              "%llu clocks; counters OUT_STALL %llu, REQ_STALL %llu, MEM_WAIT %llu; %llu counters read while "
              "running (%.1f s)\n",
              cases, (unsigned long long)samples, (unsigned long long)flagged, (unsigned long long)reads,
              (unsigned long long)lookups, (unsigned long long)clocks, (unsigned long long)out_stall,
              (unsigned long long)req_stall, (unsigned long long)mem_wait, (unsigned long long)counter_reads, secs);
  // The checks were not vacuous.
  EXPECT_GT(flagged, 0u);
  EXPECT_GT(cubes, 0);
  EXPECT_LT(flagged, samples / 4);
  EXPECT_GT(out_stall, 0u);
  EXPECT_GT(req_stall, 0u);
  EXPECT_GT(mem_wait, 0u);
  EXPECT_GT(reads, 0u);
  EXPECT_GT(counter_reads, 100u);
}

// The checkers fire: the unit's sampler 1 committed with other wrap modes than the model's table
// gives a sample mismatch; a model that expects the memory error 64 line reads later disagrees on
// a flag. The same case with the model right passes.
TEST(RtlAxiTop, PlantedBugsAreCaught) {
  AxiTop top(11);
  Case c = random_case(0xBAD, 1500, false);
  c.samplers.assign(2, SamplerConfig{});  // trilinear, no LOD clamp
  c.pyramids[1] = random_pyramid({32, 4}, 3);  // (in place: the table points at it; texture 0 has one layer)
  c.table[1] = BoundTexture{&c.pyramids[1]};   // (one layer)
  c.samplers[1].wrap_u = Wrap::Clamp;
  c.samplers[1].wrap_v = Wrap::Repeat;
  std::mt19937_64 rng(5);
  c.requests = random_requests(rng, sizes_of(c.table), c.samplers.size(), 1500);
  const CaseResult good = run_case(top, c);
  EXPECT_EQ(good.first_mismatch, "");
  EXPECT_TRUE(good.failures.empty()) << join(good.failures);

  SamplerTable rewrapped = c.samplers;  // the model's table: sampler 1 mirrored
  rewrapped[1].wrap_u = Wrap::Mirror;
  rewrapped[1].wrap_v = Wrap::Mirror;
  const CaseResult wrap = run_case(top, c, &rewrapped);
  EXPECT_EQ(wrap.first_mismatch.rfind("sample ", 0), 0u) << "a wrong wrap mode went unnoticed";
  std::printf("[ planted  ] wrap modes: %s\n", wrap.first_mismatch.c_str());

  // Reads 7 and 7 + 64 go to different samples whatever the stream (a sample reads at most 8
  // lines, in order), so the model's expectation moved to the later one flags other samples.
  c.memory.error_reads = {7};
  const std::vector<uint64_t> late = {7 + 64};
  ASSERT_GT(good.reads, 7u + 64u) << "too few lines read for the planted error";
  const CaseResult flag = run_case(top, c, nullptr, &late);
  EXPECT_NE(flag.first_mismatch.find("rsp_error"), std::string::npos) << flag.first_mismatch;
  std::printf("[ planted  ] error read: %s\n", flag.first_mismatch.c_str());
  const CaseResult right = run_case(top, c);
  EXPECT_EQ(right.first_mismatch, "");
  EXPECT_TRUE(right.failures.empty()) << join(right.failures);
  EXPECT_GT(right.flagged, 0u);
}

// The timing of a descriptor commit (docs/rtl-interface.md, "Descriptor commit"): entry 0
// rewritten from texture 0 to texture 1's pyramid (another size, 7x3), BREADY high at once, then
// requests naming entry 0 offered `after` clocks after the B handshake's edge. The unit takes none
// while it sets the entry up (req_ready low for 1 + 2^LEVEL_W clocks from the clock after
// cfg_desc_we), so every sample is texture 1's, however soon it is offered.
TEST(RtlAxiTop, RequestsRightAfterADescriptorCommit) {
  AxiTop top(13);
  Case c = random_case(0xC0, 200, false, false);  // (2D textures: two of them replaced below)
  c.pyramids[0] = random_pyramid({64, 8}, 1);
  c.pyramids[1] = random_pyramid({7, 3}, 2);
  ASSERT_EQ(run_case(top, c).first_mismatch, "");
  EngineOptions eo;
  eo.layout = c.layout;
  const std::vector<TextureDescriptor> desc = texture_descriptors(c.table, eo);
  Sampler model(*c.table[1].pyramid, c.samplers[0]);
  std::mt19937_64 rng(3);
  TextureTable one = {c.table[1]};
  for (int after = 0; after < 3; ++after) {
    // Texture 0 into entry 0 (settled), then texture 1 into entry 0: the commit under test.
    uint64_t d = 0;
    for (int to : {0, 1}) {
      const TextureDescriptor& e = desc[size_t(to)];
      EXPECT_EQ(top.write(kDescBase, e.layout.params().base), kOkay);
      EXPECT_EQ(top.write(kDescAttr, desc_attr_word(e.layout)), kOkay);
      EXPECT_EQ(top.write(kDescSize, desc_size_word(e.layout.size0())), kOkay);
      top.bready_p = to == 1 ? 1.0 : 0.7;
      EXPECT_EQ(top.write(kDescCommit, 0, &d), kOkay);
      top.bready_p = 0.7;
      if (to == 0) top.idle(5);
    }
    EXPECT_EQ(top.edge(), d + 2) << "BREADY high: the B handshake at the edge after the write's";
    top.idle(after);
    // All of entry 0. The first ones carry derivatives of one texel of texture 1 (lambda 0; 3 with
    // texture 0's size, 64x8): a sample that took the entry's old size would show it.
    std::vector<Request> requests = random_requests(rng, sizes_of(one), 1, 8);
    for (int i = 0; i < 4; ++i) {
      requests[size_t(i)].has_derivatives = true;
      requests[size_t(i)].deriv = {(1 << 24) / 8, 0, 0, (1 << 24) / 2};
    }
    std::string first;
    top.start_stream(requests, Stimulus{}, [&](size_t i, uint32_t rgba, bool) {
      const uint32_t want = pack_rgba8(model.sample(requests[i]));
      if (rgba != want && first.empty())
        first = "sample " + std::to_string(i) + " " + describe(requests[i]) + ": RTL " +
                describe(unpack_rgba8(rgba)) + ", texture 1 " + describe(unpack_rgba8(want));
    });
    top.run_until([&] { return top.stream_done(); }, 20000);
    top.end_stream();
    const uint64_t edges = top.first_request_edge() - d;
    // BVALID rises at edge d, cfg_desc_we is high after it, the unit registers it at d + 1 and is
    // busy through edge d + 18: the first handshake is at edge d + 19.
    constexpr uint64_t kSetupEdges = 2 + (1u << 4) + 1;
    EXPECT_EQ(edges, kSetupEdges) << "offered " << after << " clocks after the B handshake";
    std::printf("[ commit   ] offered %d clocks after the B handshake, taken %llu edges after BVALID rose: %s\n",
                after, (unsigned long long)edges, first.empty() ? "texture 1's samples" : ("the old entry: " + first).c_str());
    EXPECT_EQ(first, "") << "request " << edges << " edges after the commit";
    EXPECT_EQ(top.failure(), "");
  }
}
