// Texture files and pictures: the only place image files are read or written: PNG and JPEG through
// libpng and libjpeg (workloads/png_jpeg.h), everything else through the image module
// (OpenImageIO, loaded on first use: workloads/image_module.h).
#include "workloads/texture_io.h"

#include <dlfcn.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>

#include "model/error.h"
#include "workloads/image_module.h"
#include "workloads/limits.h"
#include "workloads/png_jpeg.h"
#include "workloads/query_trace.h"

namespace tex {

namespace images {

// The module next to the executable, else where this build put it (tests run from other folders).
const Module& module() {
  static const Module* loaded = nullptr;
  static std::once_flag once;
  static std::string error;
  std::call_once(once, [] {
    std::vector<std::string> candidates;
    if (const char* env = std::getenv("TEXSIM_IMAGE_MODULE"); env && *env) {
      candidates.push_back(env);
    } else {
      std::error_code ec;
      const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
      if (!ec) candidates.push_back((self.parent_path() / "libtexsim_images.so").string());
      candidates.push_back(TEXSIM_IMAGE_MODULE_PATH);
    }
    for (const std::string& path : candidates) {
      std::error_code ec;
      if (!std::filesystem::exists(path, ec)) continue;
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        error = path + ": cannot load the image module (" + dlerror() + ")";
        return;
      }
      auto entry = reinterpret_cast<const Module* (*)()>(dlsym(handle, "texsim_images_module"));
      if (!entry) {
        error = path + ": not texsim's image module (no texsim_images_module)";
        return;
      }
      loaded = entry();
      return;
    }
    error = "the image module libtexsim_images.so is missing (looked in " + candidates.front() +
            (candidates.size() > 1 ? " and " + candidates.back() : std::string()) + "; TEXSIM_IMAGE_MODULE names another)";
  });
  if (!loaded) throw Error(error);
  return *loaded;
}

}  // namespace images

namespace {

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
void warn_if_clamped(const images::Pixels& p, const std::string& file) {
  if (!p.floating_point) return;
  size_t outside = 0, total = 0;
  float lo = 0, hi = 1;
  if (images::module().float_range(file, outside, total, lo, hi) && outside > 0)
    std::fprintf(stderr, "texsim: %s: %zu of %zu values are outside 0..1 (%g to %g) and were clamped to 8 bits\n",
                 file.c_str(), outside, total, double(lo), double(hi));
}

// Reads the first subimage as 8 bits per channel, from `file` or from `size` bytes at `data`
// (then `file` only names the format by its extension).
images::Pixels read_uint8(const std::string& name, const std::string& file, const void* data = nullptr,
                          size_t size = 0) {
  images::Pixels p;
  std::string error;
  // PNG and JPEG directly; anything else, or a file they find broken, through OpenImageIO (whose
  // messages are the ones users know).
  const uint64_t max_bytes = memory_limit();
  const images::Direct direct = images::read_png_or_jpeg(file, data, size, max_bytes, p, error);
  if (direct == images::Direct::Read) return p;
  if (direct == images::Direct::TooLarge) throw Error(name + ": " + error);
  if (!images::module().read(file, data, size, max_bytes, p, error)) throw Error(name + ": " + error);
  return p;
}

void resize_pixels(images::Pixels& p, int w, int h, const std::string& name) {
  std::string error;
  if (!images::module().resize(p, w, h, error)) throw Error(name + ": " + error);
}

// The pixels as RGBA8 texels: gray -> RGB, a missing alpha -> opaque.
Image rgba8_texels(const images::Pixels& p) {
  const int nch = p.channels;
  Image img(p.width, p.height);
  for (size_t i = 0; i < img.texels.size(); ++i) {
    const uint8_t* v = &p.values[i * size_t(nch)];
    Texel& t = img.texels[i];
    if (nch >= 3) t = {v[0], v[1], v[2], uint16_t(nch >= 4 ? v[3] : 255)};
    else t = {v[0], v[0], v[0], uint16_t(nch == 2 ? v[1] : 255)};  // gray (+ alpha)
  }
  return img;
}

// A model's texture keeps its size (every engine samples any size); a side beyond 8192, which no
// unit holds, is resampled down to 8192 (the caller notes it).
ModelTexture model_texture_of(images::Pixels& p, const std::string& name) {
  ModelTexture t;
  t.file_width = p.width;
  t.file_height = p.height;
  if (t.file_width < 1 || t.file_height < 1) throw Error(name + ": the image is empty");
  const int nw = std::min(t.file_width, kMaxSize), nh = std::min(t.file_height, kMaxSize);
  if (nw != t.file_width || nh != t.file_height) {
    resize_pixels(p, nw, nh, name);
    t.resized = true;
  }
  t.image = rgba8_texels(p);
  return t;
}

int nearest_power_of_two(int n) {
  int p = 1;
  while (p < n && p < (1 << kMaxLog2Size)) p <<= 1;
  if (p > 1 && (p - n) > (n - p / 2)) p >>= 1;
  return p;
}

}  // namespace

bool is_pattern_spec(const std::string& spec) {
  std::string name;
  int w = 0, h = 0;
  return parse_pattern_spec(spec, name, w, h);
}

Image load_texture(const std::string& spec, bool resize) {
  std::string name;
  int w = 0, h = 0;
  if (!std::filesystem::exists(spec) && parse_pattern_spec(spec, name, w, h)) return make_pattern(name, w, h);
  if (!std::filesystem::exists(spec)) throw Error(spec + ": no such file or built-in pattern");

  images::Pixels p = read_uint8(spec, spec);
  w = p.width;
  h = p.height;
  warn_if_clamped(p, spec);
  if (!resize || (is_power_of_two(w) && is_power_of_two(h) && w <= (1 << kMaxLog2Size) && h <= (1 << kMaxLog2Size))) {
    check_texture_size(w, h, spec, "use --resize to resample");
  } else {
    const int nw = nearest_power_of_two(w), nh = nearest_power_of_two(h);
    std::fprintf(stderr, "texsim: %s: resampled %dx%d to %dx%d\n", spec.c_str(), w, h, nw, nh);
    resize_pixels(p, nw, nh, spec);
    w = nw;
    h = nh;
  }
  return rgba8_texels(p);
}

ModelTexture load_model_texture(const std::string& path) {
  images::Pixels p = read_uint8(path, path);
  return model_texture_of(p, path);
}

ModelTexture decode_model_texture(const std::string& name, const void* data, size_t size,
                                 const std::string& format_hint) {
  // OpenImageIO picks the reader by the name's extension: take it from the bytes when they say.
  const auto* b = static_cast<const unsigned char*>(data);
  std::string ext = format_hint.empty() ? "png" : format_hint;
  if (size >= 8 && std::memcmp(b, "\x89PNG\r\n\x1a\n", 8) == 0) ext = "png";
  else if (size >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF) ext = "jpg";
  images::Pixels p = read_uint8(name, "embedded." + ext, data, size);
  return model_texture_of(p, name);
}

ModelTexture model_texture(const std::string& name, Image rgba8) {
  const int w = rgba8.width, h = rgba8.height;
  if (w > 0 && h > 0 && w <= kMaxSize && h <= kMaxSize) return {std::move(rgba8), w, h, false};
  images::Pixels p;
  p.width = w;
  p.height = h;
  p.channels = 4;
  p.values.resize(rgba8.texels.size() * 4);
  for (size_t i = 0; i < p.values.size(); ++i) p.values[i] = uint8_t(rgba8.texels[i / 4][i % 4]);
  return model_texture_of(p, name);
}

void check_image_path(const std::string& path) {
  if (path == "-") throw Error("-: images cannot go to standard output; give a file name");
  if (!images::is_png_path(path) && !images::module().can_write(path))
    throw Error(path + ": no image writer for this file type (use .png, .tif, .exr, ...)");
}

void save_image(const Image& img, const OutputFile& out) {
  images::Pixels p;
  p.width = img.width;
  p.height = img.height;
  p.channels = 4;
  p.values.resize(img.texels.size() * 4);
  const int shift = std::max(0, img.channel_bits - 8);
  for (size_t i = 0; i < img.texels.size(); ++i)
    for (int c = 0; c < 4; ++c) p.values[i * 4 + size_t(c)] = uint8_t(img.texels[i][size_t(c)] >> shift);
  std::string error;
  const bool ok = images::is_png_path(out.path()) ? images::write_png(out.write_path(), p, error)
                                                  : images::module().write(out.path(), out.write_path(), p, error);
  if (!ok) throw Error(out.path() + ": " + error);
}

}  // namespace tex
