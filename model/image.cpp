#include "image.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fcntl.h>
#include <unistd.h>

#include "error.h"

namespace tex {

namespace OIIO = OIIO_NAMESPACE;

bool is_power_of_two(int n) { return n > 0 && (n & (n - 1)) == 0; }

int log2_exact(int n) {
  int l = 0;
  while ((1 << l) < n) ++l;
  return l;
}

const std::vector<std::string>& pattern_names() {
  static const std::vector<std::string> names = {"checker", "testcard", "noise", "gradient"};
  return names;
}

namespace {

void check_size(int w, int h, const std::string& what) {
  const int max = 1 << kMaxLog2Size;
  if (!is_power_of_two(w) || !is_power_of_two(h) || w > max || h > max)
    throw Error(what + ": size " + std::to_string(w) + "x" + std::to_string(h) +
                " is not a power of two from 1 to 2048 per side (use --resize to resample)");
}

Texel rgb(int r, int g, int b) {
  return {uint16_t(r), uint16_t(g), uint16_t(b), 255};
}

// SMPTE-like colour bars, a grey ramp, a fine checker and a circle: features at every scale,
// so each mip level shows something different.
Texel testcard_texel(int x, int y, int w, int h) {
  static const Texel bars[8] = {rgb(235, 235, 235), rgb(235, 235, 16), rgb(16, 235, 235), rgb(16, 235, 16),
                                rgb(235, 16, 235),  rgb(235, 16, 16),  rgb(16, 16, 235),  rgb(16, 16, 16)};
  const double fx = (x + 0.5) / w, fy = (y + 0.5) / h;
  const double dx = fx - 0.5, dy = (fy - 0.5) * h / std::max(w, h) * (double(std::max(w, h)) / w);
  const double r = std::sqrt(dx * dx + dy * dy);
  if (std::abs(r - 0.4) < 0.012) return rgb(255, 255, 255);
  if (fy < 0.5) return bars[std::min(7, int(fx * 8))];
  if (fy < 0.625) {
    const int g = std::min(255, int(fx * 256));
    return rgb(g, g, g);
  }
  if (fy < 0.75) {  // checkers of 1, 2, 4, 8 texels across the row
    const int cell = 1 << std::min(3, int(fx * 4));
    const int on = ((x / cell) + (y / cell)) & 1;
    return on ? rgb(255, 255, 255) : rgb(0, 0, 0);
  }
  if (fy < 0.875) {  // sine zone plate in x: frequency rises to the right
    const double s = 0.5 + 0.5 * std::cos(M_PI * fx * fx * w / 2);
    const int g = int(std::lround(s * 255));
    return rgb(g, g / 2, 255 - g);
  }
  return ((x / 8 + y / 8) & 1) ? rgb(200, 40, 40) : rgb(40, 40, 200);
}

uint32_t hash32(uint32_t x) {
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

}  // namespace

Image make_pattern(const std::string& name, int w, int h) {
  check_size(w, h, "pattern " + name);
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Texel& t = img.at(x, y);
      if (name == "checker") {
        const int cell = std::max(1, std::max(w, h) / 16);
        t = ((x / cell + y / cell) & 1) ? rgb(240, 240, 240) : rgb(20, 20, 140);
      } else if (name == "testcard") {
        t = testcard_texel(x, y, w, h);
      } else if (name == "noise") {
        const uint32_t r = hash32(uint32_t(y) * 0x9E3779B1U + uint32_t(x));
        t = {uint16_t(r & 255), uint16_t((r >> 8) & 255), uint16_t((r >> 16) & 255), uint16_t(r >> 24)};
      } else if (name == "gradient") {
        t = rgb(x * 255 / std::max(1, w - 1), y * 255 / std::max(1, h - 1), 128);
      } else {
        std::string list;
        for (const auto& n : pattern_names()) list += (list.empty() ? "" : ", ") + n;
        throw Error("unknown pattern '" + name + "' (known: " + list + ")");
      }
    }
  return img;
}

namespace {

// libpng (inside OpenImageIO) prints its own "libpng error: ..." lines on stderr; the reader's
// error message already says the same, and bad input must give exactly one line.
class QuietStderr {
 public:
  QuietStderr() : saved_(dup(STDERR_FILENO)) {
    std::fflush(stderr);
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) {
      dup2(null_fd, STDERR_FILENO);
      close(null_fd);
    }
  }
  ~QuietStderr() {
    std::fflush(stderr);
    if (saved_ >= 0) {
      dup2(saved_, STDERR_FILENO);
      close(saved_);
    }
  }

 private:
  int saved_;
};

bool parse_pattern_spec(const std::string& spec, std::string& name, int& w, int& h) {
  const auto colon = spec.find(':');
  name = spec.substr(0, colon);
  if (std::find(pattern_names().begin(), pattern_names().end(), name) == pattern_names().end()) return false;
  w = h = 512;
  if (colon == std::string::npos) return true;
  const std::string size = spec.substr(colon + 1);
  char x = 0, extra = 0;
  if (std::sscanf(size.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x')
    throw Error("pattern '" + spec + "': size must be WxH, e.g. " + name + ":256x128");
  return true;
}

int nearest_power_of_two(int n) {
  int p = 1;
  while (p < n && p < (1 << kMaxLog2Size)) p <<= 1;
  if (p > 1 && (p - n) > (n - p / 2)) p >>= 1;
  return p;
}

}  // namespace

Image load_texture(const std::string& spec, bool resize) {
  std::string name;
  int w = 0, h = 0;
  if (!std::filesystem::exists(spec) && parse_pattern_spec(spec, name, w, h)) return make_pattern(name, w, h);
  if (!std::filesystem::exists(spec)) throw Error(spec + ": no such file or built-in pattern");

  // Texels are data: keep the file's values (OpenImageIO would premultiply unassociated alpha).
  OIIO::ImageSpec read_config;
  read_config.attribute("oiio:UnassociatedAlpha", 1);
  OIIO::ImageBuf src;
  bool read_ok;
  {
    QuietStderr quiet;
    src.reset(spec, 0, 0, nullptr, &read_config);
    read_ok = src.read(0, 0, true, OIIO::TypeDesc::UINT8);
  }
  if (!read_ok) {
    std::string msg = src.geterror();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    throw Error(spec + ": cannot read image (" + msg + ")");
  }
  const OIIO::ImageSpec& s = src.spec();
  w = s.width;
  h = s.height;
  if (!resize || (is_power_of_two(w) && is_power_of_two(h) && w <= 2048 && h <= 2048)) {
    check_size(w, h, spec);
  } else {
    const int nw = nearest_power_of_two(w), nh = nearest_power_of_two(h);
    std::fprintf(stderr, "texsim: %s: resampled %dx%d to %dx%d\n", spec.c_str(), w, h, nw, nh);
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(src, "", 0, OIIO::ROI(0, nw, 0, nh, 0, 1, 0, s.nchannels));
    if (resized.has_error()) throw Error(spec + ": resize failed (" + resized.geterror() + ")");
    src = std::move(resized);
    w = nw;
    h = nh;
  }
  const int nch = src.spec().nchannels;
  std::vector<uint8_t> pixels(size_t(w) * h * nch);
  if (!src.get_pixels(OIIO::ROI(0, w, 0, h, 0, 1, 0, nch), OIIO::TypeDesc::UINT8, pixels.data()))
    throw Error(spec + ": cannot read pixels (" + src.geterror() + ")");
  Image img(w, h);
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const uint8_t* p = &pixels[i * nch];
    Texel& t = img.texels[i];
    if (nch >= 3) t = {p[0], p[1], p[2], uint16_t(nch >= 4 ? p[3] : 255)};
    else t = {p[0], p[0], p[0], uint16_t(nch == 2 ? p[1] : 255)};  // gray (+ alpha)
  }
  return img;
}

void save_image(const Image& img, const std::string& path) {
  std::vector<uint8_t> pixels(img.texels.size() * 4);
  const int shift = std::max(0, img.channel_bits - 8);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) pixels[i * 4 + c] = uint8_t(img.texels[i][c] >> shift);
  const std::filesystem::path final_path(path);
  if (final_path.has_parent_path() && !std::filesystem::is_directory(final_path.parent_path()))
    throw Error(path + ": directory does not exist");
  // Keep the extension so OpenImageIO picks the format, e.g. out.png -> out.tmp.png.
  const std::string tmp = (final_path.parent_path() / (final_path.stem().string() + ".partial" +
                                                        final_path.extension().string())).string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) throw Error(path + ": no image writer for this file type");
  OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // write the texels as they are, no un-premultiply
  if (!out->open(tmp, spec) || !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close()) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw Error(path + ": cannot write image (" + out->geterror() + ")");
  }
  std::filesystem::rename(tmp, final_path);
}

}  // namespace tex
