#include "astc.h"

#include <algorithm>

namespace tex {

namespace {

// The 128 bits of a block, bit 0 the low bit of byte 0.
struct Bits128 {
  uint64_t lo = 0, hi = 0;
  explicit Bits128(const uint8_t* b) {
    for (int i = 7; i >= 0; --i) lo = lo << 8 | b[i];
    for (int i = 15; i >= 8; --i) hi = hi << 8 | b[i];
  }
  Bits128() = default;
  int bit(int i) const { return i < 64 ? int(lo >> i & 1) : i < 128 ? int(hi >> (i - 64) & 1) : 0; }
  // `count` (<= 32) bits from bit `start` up.
  uint32_t bits(int start, int count) const {
    uint32_t v = 0;
    for (int i = count - 1; i >= 0; --i) v = v << 1 | uint32_t(bit(start + i));
    return v;
  }
  // The block read from bit 127 down: the weights' stream (bit n of it is bit 127 - n).
  Bits128 reversed() const {
    Bits128 r;
    for (int i = 0; i < 128; ++i)
      if (bit(i)) (127 - i < 64 ? r.lo : r.hi) |= uint64_t(1) << ((127 - i) & 63);
    return r;
  }
};

// An integer sequence's range of `levels` values: 2^bits, 3 * 2^bits (a trit) or 5 * 2^bits (a quint).
struct IseRange {
  int trits, quints, bits;
};
IseRange ise_range(int levels) {
  if (levels % 3 == 0) return {1, 0, __builtin_ctz(unsigned(levels / 3))};
  if (levels % 5 == 0) return {0, 1, __builtin_ctz(unsigned(levels / 5))};
  return {0, 0, __builtin_ctz(unsigned(levels))};
}
// Bits of `count` values of the range (the specification's size determination).
int ise_bits(int count, int levels) {
  const IseRange r = ise_range(levels);
  return (count * 8 * r.trits + 4) / 5 + (count * 7 * r.quints + 2) / 3 + count * r.bits;
}

// Five trits from the 8 bits T of a trit block, and three quints from the 7 bits Q of a quint
// block (the specification's bit manipulations).
std::array<int, 5> trits_of(uint32_t t) {
  auto b = [&](int i) { return int(t >> i & 1); };
  int c, t3, t4;
  if ((t >> 2 & 7) == 7) {
    c = int((t >> 5 & 7) << 2 | (t & 3));
    t4 = t3 = 2;
  } else {
    c = int(t & 31);
    if ((t >> 5 & 3) == 3) {
      t4 = 2;
      t3 = b(7);
    } else {
      t4 = b(7);
      t3 = int(t >> 5 & 3);
    }
  }
  auto cb = [&](int i) { return c >> i & 1; };
  int t0, t1, t2;
  if ((c & 3) == 3) {
    t2 = 2;
    t1 = cb(4);
    t0 = cb(3) << 1 | (cb(2) & ~cb(3) & 1);
  } else if ((c >> 2 & 3) == 3) {
    t2 = 2;
    t1 = 2;
    t0 = c & 3;
  } else {
    t2 = cb(4);
    t1 = c >> 2 & 3;
    t0 = cb(1) << 1 | (cb(0) & ~cb(1) & 1);
  }
  return {t0, t1, t2, t3, t4};
}

std::array<int, 3> quints_of(uint32_t q) {
  auto b = [&](int i) { return int(q >> i & 1); };
  int q0, q1, q2, c;
  if ((q >> 1 & 3) == 3 && (q >> 5 & 3) == 0) {
    q2 = b(0) << 2 | (b(4) & ~b(0) & 1) << 1 | (b(3) & ~b(0) & 1);
    return {4, 4, q2};
  }
  if ((q >> 1 & 3) == 3) {
    q2 = 4;
    c = int((q >> 3 & 3) << 3 | (~q >> 5 & 3) << 1 | (q & 1));
  } else {
    q2 = int(q >> 5 & 3);
    c = int(q & 31);
  }
  if ((c & 7) == 5) {
    q1 = 4;
    q0 = c >> 3 & 3;
  } else {
    q1 = c >> 3 & 3;
    q0 = c & 7;
  }
  return {q0, q1, q2};
}

// Integer sequence decoding: `count` values of the range from bit `start` of `b` up. Each value
// is its trit or quint (`high`) and its low bits (`low`); a block's trit or quint bits that follow
// values past the sequence's end are 0.
void ise_decode(const Bits128& b, int start, int count, int levels, int* high, int* low) {
  const IseRange r = ise_range(levels);
  // A block of 5 trits (3 quints; 1 value of bits alone): after value j's low bits, `packed[j]`
  // bits of the block's T (Q) at `shift[j]`.
  static constexpr int kTBits[5] = {2, 2, 1, 2, 1}, kTShift[5] = {0, 2, 4, 5, 7};
  static constexpr int kQBits[5] = {3, 2, 2}, kQShift[5] = {0, 3, 5}, kNone[5] = {};
  const int per = r.trits ? 5 : r.quints ? 3 : 1;
  const int* packed = r.trits ? kTBits : r.quints ? kQBits : kNone;
  const int* shift = r.trits ? kTShift : r.quints ? kQShift : kNone;
  int at = start;
  for (int first = 0; first < count; first += per) {
    uint32_t t = 0;
    for (int j = 0; j < per && first + j < count; ++j) {
      low[first + j] = int(b.bits(at, r.bits));
      at += r.bits;
      t |= b.bits(at, packed[j]) << shift[j];
      at += packed[j];
    }
    std::array<int, 5> v{};
    if (r.trits) v = trits_of(t);
    if (r.quints) {
      const std::array<int, 3> q = quints_of(t);
      std::copy(q.begin(), q.end(), v.begin());
    }
    for (int j = 0; j < per && first + j < count; ++j) high[first + j] = v[size_t(j)];
  }
}

// Replicates the n-bit value v to `width` bits, its most significant bit first.
int replicate(int v, int n, int width) {
  int out = 0, have = 0;
  while (have < width) {
    out = out << n | v;
    have += n;
  }
  return out >> (have - width);
}

// Endpoint unquantization to 0..255: bit replication, or the trit / quint procedure with the
// specification's A, B, C (9 bits) from the low bits a, b, c, ... and D the trit or quint.
int unquantize_colour(int levels, int high, int low) {
  const IseRange r = ise_range(levels);
  if (!r.trits && !r.quints) return replicate(low, r.bits, 8);
  auto bit = [&](int i) { return low >> i & 1; };
  const int a = bit(0) ? 0x1FF : 0;
  int b = 0, c = 0;
  const int bb = bit(1), cc = bit(2), dd = bit(3), ee = bit(4), ff = bit(5);
  switch (levels) {
    case 6: c = 204; break;
    case 10: c = 113; break;
    case 12: b = bb * 0x116; c = 93; break;                                                      // b000b0bb0
    case 20: b = bb * 0x10C; c = 54; break;                                                      // b0000bb00
    case 24: b = cc << 8 | bb << 7 | cc << 3 | bb << 2 | cc << 1 | bb; c = 44; break;            // cb000cbcb
    case 40: b = cc << 8 | bb << 7 | cc << 2 | bb << 1 | cc; c = 26; break;                      // cb0000cbc
    case 48: b = dd << 8 | cc << 7 | bb << 6 | dd << 2 | cc << 1 | bb; c = 22; break;            // dcb000dcb
    case 80: b = dd << 8 | cc << 7 | bb << 6 | dd << 1 | cc; c = 13; break;                      // dcb0000dc
    case 96: b = ee << 8 | dd << 7 | cc << 6 | bb << 5 | ee << 1 | dd; c = 11; break;            // edcb000ed
    case 160: b = ee << 8 | dd << 7 | cc << 6 | bb << 5 | ee; c = 6; break;                      // edcb0000e
    case 192: b = ff << 8 | ee << 7 | dd << 6 | cc << 5 | bb << 4 | ff; c = 5; break;            // fedcb000f
    default: break;
  }
  int unq = high * c + b;
  unq ^= a;
  return (a & 0x80) | (unq >> 2);
}

// Weight unquantization to 0..64 (A, B, C of 7 bits; then 33..63 move up by one).
int unquantize_weight(int levels, int high, int low) {
  const IseRange r = ise_range(levels);
  int unq;
  if (!r.trits && !r.quints) {
    unq = replicate(low, r.bits, 6);
  } else if (r.bits == 0) {
    static constexpr int kTrit[3] = {0, 32, 63}, kQuint[5] = {0, 16, 32, 47, 63};
    unq = r.trits ? kTrit[high] : kQuint[high];
  } else {
    const int a = (low & 1) ? 0x7F : 0, bb = low >> 1 & 1, cc = low >> 2 & 1;
    int b = 0, c = 0;
    switch (levels) {
      case 6: c = 50; break;
      case 10: c = 28; break;
      case 12: b = bb * 0x45; c = 23; break;                               // b000b0b
      case 20: b = bb * 0x42; c = 13; break;                               // b0000b0
      case 24: b = cc << 6 | bb << 5 | cc << 1 | bb; c = 11; break;        // cb000cb
      default: break;
    }
    unq = high * c + b;
    unq ^= a;
    unq = (a & 0x20) | (unq >> 2);
  }
  return unq > 32 ? unq + 1 : unq;
}

// The colour ranges an endpoint sequence may take, largest first.
constexpr int kColourLevels[] = {256, 192, 160, 128, 96, 80, 64, 48, 40, 32, 24, 20, 16, 12, 10, 8, 6};
// The weight ranges by (P, rho): rho 2..7 of the low and the high precision.
constexpr int kWeightLevels[2][8] = {{0, 0, 2, 3, 4, 5, 6, 8}, {0, 0, 10, 12, 16, 20, 24, 32}};

// The block mode (11 bits): weight grid, range and planes; false for a reserved mode.
bool decode_block_mode(uint32_t m, int& gw, int& gh, int& levels, bool& dual) {
  auto bits = [&](int lo, int n) { return int(m >> lo & ((1u << n) - 1)); };
  int rho, p = bits(9, 1);
  dual = bits(10, 1);
  if (bits(0, 2) != 0) {
    rho = bits(4, 1) | bits(0, 2) << 1;
    const int a = bits(5, 2);
    switch (bits(2, 2)) {
      case 0: gw = bits(7, 2) + 4; gh = a + 2; break;
      case 1: gw = bits(7, 2) + 8; gh = a + 2; break;
      case 2: gw = a + 2; gh = bits(7, 2) + 8; break;
      default:
        if (bits(8, 1) == 0) {
          gw = a + 2;
          gh = bits(7, 1) + 6;
        } else {
          gw = bits(7, 1) + 2;
          gh = a + 2;
        }
    }
  } else {
    rho = bits(4, 1) | bits(2, 2) << 1;
    if (bits(2, 2) == 0) return false;  // (also the void extent's pattern, tested before)
    const int a = bits(5, 2);
    switch (bits(7, 2)) {
      case 0: gw = 12; gh = a + 2; break;
      case 1: gw = a + 2; gh = 12; break;
      case 2:
        gw = a + 6;
        gh = bits(9, 2) + 6;
        dual = false;
        p = 0;
        break;
      default:
        if (bits(5, 2) == 0) { gw = 6; gh = 10; }
        else if (bits(5, 2) == 1) { gw = 10; gh = 6; }
        else return false;  // 11 1x xxxx 00: reserved (or the void extent)
    }
  }
  levels = kWeightLevels[p][rho];
  return levels != 0;
}

// A block decoded down to what each texel needs: the endpoints of each partition (8-bit, or the
// void extent's 16-bit colour), every weight of the grid (0..64), the partitioning.
struct Decoded {
  AstcMode mode;
  bool hdr_partition[4] = {};           // an HDR endpoint mode: that partition's texels are the error colour
  std::array<int, 4> e0[4] = {}, e1[4] = {};
  AstcTexel16 void_colour{};
  int weights[64] = {};                 // the grid, plane 0 and 1 interleaved in a dual-plane block
};

// The endpoint modes' helpers: a's top bit to b, a to -32..31; blue contraction; the clamp.
void bit_transfer_signed(int& a, int& b) {
  b >>= 1;
  b |= a & 0x80;
  a >>= 1;
  a &= 0x3F;
  if (a & 0x20) a -= 0x40;
}
std::array<int, 4> blue_contract(int r, int g, int b, int a) { return {(r + b) >> 1, (g + b) >> 1, b, a}; }
void clamp_unorm8(std::array<int, 4>& c) {
  for (int& v : c) v = std::clamp(v, 0, 255);
}

// Endpoints of one partition from its CEM and values v (0..255 each). false: an HDR mode.
bool interpret_endpoints(int cem, const int* v0, std::array<int, 4>& e0, std::array<int, 4>& e1) {
  int v[8];
  for (int i = 0; i < 8; ++i) v[i] = v0[i];
  switch (cem) {
    case 0:
      e0 = {v[0], v[0], v[0], 255};
      e1 = {v[1], v[1], v[1], 255};
      return true;
    case 1: {
      const int l0 = (v[0] >> 2) | (v[1] & 0xC0), l1 = std::min(l0 + (v[1] & 0x3F), 255);
      e0 = {l0, l0, l0, 255};
      e1 = {l1, l1, l1, 255};
      return true;
    }
    case 4:
      e0 = {v[0], v[0], v[0], v[2]};
      e1 = {v[1], v[1], v[1], v[3]};
      return true;
    case 5:
      bit_transfer_signed(v[1], v[0]);
      bit_transfer_signed(v[3], v[2]);
      e0 = {v[0], v[0], v[0], v[2]};
      e1 = {v[0] + v[1], v[0] + v[1], v[0] + v[1], v[2] + v[3]};
      clamp_unorm8(e0);
      clamp_unorm8(e1);
      return true;
    case 6:
    case 10:
      e0 = {v[0] * v[3] >> 8, v[1] * v[3] >> 8, v[2] * v[3] >> 8, cem == 6 ? 255 : v[4]};
      e1 = {v[0], v[1], v[2], cem == 6 ? 255 : v[5]};
      return true;
    case 8:
    case 12: {
      const int a0 = cem == 8 ? 255 : v[6], a1 = cem == 8 ? 255 : v[7];
      if (v[1] + v[3] + v[5] >= v[0] + v[2] + v[4]) {
        e0 = {v[0], v[2], v[4], a0};
        e1 = {v[1], v[3], v[5], a1};
      } else {
        e0 = blue_contract(v[1], v[3], v[5], a1);
        e1 = blue_contract(v[0], v[2], v[4], a0);
      }
      return true;
    }
    case 9:
    case 13: {
      bit_transfer_signed(v[1], v[0]);
      bit_transfer_signed(v[3], v[2]);
      bit_transfer_signed(v[5], v[4]);
      if (cem == 13) bit_transfer_signed(v[7], v[6]);
      const int a0 = cem == 9 ? 255 : v[6], a1 = cem == 9 ? 255 : v[6] + v[7];
      if (v[1] + v[3] + v[5] >= 0) {
        e0 = {v[0], v[2], v[4], a0};
        e1 = {v[0] + v[1], v[2] + v[3], v[4] + v[5], a1};
      } else {
        e0 = blue_contract(v[0] + v[1], v[2] + v[3], v[4] + v[5], a1);
        e1 = blue_contract(v[0], v[2], v[4], a0);
      }
      clamp_unorm8(e0);
      clamp_unorm8(e1);
      return true;
    }
    default: return false;  // 2, 3, 7, 11, 14, 15: HDR
  }
}

Decoded decode(const uint8_t* block, int fw, int fh) {
  Decoded d;
  AstcMode& m = d.mode;
  const Bits128 b(block);
  auto illegal = [&]() {
    m.error = true;
    return d;
  };
  // Void extent: bits 8..0 = 1 1111 1100.
  if (b.bits(0, 9) == 0x1FC) {
    m.void_extent = true;
    m.hdr = b.bit(9);
    if (b.bit(9) || !b.bit(10) || !b.bit(11)) return illegal();  // HDR (LDR profile: error), reserved bits
    const uint32_t s0 = b.bits(12, 13), s1 = b.bits(25, 13), t0 = b.bits(38, 13), t1 = b.bits(51, 13);
    const bool all_ones = s0 == 0x1FFF && s1 == 0x1FFF && t0 == 0x1FFF && t1 == 0x1FFF;
    if (!all_ones && (s0 >= s1 || t0 >= t1)) return illegal();
    for (int c = 0; c < 4; ++c) d.void_colour[size_t(c)] = uint16_t(b.bits(64 + 16 * c, 16));
    return d;
  }
  if (!decode_block_mode(b.bits(0, 11), m.grid_w, m.grid_h, m.weight_levels, m.dual_plane)) return illegal();
  m.partitions = int(b.bits(11, 2)) + 1;
  const int weight_count = m.grid_w * m.grid_h * (m.dual_plane ? 2 : 1);
  const int weight_bits = ise_bits(weight_count, m.weight_levels);
  if (weight_count > 64 || weight_bits < 24 || weight_bits > 96 || m.grid_w > fw || m.grid_h > fh) return illegal();
  if (m.dual_plane && m.partitions == 4) return illegal();

  // Colour endpoint modes.
  int config_bits = 17, extra_cem_bits = 0;
  if (m.partitions == 1) {
    m.cem[0] = int(b.bits(13, 4));
  } else {
    m.partition_seed = int(b.bits(13, 10));
    const uint32_t selector = b.bits(23, 2);
    if (selector == 0) {
      config_bits = 29;
      for (int p = 0; p < m.partitions; ++p) m.cem[size_t(p)] = int(b.bits(25, 4));
    } else {
      config_bits = 25 + 3 * m.partitions;
      extra_cem_bits = 3 * m.partitions - 4;
      // The CEM field: bits 28..23, and above them the extra bits just below the weights.
      const uint32_t field = b.bits(23, 6) | b.bits(128 - weight_bits - extra_cem_bits, extra_cem_bits) << 6;
      const int base_class = int(selector) - 1;
      for (int p = 0; p < m.partitions; ++p) {
        const int cls = base_class + int(field >> (2 + p) & 1);
        const int low = int(field >> (2 + m.partitions + 2 * p) & 3);
        m.cem[size_t(p)] = cls << 2 | low;
      }
    }
  }
  if (m.dual_plane) {
    config_bits += 2;
    m.ccs = int(b.bits(128 - weight_bits - extra_cem_bits - 2, 2));
  }
  for (int p = 0; p < m.partitions; ++p) m.colour_values += 2 * ((m.cem[size_t(p)] >> 2) + 1);
  const int remaining = 128 - config_bits - weight_bits;
  if (m.colour_values > 18 || remaining < (13 * m.colour_values + 4) / 5) return illegal();
  for (int levels : kColourLevels)
    if (ise_bits(m.colour_values, levels) <= remaining) {
      m.colour_levels = levels;
      break;
    }

  // Endpoints: the colour values follow the configuration bits (bit 17, or 29 with partitions).
  int high[64], low[64], values[18];
  ise_decode(b, m.partitions == 1 ? 17 : 29, m.colour_values, m.colour_levels, high, low);
  for (int i = 0; i < m.colour_values; ++i) values[i] = unquantize_colour(m.colour_levels, high[i], low[i]);
  for (int p = 0, at = 0; p < m.partitions; ++p) {
    const int cem = m.cem[size_t(p)];
    d.hdr_partition[p] = !interpret_endpoints(cem, values + at, d.e0[p], d.e1[p]);
    m.hdr = m.hdr || d.hdr_partition[p];
    at += 2 * ((cem >> 2) + 1);
  }

  // Weights: read from bit 127 down.
  ise_decode(b.reversed(), 0, weight_count, m.weight_levels, high, low);
  for (int i = 0; i < weight_count; ++i) d.weights[i] = unquantize_weight(m.weight_levels, high[i], low[i]);
  return d;
}

// The effective weight of texel (x, y) on `plane` (the specification's infill).
int infill_weight(const Decoded& d, int fw, int fh, int x, int y, int plane) {
  const AstcMode& m = d.mode;
  const int ds = (1024 + fw / 2) / (fw - 1), dt = (1024 + fh / 2) / (fh - 1);
  const int gs = (ds * x * (m.grid_w - 1) + 32) >> 6, gt = (dt * y * (m.grid_h - 1) + 32) >> 6;
  const int js = gs >> 4, fs = gs & 15, jt = gt >> 4, ft = gt & 15;
  const int planes = m.dual_plane ? 2 : 1, count = m.grid_w * m.grid_h;
  auto w = [&](int n) { return n < count ? d.weights[n * planes + plane] : 0; };  // (weighted 0 past the grid)
  const int v0 = js + jt * m.grid_w;
  const int w11 = (fs * ft + 8) >> 4, w10 = ft - w11, w01 = fs - w11, w00 = 16 - fs - ft + w11;
  return (w(v0) * w00 + w(v0 + 1) * w01 + w(v0 + m.grid_w) * w10 + w(v0 + m.grid_w + 1) * w11 + 8) >> 4;
}

AstcTexel16 texel(const Decoded& d, int fw, int fh, bool srgb, int x, int y) {
  static constexpr AstcTexel16 kError = {0xFFFF, 0, 0xFFFF, 0xFFFF};
  const AstcMode& m = d.mode;
  if (m.error) return kError;
  if (m.void_extent) return d.void_colour;
  const int p = m.partitions == 1 ? 0 : astc_partition(m.partition_seed, m.partitions, x, y, fw * fh < 31);
  if (d.hdr_partition[p]) return kError;
  const int w0 = infill_weight(d, fw, fh, x, y, 0), w1 = m.dual_plane ? infill_weight(d, fw, fh, x, y, 1) : w0;
  AstcTexel16 out;
  for (int c = 0; c < 4; ++c) {
    const int i = m.dual_plane && c == m.ccs ? w1 : w0;
    const int a = d.e0[p][size_t(c)], b = d.e1[p][size_t(c)];
    const int c0 = srgb ? (a << 8 | 0x80) : (a << 8 | a), c1 = srgb ? (b << 8 | 0x80) : (b << 8 | b);
    out[size_t(c)] = uint16_t((c0 * (64 - i) + c1 * i + 32) >> 6);
  }
  return out;
}

uint32_t hash52(uint32_t p) {
  p ^= p >> 15;
  p -= p << 17;
  p += p << 7;
  p += p << 4;
  p ^= p >> 5;
  p += p << 16;
  p ^= p >> 7;
  p ^= p >> 3;
  p ^= p << 6;
  p ^= p >> 17;
  return p;
}

}  // namespace

int astc_partition(int seed, int partitions, int x, int y, bool small_block) {
  if (small_block) {
    x <<= 1;
    y <<= 1;
  }
  seed += (partitions - 1) * 1024;
  const uint32_t rnum = hash52(uint32_t(seed));
  uint32_t s[13];
  for (int i = 0; i < 8; ++i) s[i + 1] = rnum >> (4 * i) & 0xF;
  s[9] = rnum >> 18 & 0xF;
  s[10] = rnum >> 22 & 0xF;
  s[11] = rnum >> 26 & 0xF;
  s[12] = ((rnum >> 30) | (rnum << 2)) & 0xF;
  for (int i = 1; i <= 12; ++i) s[i] *= s[i];
  int sh1, sh2;
  if (seed & 1) {
    sh1 = (seed & 2) ? 4 : 5;
    sh2 = partitions == 3 ? 6 : 5;
  } else {
    sh1 = partitions == 3 ? 6 : 5;
    sh2 = (seed & 2) ? 4 : 5;
  }
  for (int i = 1; i <= 8; ++i) s[i] >>= (i & 1) ? sh1 : sh2;
  // (seeds 9..12 weigh z, which is 0 in 2D)
  int a = int((s[1] * uint32_t(x) + s[2] * uint32_t(y) + (rnum >> 14)) & 0x3F);
  int b = int((s[3] * uint32_t(x) + s[4] * uint32_t(y) + (rnum >> 10)) & 0x3F);
  int c = int((s[5] * uint32_t(x) + s[6] * uint32_t(y) + (rnum >> 6)) & 0x3F);
  int d = int((s[7] * uint32_t(x) + s[8] * uint32_t(y) + (rnum >> 2)) & 0x3F);
  if (partitions < 4) d = 0;
  if (partitions < 3) c = 0;
  if (a >= b && a >= c && a >= d) return 0;
  if (b >= c && b >= d) return 1;
  if (c >= d) return 2;
  return 3;
}

AstcMode astc_mode_of(const uint8_t* block, int fw, int fh) { return decode(block, fw, fh).mode; }

AstcTexel16 astc_texel16(const uint8_t* block, int fw, int fh, bool srgb, int x, int y) {
  return texel(decode(block, fw, fh), fw, fh, srgb, x, y);
}

void astc_block16(const uint8_t* block, int fw, int fh, bool srgb, AstcTexel16* out) {
  const Decoded d = decode(block, fw, fh);
  for (int y = 0; y < fh; ++y)
    for (int x = 0; x < fw; ++x) out[y * fw + x] = texel(d, fw, fh, srgb, x, y);
}

}  // namespace tex
