// Texture files and pictures through OpenImageIO: the only place image files are read or written.
#include "workloads/texture_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fcntl.h>
#include <unistd.h>

#include "model/error.h"
#include "workloads/query_trace.h"

namespace tex {

namespace OIIO = OIIO_NAMESPACE;

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
  const auto x = size.find('x');
  auto side = [&](const std::string& text, int& out) {
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && end == text.data() + text.size() && out > (1 << kMaxLog2Size)))
      throw Error("pattern " + quote_clipped(spec) + ": size " + quote_clipped(size) + " is too large: at most " +
                  std::to_string(1 << kMaxLog2Size) + " per side");
    return ec == std::errc() && end == text.data() + text.size() && !text.empty();
  };
  if (x == std::string::npos || !side(size.substr(0, x), w) || !side(size.substr(x + 1), h))
    throw Error("pattern " + quote_clipped(spec) + ": size must be WxH, e.g. " + name + ":256x128");
  return true;
}

// Float images hold values outside 0..1 that 8-bit texels cannot: they are clamped, and the user
// is told once.
void warn_if_clamped(const OIIO::ImageBuf& src, const std::string& spec) {
  if (!src.nativespec().format.is_floating_point()) return;
  const OIIO::ImageSpec& s = src.spec();
  std::vector<float> values(size_t(s.width) * s.height * s.nchannels);
  OIIO::ImageBuf fsrc(spec);
  if (!fsrc.get_pixels(OIIO::ROI(0, s.width, 0, s.height, 0, 1, 0, s.nchannels), OIIO::TypeDesc::FLOAT, values.data()))
    return;
  size_t below = 0, above = 0;
  float lo = 0, hi = 1;
  for (float v : values) {
    below += v < 0.0f;
    above += v > 1.0f;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (below + above > 0)
    std::fprintf(stderr, "texsim: %s: %zu of %zu values are outside 0..1 (%g to %g) and were clamped to 8 bits\n",
                 spec.c_str(), below + above, values.size(), double(lo), double(hi));
}

// Reads the first subimage as 8 bits per channel, from `file` or through `proxy` (then `file` only
// names the format by its extension). Texels are data: keep the file's values (OpenImageIO would
// premultiply unassociated alpha).
void read_uint8(OIIO::ImageBuf& src, const std::string& name, const std::string& file,
                OIIO::Filesystem::IOProxy* proxy = nullptr) {
  OIIO::ImageSpec read_config;
  read_config.attribute("oiio:UnassociatedAlpha", 1);
  bool read_ok;
  {
    QuietStderr quiet;
    src.reset(file, 0, 0, nullptr, &read_config, proxy);
    read_ok = src.read(0, 0, true, OIIO::TypeDesc::UINT8);
  }
  if (!read_ok) {
    std::string msg = src.geterror();
    std::replace(msg.begin(), msg.end(), '\n', ' ');
    throw Error(name + ": cannot read image (" + msg + ")");
  }
}

// The buffer's pixels as RGBA8 texels: gray -> RGB, a missing alpha -> opaque.
Image rgba8_texels(const OIIO::ImageBuf& src, const std::string& name) {
  const int w = src.spec().width, h = src.spec().height, nch = src.spec().nchannels;
  std::vector<uint8_t> pixels(size_t(w) * h * nch);
  if (!src.get_pixels(OIIO::ROI(0, w, 0, h, 0, 1, 0, nch), OIIO::TypeDesc::UINT8, pixels.data()))
    throw Error(name + ": cannot read pixels (" + src.geterror() + ")");
  Image img(w, h);
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const uint8_t* p = &pixels[i * nch];
    Texel& t = img.texels[i];
    if (nch >= 3) t = {p[0], p[1], p[2], uint16_t(nch >= 4 ? p[3] : 255)};
    else t = {p[0], p[0], p[0], uint16_t(nch == 2 ? p[1] : 255)};  // gray (+ alpha)
  }
  return img;
}

// Model textures are resampled up, never down: no texel of the file is lost (8192 is the limit).
int next_power_of_two(int n) {
  int p = 1;
  while (p < n && p < (1 << kMaxLog2Size)) p <<= 1;
  return p;
}

ModelTexture pow2_texture(OIIO::ImageBuf& src, const std::string& name) {
  ModelTexture t;
  t.file_width = src.spec().width;
  t.file_height = src.spec().height;
  if (t.file_width < 1 || t.file_height < 1) throw Error(name + ": the image is empty");
  const int nw = next_power_of_two(t.file_width), nh = next_power_of_two(t.file_height);
  if (nw != t.file_width || nh != t.file_height) {
    const int nch = src.spec().nchannels;
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(src, "", 0, OIIO::ROI(0, nw, 0, nh, 0, 1, 0, nch));
    if (resized.has_error()) throw Error(name + ": resize failed (" + resized.geterror() + ")");
    src = std::move(resized);
    t.resized = true;
  }
  t.image = rgba8_texels(src, name);
  return t;
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

  OIIO::ImageBuf src;
  read_uint8(src, spec, spec);
  const OIIO::ImageSpec& s = src.spec();
  w = s.width;
  h = s.height;
  warn_if_clamped(src, spec);
  if (!resize || (is_power_of_two(w) && is_power_of_two(h) && w <= (1 << kMaxLog2Size) && h <= (1 << kMaxLog2Size))) {
    check_texture_size(w, h, spec, "use --resize to resample");
  } else {
    const int nw = nearest_power_of_two(w), nh = nearest_power_of_two(h);
    std::fprintf(stderr, "texsim: %s: resampled %dx%d to %dx%d\n", spec.c_str(), w, h, nw, nh);
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(src, "", 0, OIIO::ROI(0, nw, 0, nh, 0, 1, 0, s.nchannels));
    if (resized.has_error()) throw Error(spec + ": resize failed (" + resized.geterror() + ")");
    src = std::move(resized);
    w = nw;
    h = nh;
  }
  return rgba8_texels(src, spec);
}

ModelTexture load_texture_pow2(const std::string& path) {
  OIIO::ImageBuf src;
  read_uint8(src, path, path);
  return pow2_texture(src, path);
}

ModelTexture decode_texture_pow2(const std::string& name, const void* data, size_t size,
                                 const std::string& format_hint) {
  // OpenImageIO picks the reader by the name's extension: take it from the bytes when they say.
  const auto* b = static_cast<const unsigned char*>(data);
  std::string ext = format_hint.empty() ? "png" : format_hint;
  if (size >= 8 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) ext = "png";
  else if (size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) ext = "jpg";
  OIIO::Filesystem::IOMemReader proxy(data, size);
  OIIO::ImageBuf src;
  read_uint8(src, name, "embedded." + ext, &proxy);
  return pow2_texture(src, name);
}

ModelTexture texture_pow2(const std::string& name, Image rgba8) {
  const int w = rgba8.width, h = rgba8.height;
  if (w > 0 && h > 0 && next_power_of_two(w) == w && next_power_of_two(h) == h) return {std::move(rgba8), w, h, false};
  std::vector<uint8_t> pixels(rgba8.texels.size() * 4);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(rgba8.texels[i / 4][i % 4]);
  OIIO::ImageBuf src(OIIO::ImageSpec(rgba8.width, rgba8.height, 4, OIIO::TypeDesc::UINT8));
  src.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, pixels.data());
  return pow2_texture(src, name);
}

void check_image_path(const std::string& path) {
  if (path == "-") throw Error("-: images cannot go to standard output; give a file name");
  if (!OIIO::ImageOutput::create(path))
    throw Error(path + ": no image writer for this file type (use .png, .tif, .exr, ...)");
}

void save_image(const Image& img, const OutputFile& out) {
  std::vector<uint8_t> pixels(img.texels.size() * 4);
  const int shift = std::max(0, img.channel_bits - 8);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) pixels[i * 4 + c] = uint8_t(img.texels[i][c] >> shift);
  auto writer = OIIO::ImageOutput::create(out.path());  // the format of the name the user gave
  if (!writer) throw Error(out.path() + ": no image writer for this file type");
  OIIO::ImageSpec spec(img.width, img.height, 4, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // write the texels as they are, no un-premultiply
  if (!writer->open(out.write_path(), spec) || !writer->write_image(OIIO::TypeDesc::UINT8, pixels.data()) ||
      !writer->close())
    throw Error(out.path() + ": cannot write image (" + writer->geterror() + ")");
}

}  // namespace tex
