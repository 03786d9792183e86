// The two texture caches of the cached memory hierarchy (docs/memory.md §2): cache 0 holds the
// even levels, cache 1 the odd levels; set index = the block's parities in the two low bits, a hash
// of the rest above them (set_index), tag = line address, true LRU. lookup() runs one sample through
// them exactly as tex_unit_cached's tag stage does, in the same order, so the line addresses it
// appends are the RTL's memory reads, one for one.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "memory_layout.h"
#include "sampler.h"
#include "timing.h"

namespace tex {

struct CacheParams {
  int size_bytes = 8192;  // per cache
  int ways = 2;           // 1, 2 or 4
};

// What one sample did in one of its levels (slot 0 = d, slot 1 = d1).
struct SlotLookup {
  int level = 0;
  bool needed = false;    // slot 1: only when the level blend weight f != 0
  int blocks = 0;         // distinct blocks looked up, 0..4
  int misses = 0;         // of those, missing: 0..4
  uint8_t block_mask = 0; // bit p: a block with parities p = (by & 1) * 2 + (bx & 1) was looked up
  bool error = false;     // a line it looked up came from memory with an error
};
struct SampleLookup {
  std::array<SlotLookup, 2> slot;
  bool error() const { return slot[0].error || slot[1].error; }
};

struct CacheStats {
  std::array<uint64_t, 2> lookups{}, hits{}, misses{};  // per cache (0 even, 1 odd levels)
  uint64_t total_lookups() const { return lookups[0] + lookups[1]; }
  uint64_t total_hits() const { return hits[0] + hits[1]; }
  uint64_t total_misses() const { return misses[0] + misses[1]; }
  // Misses that evicted a line the previous sample used: that sample still has to read the old
  // data when the new line is allocated (the case the fill-at-the-head rule is for).
  uint64_t evictions_of_previous = 0;
};

// One entry of the cached unit's texture descriptor table (docs/memory.md §1): the texture's
// pyramid in memory (its layout: base address, log2 sizes, levels, format). How it is sampled is
// the sampler table's business (SamplerTable, Request::sampler).
struct TextureDescriptor {
  MemoryLayout layout;
};

// Layouts of several textures of `channel_bits` texels packed one after another from params.base
// (each starts on a line); sizes are level 0's, formats, level counts and layer counts one per
// texture, and kinds (none: all RGBA, full chains, one layer, 2D). Throws tex::Error when they do not fit the
// 32-bit address space.
std::vector<MemoryLayout> pack_layouts(const std::vector<Extent>& sizes, int channel_bits,
                                       const LayoutParams& params, const std::vector<TexelFormat>& formats = {},
                                       const std::vector<int>& levels = {}, const std::vector<int>& layers = {},
                                       const std::vector<TextureKind>& kinds = {});

class TextureCache {
 public:
  // Throws tex::Error naming a geometry the hardware cannot have (ways not 1/2/4, sets not a
  // power of two >= 4, size not a whole number of lines), more than kMaxTextures textures, or
  // layouts of different line sizes, no sampler or more than kMaxSamplers. Requests name a texture
  // by Request::texture and a sampler by Request::sampler.
  TextureCache(std::vector<TextureDescriptor> textures, const CacheParams& params, SamplerTable samplers);
  // One texture and one sampler.
  TextureCache(const MemoryLayout& layout, const CacheParams& params, const SamplerConfig& config);

  // One probe (a request without derivatives, as tex_probe gives them): looks its needed blocks up
  // in request order, updates the LRU state, and appends the line address of every miss to
  // `misses` (if not null), in the order docs/memory.md gives.
  SampleLookup lookup(const Request& probe, std::vector<uint32_t>* misses);
  // (A cube map's probe: its face's 2D probe, in `layer`.)
  SampleLookup lookup_at(const Request& probe, int layer, bool cube, std::vector<uint32_t>* misses);
  // A whole request: its probes (tex_probe) one after another, as the RTL's FIFO holds them.
  // Returns what its timing depends on: the probes and the lines each misses; and whether a line
  // it looked up came from memory with an error (RequestWork::error).
  RequestWork lookup_sample(const Request& r, std::vector<uint32_t>* misses);

  // Memory errors (docs/memory.md §3): the line reads, counted from 1 at construction in miss
  // order, that memory answers with an error, ascending. Such a line is cached as any other,
  // marked; a lookup of a marked line marks the sample (the unit answers it with rsp_error and 0).
  void set_error_reads(std::vector<uint64_t> ordinals) { error_reads_ = std::move(ordinals); }

  const CacheStats& stats() const { return stats_; }
  void reset_stats() { stats_ = {}; }
  uint64_t memory_read_bytes() const { return stats_.total_misses() * uint64_t(line_bytes_); }
  int line_bytes() const { return line_bytes_; }
  int sets() const { return sets_; }
  int ways() const { return ways_; }
  // The set of block (bx, by) of any level (docs/memory.md §2): {hash, by & 1, bx & 1} with
  // hash = (xh XOR reverse_k(yh mod 2^k) XOR (yh >> k)) mod 2^k, xh = bx >> 1, yh = by >> 1,
  // k = log2(SETS / 4). A row of blocks spreads over half of the sets (the other y parity has the
  // other half), a column too, and neighbouring block rows land far apart.
  int set_index(uint32_t bx, uint32_t by) const {
    const uint32_t xh = bx >> 1, yh = by >> 1, k_mask = uint32_t(sets_ / 4 - 1);
    const uint32_t hash = (xh ^ reversed_[yh & k_mask] ^ (yh >> log2_sets_hi_)) & k_mask;
    return int(hash << 2 | (by & 1) << 1 | (bx & 1));
  }

  // One way of a set, for tests.
  struct Way {
    bool valid = false;
    uint32_t tag = 0;       // the line address
    int age = 0;            // 0 = most recently used
    uint64_t last_use = 0;  // 1 + the number of the last sample that looked it up
    bool error = false;     // memory answered its line with an error
  };
  Way way(int cache, int set, int w) const { return caches_[size_t(cache)][size_t(set * ways_ + w)]; }

 private:
  // Looks the line up in its set; on a miss allocates the LRU way. Returns true on a hit; `used`:
  // the way that now holds the line.
  bool access(int cache, int set, uint32_t address, Way*& used);

  const TextureDescriptor& texture(const Request& r) const {
    if (r.texture >= textures_.size()) [[unlikely]] bad_texture(r);
    return textures_[r.texture];
  }
  [[noreturn]] void bad_texture(const Request& r) const;
  const SamplerConfig& sampler(const Request& r) const {
    if (r.sampler >= samplers_.size()) [[unlikely]] bad_sampler(r);
    return samplers_[r.sampler];
  }
  [[noreturn]] void bad_sampler(const Request& r) const;

  std::vector<TextureDescriptor> textures_;
  SamplerTable samplers_;
  int line_bytes_;
  int sets_, ways_;
  int log2_sets_hi_ = 0;             // k = log2(SETS / 4)
  std::vector<uint32_t> reversed_;   // reversed_[i]: the k bits of i in reverse order
  std::array<std::vector<Way>, 2> caches_;
  // Per cache, the lines of the last slot that looked it up (block parity p: address[p], the way
  // holding it). A slot that needs the same lines again hits in every one of them and changes no
  // age (each is already the most recent of its set, and each parity has its own sets), so only the
  // counters move: the simulator skips the tag search (most probes of a coherent frame repeat it).
  struct LastLookup {
    uint8_t mask = 0;  // 0: none yet
    std::array<uint32_t, 4> address{};
    std::array<Way*, 4> way{};
  };
  std::array<LastLookup, 2> last_;
  CacheStats stats_;
  uint64_t sample_ = 0;  // samples looked up so far
  std::vector<uint64_t> error_reads_;
  uint64_t reads_ = 0;        // line reads so far (misses since construction)
  size_t next_error_ = 0;     // the next of error_reads_ to come
};

}  // namespace tex
