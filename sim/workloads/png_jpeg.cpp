// PNG and JPEG through libpng and libjpeg (png_jpeg.h). Both libraries report errors by longjmp:
// each call that can fail sits in a small function of its own that holds no C++ object, and the
// buffers those calls fill are allocated by the caller between them.
#include "workloads/png_jpeg.h"

#include <jpeglib.h>
#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <vector>

#include "workloads/limits.h"

namespace tex::images {

namespace {

// ---------------------------------------------------------------- PNG

struct PngContext {
  const unsigned char* data = nullptr;  // bytes in memory (else the FILE set by png_init_io)
  size_t size = 0, at = 0;
  char message[256] = {};
};

void png_fail(png_structp png, png_const_charp text) {
  auto* c = static_cast<PngContext*>(png_get_error_ptr(png));
  std::snprintf(c->message, sizeof c->message, "%s", text);
  png_longjmp(png, 1);
}
void png_quiet(png_structp, png_const_charp) {}  // warnings: not for the user

// The refusal of an image too large for the limit.
std::string too_large(const char* format, uint64_t w, uint64_t h, int channels, uint64_t max_bytes) {
  return std::string(format) + " of " + std::to_string(w) + " x " + std::to_string(h) + " pixels needs " +
         memory_words(decoded_image_bytes(w, h, channels)) + " once read, more than --max-memory allows (" +
         memory_words(max_bytes) + ")";
}

void png_from_memory(png_structp png, png_bytep out, size_t n) {
  auto* c = static_cast<PngContext*>(png_get_io_ptr(png));
  if (n > c->size - c->at) png_error(png, "the PNG data ends early");
  std::memcpy(out, c->data + c->at, n);
  c->at += n;
}

struct PngShape {
  png_uint_32 width = 0, height = 0;
  int channels = 0;
  bool sixteen_bits = false;
};

// The header, and the transforms to 8-bit gray, gray-alpha, RGB or RGBA as OpenImageIO sets them.
bool png_begin(png_structp png, png_infop info, PngShape* shape) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_info(png, info);
  const int depth = png_get_bit_depth(png, info), colour = png_get_color_type(png, info);
  if (depth == 16) {
    shape->sixteen_bits = true;
    return true;
  }
  if (colour == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (colour == PNG_COLOR_TYPE_GRAY && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  shape->width = png_get_image_width(png, info);
  shape->height = png_get_image_height(png, info);
  shape->channels = png_get_channels(png, info);
  return true;
}

bool png_rows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  return true;
}

Direct read_png(std::FILE* file, const void* data, size_t size, uint64_t max_bytes, Pixels& out, std::string& error) {
  PngContext ctx;
  ctx.data = static_cast<const unsigned char*>(data);
  ctx.size = size;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &ctx, png_fail, png_quiet);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  if (!info) {
    png_destroy_read_struct(&png, nullptr, nullptr);
    error = "out of memory";
    return Direct::Broken;
  }
  png_set_user_limits(png, 1u << 16, 1u << 16);
  if (file) png_init_io(png, file);
  else png_set_read_fn(png, &ctx, png_from_memory);
  PngShape shape;
  Direct result = Direct::Broken;
  if (png_begin(png, info, &shape)) {
    if (shape.sixteen_bits) {
      result = Direct::NotMine;  // (OpenImageIO's 16-to-8-bit conversion is its own)
    } else if (decoded_image_bytes(shape.width, shape.height, shape.channels) > max_bytes) {
      error = too_large("PNG", shape.width, shape.height, shape.channels, max_bytes);
      result = Direct::TooLarge;
    } else if (png_get_rowbytes(png, info) != size_t(shape.width) * size_t(shape.channels)) {
      std::snprintf(ctx.message, sizeof ctx.message, "unexpected row size");
    } else {
      out.width = int(shape.width);
      out.height = int(shape.height);
      out.channels = shape.channels;
      out.floating_point = false;
      out.values.assign(size_t(shape.width) * shape.height * size_t(shape.channels), 0);
      std::vector<png_bytep> rows(shape.height);
      for (png_uint_32 y = 0; y < shape.height; ++y)
        rows[y] = out.values.data() + size_t(y) * shape.width * size_t(shape.channels);
      if (png_rows(png, rows.data())) result = Direct::Read;
    }
  }
  png_destroy_read_struct(&png, &info, nullptr);
  if (result == Direct::Broken) error = std::string("PNG: ") + ctx.message;
  return result;
}

// ---------------------------------------------------------------- JPEG

struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
};

void jpeg_fail(j_common_ptr c) {
  auto* e = reinterpret_cast<JpegError*>(c->err);
  (*c->err->format_message)(c, e->message);
  std::longjmp(e->jump, 1);
}
void jpeg_quiet(j_common_ptr, int) {}  // warnings and trace messages: not for the user

struct JpegShape {
  JDIMENSION width = 0, height = 0;
  int channels = 0;
  bool mine = true;
};

bool jpeg_begin(jpeg_decompress_struct* c, JpegError* e, std::FILE* file, const void* data, size_t size,
                JpegShape* shape) {
  if (setjmp(e->jump)) return false;
  if (file) jpeg_stdio_src(c, file);
  else jpeg_mem_src(c, static_cast<const unsigned char*>(data), static_cast<unsigned long>(size));
  jpeg_read_header(c, TRUE);
  if (c->jpeg_color_space == JCS_GRAYSCALE) {
    c->out_color_space = JCS_GRAYSCALE;
  } else if (c->jpeg_color_space == JCS_YCbCr || c->jpeg_color_space == JCS_RGB) {
    c->out_color_space = JCS_RGB;
  } else {
    shape->mine = false;  // CMYK, YCCK: OpenImageIO's conversion
    return true;
  }
  jpeg_start_decompress(c);
  shape->width = c->output_width;
  shape->height = c->output_height;
  shape->channels = c->output_components;
  return true;
}

bool jpeg_rows(jpeg_decompress_struct* c, JpegError* e, unsigned char* pixels, size_t stride) {
  if (setjmp(e->jump)) return false;
  while (c->output_scanline < c->output_height) {
    JSAMPROW row = pixels + size_t(c->output_scanline) * stride;
    jpeg_read_scanlines(c, &row, 1);
  }
  return true;
}

Direct read_jpeg(std::FILE* file, const void* data, size_t size, uint64_t max_bytes, Pixels& out, std::string& error) {
  jpeg_decompress_struct c;
  JpegError e;
  c.err = jpeg_std_error(&e.manager);
  e.manager.error_exit = jpeg_fail;
  e.manager.emit_message = jpeg_quiet;
  jpeg_create_decompress(&c);
  JpegShape shape;
  Direct result = Direct::Broken;
  if (jpeg_begin(&c, &e, file, data, size, &shape)) {
    if (!shape.mine) {
      result = Direct::NotMine;
    } else if (decoded_image_bytes(shape.width, shape.height, shape.channels) > max_bytes) {
      error = too_large("JPEG", shape.width, shape.height, shape.channels, max_bytes);
      result = Direct::TooLarge;
    } else {
      out.width = int(shape.width);
      out.height = int(shape.height);
      out.channels = shape.channels;
      out.floating_point = false;
      const size_t stride = size_t(shape.width) * size_t(shape.channels);
      out.values.assign(stride * shape.height, 0);
      if (jpeg_rows(&c, &e, out.values.data(), stride)) result = Direct::Read;
    }
  }
  jpeg_destroy_decompress(&c);
  if (result == Direct::Broken) error = std::string("JPEG: ") + e.message;
  return result;
}

bool png_write_all(png_structp png, png_infop info, png_bytepp rows, png_uint_32 w, png_uint_32 h) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_IHDR(png, info, w, h, 8, PNG_COLOR_TYPE_RGBA, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

bool ends_with_ci(const std::string& s, const char* suffix) {
  const size_t n = std::strlen(suffix);
  if (s.size() < n) return false;
  for (size_t i = 0; i < n; ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - n + i])) != suffix[i]) return false;
  return true;
}

}  // namespace

Direct read_png_or_jpeg(const std::string& file, const void* data, size_t size, uint64_t max_bytes, Pixels& out,
                        std::string& error) {
  unsigned char head[8] = {};
  size_t have = 0;
  std::FILE* f = nullptr;
  if (data) {
    have = std::min<size_t>(size, 8);
    std::memcpy(head, data, have);
  } else {
    f = std::fopen(file.c_str(), "rb");
    if (!f) return Direct::NotMine;  // (the image module names the problem)
    have = std::fread(head, 1, 8, f);
    std::rewind(f);
  }
  Direct result = Direct::NotMine;
  if (have == 8 && std::memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0) result = read_png(f, data, size, max_bytes, out, error);
  else if (have >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF) result = read_jpeg(f, data, size, max_bytes, out, error);
  if (f) std::fclose(f);
  return result;
}

bool write_png(const std::string& path, const Pixels& pixels, std::string& error) {
  if (pixels.channels != 4) {
    error = "write_png takes RGBA8";
    return false;
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) {
    error = "cannot open for writing: " + std::string(std::strerror(errno));
    return false;
  }
  PngContext ctx;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &ctx, png_fail, png_quiet);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  bool ok = info != nullptr;
  if (ok) {
    png_init_io(png, f);
    std::vector<png_bytep> rows(size_t(pixels.height));
    for (int y = 0; y < pixels.height; ++y)
      rows[size_t(y)] = const_cast<png_bytep>(pixels.values.data() + size_t(y) * size_t(pixels.width) * 4);
    ok = png_write_all(png, info, rows.data(), png_uint_32(pixels.width), png_uint_32(pixels.height));
    if (!ok) error = std::string("PNG: ") + ctx.message;
  } else {
    error = "out of memory";
  }
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0 && ok) {
    error = "cannot write: " + std::string(std::strerror(errno));
    ok = false;
  }
  return ok;
}

bool is_png_path(const std::string& path) { return ends_with_ci(path, ".png"); }

}  // namespace tex::images
