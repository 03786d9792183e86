#include "sampler.h"

#include "stages.h"

namespace tex {

Sampler::Sampler(const Pyramid& pyramid, const SamplerConfig& config)
    : config_(config),
      memory_(pyramid),
      channel_bits_(pyramid.levels[0].channel_bits),
      log2_w0_(pyramid.log2_w0()),
      log2_h0_(pyramid.log2_h0()) {
  if (channel_bits_ == 8)
    for (const Image& img : pyramid.levels) {
      std::vector<uint32_t> p(img.texels.size());
      for (size_t i = 0; i < p.size(); ++i) {
        const Texel& t = img.texels[i];
        p[i] = uint32_t(t[0]) | uint32_t(t[1]) << 8 | uint32_t(t[2]) << 16 | uint32_t(t[3]) << 24;
      }
      packed_.push_back(std::move(p));
    }
}

Texel Sampler::sample(const Request& r) {
  const int32_t lod = stage::bias_and_clamp(r.lod, config_.lod_bias, config_.min_lod, config_.max_lod);
  const stage::LevelSelect sel = stage::select_levels(lod, config_.filter.mip, last_level());
  const bool linear = config_.filter.texel == TexelFilter::Linear;

  int64_t bil[2][4] = {};
  const int levels_used = sel.two_levels ? 2 : 1;
  for (int l = 0; l < levels_used; ++l) {
    const int k = l == 0 ? sel.d : sel.d1;
    const LevelShape shape = memory_.shape(k);
    const stage::AxisTaps tu = stage::axis_taps(r.u, shape.log2_w, config_.filter.texel);
    const stage::AxisTaps tv = stage::axis_taps(r.v, shape.log2_h, config_.filter.texel);
    const auto t = memory_.read_footprint(
        k, stage::wrap_index(tu.i0, shape.log2_w, config_.wrap_u), stage::wrap_index(tu.i1, shape.log2_w, config_.wrap_u),
        stage::wrap_index(tv.i0, shape.log2_h, config_.wrap_v), stage::wrap_index(tv.i1, shape.log2_h, config_.wrap_v),
        !linear);
    for (int c = 0; c < 4; ++c) bil[l][c] = stage::bilerp(t[0][c], t[1][c], t[2][c], t[3][c], tu.w, tv.w);
    if (linear) multiplies_ += 3;
  }
  if (sel.two_levels) multiplies_ += 1;
  ++samples_;

  Texel out;
  for (int c = 0; c < 4; ++c)
    out[c] = uint16_t(stage::blend_and_round(bil[0][c], sel.two_levels ? bil[1][c] : bil[0][c], sel.f));
  return out;
}

namespace {

// Bilinear of all four 8-bit channels of one level; results CW.16 per channel (24 bits).
struct Bilinear4 {
  uint32_t c[4];
};

inline Bilinear4 bilinear_rgba8(const uint32_t* level, int log2_w, int log2_h, int32_t u, int32_t v,
                                const SamplerConfig& cfg) {
  const stage::AxisTaps tu = stage::axis_taps(u, log2_w, cfg.filter.texel);
  const stage::AxisTaps tv = stage::axis_taps(v, log2_h, cfg.filter.texel);
  const int32_t x0 = stage::wrap_index(tu.i0, log2_w, cfg.wrap_u), x1 = stage::wrap_index(tu.i1, log2_w, cfg.wrap_u);
  const int32_t y0 = stage::wrap_index(tv.i0, log2_h, cfg.wrap_v), y1 = stage::wrap_index(tv.i1, log2_h, cfg.wrap_v);
  const uint32_t* row0 = level + (size_t(y0) << log2_w);
  const uint32_t* row1 = level + (size_t(y1) << log2_w);
  const uint32_t a = row0[x0], b = row0[x1], c = row1[x0], e = row1[x1];
  Bilinear4 r;
  for (int ch = 0; ch < 4; ++ch) {
    const int sh = ch * 8;
    const int32_t ta = (a >> sh) & 255, tb = (b >> sh) & 255, tc = (c >> sh) & 255, te = (e >> sh) & 255;
    const int32_t top = (ta << 8) + (tb - ta) * tu.w;
    const int32_t bot = (tc << 8) + (te - tc) * tu.w;
    r.c[ch] = uint32_t((top << 8) + (bot - top) * tv.w);
  }
  return r;
}

}  // namespace

void Sampler::sample_rgba8(const Request* requests, size_t n, uint32_t* out) const {
  const int last = int(packed_.size()) - 1;
  for (size_t i = 0; i < n; ++i) {
    const Request& r = requests[i];
    const int32_t lod = stage::bias_and_clamp(r.lod, config_.lod_bias, config_.min_lod, config_.max_lod);
    const stage::LevelSelect sel = stage::select_levels(lod, config_.filter.mip, last);
    const LevelShape s0 = level_shape(log2_w0_, log2_h0_, sel.d);
    const Bilinear4 b0 = bilinear_rgba8(packed_[sel.d].data(), s0.log2_w, s0.log2_h, r.u, r.v, config_);
    Bilinear4 b1 = b0;
    if (sel.two_levels) {
      const LevelShape s1 = level_shape(log2_w0_, log2_h0_, sel.d1);
      b1 = bilinear_rgba8(packed_[sel.d1].data(), s1.log2_w, s1.log2_h, r.u, r.v, config_);
    }
    uint32_t px = 0;
    for (int ch = 0; ch < 4; ++ch) {
      // (b0 << 8) + (b1 - b0) * f fits in 32 bits unsigned; modular arithmetic is exact here.
      const uint32_t tri = (b0.c[ch] << 8) + (b1.c[ch] - b0.c[ch]) * uint32_t(sel.f);
      px |= ((tri + (1u << 23)) >> 24) << (ch * 8);
    }
    out[i] = px;
  }
}

SamplerStats Sampler::stats() const { return {samples_, multiplies_, memory_.stats()}; }

void Sampler::reset_stats() {
  samples_ = multiplies_ = 0;
  memory_.reset_stats();
}

}  // namespace tex
