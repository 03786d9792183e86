// The real-valued reference of the scenes and the image metrics (docs/scenes.md).
// Independent of the model: it reads only level 0 and works in double precision.
#include <algorithm>
#include <cmath>

#include "model/error.h"
#include "reports/reference.h"

namespace tex {

namespace {

double mean_of(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / double(v.size());
}

// Box integrals of level 0 seen as a piecewise-constant image (texel (i, j) covers [i, i+1) x [j, j+1)),
// continued outside [0, W) x [0, H) by the wrap modes. A summed-area table, interpolated bilinearly
// (exact for a piecewise-constant image), gives F(x, y) = integral over [0, x] x [0, y] inside one period;
// each wrap mode writes the integral from 0 to any x as a weighted sum of F at points inside [0, n].
class BoxIntegrator {
 public:
  BoxIntegrator(const Image& level0, Wrap wu, Wrap wv) : w_(level0.width), h_(level0.height), wu_(wu), wv_(wv) {
    const double maxv = (1 << level0.channel_bits) - 1;
    sat_.assign(size_t(w_ + 1) * (h_ + 1), Rgba{0, 0, 0, 0});
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x)
        for (int c = 0; c < 4; ++c)
          at(x + 1, y + 1)[c] = level0.at(x, y)[c] / maxv + at(x, y + 1)[c] + at(x + 1, y)[c] - at(x, y)[c];
  }

  // Mean over [x0, x1] x [y0, y1] in texels (x0 < x1, y0 < y1).
  Rgba mean(double x0, double x1, double y0, double y1) const {
    Terms tx0, tx1, ty0, ty1;
    terms(x0, w_, wu_, tx0), terms(x1, w_, wu_, tx1), terms(y0, h_, wv_, ty0), terms(y1, h_, wv_, ty1);
    Rgba sum{0, 0, 0, 0};
    accumulate(tx1, ty1, 1, sum), accumulate(tx0, ty1, -1, sum), accumulate(tx1, ty0, -1, sum), accumulate(tx0, ty0, 1, sum);
    const double area = (x1 - x0) * (y1 - y0);
    for (double& c : sum) c /= area;
    return sum;
  }

 private:
  struct Terms {
    int count = 0;
    double weight[3], pos[3];
    void add(double w, double p) { weight[count] = w, pos[count++] = p; }
  };

  // Integral of the continued 1-D function from 0 to x = sum of weight * F1(pos), pos in [0, n].
  static void terms(double x, int n, Wrap wrap, Terms& t) {
    if (wrap == Wrap::Repeat) {
      const double q = std::floor(x / n);
      t.add(q, n), t.add(1, x - q * n);
    } else if (wrap == Wrap::Clamp) {
      if (x < 0) t.add(x, 1);  // texel 0 continues to the left
      else if (x <= n) t.add(1, x);
      else t.add(1 + (x - n), n), t.add(-(x - n), n - 1);  // texel n-1 continues to the right
    } else {  // mirror: period 2n, the second half reversed
      const double q = std::floor(x / (2.0 * n)), r = x - q * 2 * n;
      if (r <= n) t.add(2 * q, n), t.add(1, r);
      else t.add(2 * q + 2, n), t.add(-1, 2 * n - r);
    }
  }

  void accumulate(const Terms& tx, const Terms& ty, double sign, Rgba& sum) const {
    for (int i = 0; i < tx.count; ++i)
      for (int j = 0; j < ty.count; ++j) {
        const double w = sign * tx.weight[i] * ty.weight[j];
        if (w == 0) continue;
        const Rgba f = sat_lerp(tx.pos[i], ty.pos[j]);
        for (int c = 0; c < 4; ++c) sum[c] += w * f[c];
      }
  }

  Rgba sat_lerp(double x, double y) const {
    x = std::clamp(x, 0.0, double(w_));
    y = std::clamp(y, 0.0, double(h_));
    const int ix = std::min(int(x), w_ - 1), iy = std::min(int(y), h_ - 1);
    const double fx = x - ix, fy = y - iy;
    const Rgba &a = at(ix, iy), &b = at(ix + 1, iy), &c = at(ix, iy + 1), &d = at(ix + 1, iy + 1);
    Rgba r;
    for (int k = 0; k < 4; ++k)
      r[k] = (a[k] * (1 - fx) + b[k] * fx) * (1 - fy) + (c[k] * (1 - fx) + d[k] * fx) * fy;
    return r;
  }

  Rgba& at(int x, int y) { return sat_[size_t(y) * (w_ + 1) + x]; }
  const Rgba& at(int x, int y) const { return sat_[size_t(y) * (w_ + 1) + x]; }

  int w_, h_;
  Wrap wu_, wv_;
  std::vector<Rgba> sat_;
};

// The mean of the texture over a footprint centred on (u, v) with extents (eu, ev) in texels,
// widened by one texel: a point footprint gives exactly the bilinear interpolation of level 0.
Rgba footprint_mean(const BoxIntegrator& box, int w, int h, double u, double v, double eu, double ev) {
  const double cx = u * w, cy = v * h, hx = 0.5 * (eu + 1), hy = 0.5 * (ev + 1);
  return box.mean(cx - hx, cx + hx, cy - hy, cy + hy);
}

}  // namespace

int reference_sub_positions(double step_texels, int samples_per_axis) {
  const int s = std::max(1, samples_per_axis), most = std::max(s, kReferenceMaxSubPositions);
  return int(std::clamp(std::ceil(step_texels), double(s), double(most)));
}

std::vector<Rgba> reference_values(const SceneFrame& frame, const Image& level0, Wrap wrap_u, Wrap wrap_v,
                                   int samples_per_axis) {
  const BoxIntegrator box(level0, wrap_u, wrap_v);
  const int w = level0.width, h = level0.height;
  std::vector<Rgba> out(frame.queries.size());
  for (size_t i = 0; i < frame.queries.size(); ++i) {
    const Query& q = frame.queries[i];
    // The pixel's steps in texels: (au, av) along screen x, (bu, bv) along screen y.
    const double au = std::fabs(q.deriv.dudx) * w, av = std::fabs(q.deriv.dvdx) * h;
    const double bu = std::fabs(q.deriv.dudy) * w, bv = std::fabs(q.deriv.dvdy) * h;
    if (frame.is_mesh() || !frame.map) {
      out[i] = footprint_mean(box, w, h, q.u, q.v, au + bu, av + bv);  // the footprint's bounding box
      continue;
    }
    // Stratified sub-pixel positions through the exact mapping, nx across and ny down: at least
    // samples_per_axis, and enough that one sub-pixel step moves (u, v) by at most one texel (up to
    // kReferenceMaxSubPositions). Each averages its own share of the footprint, the bounding box of
    // the sub-pixel's parallelogram (below the cap at most 2 texels a side): a long, thin, oblique
    // footprint (the plane's sides near the horizon) is not widened across its minor axis by the
    // bounding box of a large share, and far-away perspective pixels do not alias in the reference.
    const int nx = reference_sub_positions(std::max(au, av), samples_per_axis);
    const int ny = reference_sub_positions(std::max(bu, bv), samples_per_axis);
    const double eu = au / nx + bu / ny, ev = av / nx + bv / ny;
    const int px = frame.pixel[i] % frame.width, py = frame.pixel[i] / frame.width;
    Rgba sum{0, 0, 0, 0};
    int n = 0;
    for (int sy = 0; sy < ny; ++sy)
      for (int sx = 0; sx < nx; ++sx) {
        double u, v;
        if (frame.map(px + (sx + 0.5) / nx, py + (sy + 0.5) / ny, u, v) == Hit::None) continue;
        const Rgba m = footprint_mean(box, w, h, u, v, eu, ev);
        for (int c = 0; c < 4; ++c) sum[c] += m[c];
        ++n;
      }
    if (n == 0) {
      out[i] = footprint_mean(box, w, h, q.u, q.v, au + bu, av + bv);
    } else {
      for (int c = 0; c < 4; ++c) out[i][c] = sum[c] / n;
    }
  }
  return out;
}

ErrorStats compare_images(const RgbaImage& image, const RgbaImage& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw Error("compare_images: sizes differ");
  double sq = 0, abs_sum = 0, max_err = 0;
  size_t n = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    if (!reference.covered[i]) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = image.pixels[i][c] - reference.pixels[i][c];
      sq += d * d;
      abs_sum += std::fabs(d);
      max_err = std::max(max_err, std::fabs(d));
      ++n;
    }
  }
  ErrorStats s;
  if (n == 0) return s;
  const double mse = sq / n;
  s.psnr_db = mse > 0 ? std::min(999.0, 10 * std::log10(1.0 / mse)) : 999.0;
  s.max_error_lsb = 255 * max_err;
  s.mean_error_lsb = 255 * abs_sum / n;
  return s;
}

Image error_heat_map(const RgbaImage& image, const RgbaImage& reference, double full_scale_lsb) {
  Image out(image.width, image.height, 8);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    double e = 0;
    for (int c = 0; c < 3; ++c) e = std::max(e, std::fabs(image.pixels[i][c] - reference.pixels[i][c]));
    const double t = std::clamp(255 * e / full_scale_lsb, 0.0, 1.0);
    // black -> red -> yellow -> white
    out.texels[i] = {uint16_t(std::lround(255 * std::clamp(3 * t, 0.0, 1.0))),
                     uint16_t(std::lround(255 * std::clamp(3 * t - 1, 0.0, 1.0))),
                     uint16_t(std::lround(255 * std::clamp(3 * t - 2, 0.0, 1.0))), 255};
  }
  return out;
}

FlickerStats flicker(const std::vector<RgbaImage>& frames, const std::vector<RgbaImage>& reference_frames) {
  if (frames.size() != reference_frames.size()) throw Error("flicker: frame counts differ");
  FlickerStats s;
  for (size_t t = 0; t + 1 < frames.size(); ++t) {
    const RgbaImage &a = frames[t], &b = frames[t + 1], &ra = reference_frames[t], &rb = reference_frames[t + 1];
    double change = 0, ref_change = 0, excess = 0;
    size_t n = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) {
      if (!ra.covered[i] || !rb.covered[i]) continue;  // pixels on the surface in both frames
      for (int c = 0; c < 3; ++c) {
        const double d = b.pixels[i][c] - a.pixels[i][c], rd = rb.pixels[i][c] - ra.pixels[i][c];
        change += std::fabs(d);
        ref_change += std::fabs(rd);
        excess += std::fabs(d - rd);
        ++n;
      }
    }
    const double k = n ? 255.0 / n : 0;
    s.change.push_back(change * k);
    s.reference_change.push_back(ref_change * k);
    s.excess.push_back(excess * k);
  }
  s.mean_change = mean_of(s.change);
  s.mean_reference_change = mean_of(s.reference_change);
  s.mean_excess = mean_of(s.excess);
  return s;
}

namespace {

// A mesh frame's faces: consecutive blocks of n^2 vertices, n = q + 1 = 1 / (the block's u step).
struct FaceBlock {
  size_t first;
  int quads;
};
std::vector<FaceBlock> face_blocks(const SceneFrame& frame) {
  std::vector<FaceBlock> faces;
  for (size_t i = 0; i < frame.queries.size();) {
    const int q = int(std::lround(1 / frame.queries[i].deriv.dudx)) - 1;
    if (q < 1) throw Error("mesh: a face's vertex step is not 1/n");
    faces.push_back({i, q});
    i += size_t(q + 1) * (q + 1);
    if (i > frame.queries.size()) throw Error("mesh: the vertices do not form whole faces");
  }
  return faces;
}

// The bilinear patch through a face's vertex grid at (u, v) in [0, 1].
Rgba patch_at(const std::vector<Rgba>& values, const FaceBlock& f, double u, double v) {
  const int n = f.quads + 1;
  const double x = u * f.quads, y = v * f.quads;
  const int i = std::min(int(x), f.quads - 1), j = std::min(int(y), f.quads - 1);
  const double fx = x - i, fy = y - j;
  const Rgba &a = values[f.first + j * n + i], &b = values[f.first + j * n + i + 1];
  const Rgba &c = values[f.first + (j + 1) * n + i], &d = values[f.first + (j + 1) * n + i + 1];
  Rgba r;
  for (int k = 0; k < 4; ++k) r[k] = (a[k] * (1 - fx) + b[k] * fx) * (1 - fy) + (c[k] * (1 - fx) + d[k] * fx) * fy;
  return r;
}

}  // namespace

VertexErrorStats compare_vertices(const SceneFrame& frame, const std::vector<Rgba>& values,
                                  const std::vector<Rgba>& reference, double texels_per_unit) {
  if (values.size() != reference.size() || values.size() != frame.queries.size())
    throw Error("compare_vertices: vertex counts differ");
  VertexErrorStats s;
  double sq_all = 0, sq_interior = 0, sq_border = 0;
  auto add = [](VertexErrorStats::Part& p, double& sq, double d2) {
    sq += d2;
    p.max_texels = std::max(p.max_texels, std::sqrt(d2));
    ++p.vertices;
  };
  for (const FaceBlock& f : face_blocks(frame)) {
    const int n = f.quads + 1;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const size_t k = f.first + size_t(j) * n + i;
        double d2 = 0;
        for (int c = 0; c < 3; ++c) {
          const double d = (values[k][c] - reference[k][c]) * texels_per_unit;
          d2 += d * d;
        }
        add(s.all, sq_all, d2);
        if (i == 0 || j == 0 || i == f.quads || j == f.quads) add(s.border, sq_border, d2);
        else add(s.interior, sq_interior, d2);
      }
  }
  auto finish = [](VertexErrorStats::Part& p, double sq) {
    if (p.vertices) p.rms_texels = std::sqrt(sq / p.vertices);
  };
  finish(s.all, sq_all), finish(s.interior, sq_interior), finish(s.border, sq_border);
  return s;
}


SurfaceJitterStats mesh_jitter(const std::vector<SceneFrame>& frames, const std::vector<std::vector<Rgba>>& values,
                               const std::vector<std::vector<Rgba>>& reference, double texels_per_unit,
                               int samples_per_axis) {
  if (frames.size() != values.size() || frames.size() != reference.size())
    throw Error("mesh_jitter: frame counts differ");
  const int s = std::max(2, samples_per_axis);
  SurfaceJitterStats out;
  double inner_change = 0, inner_ref_change = 0, inner_excess = 0;
  size_t inner_n = 0;
  for (size_t t = 0; t + 1 < frames.size(); ++t) {
    const auto fa = face_blocks(frames[t]), fb = face_blocks(frames[t + 1]);
    if (fa.size() != fb.size()) throw Error("mesh_jitter: face counts differ between frames");
    double change = 0, ref_change = 0, excess = 0;
    size_t n = 0;
    for (size_t k = 0; k < fa.size(); ++k)
      for (int j = 0; j < s; ++j)
        for (int i = 0; i < s; ++i) {
          const double u = double(i) / (s - 1), v = double(j) / (s - 1);
          const Rgba a = patch_at(values[t], fa[k], u, v), b = patch_at(values[t + 1], fb[k], u, v);
          const Rgba ra = patch_at(reference[t], fa[k], u, v), rb = patch_at(reference[t + 1], fb[k], u, v);
          double d2 = 0, rd2 = 0, e2 = 0;
          for (int c = 0; c < 3; ++c) {
            const double d = (b[c] - a[c]) * texels_per_unit, rd = (rb[c] - ra[c]) * texels_per_unit;
            d2 += d * d, rd2 += rd * rd, e2 += (d - rd) * (d - rd);
          }
          change += std::sqrt(d2), ref_change += std::sqrt(rd2), excess += std::sqrt(e2);
          ++n;
          const double inner = 1.0 / std::min(fa[k].quads, fb[k].quads);
          if (u >= inner && u <= 1 - inner && v >= inner && v <= 1 - inner) {
            inner_change += std::sqrt(d2), inner_ref_change += std::sqrt(rd2), inner_excess += std::sqrt(e2);
            ++inner_n;
          }
        }
    out.change.push_back(n ? change / n : 0);
    out.reference_change.push_back(n ? ref_change / n : 0);
    out.excess.push_back(n ? excess / n : 0);
  }
  out.mean_change = mean_of(out.change);
  out.mean_reference_change = mean_of(out.reference_change);
  out.mean_excess = mean_of(out.excess);
  if (inner_n) {  // pooled over all steps' interior points (their number varies with q)
    out.mean_interior_change = inner_change / inner_n;
    out.mean_interior_reference_change = inner_ref_change / inner_n;
    out.mean_interior_excess = inner_excess / inner_n;
  }
  return out;
}

}  // namespace tex
