// The image module: OpenImageIO behind image_module.h's plain buffers, and Mesa's BC7 encoder
// (built as libtexsim_images.so; texture_io.cpp loads it on first use).
#include "workloads/image_module.h"
#include "workloads/limits.h"

#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <dlfcn.h>

#include <algorithm>
#include <cstdio>
#include <fcntl.h>
#include <type_traits>
#include <unistd.h>

namespace {

namespace OIIO = OIIO_NAMESPACE;
using tex::images::Pixels;

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

std::string one_line(std::string s) {
  std::replace(s.begin(), s.end(), '\n', ' ');
  return s;
}

bool to_pixels(const OIIO::ImageBuf& src, Pixels& out, std::string& error) {
  out.width = src.spec().width;
  out.height = src.spec().height;
  out.channels = src.spec().nchannels;
  out.values.assign(size_t(out.width) * out.height * out.channels, 0);
  if (!src.get_pixels(OIIO::ROI(0, out.width, 0, out.height, 0, 1, 0, out.channels), OIIO::TypeDesc::UINT8,
                      out.values.data())) {
    error = "cannot read pixels (" + one_line(src.geterror()) + ")";
    return false;
  }
  return true;
}

bool read(const std::string& file, const void* data, size_t size, uint64_t max_bytes, Pixels& out,
          std::string& error) {
  try {
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    std::unique_ptr<OIIO::Filesystem::IOMemReader> proxy;
    if (data) proxy = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<void*>(data), size);
    OIIO::ImageBuf src;
    bool ok;
    {
      QuietStderr quiet;
      src.reset(file, 0, 0, nullptr, &config, proxy.get());
      ok = src.init_spec(file, 0, 0);  // the header alone
      const OIIO::ImageSpec& spec = src.spec();
      const uint64_t w = uint64_t(std::max(spec.width, 0)), h = uint64_t(std::max(spec.height, 0)),
                     depth = uint64_t(std::max(spec.depth, 1));
      // (OpenImageIO reads the native values first: up to 4 bytes a channel beside the 8-bit ones)
      const uint64_t needed = tex::decoded_image_bytes(w, h * depth, 4 * std::max(spec.nchannels, 1));
      if (ok && needed > max_bytes) {
        error = "an image of " + std::to_string(w) + " x " + std::to_string(h) +
                (depth > 1 ? " x " + std::to_string(depth) : "") + " pixels needs " + tex::memory_words(needed) +
                " once read, more than --max-memory allows (" + tex::memory_words(max_bytes) + ")";
        return false;
      }
      ok = ok && src.read(0, 0, true, OIIO::TypeDesc::UINT8);
    }
    if (!ok) {
      error = "cannot read image (" + one_line(src.geterror()) + ")";
      return false;
    }
    out.floating_point = src.nativespec().format.is_floating_point();
    return to_pixels(src, out, error);
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool float_range(const std::string& file, size_t& outside, size_t& total, float& low, float& high) {
  outside = total = 0;
  low = 0;
  high = 1;
  try {
    OIIO::ImageBuf f(file);
    if (!f.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return false;
    const OIIO::ImageSpec& s = f.spec();
    std::vector<float> values(size_t(s.width) * s.height * s.nchannels);
    if (!f.get_pixels(OIIO::ROI(0, s.width, 0, s.height, 0, 1, 0, s.nchannels), OIIO::TypeDesc::FLOAT, values.data()))
      return false;
    total = values.size();
    for (float v : values) {
      outside += v < 0.0f || v > 1.0f;
      low = std::min(low, v);
      high = std::max(high, v);
    }
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

bool resize(Pixels& p, int w, int h, std::string& error) {
  try {
    OIIO::ImageBuf src(OIIO::ImageSpec(p.width, p.height, p.channels, OIIO::TypeDesc::UINT8));
    src.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::UINT8, p.values.data());
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(src, "", 0, OIIO::ROI(0, w, 0, h, 0, 1, 0, p.channels));
    if (resized.has_error()) {
      error = "resize failed (" + one_line(resized.geterror()) + ")";
      return false;
    }
    const bool floating = p.floating_point;
    if (!to_pixels(resized, p, error)) return false;
    p.floating_point = floating;
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

bool can_write(const std::string& path) {
  try {
    return OIIO::ImageOutput::create(path) != nullptr;
  } catch (const std::exception&) {
    return false;
  }
}

bool write(const std::string& format_path, const std::string& write_path, const Pixels& p, std::string& error) {
  try {
    auto writer = OIIO::ImageOutput::create(format_path);  // the format of the name the user gave
    if (!writer) {
      error = "no image writer for this file type";
      return false;
    }
    OIIO::ImageSpec spec(p.width, p.height, p.channels, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:UnassociatedAlpha", 1);  // write the texels as they are, no un-premultiply
    if (!writer->open(write_path, spec) || !writer->write_image(OIIO::TypeDesc::UINT8, p.values.data()) ||
        !writer->close()) {
      error = "cannot write image (" + one_line(writer->geterror()) + ")";
      return false;
    }
    return true;
  } catch (const std::exception& e) {
    error = e.what();
    return false;
  }
}

// Mesa, loaded on the first BC7 encoding only: libOSMesa brings LLVM (llvmpipe), some 100 MB that
// no other image operation needs.
struct Mesa {
  decltype(&OSMesaCreateContextExt) create_context = nullptr;
  decltype(&OSMesaMakeCurrent) make_current = nullptr;
  decltype(&glGenTextures) gen_textures = nullptr;
  decltype(&glBindTexture) bind_texture = nullptr;
  decltype(&glPixelStorei) pixel_store = nullptr;
  decltype(&glTexImage2D) tex_image = nullptr;
  decltype(&glGetTexLevelParameteriv) level_parameter = nullptr;
  decltype(&glGetError) get_error = nullptr;
  decltype(&glGetCompressedTexImage) get_compressed = nullptr;
  decltype(&glDeleteTextures) delete_textures = nullptr;
  std::string error;  // why it could not be loaded (empty: loaded)
};

const Mesa& mesa() {
  static const Mesa loaded = [] {
    Mesa m;
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
      m.error = std::string("cannot load Mesa's libOSMesa, the BC7 encoder (") + dlerror() + ")";
      return m;
    }
    auto find = [&](auto& f, const char* name) {
      f = reinterpret_cast<std::remove_reference_t<decltype(f)>>(dlsym(lib, name));
      if (!f && m.error.empty()) m.error = std::string("libOSMesa has no ") + name;
    };
    find(m.create_context, "OSMesaCreateContextExt");
    find(m.make_current, "OSMesaMakeCurrent");
    find(m.gen_textures, "glGenTextures");
    find(m.bind_texture, "glBindTexture");
    find(m.pixel_store, "glPixelStorei");
    find(m.tex_image, "glTexImage2D");
    find(m.level_parameter, "glGetTexLevelParameteriv");
    find(m.get_error, "glGetError");
    find(m.get_compressed, "glGetCompressedTexImage");
    find(m.delete_textures, "glDeleteTextures");
    return m;
  }();
  return loaded;
}

bool compress_bc7(const Pixels& p, std::vector<uint8_t>& blocks, std::string& error) {
  const Mesa& gl = mesa();
  if (!gl.error.empty()) {
    error = gl.error;
    return false;
  }
  // One off-screen context for the process: Mesa compresses what glTexImage2D is given when the
  // internal format is a compressed one.
  static std::vector<uint8_t> surface(4 * 4 * 4);
  static OSMesaContext context = gl.create_context(OSMESA_RGBA, 0, 0, 0, nullptr);
  if (!context || !gl.make_current(context, surface.data(), GL_UNSIGNED_BYTE, 4, 4)) {
    error = "cannot create an OSMesa context for Mesa's BC7 encoder";
    return false;
  }
  if (p.channels != 4) {
    error = "BC7 encoding takes RGBA8";
    return false;
  }
  GLuint texture = 0;
  gl.gen_textures(1, &texture);
  gl.bind_texture(GL_TEXTURE_2D, texture);
  gl.pixel_store(GL_UNPACK_ALIGNMENT, 1);
  gl.tex_image(GL_TEXTURE_2D, 0, GL_COMPRESSED_RGBA_BPTC_UNORM, p.width, p.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
               p.values.data());
  GLint compressed = 0, size = 0;
  gl.level_parameter(GL_TEXTURE_2D, 0, GL_TEXTURE_COMPRESSED, &compressed);
  gl.level_parameter(GL_TEXTURE_2D, 0, GL_TEXTURE_COMPRESSED_IMAGE_SIZE, &size);
  const size_t want = size_t((p.width + 3) / 4) * size_t((p.height + 3) / 4) * 16;
  bool ok = gl.get_error() == GL_NO_ERROR && compressed && size_t(size) == want;
  if (ok) {
    blocks.resize(want);
    gl.pixel_store(GL_PACK_ALIGNMENT, 1);
    gl.get_compressed(GL_TEXTURE_2D, 0, blocks.data());
    ok = gl.get_error() == GL_NO_ERROR;
  }
  gl.delete_textures(1, &texture);
  if (!ok) error = "Mesa did not compress the level to BC7 (" + std::to_string(size) + " bytes)";
  return ok;
}

const tex::images::Module kModule = {read, float_range, resize, can_write, write, compress_bc7};

}  // namespace

extern "C" const tex::images::Module* texsim_images_module() { return &kModule; }
