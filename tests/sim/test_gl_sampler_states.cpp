// Sampler state against OpenGL: Mesa's llvmpipe (OSMesa, a GL 3.3 core context) samples the
// model's own pyramid (every level uploaded, so both filter the same texels) with textureLod in a
// fragment shader, one query per pixel, under each sampler state: magnification and minification
// filters apart, mipmap modes, the five address modes per axis and border colours (named and
// custom, on RGBA8 and sRGB textures, with sides that are powers of two and sides that are not:
// odd, so the repeat seams of odd levels and the area-mean pyramid are compared too). The golden model samples the same queries; the two must
// agree within the precision GLES 3.0 allows an RGBA8 texture (4 LSB for filtered lookups, the
// conformance suite's threshold): here at most 2 LSB (8-bit steps of full scale), 0.3 on average,
// and nearest filters exact, away from texel and level edges. Unnormalized coordinates are
// compared with GL's rectangle textures (sampler2DRect: texel coordinates, level 0 only).
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "gl_shader.h"
#include "model/image.h"
#include "model/sampler.h"
#include "model/srgb.h"

using namespace tex;

namespace {

constexpr int kW = 128, kH = 64;  // one query per pixel

GLint gl_wrap(Wrap w) {
  switch (w) {
    case Wrap::Repeat: return GL_REPEAT;
    case Wrap::Clamp: return GL_CLAMP_TO_EDGE;
    case Wrap::Mirror: return GL_MIRRORED_REPEAT;
    case Wrap::Border: return GL_CLAMP_TO_BORDER;
    case Wrap::MirrorClamp: return GL_MIRROR_CLAMP_TO_EDGE;
  }
  return GL_REPEAT;
}

GLint gl_min_filter(Filter f) {
  const bool lin = f.texel == TexelFilter::Linear;
  switch (f.mip) {
    case MipMode::None: return lin ? GL_LINEAR : GL_NEAREST;
    case MipMode::Nearest: return lin ? GL_LINEAR_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_NEAREST;
    case MipMode::Linear: return lin ? GL_LINEAR_MIPMAP_LINEAR : GL_NEAREST_MIPMAP_LINEAR;
  }
  return GL_LINEAR;
}

// A program of the two shaders, its sampler `tex` on texture unit `unit` and `queries` on unit 1.
GLuint link(const char* vs, const char* fs, GLint unit) {
  const GLuint p = glCreateProgram();
  glAttachShader(p, compile_shader(GL_VERTEX_SHADER, vs));
  glAttachShader(p, compile_shader(GL_FRAGMENT_SHADER, fs));
  glLinkProgram(p);
  glUseProgram(p);
  glUniform1i(glGetUniformLocation(p, "tex"), unit);
  glUniform1i(glGetUniformLocation(p, "queries"), 1);
  return p;
}

// A GL 3.3 core context on llvmpipe drawing into a kW x kH RGBA32F framebuffer object, and the
// program: every fragment samples `tex` at the (u, v, lambda) of its pixel in `queries`.
class GlSampling {
 public:
  GlSampling() {
    setenv("GALLIUM_DRIVER", "llvmpipe", 1);
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, 3, OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    ctx_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_ || !OSMesaMakeCurrent(ctx_, window_.data(), GL_UNSIGNED_BYTE, kW, kH)) return;
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glGenRenderbuffers(1, &colour_);
    glBindRenderbuffer(GL_RENDERBUFFER, colour_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, kW, kH);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
    const char* vs = R"(#version 330 core
      void main() {  // a triangle that covers the viewport
        vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
        gl_Position = vec4(p, 0.0, 1.0);
      })";
    const char* fs = R"(#version 330 core
      uniform sampler2D tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = textureLod(tex, q.xy, q.z);
      })";
    program_ = link(vs, fs, 0);
    const char* rect_fs = R"(#version 330 core
      uniform sampler2DRect tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {  // texel coordinates of the base level
        colour = texture(tex, texelFetch(queries, ivec2(gl_FragCoord.xy), 0).xy);
      })";
    rect_program_ = link(vs, rect_fs, 2);
    glGenTextures(1, &rect_);
    const char* fetch_fs = R"(#version 330 core
      uniform sampler2D tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {  // texel (i, j) of level k
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = texelFetch(tex, ivec2(q.xy), int(q.z));
      })";
    fetch_program_ = link(vs, fetch_fs, 0);
    const char* gather_fs = R"(#version 400 core
      uniform sampler2D tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {  // component q.z of the four texels at (u, v) (the component must be a constant)
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        int c = int(q.z);
        colour = c == 0 ? textureGather(tex, q.xy, 0) : c == 1 ? textureGather(tex, q.xy, 1)
               : c == 2 ? textureGather(tex, q.xy, 2) : textureGather(tex, q.xy, 3);
      })";
    gather_program_ = link(vs, gather_fs, 0);
    // The same three on an array texture (unit 3): the query's w is the layer coordinate of a
    // sample, the integer layer of a fetch; a gather's layer is its z, the component its w.
    const char* array_fs = R"(#version 330 core
      uniform sampler2DArray tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = textureLod(tex, q.xyw, q.z);
      })";
    array_program_ = link(vs, array_fs, 3);
    const char* array_fetch_fs = R"(#version 330 core
      uniform sampler2DArray tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = texelFetch(tex, ivec3(q.xyw), int(q.z));
      })";
    array_fetch_program_ = link(vs, array_fetch_fs, 3);
    const char* array_gather_fs = R"(#version 400 core
      uniform sampler2DArray tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        int c = int(q.w);
        colour = c == 0 ? textureGather(tex, q.xyz, 0) : c == 1 ? textureGather(tex, q.xyz, 1)
               : c == 2 ? textureGather(tex, q.xyz, 2) : textureGather(tex, q.xyz, 3);
      })";
    array_gather_program_ = link(vs, array_gather_fs, 3);
    glGenTextures(1, &array_);
    // A shadow lookup (unit 4): textureLod of a sampler2DShadow at (u, v) with reference q.w, level q.z.
    const char* shadow_fs = R"(#version 330 core
      uniform sampler2DShadow tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = vec4(textureLod(tex, vec3(q.xy, q.w), q.z), 0.0, 0.0, 1.0);
      })";
    shadow_program_ = link(vs, shadow_fs, 4);
    glGenTextures(1, &depth_);
    // A cube map (unit 5), seamless: textureLod at direction q.xyz, level q.w; textureGrad with the
    // derivatives of a second query texture (unit 6).
    const char* cube_fs = R"(#version 330 core
      uniform samplerCube tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = textureLod(tex, q.xyz, q.w);
      })";
    cube_program_ = link(vs, cube_fs, 5);
    // A cube array (unit 7): direction q.xyz, cube q.w, level `lod`.
    const char* cube_array_fs = R"(#version 400 core
      uniform samplerCubeArray tex;
      uniform sampler2D queries;
      uniform float lod;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = textureLod(tex, q, lod);
      })";
    cube_array_program_ = link(vs, cube_array_fs, 7);
    // A cube map's textureGather (unit 5, the cube above) of component `comp` at direction q.xyz.
    const char* cube_gather_fs = R"(#version 400 core
      uniform samplerCube tex;
      uniform sampler2D queries;
      uniform int comp;
      out vec4 colour;
      void main() {
        vec3 d = texelFetch(queries, ivec2(gl_FragCoord.xy), 0).xyz;
        colour = comp == 0 ? textureGather(tex, d, 0) : comp == 1 ? textureGather(tex, d, 1)
               : comp == 2 ? textureGather(tex, d, 2) : textureGather(tex, d, 3);
      })";
    cube_gather_program_ = link(vs, cube_gather_fs, 5);
    // A depth cube's shadow lookup (unit 8, samplerCubeShadow) at direction q.xyz with reference q.w,
    // level 0 (zero gradients: the magnification filter).
    const char* cube_shadow_fs = R"(#version 330 core
      uniform samplerCubeShadow tex;
      uniform sampler2D queries;
      out vec4 colour;
      void main() {
        vec4 q = texelFetch(queries, ivec2(gl_FragCoord.xy), 0);
        colour = vec4(textureGrad(tex, q, vec3(0.0), vec3(0.0)), 0.0, 0.0, 1.0);
      })";
    cube_shadow_program_ = link(vs, cube_shadow_fs, 8);
    glGenTextures(1, &cube_depth_);
    glGenTextures(1, &cube_array_);
    glGenTextures(1, &cube_);
    glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    glGenVertexArrays(1, &vao_);
    glBindVertexArray(vao_);
    glGenTextures(1, &tex_);
    glGenTextures(1, &queries_);
    ready_ = glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
  }
  ~GlSampling() {
    if (ctx_) OSMesaDestroyContext(ctx_);
  }
  bool ready() const { return ready_; }

  // Every level of the pyramid as stored (8-bit codes; sRGB8_ALPHA8 for an sRGB texture).
  void upload(const Pyramid& p) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const std::vector<Image>& levels = p.srgb ? p.codes : p.levels;
    for (size_t k = 0; k < levels.size(); ++k) {
      const Image& img = levels[k];
      const std::vector<uint8_t> rgba = rgba8_bytes(img);
      glTexImage2D(GL_TEXTURE_2D, GLint(k), p.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, img.width, img.height, 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, rgba.data());
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(levels.size()) - 1);
    // Level 0 as a rectangle texture too (unnormalized samplers).
    glActiveTexture(GL_TEXTURE2);
    glBindTexture(GL_TEXTURE_RECTANGLE, rect_);
    const std::vector<uint8_t> rgba = rgba8_bytes(levels[0]);
    glTexImage2D(GL_TEXTURE_RECTANGLE, 0, p.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, levels[0].width, levels[0].height, 0,
                 GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  }
  // An array texture (GL_TEXTURE_2D_ARRAY, unit 3): every level of every layer, RGBA8.
  void upload_array(const std::vector<const Pyramid*>& layers) {
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D_ARRAY, array_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t k = 0; k < layers[0]->levels.size(); ++k) {
      std::vector<uint8_t> rgba;
      for (const Pyramid* p : layers) {
        const std::vector<uint8_t> layer = rgba8_bytes(p->levels[k]);
        rgba.insert(rgba.end(), layer.begin(), layer.end());
      }
      const Image& img = layers[0]->levels[k];
      glTexImage3D(GL_TEXTURE_2D_ARRAY, GLint(k), GL_RGBA8, img.width, img.height, GLsizei(layers.size()), 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, rgba.data());
    }
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAX_LEVEL, GLint(layers[0]->levels.size()) - 1);
  }
  std::vector<std::array<float, 4>> sample_array(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(array_program_);
    apply(c, GL_TEXTURE_2D_ARRAY);
    return draw(q);
  }
  std::vector<std::array<float, 4>> fetch_array(const std::vector<std::array<float, 4>>& q) {
    glUseProgram(array_fetch_program_);
    apply(SamplerConfig{}, GL_TEXTURE_2D_ARRAY);
    return draw(q);
  }
  std::vector<std::array<float, 4>> gather_array(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(array_gather_program_);
    apply(c, GL_TEXTURE_2D_ARRAY);
    return draw(q);
  }

  // A depth texture (GL_DEPTH_COMPONENT16, unit 4): every level's R channel (16-bit codes).
  void upload_depth(const Pyramid& p) {
    glActiveTexture(GL_TEXTURE4);
    glBindTexture(GL_TEXTURE_2D, depth_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 2);
    for (size_t k = 0; k < p.levels.size(); ++k) {
      const Image& img = p.levels[k];
      std::vector<uint16_t> d;
      for (const Texel& t : img.texels) d.push_back(t[0]);
      glTexImage2D(GL_TEXTURE_2D, GLint(k), GL_DEPTH_COMPONENT16, img.width, img.height, 0, GL_DEPTH_COMPONENT,
                   GL_UNSIGNED_SHORT, d.data());
    }
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, GLint(p.levels.size()) - 1);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  }
  // A shadow lookup per query (u, v, lambda, reference) under the sampler state of `c`, its compare op.
  std::vector<std::array<float, 4>> sample_shadow(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(shadow_program_);
    apply(c, 0, true);
    static constexpr GLenum kFuncs[kCompareOps] = {GL_NEVER,   GL_LESS,     GL_EQUAL,  GL_LEQUAL,
                                                   GL_GREATER, GL_NOTEQUAL, GL_GEQUAL, GL_ALWAYS};
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_COMPARE_FUNC, kFuncs[int(c.compare_op)]);
    return draw(q);
  }

  // A cube map (unit 5): faces +X, -X, +Y, -Y, +Z, -Z, every level, RGBA8.
  void upload_cube(const std::vector<const Pyramid*>& faces) {
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int f = 0; f < 6; ++f)
      for (size_t k = 0; k < faces[size_t(f)]->levels.size(); ++k) {
        const Image& img = faces[size_t(f)]->levels[k];
        const std::vector<uint8_t> rgba = rgba8_bytes(img);
        glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), GLint(k), GL_RGBA8, img.width, img.height, 0, GL_RGBA,
                     GL_UNSIGNED_BYTE, rgba.data());
      }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, GLint(faces[0]->levels.size()) - 1);
  }
  // textureGather of `component` at each query's direction (q[0..2]) from the cube of upload_cube.
  std::vector<std::array<float, 4>> gather_cube(int component, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(cube_gather_program_);
    glUniform1i(glGetUniformLocation(cube_gather_program_, "comp"), component);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube_);
    return draw(q);
  }
  // A depth cube (unit 8): each face's level 0 as DEPTH_COMPONENT16, its R code d as d * 257.
  void upload_cube_depth(const std::vector<const Pyramid*>& faces) {
    glActiveTexture(GL_TEXTURE8);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube_depth_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int f = 0; f < 6; ++f) {
      const Image& img = faces[size_t(f)]->levels[0];
      std::vector<uint16_t> d;
      for (const Texel& t : img.texels) d.push_back(uint16_t(t[0] * 257));
      glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + f), 0, GL_DEPTH_COMPONENT16, img.width, img.height, 0,
                   GL_DEPTH_COMPONENT, GL_UNSIGNED_SHORT, d.data());
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
  }
  // A shadow lookup per query (direction q[0..2], reference q[3]) at level 0 under `c`'s
  // magnification filter and compare op.
  std::vector<std::array<float, 4>> sample_cube_shadow(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(cube_shadow_program_);
    glActiveTexture(GL_TEXTURE8);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube_depth_);
    const GLint filter = c.filter.mag == TexelFilter::Linear ? GL_LINEAR : GL_NEAREST;
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_COMPARE_FUNC, GLint(GL_NEVER + int(c.compare_op)));
    return draw(q);
  }
  // A cube array (unit 7): faces 6c + f of cube c, every level, RGBA8.
  void upload_cube_array(const std::vector<const Pyramid*>& faces) {
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, cube_array_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (size_t k = 0; k < faces[0]->levels.size(); ++k) {
      std::vector<uint8_t> rgba;
      for (const Pyramid* p : faces) {
        const std::vector<uint8_t> layer = rgba8_bytes(p->levels[k]);
        rgba.insert(rgba.end(), layer.begin(), layer.end());
      }
      const Image& img = faces[0]->levels[k];
      glTexImage3D(GL_TEXTURE_CUBE_MAP_ARRAY, GLint(k), GL_RGBA8, img.width, img.height, GLsizei(faces.size()), 0,
                   GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
    }
    glTexParameteri(GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_BASE_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_MAX_LEVEL, GLint(faces[0]->levels.size()) - 1);
  }
  // textureLod of the cube array at (x, y, z) = q.xyz of cube q.w, level `lod`, under the filters of `c`.
  std::vector<std::array<float, 4>> sample_cube_array(const SamplerConfig& c, float lod,
                                                      const std::vector<std::array<float, 4>>& q) {
    glUseProgram(cube_array_program_);
    glUniform1f(glGetUniformLocation(cube_array_program_, "lod"), lod);
    glActiveTexture(GL_TEXTURE7);
    glBindTexture(GL_TEXTURE_CUBE_MAP_ARRAY, cube_array_);
    glTexParameteri(GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_MIN_FILTER, gl_min_filter(c.filter));
    glTexParameteri(GL_TEXTURE_CUBE_MAP_ARRAY, GL_TEXTURE_MAG_FILTER, c.filter.mag == TexelFilter::Linear ? GL_LINEAR : GL_NEAREST);
    return draw(q);
  }

  // textureLod of the cube at (x, y, z) = q.xyz, level q.w, under the filters of `c`.
  std::vector<std::array<float, 4>> sample_cube(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(cube_program_);
    glActiveTexture(GL_TEXTURE5);
    glBindTexture(GL_TEXTURE_CUBE_MAP, cube_);
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, gl_min_filter(c.filter));
    glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, c.filter.mag == TexelFilter::Linear ? GL_LINEAR : GL_NEAREST);
    return draw(q);
  }

  // A view of the uploaded texture: TEXTURE_BASE_LEVEL and TEXTURE_MAX_LEVEL.
  void view(int base_level, int max_level) {
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_BASE_LEVEL, base_level);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, max_level);
  }

  // The sampler state of `c` on the texture, then one sample per query (u, v, lambda); an
  // unnormalized sampler reads the rectangle texture at texel coordinates (u, v).
  std::vector<std::array<float, 4>> sample(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(c.unnormalized ? rect_program_ : program_);
    apply(c);
    return draw(q);
  }

  // textureGather of component q[2] at (u, v) = (q[0], q[1]) under the sampler state of `c`.
  std::vector<std::array<float, 4>> gather(const SamplerConfig& c, const std::vector<std::array<float, 4>>& q) {
    glUseProgram(gather_program_);
    apply(c);
    return draw(q);
  }

  // texelFetch of (i, j, level) = (q[0], q[1], q[2]) (whole numbers) from the uploaded texture.
  std::vector<std::array<float, 4>> fetch(const std::vector<std::array<float, 4>>& q) {
    glUseProgram(fetch_program_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, tex_);
    return draw(q);
  }

 private:
  // The sampler state of `c` on the texture (the rectangle texture for an unnormalized sampler; the
  // array texture for GL_TEXTURE_2D_ARRAY).
  void apply(const SamplerConfig& c, GLenum array = 0, bool depth = false) {
    const GLenum target = array ? array : c.unnormalized ? GL_TEXTURE_RECTANGLE : GL_TEXTURE_2D;
    glActiveTexture(depth ? GL_TEXTURE4 : array ? GL_TEXTURE3 : c.unnormalized ? GL_TEXTURE2 : GL_TEXTURE0);
    glBindTexture(target, depth ? depth_ : array ? array_ : c.unnormalized ? rect_ : tex_);
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, c.unnormalized ? (c.filter.texel == TexelFilter::Linear ? GL_LINEAR : GL_NEAREST)
                                                                  : gl_min_filter(c.filter));
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, c.filter.mag == TexelFilter::Linear ? GL_LINEAR : GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, gl_wrap(c.wrap_u));
    glTexParameteri(target, GL_TEXTURE_WRAP_T, gl_wrap(c.wrap_v));
    const Texel b = c.border_unorm16();
    const float border[4] = {b[0] / 65535.f, b[1] / 65535.f, b[2] / 65535.f, b[3] / 65535.f};
    glTexParameterfv(target, GL_TEXTURE_BORDER_COLOR, border);
    glTexParameteri(target, GL_TEXTURE_REDUCTION_MODE_ARB,  // GL_ARB_texture_filter_minmax
                    c.reduction == Reduction::Min   ? GL_MIN
                    : c.reduction == Reduction::Max ? GL_MAX
                                                    : GL_WEIGHTED_AVERAGE_ARB);
  }

  // One fragment per query with the bound program; the results.
  std::vector<std::array<float, 4>> draw(const std::vector<std::array<float, 4>>& q) {
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, queries_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, kW, kH, 0, GL_RGBA, GL_FLOAT, q.data());
    glViewport(0, 0, kW, kH);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<std::array<float, 4>> out(size_t(kW) * kH);
    glReadPixels(0, 0, kW, kH, GL_RGBA, GL_FLOAT, out.data());
    return out;
  }

  OSMesaContext ctx_ = nullptr;
  std::vector<uint8_t> window_ = std::vector<uint8_t>(size_t(kW) * kH * 4);
  GLuint fbo_ = 0, colour_ = 0, program_ = 0, rect_program_ = 0, fetch_program_ = 0, gather_program_ = 0, vao_ = 0,
         tex_ = 0, rect_ = 0, queries_ = 0, array_program_ = 0, array_fetch_program_ = 0, array_gather_program_ = 0,
         array_ = 0, shadow_program_ = 0, depth_ = 0, cube_program_ = 0, cube_ = 0, cube_array_program_ = 0,
         cube_array_ = 0, cube_gather_program_ = 0, cube_shadow_program_ = 0, cube_depth_ = 0;
  bool ready_ = false;
};

struct Outcome {
  int compared = 0, excluded = 0, max_lsb_x100 = 0;
  double sum = 0;
};

// Random on-grid queries (u, v multiples of 2^-16: exact in float and in Q8.24; lambda of 1/256),
// each 2x2 pixel quad one lambda. A nearest filter's texel, or a level choice, at an edge within
// 1/64 texel or level is either side's (both are right): such queries are not compared.
// `model_cfg`: the model's sampler instead of cfg (a planted bug).
// `layers`: the queries sample the array texture (GlSampling::upload_array; pyr its layer 0) at a
// layer coordinate on a 1/256 grid from -1.5 to 1.5 past the last layer; one within 1/64 of a tie
// between two layers is not compared (GL rounds a tie as it likes; the unit to even).
Outcome compare(GlSampling& gl, const Pyramid& pyr, const SamplerConfig& cfg, uint32_t seed,
                const SamplerConfig* model_cfg = nullptr, const std::vector<const Pyramid*>* layers = nullptr) {
  std::mt19937 rng(seed);
  const int q = pyr.last_level();
  std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
  std::vector<Request> requests(queries.size());
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const size_t i = size_t(y) * kW + size_t(x);
      double u = (int(rng() % (4 << 16)) - (3 << 15)) / 65536.0, v = (int(rng() % (4 << 16)) - (3 << 15)) / 65536.0;
      if (cfg.unnormalized) {  // texels of level 0, 3 beyond each edge, on a 1/256 grid
        const Extent e = pyr.extent0();
        u = (int(rng() % uint32_t((e.w + 6) << 8)) - (3 << 8)) / 256.0;
        v = (int(rng() % uint32_t((e.h + 6) << 8)) - (3 << 8)) / 256.0;
      }
      const double lambda = (x & 1) || (y & 1) ? queries[size_t(y & ~1) * kW + size_t(x & ~1)][2]
                                                 : (int(rng() % uint32_t((q + 4) * 256)) - 2 * 256) / 256.0;
      queries[i] = {float(u), float(v), float(lambda), 0.f};
      if (layers) {
        const double a = (int(rng() % uint32_t((layers->size() + 3) * 256)) - 384) / 256.0;
        queries[i][3] = float(a);
        EXPECT_TRUE(to_texel_coord_fixed(a, requests[i].layer));
      }
      const bool coords = cfg.unnormalized ? to_texel_coord_fixed(u, requests[i].u) && to_texel_coord_fixed(v, requests[i].v)
                                           : to_coord_fixed(u, requests[i].u) && to_coord_fixed(v, requests[i].v);
      EXPECT_TRUE(coords && to_lod_fixed(lambda, requests[i].lod));
    }
  const std::vector<std::array<float, 4>> got = layers ? gl.sample_array(cfg, queries) : gl.sample(cfg, queries);
  Sampler model(layers ? *layers : std::vector<const Pyramid*>{&pyr}, model_cfg ? *model_cfg : cfg);
  const bool srgb = pyr.srgb;
  Outcome o;
  for (size_t i = 0; i < requests.size(); ++i) {
    const Request& r = requests[i];
    const double lambda = std::clamp(r.lod + cfg.lod_bias, cfg.min_lod, cfg.max_lod) / 256.0;
    const bool magnify = lambda <= 0;
    const TexelFilter tf = magnify ? cfg.filter.mag : cfg.filter.texel;
    bool edge = std::fabs(lambda) < 1.0 / 64;  // (magnification or minification)
    if (!magnify && cfg.filter.mip == MipMode::Nearest)
      edge = edge || std::fabs(lambda - std::floor(lambda) - 0.5) < 1.0 / 64;
    if (tf == TexelFilter::Nearest)
      for (int k = 0; k <= (cfg.unnormalized ? 0 : q); ++k)
        for (double t : {queries[i][0] * (cfg.unnormalized ? 1 : pyr.levels[size_t(k)].width),
                         queries[i][1] * (cfg.unnormalized ? 1 : pyr.levels[size_t(k)].height)})
          edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
    if (cfg.reduction != Reduction::WeightedAverage) {
      // Min and max take the texels of weight above 0: a linear filter's second tap, or the second
      // level, at a weight within 1/64 of 0 is in on one side and out on the other.
      if (tf == TexelFilter::Linear)
        for (int k = 0; k <= (cfg.unnormalized ? 0 : q); ++k)
          for (double t : {queries[i][0] * (cfg.unnormalized ? 1 : pyr.levels[size_t(k)].width) - 0.5,
                           queries[i][1] * (cfg.unnormalized ? 1 : pyr.levels[size_t(k)].height) - 0.5})
            edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
      if (!magnify && cfg.filter.mip == MipMode::Linear) edge = edge || std::fabs(lambda - std::round(lambda)) < 1.0 / 64;
    }
    if (layers) edge = edge || std::fabs(queries[i][3] - std::floor(queries[i][3]) - 0.5) < 1.0 / 64;
    if (edge) {
      ++o.excluded;
      continue;
    }
    const Texel m = model.sample(r);
    for (int c = 0; c < 4; ++c) {
      // In 8-bit steps of full scale (an sRGB texture's results are linear unorm16).
      const double mine = srgb ? m[size_t(c)] / 65535.0 * 255 : m[size_t(c)];
      const double err = std::fabs(mine - double(got[i][size_t(c)]) * 255);
      o.max_lsb_x100 = std::max(o.max_lsb_x100, int(std::lround(err * 100)));  // (GL gives k / 255 as a float)
      o.sum += err;
    }
    ++o.compared;
  }
  return o;
}

// The precision asserted of every state (8-bit steps of full scale): more than half of the lookups
// compared; nearest filters take the same texel (RGBA8: exact, but for a custom border colour, which
// GL returns unquantized and the unit rounds to 8 bits; sRGB: llvmpipe's decode and the model's
// unorm16 table within 0.35 step); linear filters within 2 LSB (llvmpipe weighs with fewer
// sub-texel bits), 0.4 LSB on average. Returns the mean.
double expect_gl_precision(const Outcome& o, const Pyramid& pyr, const SamplerConfig& cfg) {
  const double mean = o.sum / (4.0 * o.compared);
  EXPECT_GT(o.compared, kW * kH / 2) << o.excluded << " excluded";
  const bool custom = cfg.border == BorderColor::Custom && cfg.uses_border();
  if (cfg.filter.texel == TexelFilter::Nearest && cfg.filter.mag == TexelFilter::Nearest &&
      cfg.filter.mip != MipMode::Linear) {
    EXPECT_LE(o.max_lsb_x100, pyr.srgb ? 35 : custom ? 50 : 0) << "mean " << mean;
  }
  EXPECT_LE(o.max_lsb_x100, 200) << "mean " << mean;
  EXPECT_LE(mean, 0.4);
  return mean;
}

constexpr Wrap kWraps[] = {Wrap::Repeat, Wrap::Clamp, Wrap::Mirror, Wrap::Border, Wrap::MirrorClamp};

// The textures most states are compared on: RGBA8 with sides powers of two (32x16) and not (37x23:
// odd levels, repeat seams), and an sRGB one with sides not powers of two (25x48).
struct TestTextures {
  Pyramid rgba, rgba_npot, srgb_npot;
};
TestTextures test_textures() {
  return {build_pyramid(make_pattern("noise", 32, 16)), build_pyramid(make_pattern("noise", 37, 23)),
          build_srgb_pyramid(make_pattern("testcard", 25, 48), PyramidMode::Exact)};
}

// The largest difference between the model's texel (R, G, B, A; its channels taken `rotate` places
// on: a planted reordering) and GL's, in 1/100 of an 8-bit step (an sRGB texture's results are
// linear unorm16). 0: the same texel.
int error_lsb_x100(const Texel& model, const std::array<float, 4>& gl, bool srgb, int rotate = 0) {
  int err = 0;
  for (int c = 0; c < 4; ++c) {
    const double mine = model[size_t((c + rotate) % 4)] * (srgb ? 255.0 / 65535 : 1.0);
    err = std::max(err, int(std::lround(std::fabs(mine - double(gl[size_t(c)]) * 255) * 100)));
  }
  return err;
}

// A texel fetch of level k: (i, j) up to one texel beyond the level's sides (k clamped to the
// texture's levels for the size). The GL query (i, j, k) and the model's request.
void fetch_query(std::mt19937& rng, Extent size0, int last, int k, std::array<float, 4>& query, Request& request) {
  const Extent e = level_extent(size0, std::clamp(k, 0, last));
  const int i = int(rng() % uint32_t(e.w + 2)) - 1, j = int(rng() % uint32_t(e.h + 2)) - 1;
  query = {float(i), float(j), float(k), 0.f};
  request = fetch_request(i, j, k);
}

// A gather of a random component at u, v on the 2^-16 grid (exact in float and in Q8.24) in
// [lo, lo + span): the GL query (u, v, component) and the model's request.
void gather_query(std::mt19937& rng, double lo, int span, std::array<float, 4>& query, Request& request) {
  const double u = lo + int(rng() % uint32_t(span << 16)) / 65536.0, v = lo + int(rng() % uint32_t(span << 16)) / 65536.0;
  const int c = int(rng() % 4);
  query = {float(u), float(v), float(c), 0.f};
  int32_t fu = 0, fv = 0;
  EXPECT_TRUE(to_coord_fixed(u, fu) && to_coord_fixed(v, fv));
  request = gather_request(fu, fv, c);
}

// Whether a gather at the query's (u, v) lies within 1/64 texel of where the footprint moves
// (u w - 1/2 a whole number): GL and the unit may each take either footprint there.
bool near_footprint_edge(const std::array<float, 4>& query, Extent size0) {
  bool edge = false;
  for (double t : {query[0] * size0.w - 0.5, query[1] * size0.h - 0.5}) edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
  return edge;
}

std::string name_of(const SamplerConfig& c) {
  return "min " + filter_name(Filter{c.filter.texel, c.filter.mip}) + ", mag " + texel_filter_name(c.filter.mag) +
         ", wrap " + wrap_name(c.wrap_u) + "/" + wrap_name(c.wrap_v) + ", border " + border_color_name(c.border);
}

}  // namespace

TEST(GlSamplerStates, LlvmpipeAgreesWithTheModelOnEverySamplerState) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const Pyramid rgba = build_pyramid(make_pattern("noise", 32, 16));
  const Pyramid srgb = build_srgb_pyramid(make_pattern("testcard", 16, 32), PyramidMode::Exact);
  const Pyramid rgba_npot = build_pyramid(make_pattern("noise", 37, 23));  // 37x23, 18x11, 9x5, 4x2, 2x1, 1x1
  const Pyramid srgb_npot = build_srgb_pyramid(make_pattern("testcard", 25, 48), PyramidMode::Exact);
  std::mt19937 rng(39);
  int states = 0, compared = 0, worst = 0;
  double mean_sum = 0;
  for (const Pyramid* pyr : {&rgba, &srgb, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    for (int mip = 0; mip < 3; ++mip)
      for (int texel = 0; texel < 2; ++texel)
        for (int mag = 0; mag < 2; ++mag)
          for (int w = 0; w < 5; ++w) {
            SamplerConfig cfg{{TexelFilter(texel), MipMode(mip)}, kWraps[w], kWraps[(w + 1 + rng() % 4) % 5]};
            cfg.filter.mag = TexelFilter(mag);
            cfg.border = BorderColor(rng() % kBorderColors);
            if (cfg.border == BorderColor::Custom)
              for (auto& c : cfg.border_custom) c = uint16_t(rng() % 65536);
            const Outcome o = compare(gl, *pyr, cfg, uint32_t(states));
            ++states;
            compared += o.compared;
            SCOPED_TRACE((pyr->srgb ? "sRGB " : "RGBA8 ") + std::to_string(pyr->extent0().w) + "x" +
                         std::to_string(pyr->extent0().h) + ", " + name_of(cfg));
            const double mean = expect_gl_precision(o, *pyr, cfg);
            worst = std::max(worst, o.max_lsb_x100);
            mean_sum += mean;
          }
  }
  EXPECT_EQ(states, 240);
  std::printf("  %d sampler states, %d lookups compared with llvmpipe: max %.2f LSB, mean %.3f LSB\n", states,
              compared, worst / 100.0, mean_sum / states);
}

// Views (GL's TEXTURE_BASE_LEVEL and TEXTURE_MAX_LEVEL; texsim --base-level, --max-level): GL
// samples the whole uploaded pyramid through the view, the model samples view_pyramid (the view as
// a texture of its own: level b as level 0, lambda in its texels, the chain cut at m). Both must
// agree as they do without a view, on RGBA8 and sRGB, sides powers of two and not, for bases and
// max levels inside, at and beyond the chain, every mip mode.
TEST(GlSamplerStates, ViewsAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const auto [rgba, rgba_npot, srgb_npot] = test_textures();
  const std::pair<int, int> views[] = {{1, 3}, {2, 99}, {0, 1}, {3, 3}, {1, 1}};
  std::mt19937 rng(40);
  int states = 0, worst = 0;
  for (const Pyramid* pyr : {&rgba, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    for (auto [b, m] : views)
      for (int mip = 0; mip < 3; ++mip) {
        const Pyramid view = view_pyramid(*pyr, b, m);
        gl.view(b, m);
        SamplerConfig cfg{{TexelFilter(rng() % 2), MipMode(mip)}, kWraps[rng() % 5], kWraps[rng() % 5]};
        cfg.filter.mag = TexelFilter(rng() % 2);
        const Outcome o = compare(gl, view, cfg, uint32_t(1000 + states));
        ++states;
        SCOPED_TRACE((pyr->srgb ? "sRGB " : "RGBA8 ") + std::to_string(pyr->extent0().w) + "x" +
                     std::to_string(pyr->extent0().h) + " levels " + std::to_string(b) + ".." + std::to_string(m) +
                     ", " + name_of(cfg));
        expect_gl_precision(o, *pyr, cfg);  // (the default border colour: never custom)
        worst = std::max(worst, o.max_lsb_x100);
      }
  }
  EXPECT_EQ(states, 45);
  std::printf("  %d views, max %.2f LSB against llvmpipe\n", states, worst / 100.0);
  // The check fires: the model sampling the whole pyramid where GL samples a view disagrees.
  gl.upload(rgba_npot);
  gl.view(2, 4);
  const Outcome wrong = compare(gl, rgba_npot, SamplerConfig{}, 7);
  EXPECT_GT(wrong.max_lsb_x100, 1000) << "a view ignored went unnoticed";
}

// Unnormalized coordinates (texsim --unnormalized, Vulkan unnormalizedCoordinates) against GL's
// rectangle textures: texel coordinates of level 0, clamp to edge or border on each axis, each
// texel filter, border colours named and custom, on RGBA8 and sRGB textures of sides powers of two
// and not; the same precision as the normalized states.
TEST(GlSamplerStates, UnnormalizedCoordinatesAgreeWithRectangleTextures) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const auto [rgba, rgba_npot, srgb_npot] = test_textures();
  std::mt19937 rng(41);
  int states = 0, worst = 0;
  for (const Pyramid* pyr : {&rgba, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    for (Wrap wu : {Wrap::Clamp, Wrap::Border})
      for (Wrap wv : {Wrap::Clamp, Wrap::Border})
        for (int texel = 0; texel < 2; ++texel) {
          SamplerConfig cfg{{TexelFilter(texel), MipMode::None}, wu, wv};
          cfg.unnormalized = true;
          cfg.border = BorderColor(rng() % kBorderColors);
          if (cfg.border == BorderColor::Custom)
            for (auto& c : cfg.border_custom) c = uint16_t(rng() % 65536);
          const Outcome o = compare(gl, *pyr, cfg, uint32_t(2000 + states));
          ++states;
          SCOPED_TRACE((pyr->srgb ? "sRGB " : "RGBA8 ") + std::to_string(pyr->extent0().w) + "x" +
                       std::to_string(pyr->extent0().h) + ", unnormalized, " + name_of(cfg));
          expect_gl_precision(o, *pyr, cfg);
          worst = std::max(worst, o.max_lsb_x100);
        }
  }
  EXPECT_EQ(states, 24);
  std::printf("  %d unnormalized sampler states against rectangle textures: max %.2f LSB\n", states, worst / 100.0);
  // The check fires: the model taking the texel coordinates as texture widths disagrees.
  gl.upload(rgba_npot);
  SamplerConfig rect{{TexelFilter::Linear, MipMode::None}, Wrap::Clamp, Wrap::Clamp};
  rect.unnormalized = true;
  SamplerConfig normalized = rect;
  normalized.unnormalized = false;
  const Outcome wrong = compare(gl, rgba_npot, rect, 9, &normalized);
  EXPECT_GT(wrong.max_lsb_x100, 1000) << "texel coordinates read as texture widths went unnoticed";
}

// The min/max reduction (Vulkan reductionMode, GL_ARB_texture_filter_minmax) against llvmpipe: the
// component-wise minimum or maximum of the texels the filter weighs (above 0) within a level, for
// both texel filters and the mipmap modes that sample one level, every address mode, on RGBA8 and
// sRGB textures of sides powers of two and not. The result is a texel, not a blend: RGBA8 exact,
// sRGB within the decode tables' 0.35 step (away from weights within 1/64 of 0, where either
// answer is right).
// Where llvmpipe (Mesa 22.3) and the model part, not compared here: with a nearest filter beside a
// linear one (min point, mag linear or the reverse) llvmpipe reduces over the 2x2 footprint in both
// (the model: one texel where the filter is nearest), and between two levels it blends the two
// levels' reductions by the level weight (the model, as Vulkan's "Texel Mipmap Filtering" says,
// takes the minimum or maximum of both levels' values of weight above 0: docs/numerics.md 5b).
// Both were seen on these textures (every filter pair and mipmap mode: 24 of 36 states apart).
TEST(GlSamplerStates, MinMaxReductionAgreesWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const auto [rgba, rgba_npot, srgb_npot] = test_textures();
  std::mt19937 rng(42);
  int states = 0, compared = 0, worst = 0;
  for (const Pyramid* pyr : {&rgba, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    for (Reduction red : {Reduction::Min, Reduction::Max})
      for (MipMode mip : {MipMode::None, MipMode::Nearest})
        for (int texel = 0; texel < 2; ++texel) {
          SamplerConfig cfg{{TexelFilter(texel), mip}, kWraps[rng() % 5], kWraps[rng() % 5]};
          cfg.reduction = red;
          cfg.border = BorderColor(rng() % (kBorderColors - 1));  // named colours: GL returns them exactly
          const Outcome o = compare(gl, *pyr, cfg, uint32_t(3000 + states));
          ++states;
          compared += o.compared;
          SCOPED_TRACE((pyr->srgb ? "sRGB " : "RGBA8 ") + std::to_string(pyr->extent0().w) + "x" +
                       std::to_string(pyr->extent0().h) + ", " + reduction_name(red) + ", " + name_of(cfg));
          EXPECT_GT(o.compared, kW * kH / 3) << o.excluded << " excluded";
          EXPECT_LE(o.max_lsb_x100, pyr->srgb ? 35 : 0);
          worst = std::max(worst, o.max_lsb_x100);
        }
  }
  EXPECT_EQ(states, 24);
  std::printf("  %d min/max sampler states, %d lookups compared with llvmpipe: max %.2f LSB\n", states, compared,
              worst / 100.0);
  // The check fires: the model averaging where GL takes the minimum disagrees.
  gl.upload(rgba);
  SamplerConfig min{{TexelFilter::Linear, MipMode::Nearest}, Wrap::Repeat, Wrap::Repeat};
  min.reduction = Reduction::Min;
  const SamplerConfig average{{TexelFilter::Linear, MipMode::Nearest}, Wrap::Repeat, Wrap::Repeat};
  const Outcome wrong = compare(gl, rgba, min, 11, &average);
  EXPECT_GT(wrong.max_lsb_x100, 1000) << "an average for a minimum went unnoticed";
}

// texelFetch: every texel llvmpipe fetches inside the texture, on every level of the three test
// textures, is the model's (RGBA8 exactly; sRGB within the decode tables' 0.35 step). Outside the
// texture GL leaves the result undefined; the model's 0 (Vulkan's robust access) is compared
// where llvmpipe also answers 0 in every channel, and the rest are counted.
TEST(GlSamplerStates, TexelFetchAgreesWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const auto [rgba, rgba_npot, srgb_npot] = test_textures();
  std::mt19937 rng(45);
  int compared = 0, outside = 0, outside_zero = 0, worst = 0, planted = 0;
  for (const Pyramid* pyr : {&rgba, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    const int last = pyr->last_level();
    std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
    std::vector<Request> requests(queries.size());
    for (size_t n = 0; n < queries.size(); ++n) {  // a level of the texture, 1 in 8 one beyond either end
      const int k = rng() % 8 == 0 ? (rng() % 2 ? -1 : last + 1) : int(rng() % uint32_t(last + 1));
      fetch_query(rng, pyr->extent0(), last, k, queries[n], requests[n]);
    }
    const std::vector<std::array<float, 4>> got = gl.fetch(queries);
    Sampler model(*pyr, SamplerConfig{});
    for (size_t n = 0; n < requests.size(); ++n) {
      const Request& r = requests[n];
      const Texel m = model.sample(r);
      const bool inside = stage::fetch_inside(r.u, r.v, r.lod, last, pyr->extent0());
      if (!inside) {
        ++outside;
        if (got[n] != std::array<float, 4>{0, 0, 0, 0}) continue;  // (undefined in GL)
        ++outside_zero;
      }
      const int err = error_lsb_x100(m, got[n], pyr->srgb);
      ASSERT_LE(err, pyr->srgb ? 35 : 0) << (pyr->srgb ? "sRGB " : "RGBA8 ") << pyr->extent0().w << "x"
                                         << pyr->extent0().h << " fetch (" << r.u << ", " << r.v << ") level " << r.lod;
      worst = std::max(worst, err);
      ++compared;
      // The check fires: a model that fetches the texel to the right (RGBA8) disagrees.
      if (!pyr->srgb && inside) planted += error_lsb_x100(model.sample(fetch_request(r.u + 1, r.v, r.lod)), got[n], false) > 0;
    }
  }
  EXPECT_GT(planted, kW * kH / 2) << "a fetch one texel off went unnoticed";
  EXPECT_GT(compared - outside_zero, kW * kH) << "fetches inside the texture";
  EXPECT_GT(outside, 1000);
  std::printf("  %d texel fetches compared with llvmpipe (max %.2f LSB): %d inside the texture, %d outside (0 in "
              "llvmpipe too: %d)\n", compared, worst / 100.0, compared - outside_zero, outside, outside_zero);
}

// textureGather: llvmpipe gathers each component under random sampler states (every address mode
// on each axis, named border colours, filters and LOD fields that must not matter) on the three
// test textures; the model's four texels are its (RGBA8 exactly; sRGB within the decode tables).
// A coordinate within 1/64 texel of where the footprint moves (u w - 1/2 a whole number) may take
// either footprint and is not compared. A model gathering in another order is caught.
TEST(GlSamplerStates, GatherAgreesWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const auto [rgba, rgba_npot, srgb_npot] = test_textures();
  std::mt19937 rng(46);
  int states = 0, compared = 0, excluded = 0, worst = 0, rotated = 0;
  for (const Pyramid* pyr : {&rgba, &rgba_npot, &srgb_npot}) {
    gl.upload(*pyr);
    const Extent e = pyr->extent0();
    for (int w = 0; w < 5; ++w) {
      SamplerConfig cfg{{TexelFilter(rng() % 2), MipMode(rng() % 3)}, kWraps[w], kWraps[rng() % 5]};
      cfg.border = BorderColor(rng() % (kBorderColors - 1));  // named colours: GL returns them exactly
      cfg.lod_bias = int32_t(rng() % 512);
      std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
      std::vector<Request> requests(queries.size());
      for (size_t n = 0; n < queries.size(); ++n) gather_query(rng, -1.5, 4, queries[n], requests[n]);
      const std::vector<std::array<float, 4>> got = gl.gather(cfg, queries);
      Sampler model(*pyr, cfg);
      for (size_t n = 0; n < requests.size(); ++n) {
        if (near_footprint_edge(queries[n], e)) {
          ++excluded;
          continue;
        }
        const Texel m = model.sample(requests[n]);
        const int err = error_lsb_x100(m, got[n], pyr->srgb);
        ASSERT_LE(err, pyr->srgb ? 35 : 0) << (pyr->srgb ? "sRGB " : "RGBA8 ") << e.w << "x" << e.h << " "
                                           << name_of(cfg) << " gather " << requests[n].component << " at ("
                                           << queries[n][0] << ", " << queries[n][1] << ")";
        worst = std::max(worst, err);
        rotated += error_lsb_x100(m, got[n], pyr->srgb, 1) > 100;
        ++compared;
      }
      ++states;
    }
  }
  EXPECT_EQ(states, 15);
  EXPECT_GT(compared, 15 * kW * kH * 3 / 4) << excluded << " excluded";
  EXPECT_GT(rotated, compared / 2) << "a gather in another order went unnoticed";
  std::printf("  %d gathers in %d sampler states compared with llvmpipe: max %.2f LSB (%d near a footprint edge "
              "not compared)\n", compared, states, worst / 100.0, excluded);
}

// Fetch and gather through a view (GL_TEXTURE_BASE_LEVEL 2, GL_TEXTURE_MAX_LEVEL 4 of 37x23): the
// fetch's level counts from the view's base and stops at its last level, the gather reads the
// view's base level. The model samples view_pyramid; RGBA8, so both must be exact. A model that
// ignores the view (the whole pyramid) disagrees.
TEST(GlSamplerStates, FetchAndGatherThroughAViewAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  const Pyramid whole = build_pyramid(make_pattern("noise", 37, 23));
  const Pyramid view = view_pyramid(whole, 2, 4);  // 9x5, 4x2, 2x1
  gl.upload(whole);
  gl.view(2, 4);
  std::mt19937 rng(47);
  std::vector<std::array<float, 4>> fetches(size_t(kW) * kH), gathers(size_t(kW) * kH);
  std::vector<Request> fetch_reqs(fetches.size()), gather_reqs(gathers.size());
  for (size_t n = 0; n < fetches.size(); ++n) {
    const int k = int(rng() % 5) - 1;  // -1 .. 3: one below the view and one past its last
    fetch_query(rng, view.extent0(), view.last_level(), k, fetches[n], fetch_reqs[n]);
    gather_query(rng, -0.5, 2, gathers[n], gather_reqs[n]);
  }
  SamplerConfig cfg;  // repeat, trilinear (a gather does not filter)
  const std::vector<std::array<float, 4>> got_fetch = gl.fetch(fetches), got_gather = gl.gather(cfg, gathers);
  Sampler model(view, cfg), wrong(whole, cfg);
  int compared = 0, ignored_view = 0;
  for (size_t n = 0; n < fetch_reqs.size(); ++n) {
    ASSERT_EQ(error_lsb_x100(model.sample(fetch_reqs[n]), got_fetch[n], false), 0)
        << "fetch (" << fetch_reqs[n].u << ", " << fetch_reqs[n].v << ") level " << fetch_reqs[n].lod;
    ignored_view += error_lsb_x100(wrong.sample(fetch_reqs[n]), got_fetch[n], false) > 0;
    ++compared;
    if (near_footprint_edge(gathers[n], view.extent0())) continue;
    ASSERT_EQ(error_lsb_x100(model.sample(gather_reqs[n]), got_gather[n], false), 0)
        << "gather " << int(gather_reqs[n].component) << " at (" << gathers[n][0] << ", " << gathers[n][1] << ")";
    ignored_view += error_lsb_x100(wrong.sample(gather_reqs[n]), got_gather[n], false) > 0;
    ++compared;
  }
  EXPECT_GT(compared, 3 * kW * kH / 2);
  EXPECT_GT(ignored_view, compared / 2) << "a model that ignores the view went unnoticed";
  gl.view(0, whole.last_level());
}

// 2D arrays (sampler2DArray, the unit's layers): five RGBA8 layers of 37x23, each its own texels.
// llvmpipe samples them under every filter (a wrap pair each), fetches (i, j, layer, level) and
// gathers at a layer coordinate; the model's are its within the precision of a 2D texture (fetch
// and gather exactly), away from the ties between two layers; at the ties llvmpipe takes the even
// layer, as the unit does (Vulkan's RNE). A model with its layers in the other order is caught.
TEST(GlSamplerStates, ArrayLayersAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  constexpr int kLayers = 5;
  std::vector<Pyramid> layers;
  for (int l = 0; l < kLayers; ++l) {
    Image img = make_pattern("noise", 37, 23);
    for (Texel& t : img.texels)
      for (uint16_t& c : t) c = uint16_t((c * (l + 1) + 40 * l) & 255);
    layers.push_back(build_pyramid(std::move(img)));
  }
  std::vector<const Pyramid*> array;
  for (const Pyramid& p : layers) array.push_back(&p);
  const std::vector<const Pyramid*> reversed(array.rbegin(), array.rend());
  gl.upload_array(array);
  const Pyramid& pyr = layers[0];
  const int last = pyr.last_level();
  std::mt19937 rng(48);
  int states = 0, compared = 0, worst = 0;
  for (int mip = 0; mip < 3; ++mip)
    for (int texel = 0; texel < 2; ++texel) {
      SamplerConfig cfg{{TexelFilter(texel), MipMode(mip)}, kWraps[rng() % 5], kWraps[rng() % 5]};
      cfg.border = BorderColor(rng() % (kBorderColors - 1));
      const Outcome o = compare(gl, pyr, cfg, 100 + uint32_t(states), nullptr, &array);
      SCOPED_TRACE("array, " + name_of(cfg));
      expect_gl_precision(o, pyr, cfg);
      worst = std::max(worst, o.max_lsb_x100);
      compared += o.compared;
      ++states;
    }
  const Outcome planted = compare(gl, pyr, SamplerConfig{}, 99, nullptr, &reversed);
  EXPECT_GT(planted.max_lsb_x100, 2000) << "a model with its layers reversed went unnoticed";

  // Fetches: a level of the texture, a layer from -1 to one past the last; inside exactly, outside
  // the layers 0 in the model (GL: undefined; compared where llvmpipe answers 0 too).
  std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
  std::vector<Request> requests(queries.size());
  for (size_t n = 0; n < queries.size(); ++n) {
    fetch_query(rng, pyr.extent0(), last, int(rng() % uint32_t(last + 1)), queries[n], requests[n]);
    const int layer = int(rng() % (kLayers + 2)) - 1;
    queries[n][3] = float(layer);
    requests[n].layer = layer;
  }
  std::vector<std::array<float, 4>> got = gl.fetch_array(queries);
  Sampler model(array, SamplerConfig{});
  int fetched = 0, outside_layers = 0;
  for (size_t n = 0; n < requests.size(); ++n) {
    const Request& r = requests[n];
    const bool inside = stage::fetch_inside(r.u, r.v, r.lod, last, pyr.extent0()) && stage::fetch_layer_inside(r.layer, kLayers);
    if (!inside && got[n] != std::array<float, 4>{0, 0, 0, 0}) continue;  // (undefined in GL)
    outside_layers += !stage::fetch_layer_inside(r.layer, kLayers);
    ASSERT_EQ(error_lsb_x100(model.sample(r), got[n], false), 0)
        << "fetch (" << r.u << ", " << r.v << ") layer " << r.layer << " level " << r.lod;
    ++fetched;
  }
  EXPECT_GT(fetched, kW * kH / 2);

  // Gathers at a layer coordinate on a 1/256 grid (away from ties and footprint edges), and at
  // ties exactly: which way llvmpipe rounds those.
  int gathered = 0, ties = 0, tie_even = 0, tie_up = 0;
  SamplerConfig cfg;
  cfg.wrap_u = Wrap::Clamp;
  for (size_t n = 0; n < queries.size(); ++n) {
    gather_query(rng, -0.5, 2, queries[n], requests[n]);
    const bool tie = n % 8 == 0;
    const double a = tie ? int(rng() % (kLayers + 1)) - 0.5 : (int(rng() % ((kLayers + 2) * 256)) - 256) / 256.0;
    std::swap(queries[n][2], queries[n][3]);  // (u, v, layer, component)
    queries[n][2] = float(a);
    EXPECT_TRUE(to_texel_coord_fixed(a, requests[n].layer));
  }
  got = gl.gather_array(cfg, queries);
  Sampler gather_model(array, cfg);
  for (size_t n = 0; n < requests.size(); ++n) {
    const std::array<float, 4> uv = {queries[n][0], queries[n][1], 0, 0};
    if (near_footprint_edge(uv, pyr.extent0())) continue;
    const Request& r = requests[n];
    if (n % 8 == 0) {  // a tie: to the even layer (the model) or up?
      Request up = r;
      up.layer += 1;
      ++ties;
      tie_even += error_lsb_x100(gather_model.sample(r), got[n], false) == 0;
      tie_up += error_lsb_x100(gather_model.sample(up), got[n], false) == 0;
      continue;
    }
    if (std::fabs(queries[n][2] - std::floor(queries[n][2]) - 0.5) < 1.0 / 64) continue;
    ASSERT_EQ(error_lsb_x100(gather_model.sample(r), got[n], false), 0)
        << "gather " << int(r.component) << " at (" << queries[n][0] << ", " << queries[n][1] << ") layer " << queries[n][2];
    ++gathered;
  }
  EXPECT_GT(gathered, kW * kH / 2);
  // llvmpipe rounds a tie to the even layer as the unit does; rounding up would differ in some.
  EXPECT_EQ(tie_even, ties);
  EXPECT_LT(tie_up, ties * 3 / 4);
  std::printf("  arrays of %d layers compared with llvmpipe: %d samples in %d sampler states (max %.2f LSB), %d "
              "fetches (%d outside the layers), %d gathers exact; of %d ties between two layers llvmpipe takes "
              "the even one in %d (rounding up would agree in %d)\n", kLayers, compared, states, worst / 100.0,
              fetched, outside_layers, gathered, ties, tie_even, tie_up);
}

// Depth compare (sampler2DShadow, GL_COMPARE_REF_TO_TEXTURE; the unit's Op::Compare) on a
// GL_DEPTH_COMPONENT16 texture, the model's D16 (16-bit R) pyramid: llvmpipe's percentage-closer
// filtering under the 8 compare functions, every filter and address modes, agrees with the model's
// within a linear filter's precision (nearest filters exactly). The unit rounds a reference to the
// depth's code before testing, GL compares it as a float: the textures hold even codes, the
// references sit near odd codes, so that no texel's depth equals a reference's code and both
// readings agree; at references exactly on a code (where the two may differ) the agreement is
// counted. A model that tests `depth OP reference` (the operands swapped) is caught.
TEST(GlSamplerStates, DepthCompareAgreesWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  Pyramid depth = build_pyramid(make_pattern("noise", 37, 23));
  for (Image& img : depth.levels) {  // 16-bit depth codes, every one even
    img.channel_bits = 16;
    for (Texel& t : img.texels) t = {uint16_t((t[0] * 257 + t[1]) & ~1), 0, 0, 65535};
  }
  gl.upload_depth(depth);
  std::mt19937 rng(49);
  int states = 0, compared = 0, worst = 0, swapped = 0, on_code = 0, on_code_agree = 0;
  for (int op = 0; op < kCompareOps; ++op)
    for (int mip = 0; mip < 3; ++mip)
      for (int texel = 0; texel < 2; ++texel) {
        SamplerConfig cfg{{TexelFilter(texel), MipMode(mip)}, kWraps[rng() % 5], kWraps[rng() % 5]};
        cfg.border = BorderColor(rng() % (kBorderColors - 1));
        cfg.compare_op = CompareOp(op);
        std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
        std::vector<Request> requests(queries.size());
        for (size_t n = 0; n < queries.size(); ++n) {
          const double u = (int(rng() % (4 << 16)) - (3 << 15)) / 65536.0, v = (int(rng() % (4 << 16)) - (3 << 15)) / 65536.0;
          const double lambda = (int(rng() % uint32_t((depth.last_level() + 3) * 256)) - 256) / 256.0;
          const bool exact = n % 16 == 0;  // on an even code exactly, else near an odd one
          const int code = exact ? int(rng() % 32768) * 2 : int(rng() % 32767) * 2 + 1;
          const double ref = exact ? code / 65535.0 : (code + (int(rng() % 101) - 50) / 200.0) / 65535.0;
          queries[n] = {float(u), float(v), float(lambda), float(ref)};
          Request& r = requests[n];
          r.op = Op::Compare;
          EXPECT_TRUE(to_coord_fixed(u, r.u) && to_coord_fixed(v, r.v) && to_lod_fixed(lambda, r.lod) &&
                      to_coord_fixed(double(float(ref)), r.ref));
        }
        const std::vector<std::array<float, 4>> got = gl.sample_shadow(cfg, queries);
        Sampler model(depth, cfg);
        for (size_t n = 0; n < requests.size(); ++n) {
          const double lambda = requests[n].lod / 256.0;
          const TexelFilter tf = lambda <= 0 ? cfg.filter.mag : cfg.filter.texel;
          bool edge = std::fabs(lambda) < 1.0 / 64;  // (as compare(): a filter or level choice either side)
          if (lambda > 0 && cfg.filter.mip == MipMode::Nearest) edge = edge || std::fabs(lambda - std::floor(lambda) - 0.5) < 1.0 / 64;
          if (tf == TexelFilter::Nearest)
            for (const Image& img : depth.levels)
              for (double t : {queries[n][0] * img.width, queries[n][1] * img.height}) edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
          if (edge) continue;
          const Texel m = model.sample(requests[n]);
          const int err = int(std::lround(std::fabs(m[0] / 65535.0 - double(got[n][0])) * 255 * 100));
          if (n % 16 == 0) {  // a reference on a code
            ++on_code;
            on_code_agree += err <= 200;
            continue;
          }
          const bool nearest = tf == TexelFilter::Nearest && cfg.filter.mip != MipMode::Linear;
          ASSERT_LE(err, nearest ? 0 : 200) << "compare " << compare_op_name(cfg.compare_op) << ", " << name_of(cfg)
                                            << " at (" << queries[n][0] << ", " << queries[n][1] << ") lod " << lambda
                                            << " ref " << queries[n][3] << ": model " << m[0] << ", GL " << got[n][0];
          EXPECT_EQ(m[1], 0);
          EXPECT_EQ(m[3], 65535);
          worst = std::max(worst, err);
          ++compared;
          // The operands swapped (`depth OP ref`): another result where a tap's depth differs from
          // the reference (every one here) for the ordered operators.
          if (op == int(CompareOp::Less) || op == int(CompareOp::Greater)) {
            SamplerConfig flipped = cfg;
            flipped.compare_op = op == int(CompareOp::Less) ? CompareOp::Greater : CompareOp::Less;
            swapped += std::abs(int(Sampler(depth, flipped).sample(requests[n])[0]) - int(m[0])) > 1000;
          }
        }
        ++states;
      }
  EXPECT_EQ(states, 48);
  EXPECT_GT(compared, 48 * kW * kH / 2);
  EXPECT_GT(swapped, kW * kH / 4) << "a model with the operands swapped went unnoticed";
  std::printf("  %d depth compares in %d sampler states compared with llvmpipe: max %.2f LSB; references exactly on "
              "a depth code: %d of %d agree\n", compared, states, worst / 100.0, on_code_agree, on_code);
}

// textureGather and depth compare on a cube map (samplerCube's textureGather, samplerCubeShadow):
// the four texels a bilinear footprint takes and the tests of each, across the seams and corners
// (the skirt's neighbour texels and its average of three), against the model's Op::Gather and
// Op::Compare. Gathers must be exact. The shadow cube's depths are multiples of 17 and each
// reference lies 8 codes above one, so that no test is a tie in either arithmetic; nearest exact,
// linear within 2 LSB (llvmpipe's weights, as for sampler2DShadow) — but at a corner: where a
// linear footprint takes the skirt's corner texel, the unit tests the average of the three depths
// that meet there (what the skirt holds) and llvmpipe averages their three tests; both are the
// specification's "should", and such lookups are counted apart. A footprint edge (or a nearest texel's) within 1/64
// texel is either side's and not compared; nor a tie of two major axes.
TEST(GlSamplerStates, CubeGatherAndCompareAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  constexpr int kN = 8;
  std::mt19937 rng(51);
  std::vector<Pyramid> faces, depths;
  for (int f = 0; f < 6; ++f) {
    Image img = make_pattern("noise", kN, kN);
    for (Texel& t : img.texels)
      for (uint16_t& c : t) c = uint16_t((c * (f + 3) + 29 * f) & 255);
    faces.push_back(build_pyramid(std::move(img)));
    Image d(kN, kN);
    for (Texel& t : d.texels) t = {uint16_t(17 * (rng() % 16)), 0, 0, 255};
    depths.push_back(build_pyramid(std::move(d)));
  }
  std::vector<const Pyramid*> cube, depth_cube;
  for (const Pyramid& p : faces) cube.push_back(&p);
  for (const Pyramid& p : depths) depth_cube.push_back(&p);
  gl.upload_cube(cube);
  gl.upload_cube_depth(depth_cube);
  auto grid = [&](double lo, double hi) { return lo + int(rng() % uint32_t((hi - lo) * 65536)) / 65536.0; };
  // Directions, half of them within two texels of a face's edge or corner.
  std::vector<std::array<float, 4>> dirs(size_t(kW) * kH);
  for (size_t n = 0; n < dirs.size(); ++n) {
    const int f = int(rng() % 6);
    auto near_edge = [&] { return rng() % 2 ? grid(0, 2.0 / kN) : 1 - grid(0, 2.0 / kN); };
    const double s = n % 2 ? grid(0, 1) : near_edge(), t = n % 2 || rng() % 3 ? grid(0, 1) : near_edge();
    const double sc = 2 * s - 1, tc = 2 * t - 1;
    const double table[6][3] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
    dirs[n] = {float(table[f][0]), float(table[f][1]), float(table[f][2]), 0.0f};
  }
  // Whether a query's footprint edge (linear) or texel edge (nearest) lies within 1/64 texel, or two
  // major axes tie.
  auto excluded = [&](const Request& r, bool linear) {
    double a[3] = {std::fabs(r.u / 16777216.0), std::fabs(r.v / 16777216.0), std::fabs(r.w / 16777216.0)};
    std::sort(a, a + 3);
    if (a[2] - a[1] < 1e-5 * a[2]) return true;
    int face = 0;
    Request plain = r;
    plain.op = Op::Sample;
    const Request q = cube_face_request(plain, face);
    for (int32_t c : {q.u, q.v}) {
      const double t = c / 16777216.0 * kN - (linear ? 0.5 : 0.0);
      if (std::fabs(t - std::round(t)) < 1.0 / 64) return true;
    }
    return false;
  };
  auto request_of = [&](const std::array<float, 4>& d) {
    Request r;
    EXPECT_TRUE(to_coord_fixed(d[0], r.u) && to_coord_fixed(d[1], r.v) && to_coord_fixed(d[2], r.w));
    return r;
  };
  // Whether a linear footprint takes a skirt corner texel (outside the face on both axes).
  auto at_corner = [&](const Request& r) {
    int face = 0;
    Request plain = r;
    plain.op = Op::Sample;
    const Request q = cube_face_request(plain, face);
    bool out[2];
    for (int a = 0; a < 2; ++a) {
      const double t = (a == 0 ? q.u : q.v) / 16777216.0 * kN - 0.5;
      out[a] = t < 0 || t > kN - 1;
    }
    return out[0] && out[1];
  };
  int gathers = 0, compares = 0, worst = 0, gather_excluded = 0, corners = 0, corners_differ = 0;
  Sampler colour(cube, SamplerConfig{}, SamplerPaths::Both, TextureKind::Cube);
  for (int component = 0; component < 4; ++component) {
    const std::vector<std::array<float, 4>> got = gl.gather_cube(component, dirs);
    for (size_t n = 0; n < dirs.size(); ++n) {
      Request r = request_of(dirs[n]);
      r.op = Op::Gather;
      r.component = uint8_t(component);
      if (excluded(r, true)) {
        ++gather_excluded;
        continue;
      }
      const Texel m = colour.sample(r);
      for (int c = 0; c < 4; ++c)
        ASSERT_EQ(std::lround(got[n][size_t(c)] * 255), m[size_t(c)])
            << "component " << component << " direction (" << dirs[n][0] << ", " << dirs[n][1] << ", " << dirs[n][2]
            << ") texel " << c;
      ++gathers;
    }
  }
  for (const CompareOp op : {CompareOp::LessOrEqual, CompareOp::Greater, CompareOp::Less, CompareOp::NotEqual})
    for (const TexelFilter filter : {TexelFilter::Nearest, TexelFilter::Linear}) {
      SamplerConfig cfg{{filter, MipMode::None}};
      cfg.compare_op = op;
      std::vector<std::array<float, 4>> queries = dirs;
      std::vector<int> refs(queries.size());
      for (size_t n = 0; n < queries.size(); ++n) {
        refs[n] = int(17 * (rng() % 15) + 8);
        queries[n][3] = float(refs[n] / 255.0);
      }
      const std::vector<std::array<float, 4>> got = gl.sample_cube_shadow(cfg, queries);
      Sampler model(depth_cube, cfg, SamplerPaths::Both, TextureKind::Cube);
      for (size_t n = 0; n < queries.size(); ++n) {
        Request r = request_of(queries[n]);
        r.op = Op::Compare;
        r.lod = -8 * 256;  // (level 0, the magnification filter, as GL's zero gradients)
        EXPECT_TRUE(to_coord_fixed(refs[n] / 255.0, r.ref));
        if (excluded(r, filter == TexelFilter::Linear)) continue;
        const int m = model.sample(r)[0];
        const int err = int(std::lround(std::fabs(got[n][0] * 255 - m) * 100));
        if (filter == TexelFilter::Linear && at_corner(r)) {
          ++corners;
          corners_differ += err > 200;
          continue;
        }
        ASSERT_LE(err, filter == TexelFilter::Linear ? 200 : 0)
            << compare_op_name(op) << " " << texel_filter_name(filter) << " direction (" << queries[n][0] << ", "
            << queries[n][1] << ", " << queries[n][2] << ") ref " << refs[n] << ": model " << m << ", GL "
            << got[n][0] * 255;
        worst = std::max(worst, err);
        ++compares;
      }
    }
  EXPECT_GT(gathers, 4 * kW * kH * 3 / 4);
  EXPECT_GT(compares, 8 * kW * kH * 3 / 4);
  EXPECT_GT(corners, 0);
  std::printf("  cube maps: %d gathers compared with llvmpipe, all exact (%d near a footprint edge left out); %d "
              "compares under 4 operators and both filters: max %.2f LSB; %d linear compares at a corner, %d of them "
              "more than 2 LSB from llvmpipe's average of three tests\n",
              gathers, gather_excluded, compares, worst / 100.0, corners, corners_differ);
}

// Cube maps (samplerCube, GL_TEXTURE_CUBE_MAP_SEAMLESS; the unit's TextureKind::Cube over skirted
// faces): six 16x16 faces of their own noise, every level. Directions anywhere and, half of them,
// within two texels of a face's edge or corner; textureLod under every filter. The model's texels
// are llvmpipe's within a linear filter's precision (nearest filters exactly), away from a tie
// between two major axes (either face is right), texel and level edges. A model that clamps to
// its face instead of reading across the seam is caught near the edges.
TEST(GlSamplerStates, CubeMapsAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  constexpr int kN = 16;
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6; ++f) {
    Image img = make_pattern("noise", kN, kN);
    for (Texel& t : img.texels)
      for (uint16_t& c : t) c = uint16_t((c * (f + 2) + 41 * f) & 255);
    faces.push_back(build_pyramid(std::move(img)));
  }
  std::vector<const Pyramid*> cube;
  for (const Pyramid& p : faces) cube.push_back(&p);
  gl.upload_cube(cube);
  std::mt19937 rng(50);
  auto grid = [&](double lo, double hi) { return lo + int(rng() % uint32_t((hi - lo) * 65536)) / 65536.0; };
  int states = 0, compared = 0, worst = 0, seam = 0, clamped_differs = 0;
  double sum = 0;
  for (int mip = 0; mip < 3; ++mip)
    for (int texel = 0; texel < 2; ++texel) {
      SamplerConfig cfg{{TexelFilter(texel), MipMode(mip)}};
      std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
      std::vector<bool> near_seam(queries.size());
      std::vector<Request> requests(queries.size());
      for (size_t n = 0; n < queries.size(); ++n) {
        double d[3];
        if (n % 2) {
          for (double& c : d) c = grid(-1, 1);
        } else {  // a face's point within two texels of its edge (or corner), on the unit cube
          const int f = int(rng() % 6);
          auto near_edge = [&] { return rng() % 2 ? grid(0, 2.0 / kN) : 1 - grid(0, 2.0 / kN); };
          const double s = near_edge(), t = rng() % 3 ? grid(0, 1) : near_edge();
          const double sc = 2 * s - 1, tc = 2 * t - 1;
          const double table[6][3] = {{1, -tc, -sc}, {-1, -tc, sc}, {sc, 1, tc}, {sc, -1, -tc}, {sc, -tc, 1}, {-sc, -tc, -1}};
          for (int c = 0; c < 3; ++c) d[c] = table[f][c];
          near_seam[n] = true;
        }
        const double lambda = (int(rng() % uint32_t(7 * 256)) - 2 * 256) / 256.0;
        queries[n] = {float(d[0]), float(d[1]), float(d[2]), float(lambda)};
        Request& r = requests[n];
        EXPECT_TRUE(to_coord_fixed(d[0], r.u) && to_coord_fixed(d[1], r.v) && to_coord_fixed(d[2], r.w) &&
                    to_lod_fixed(lambda, r.lod));
      }
      const std::vector<std::array<float, 4>> got = gl.sample_cube(cfg, queries);
      Sampler model(cube, cfg, SamplerPaths::Both, TextureKind::Cube);
      for (size_t n = 0; n < requests.size(); ++n) {
        const Request& r = requests[n];
        double a[3] = {std::fabs(queries[n][0]), std::fabs(queries[n][1]), std::fabs(queries[n][2])};
        std::sort(a, a + 3);
        if (a[2] == 0 || a[2] - a[1] < 1e-5 * a[2]) continue;  // a tie of two major axes
        const double lambda = r.lod / 256.0;
        const TexelFilter tf = lambda <= 0 ? cfg.filter.mag : cfg.filter.texel;
        bool edge = std::fabs(lambda) < 1.0 / 64;
        if (lambda > 0 && cfg.filter.mip == MipMode::Nearest) edge = edge || std::fabs(lambda - std::floor(lambda) - 0.5) < 1.0 / 64;
        int face = 0;
        const Request q = cube_face_request(r, face);
        if (tf == TexelFilter::Nearest)
          for (int k = 0; k < 5; ++k)
            for (int32_t c : {q.u, q.v}) {
              const double t = c / 16777216.0 * (kN >> k);
              edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
            }
        if (edge) continue;
        const Texel m = model.sample(r);
        const int err = error_lsb_x100(m, got[n], false);
        const bool nearest = tf == TexelFilter::Nearest && cfg.filter.mip != MipMode::Linear;
        ASSERT_LE(err, nearest ? 0 : 200) << filter_name(cfg.filter) << " direction (" << queries[n][0] << ", "
                                          << queries[n][1] << ", " << queries[n][2] << ") lod " << lambda << " face "
                                          << face << ": model " << m[0] << "," << m[1] << "," << m[2] << "," << m[3];
        worst = std::max(worst, err);
        sum += err / 100.0;
        ++compared;
        if (near_seam[n]) {
          ++seam;
          // The face alone, clamped at its edges: what a unit without seamless filtering gives.
          SamplerConfig clamp = cfg;
          clamp.wrap_u = clamp.wrap_v = Wrap::Clamp;
          Request flat = q;
          flat.has_derivatives = false;
          clamped_differs += error_lsb_x100(Sampler(faces[size_t(face)], clamp).sample(flat), got[n], false) > 200;
        }
      }
      ++states;
    }
  EXPECT_EQ(states, 6);
  EXPECT_GT(compared, 6 * kW * kH * 3 / 4);
  EXPECT_LE(sum / compared, 0.4);
  EXPECT_GT(clamped_differs, seam / 20) << "a cube clamped at its face edges went unnoticed";
  std::printf("  %d cube lookups (%d within two texels of a seam) in %d filters compared with llvmpipe: max %.2f LSB, "
              "mean %.3f; a face clamped at its edges instead differs in %d\n", compared, seam, states, worst / 100.0,
              sum / compared, clamped_differs);
}

// Cube arrays (samplerCubeArray): three cubes of six 8x8 faces each of their own noise, the cube
// index a layer coordinate from -1 to 3.5 (rounded and clamped as an array's layer; ties between
// two cubes not compared); every filter at levels -0.5, 0.3, 1.6. The model's texels are llvmpipe's
// within a linear filter's precision (nearest exact). A model with its cubes in the other order is
// caught.
TEST(GlSamplerStates, CubeArraysAgreeWithLlvmpipe) {
  GlSampling gl;
  ASSERT_TRUE(gl.ready()) << "no GL 3.3 core context from OSMesa";
  constexpr int kN = 8, kCubes = 3;
  std::vector<Pyramid> faces;
  for (int f = 0; f < 6 * kCubes; ++f) {
    Image img = make_pattern("noise", kN, kN);
    for (Texel& t : img.texels)
      for (uint16_t& c : t) c = uint16_t((c * (f % 7 + 2) + 29 * f) & 255);
    faces.push_back(build_pyramid(std::move(img)));
  }
  std::vector<const Pyramid*> cubes;
  for (const Pyramid& p : faces) cubes.push_back(&p);
  std::vector<const Pyramid*> swapped(cubes.begin() + 6, cubes.begin() + 12);  // cubes 1, 0, 2
  swapped.insert(swapped.end(), cubes.begin(), cubes.begin() + 6);
  swapped.insert(swapped.end(), cubes.begin() + 12, cubes.end());
  gl.upload_cube_array(cubes);
  std::mt19937 rng(51);
  int compared = 0, worst = 0, caught = 0;
  for (int mip = 0; mip < 3; ++mip)
    for (int texel = 0; texel < 2; ++texel)
      for (const double lambda : {-0.5, 0.3, 1.6}) {
        SamplerConfig cfg{{TexelFilter(texel), MipMode(mip)}};
        std::vector<std::array<float, 4>> queries(size_t(kW) * kH);
        std::vector<Request> requests(queries.size());
        for (size_t n = 0; n < queries.size(); ++n) {
          double d[3];
          for (double& c : d) c = (int(rng() % (2 << 16)) - (1 << 16)) / 65536.0;
          const double layer = (int(rng() % (18 * 64)) - 4 * 64) / 256.0;  // -1 .. 3.5 on a 1/256 grid
          queries[n] = {float(d[0]), float(d[1]), float(d[2]), float(layer)};
          Request& r = requests[n];
          EXPECT_TRUE(to_coord_fixed(d[0], r.u) && to_coord_fixed(d[1], r.v) && to_coord_fixed(d[2], r.w) &&
                      to_texel_coord_fixed(layer, r.layer) && to_lod_fixed(lambda, r.lod));
        }
        const std::vector<std::array<float, 4>> got = gl.sample_cube_array(cfg, float(lambda), queries);
        Sampler model(cubes, cfg, SamplerPaths::Both, TextureKind::Cube), wrong(swapped, cfg, SamplerPaths::Both, TextureKind::Cube);
        for (size_t n = 0; n < requests.size(); ++n) {
          const Request& r = requests[n];
          double a[3] = {std::fabs(queries[n][0]), std::fabs(queries[n][1]), std::fabs(queries[n][2])};
          std::sort(a, a + 3);
          if (a[2] == 0 || a[2] - a[1] < 1e-5 * a[2]) continue;  // a tie of two major axes
          if (std::fabs(queries[n][3] - std::floor(queries[n][3]) - 0.5) < 1.0 / 64) continue;  // a tie of two cubes
          const TexelFilter tf = lambda <= 0 ? cfg.filter.mag : cfg.filter.texel;
          int face = 0;
          const Request q = cube_face_request(r, face);
          bool edge = cfg.filter.mip == MipMode::Nearest && std::fabs(lambda - std::floor(lambda) - 0.5) < 1.0 / 64;
          if (tf == TexelFilter::Nearest)
            for (int k = 0; k < 4; ++k)
              for (int32_t c : {q.u, q.v}) {
                const double t = c / 16777216.0 * (kN >> k);
                edge = edge || std::fabs(t - std::round(t)) < 1.0 / 64;
              }
          if (edge) continue;
          const Texel m = model.sample(r);
          const int err = error_lsb_x100(m, got[n], false);
          const bool nearest = tf == TexelFilter::Nearest && cfg.filter.mip != MipMode::Linear;
          ASSERT_LE(err, nearest ? 0 : 200) << filter_name(cfg.filter) << " lod " << lambda << " direction ("
                                            << queries[n][0] << ", " << queries[n][1] << ", " << queries[n][2]
                                            << ") cube " << queries[n][3];
          worst = std::max(worst, err);
          caught += error_lsb_x100(wrong.sample(r), got[n], false) > 200;
          ++compared;
        }
      }
  EXPECT_GT(compared, 18 * kW * kH / 2);
  EXPECT_GT(caught, compared / 4) << "a model with two cubes swapped went unnoticed";
  std::printf("  %d cube-array lookups (3 cubes) compared with llvmpipe: max %.2f LSB; cubes 0 and 1 swapped differ "
              "in %d\n", compared, worst / 100.0, caught);
}
