#include "memory_layout.h"

#include <algorithm>
#include <array>
#include <vector>

#include "cube_map.h"
#include "error.h"

namespace tex {

namespace {
int log2_of_side(int v, const char* what) {
  if (v != 2 && v != 4 && v != 8)
    throw Error(std::string("block ") + what + " " + std::to_string(v) + " texels: must be 2, 4 or 8");
  return v == 2 ? 1 : v == 4 ? 2 : 3;
}
}  // namespace

bool parse_block_order(const std::string& name, BlockOrder& out) {
  if (name == "row-major") out = BlockOrder::RowMajor;
  else if (name == "morton") out = BlockOrder::Morton;
  else return false;
  return true;
}
std::string block_order_name(BlockOrder o) { return o == BlockOrder::Morton ? "morton" : "row-major"; }

bool parse_block_size(const std::string& text, LayoutParams& out) {
  const auto x = text.find('x');
  auto side = [](const std::string& t) { return t == "2" ? 2 : t == "4" ? 4 : t == "8" ? 8 : 0; };
  const int w = x == std::string::npos ? 0 : side(text.substr(0, x));
  const int h = x == std::string::npos ? 0 : side(text.substr(x + 1));
  if (!w || !h) return false;
  out.block_w = w;
  out.block_h = h;
  return true;
}
std::string block_size_name(const LayoutParams& p) { return std::to_string(p.block_w) + "x" + std::to_string(p.block_h); }

MemoryLayout::MemoryLayout(Extent size0, int channel_bits, const LayoutParams& params, TexelFormat format,
                           int levels, int layers, TextureKind kind)
    : params_(params), size0_(size0), channel_bits_(channel_bits), format_(format), layers_(layers), kind_(kind) {
  const bool cube = kind == TextureKind::Cube;
  if (cube && (layers % 6 != 0 || size0.w != size0.h || is_compressed(format)))
    throw Error("a cube map of " + std::to_string(layers) + " layers of " + std::to_string(size0.w) + "x" +
                std::to_string(size0.h) + " " + format_info(format).name +
                ": it takes 6 layers a cube, square faces, RGBA texels");
  if (layers < 1 || layers > kMaxLayers)
    throw Error(std::to_string(layers) + " layers: an array texture has 1 to " + std::to_string(kMaxLayers));
  for (const int s : {size0.w, size0.h})
    if (s < 1 || s > kMaxSize)
      throw Error("texture side " + std::to_string(s) + " texels: must be 1 to " + std::to_string(kMaxSize));
  if (levels < 0 || levels > level_count(size0))
    throw Error(std::to_string(levels) + " levels: a " + std::to_string(size0.w) + "x" + std::to_string(size0.h) +
                " texture has 1 to " + std::to_string(level_count(size0)));
  if (levels == 0) levels = level_count(size0);
  if (channel_bits < 1 || channel_bits > kMaxChannelBits)
    throw Error("channel width " + std::to_string(channel_bits) + " bits: must be 1 to " +
                std::to_string(kMaxChannelBits));
  log2_lbx_ = log2_of_side(params.block_w, "width");
  log2_lby_ = log2_of_side(params.block_h, "height");
  texel_bytes_ = channel_bits > 8 ? 8 : 4;
  line_bytes_ = params.block_w * params.block_h * texel_bytes_;
  if (is_compressed(format)) {
    // Whole blocks per line, as 2^a x 2^b blocks with a = b or b + 1 (wider than tall).
    block_bytes_ = format_info(format).block_bytes;
    fw_ = format_info(format).block_w;
    fh_ = format_info(format).block_h;
    recip_w_ = ((uint64_t(1) << 32) + uint64_t(fw_) - 1) / uint64_t(fw_);
    recip_h_ = ((uint64_t(1) << 32) + uint64_t(fh_) - 1) / uint64_t(fh_);
    if (channel_bits != 8)
      throw Error(std::string(format_info(format).name) + " holds 8-bit channels, not " + std::to_string(channel_bits));
    if (line_bytes_ < block_bytes_)
      throw Error(std::to_string(line_bytes_) + "-byte lines (block " + std::to_string(params.block_w) + "x" +
                  std::to_string(params.block_h) + ") cannot hold a " + std::to_string(block_bytes_) + "-byte " +
                  format_info(format).name + " block");
    const int log2_blocks = log2_exact(line_bytes_ / block_bytes_);
    log2_lbx_ = (log2_blocks + 1) / 2;
    log2_lby_ = log2_blocks / 2;
  }
  if (params.base % uint32_t(line_bytes_) != 0)
    throw Error("memory base address " + std::to_string(params.base) + " is not a multiple of the " +
                std::to_string(line_bytes_) + "-byte line");
  // The seam copy's index along a side n: n (texels) or n rounded up to the block (a block format:
  // fw across, fh down), and the texels a level row then spans. A side has one where the repeat
  // seam's pair (n - 1, 0) would otherwise read two blocks of one parity: a side that is not a power
  // of two, or one longer than a block that the block does not divide (ASTC 5, 6, 10, 12: 32 texels
  // of 6x6 blocks end in block column 5, of parity 0 as block column 0's). A cube face: its skirt on
  // both sides and no seam copy.
  auto has_seam = [&](int n, uint32_t align) {
    return !cube && (!is_power_of_two(n) || (uint32_t(n) > align && uint32_t(n) % align != 0));
  };
  auto seam_of = [&](int n, uint32_t align) { return has_seam(n, align) ? (uint32_t(n) + align - 1) / align * align : 0u; };
  auto span_of = [&](int n, uint32_t align) {
    return cube ? uint32_t(n) + 2 : has_seam(n, align) ? seam_of(n, align) + align : uint32_t(n);
  };
  const uint32_t line_w = uint32_t(block_w()), line_h = uint32_t(block_h());
  uint64_t at = params.base;
  for (int k = 0; k < levels; ++k) {
    Level l;
    l.size = level_extent(size0, k);
    l.seam_x = seam_of(l.size.w, uint32_t(fw_));
    l.seam_y = seam_of(l.size.h, uint32_t(fh_));
    l.nbx = std::max(1u, (span_of(l.size.w, uint32_t(fw_)) + line_w - 1) / line_w);
    l.nby = std::max(1u, (span_of(l.size.h, uint32_t(fh_)) + line_h - 1) / line_h);
    l.log2_bx = log2_ceil(int(l.nbx));
    l.log2_by = log2_ceil(int(l.nby));
    l.base = uint32_t(at);
    const uint64_t blocks = params.order == BlockOrder::RowMajor ? uint64_t(l.nbx) * l.nby
                                                                 : uint64_t(1) << (l.log2_bx + l.log2_by);
    at += uint64_t(line_bytes_) * blocks;
    levels_.push_back(l);
    if (at > (uint64_t(1) << 32)) break;  // (reported below)
  }
  // The last byte must have a 32-bit address: the image may end exactly at 2^32.
  const uint64_t end = params.base + (at - params.base) * uint64_t(layers);
  if (at > (uint64_t(1) << 32) || end > (uint64_t(1) << 32))
    throw Error("the texture's memory image ends at byte " + std::to_string(std::max(at, end)) +
                ", beyond the 32-bit address space of the memory port");
  layer_bytes_ = uint32_t(at - params.base);
}

uint32_t MemoryLayout::block_index(int level, uint32_t bx, uint32_t by) const {
  const Level& l = levels_[size_t(level)];
  if (params_.order == BlockOrder::RowMajor) return by * l.nbx + bx;
  // The square part interleaved; the longer side's remaining bits above it.
  const int m = std::min(l.log2_bx, l.log2_by);
  const uint32_t low = (1u << m) - 1;
  return uint32_t(interleave_bits(bx & low, by & low)) | ((bx >> m) | (by >> m)) << (2 * m);
}

bool MemoryLayout::locate_line(uint32_t address, int& layer, int& level, uint32_t& bx, uint32_t& by) const {
  if (address < params_.base || (address - params_.base) % uint32_t(line_bytes_) != 0) return false;
  layer = int((address - params_.base) / layer_bytes_);
  if (layer >= layers_) return false;
  address -= uint32_t(layer) * layer_bytes_;
  for (level = levels() - 1; level >= 0 && address < levels_[size_t(level)].base; --level) {
  }
  if (level < 0) return false;
  const Level& l = levels_[size_t(level)];
  const uint32_t index = (address - l.base) / uint32_t(line_bytes_);
  if (params_.order == BlockOrder::RowMajor) {
    if (index >= l.nbx * l.nby) return false;  // beyond the last level
    bx = index % l.nbx;
    by = index / l.nbx;
    return true;
  }
  if (index >> (l.log2_bx + l.log2_by)) return false;  // beyond the last level
  // Inverse of block_index: the interleaved square part, then the longer side's bits above it.
  const int m = std::min(l.log2_bx, l.log2_by);
  bx = by = 0;
  for (int i = 0; i < m; ++i) {
    bx |= (index >> (2 * i) & 1u) << i;
    by |= (index >> (2 * i + 1) & 1u) << i;
  }
  const uint32_t high = index >> (2 * m);
  if (l.log2_bx > l.log2_by) bx |= high << m;
  else by |= high << m;
  return bx < l.nbx && by < l.nby;  // (a Morton grid rounded up to powers of two has holes)
}

bool decode_line(const MemoryLayout& layout, uint32_t address, const uint8_t* line,
                 const std::function<void(int layer, int level, int x, int y, const Texel& t)>& texel,
                 bool seam_copies, bool srgb) {
  int layer = 0, level = 0;
  uint32_t bx = 0, by = 0;
  if (!layout.locate_line(address, layer, level, bx, by)) return false;
  const int bw = layout.block_w(), bh = layout.block_h(), tb = layout.texel_bytes();
  const uint32_t w = uint32_t(layout.level_size(level).w), h = uint32_t(layout.level_size(level).h);
  const bool blocks = is_compressed(layout.format());
  // A stored column (row) past the side: the seam copy's (of column 0 .. align - 1) or padding.
  const FormatInfo& info = format_info(layout.format());
  const uint32_t align_x = blocks ? uint32_t(info.block_w) : 1, align_y = blocks ? uint32_t(info.block_h) : 1;
  const uint32_t seam_x = layout.seam_x(level), seam_y = layout.seam_y(level);
  const bool cube = layout.kind() == TextureKind::Cube;
  auto original = [&](uint32_t i, uint32_t n, uint32_t seam, uint32_t align, uint32_t& o) {
    if (cube) {  // the face at 1..n; the skirt (0, n + 1) holds copies
      o = i - 1;
      return i >= 1 && i <= n;
    }
    o = i;
    if (i < n) return true;
    o = i - seam;
    return seam_copies && seam != 0 && i >= seam && o < align && o < n;
  };
  // A block format's blocks decoded once each (an ASTC block decodes its weights and endpoints
  // as a whole), on first use: the line's block b at decoded[b].
  const int block_bytes = blocks ? info.block_bytes : 0;
  std::vector<std::array<Texel, kMaxBlockTexels>> decoded(blocks ? size_t(layout.line_bytes() / block_bytes) : 0);
  std::vector<bool> done(decoded.size(), false);
  for (int ty = 0; ty < bh; ++ty)
    for (int tx = 0; tx < bw; ++tx) {
      const uint32_t x = bx * uint32_t(bw) + uint32_t(tx), y = by * uint32_t(bh) + uint32_t(ty);
      uint32_t ox = 0, oy = 0;
      if (!original(x, w, seam_x, align_x, ox) || !original(y, h, seam_y, align_y, oy)) continue;  // padding (and seam copies)
      const uint8_t* at = line + layout.texel_offset(x, y);
      Texel t{};
      if (blocks) {
        const size_t b = size_t((at - line) / block_bytes);
        if (!done[b]) decode_block(layout.format(), at, decoded[b].data(), srgb);
        done[b] = true;
        t = decoded[b][size_t(layout.texel_in_block(x, y))];
      } else {
        for (size_t c = 0; c < 4; ++c) t[c] = tb == 4 ? at[c] : uint16_t(at[2 * c] | at[2 * c + 1] << 8);
      }
      texel(layer, level, int(ox), int(oy), t);
    }
  return true;
}

namespace {
// A texel as memory holds it: 4 bytes (channels of 8 bits) or 8 (16-bit channels, little-endian).
void store_texel(uint8_t* at, const Texel& t, int texel_bytes) {
  for (size_t c = 0; c < 4; ++c) {
    if (texel_bytes == 4) {
      at[c] = uint8_t(t[c]);
    } else {
      at[2 * c] = uint8_t(t[c]);
      at[2 * c + 1] = uint8_t(t[c] >> 8);
    }
  }
}
}  // namespace

std::vector<uint8_t> build_memory_image(const std::vector<const Pyramid*>& layers, const MemoryLayout& layout) {
  if (int(layers.size()) != layout.layers())
    throw Error("the memory layout is for " + std::to_string(layout.layers()) + " layers; the texture has " +
                std::to_string(layers.size()));
  std::vector<uint8_t> image(size_t(layout.image_bytes()), 0);
  const uint32_t base = layout.params().base;
  if (layout.kind() == TextureKind::Cube) {  // the skirted faces, every texel where it stands
    const std::vector<Pyramid> skirted = cube_skirts(layers);
    const int tb = layout.texel_bytes();
    for (int layer = 0; layer < layout.layers(); ++layer)
      for (int k = 0; k < layout.levels(); ++k) {
        const Pyramid& p = skirted[size_t(layer)];
        if (int(p.levels.size()) != layout.levels() || p.levels[size_t(k)].width != layout.level_size(k).w + 2)
          throw Error("the memory layout is for cube faces of " + std::to_string(layout.size0().w) + " texels");
        const Image& img = p.srgb ? p.codes[size_t(k)] : p.levels[size_t(k)];
        for (int y = 0; y < img.height; ++y)
          for (int x = 0; x < img.width; ++x) {
            uint8_t* at = &image[layout.line_address(k, uint32_t(x), uint32_t(y), layer) - base +
                                 layout.texel_offset(uint32_t(x), uint32_t(y))];
            store_texel(at, img.at(x, y), tb);
          }
      }
    return image;
  }
  for (int layer = 0; layer < layout.layers(); ++layer) {
    const Pyramid& pyramid = *layers[size_t(layer)];
    if (pyramid.extent0() != layout.size0() || pyramid.memory_channel_bits() != layout.channel_bits() ||
        int(pyramid.levels.size()) != layout.levels() || pyramid.format != layout.format())
      throw Error("the memory layout is for a " + std::to_string(layout.size0().w) + "x" +
                  std::to_string(layout.size0().h) + " texture of " + std::to_string(layout.channel_bits()) +
                  "-bit channels; the pyramid is " + std::to_string(pyramid.levels[0].width) + "x" +
                  std::to_string(pyramid.levels[0].height) + ", " + std::to_string(pyramid.memory_channel_bits()) +
                  "-bit, " + std::to_string(pyramid.levels.size()) + " levels" +
                  (pyramid.format != layout.format() ? std::string(", ") + format_info(pyramid.format).name + " not " +
                                                           format_info(layout.format()).name
                                                     : std::string()));
    // Each place texel (x, y) of level k goes: itself, and for column (row) 0 of a side with a seam
    // its copy (a block format: the block's, at the seam block column).
    auto each_place = [&](int k, uint32_t x, uint32_t y, auto&& put) {
      with_seam_copies(int(x), int(y), int(layout.seam_x(k)), int(layout.seam_y(k)),
                       [&](int sx, int sy) { put(uint32_t(sx), uint32_t(sy)); });
    };
    if (is_compressed(layout.format())) {  // each block where its top-left texel goes
      const FormatInfo& info = format_info(layout.format());
      const size_t bytes = size_t(info.block_bytes);
      const int fw = info.block_w, fh = info.block_h;
      for (int k = 0; k < layout.levels(); ++k) {
        const Image& img = pyramid.levels[size_t(k)];
        const int nbx = (img.width + fw - 1) / fw, nby = (img.height + fh - 1) / fh;
        for (int by = 0; by < nby; ++by)
          for (int bx = 0; bx < nbx; ++bx)
            each_place(k, uint32_t(bx * fw), uint32_t(by * fh), [&](uint32_t x, uint32_t y) {
              std::copy_n(&pyramid.blocks[size_t(k)][(size_t(by) * size_t(nbx) + size_t(bx)) * bytes], bytes,
                          &image[layout.line_address(k, x, y, layer) - base + layout.texel_offset(x, y)]);
            });
      }
      continue;
    }
    const int tb = layout.texel_bytes();
    for (int k = 0; k < layout.levels(); ++k) {
      const Image& img = pyramid.srgb ? pyramid.codes[size_t(k)] : pyramid.levels[size_t(k)];  // what memory holds
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          each_place(k, uint32_t(x), uint32_t(y), [&](uint32_t ux, uint32_t uy) {
            uint8_t* at = &image[layout.line_address(k, ux, uy, layer) - base + layout.texel_offset(ux, uy)];
            store_texel(at, img.at(x, y), tb);
          });
    }
  }
  return image;
}

std::vector<uint8_t> memory_image_file(const Pyramid& pyramid, const MemoryLayout& layout) {
  std::vector<uint8_t> image = build_memory_image(pyramid, layout);
  std::vector<uint8_t> out;
  out.reserve(72 + 8 * size_t(layout.levels()) + image.size());
  auto u32 = [&](uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
  };
  auto u64 = [&](uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(uint8_t(v >> (8 * i)));
  };
  for (const char c : std::string("TEXMEM03")) out.push_back(uint8_t(c));
  u32(uint32_t(72 + 8 * layout.levels()));
  u32(uint32_t(layout.size0().w));
  u32(uint32_t(layout.size0().h));
  u32(uint32_t(layout.levels()));
  u32(uint32_t(layout.channel_bits()));
  u32(is_compressed(layout.format()) ? 0u : uint32_t(layout.texel_bytes()));
  u32(uint32_t(layout.block_w()));
  u32(uint32_t(layout.block_h()));
  u32(uint32_t(layout.params().order));
  u32(uint32_t(layout.line_bytes()));
  u64(layout.params().base);
  u64(layout.image_bytes());
  u32(uint32_t(layout.format()));
  u32(0);
  for (int k = 0; k < layout.levels(); ++k) u64(layout.level_base(k));
  out.insert(out.end(), image.begin(), image.end());
  return out;
}

}  // namespace tex
