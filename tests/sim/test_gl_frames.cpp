// Real frames against OpenGL (Mesa through OSMesa): each test model drawn the way an OpenGL viewer
// draws it (unlit, base colour only), from Assimp's own texture coordinates (v = 0 at the bottom of
// the image, GL's convention, no flip) on textures uploaded bottom row first, gluLookAt +
// gluPerspective, back faces culled unless double-sided, GL_LINEAR_MIPMAP_LINEAR on texsim's
// levels (upload()), GL_LESS depth. texsim renders the same view through its own loader, camera,
// rasterizer and golden model; the two pictures must agree (docs/scenes.md, "Conventions").
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/glu.h>
#include <GL/osmesa.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <assimp/GltfMaterial.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli_fixture.h"
#include "gl_shader.h"
#include "model/pyramid.h"
#include "model/srgb.h"
#include "workloads/texture_files.h"

namespace {

constexpr int kW = 192, kH = 144;
const uint8_t kBackground[3] = {48, 48, 56};  // texsim's background

GLint gl_wrap(int mode) {
  return mode == aiTextureMapMode_Clamp || mode == aiTextureMapMode_Decal ? GL_CLAMP_TO_EDGE
         : mode == aiTextureMapMode_Mirror                                 ? GL_MIRRORED_REPEAT
                                                                          : GL_REPEAT;
}

// A texture file as a GL viewer uploads it: RGBA8 (gray to RGB, opaque without alpha; sRGB8_ALPHA8
// for colour data in sRGB), of the file's size (GL ES 3 takes any), the bottom row first; the
// material's sampler (glTF's filters, GL's codes) or trilinear. Level 0 is the file as OpenImageIO
// reads it; levels 1.. are texsim's box pyramid of it (`build_pyramid`, `srgb_box_levels`), not
// glGenerateMipmap's: GL leaves the filter of a level to the implementation, and on odd sides
// Mesa's differs from texsim's area mean (docs/numerics.md "Pyramid"), while the sampling is what
// is compared here (the pyramids have their own checks: Pyramid.*).
GLuint upload(const std::string& path, GLint wrap_s, GLint wrap_t, bool srgb, GLint min_filter, GLint mag_filter) {
  OIIO::ImageBuf src(path);
  EXPECT_TRUE(src.read(0, 0, true, OIIO::TypeDesc::UINT8)) << path;
  const int w = src.spec().width, h = src.spec().height, nc = src.spec().nchannels;
  std::vector<uint8_t> px(size_t(w) * h * nc);
  src.get_pixels(OIIO::ROI(0, w, 0, h, 0, 1, 0, nc), OIIO::TypeDesc::UINT8, px.data());
  tex::Image level0(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const uint8_t* s = &px[(size_t(y) * w + x) * nc];
      level0.at(x, y) = {s[0], uint16_t(nc >= 3 ? s[1] : s[0]), uint16_t(nc >= 3 ? s[2] : s[0]),
                         uint16_t(nc == 4 ? s[3] : nc == 2 ? s[1] : 255)};
    }
  const std::vector<tex::Image> levels = srgb ? tex::srgb_box_levels(level0, tex::PyramidMode::Exact)
                                              : tex::build_pyramid(level0, tex::PyramidMode::Exact).levels;
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (size_t k = 0; k < levels.size(); ++k) {
    const tex::Image& l = levels[k];
    std::vector<uint8_t> rgba(size_t(l.width) * l.height * 4);
    for (int y = 0; y < l.height; ++y)
      for (int x = 0; x < l.width; ++x)
        for (int c = 0; c < 4; ++c)  // bottom row first
          rgba[(size_t(l.height - 1 - y) * l.width + x) * 4 + c] = uint8_t(l.at(x, y)[size_t(c)]);
    glTexImage2D(GL_TEXTURE_2D, GLint(k), srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, l.width, l.height, 0, GL_RGBA,
                 GL_UNSIGNED_BYTE, rgba.data());
  }
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, min_filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, mag_filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, wrap_s);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, wrap_t);
  return id;
}

struct GlFrame {
  std::vector<uint8_t> rgb;  // top row first
  double eye[3], target[3];
};

// The model drawn by OpenGL from a camera looking at its bounding box's centre. `flip_rows`
// false uploads the textures top row first (a planted convention bug). `srgb`: the textures are
// sRGB (glTF 2's base colour): GL decodes them before filtering into a float frame, which is
// encoded to sRGB codes after, as an sRGB framebuffer stores it.
GlFrame render_gl(const std::string& path, bool flip_rows, bool srgb) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                     aiProcess_JoinIdenticalVertices | aiProcess_SortByPType);
  EXPECT_TRUE(scene) << path << ": " << importer.GetErrorString();
  GlFrame f;
  if (!scene) return f;
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    for (unsigned i = 0; i < scene->mMeshes[m]->mNumVertices; ++i)
      for (int c = 0; c < 3; ++c) {
        lo[c] = std::min(lo[c], double(scene->mMeshes[m]->mVertices[i][c]));
        hi[c] = std::max(hi[c], double(scene->mMeshes[m]->mVertices[i][c]));
      }
  double radius = 0;
  for (int c = 0; c < 3; ++c) {
    f.target[c] = (lo[c] + hi[c]) / 2;
    radius += (hi[c] - lo[c]) * (hi[c] - lo[c]) / 4;
  }
  radius = std::sqrt(radius);
  const double dir[3] = {0.55, 0.35, 0.76};  // from the front right, a little above
  for (int c = 0; c < 3; ++c) f.eye[c] = f.target[c] + dir[c] * 2.6 * radius;

  std::vector<uint8_t> buffer(size_t(kW) * kH * 4);
  std::vector<float> linear(srgb ? size_t(kW) * kH * 4 : 0);
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  EXPECT_TRUE(ctx);
  EXPECT_TRUE(srgb ? OSMesaMakeCurrent(ctx, linear.data(), GL_FLOAT, kW, kH)
                   : OSMesaMakeCurrent(ctx, buffer.data(), GL_UNSIGNED_BYTE, kW, kH));
  glViewport(0, 0, kW, kH);
  auto clear = [&](int c) { return float(srgb ? tex::srgb_to_linear(kBackground[c] / 255.0) : kBackground[c] / 255.0); };
  glClearColor(clear(0), clear(1), clear(2), 1.f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  gluPerspective(45.0, double(kW) / kH, radius * 0.05, radius * 10);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  gluLookAt(f.eye[0], f.eye[1], f.eye[2], f.target[0], f.target[1], f.target[2], 0, 1, 0);
  glEnable(GL_TEXTURE_2D);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glFrontFace(GL_CCW);
  const std::string dir_of = fs::path(path).parent_path().string();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    const aiMaterial* mat = scene->mMaterials[mesh->mMaterialIndex];
    aiString tex;
    aiTextureType type = aiTextureType_BASE_COLOR;
    if (mat->GetTexture(type, 0, &tex) != AI_SUCCESS) {
      type = aiTextureType_DIFFUSE;
      if (mat->GetTexture(type, 0, &tex) != AI_SUCCESS) continue;
    }
    if (!mesh->HasTextureCoords(0)) continue;
    std::string name = tex.C_Str();
    std::replace(name.begin(), name.end(), '\\', '/');
    int mode_u = aiTextureMapMode_Wrap, mode_v = aiTextureMapMode_Wrap;
    mat->Get(AI_MATKEY_MAPPINGMODE_U(type, 0), mode_u);
    mat->Get(AI_MATKEY_MAPPINGMODE_V(type, 0), mode_v);
    int min_filter = GL_LINEAR_MIPMAP_LINEAR, mag_filter = GL_LINEAR;  // glTF samplers: GL's codes
    mat->Get(AI_MATKEY_GLTF_MAPPINGFILTER_MIN(type, 0), min_filter);
    mat->Get(AI_MATKEY_GLTF_MAPPINGFILTER_MAG(type, 0), mag_filter);
    const GLuint id = upload(dir_of + "/" + name, gl_wrap(mode_u), gl_wrap(mode_v), srgb, min_filter, mag_filter);
    if (!flip_rows) {  // planted: the same texels uploaded top row first
      glDeleteTextures(1, &id);
      OIIO::ImageBuf src(dir_of + "/" + name);
      OIIO::ImageBuf flipped = OIIO::ImageBufAlgo::flip(src);
      const std::string tmp = (fs::temp_directory_path() / ("gl_flip_" + std::to_string(getpid()) + ".png")).string();
      flipped.write(tmp);
      upload(tmp, gl_wrap(mode_u), gl_wrap(mode_v), srgb, min_filter, mag_filter);
      fs::remove(tmp);
    }
    int two_sided = 0;
    mat->Get(AI_MATKEY_TWOSIDED, two_sided);
    if (two_sided) glDisable(GL_CULL_FACE);
    else glEnable(GL_CULL_FACE);
    glBegin(GL_TRIANGLES);
    for (unsigned t = 0; t < mesh->mNumFaces; ++t) {
      if (mesh->mFaces[t].mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        const unsigned i = mesh->mFaces[t].mIndices[k];
        glTexCoord2f(mesh->mTextureCoords[0][i].x, mesh->mTextureCoords[0][i].y);
        glVertex3f(mesh->mVertices[i].x, mesh->mVertices[i].y, mesh->mVertices[i].z);
      }
    }
    glEnd();
  }
  glFinish();
  for (size_t i = 0; i < linear.size(); ++i)  // the sRGB framebuffer's encoding
    buffer[i] = uint8_t(std::lround(255.0 * tex::linear_to_srgb(std::clamp(double(linear[i]), 0.0, 1.0))));
  f.rgb.resize(size_t(kW) * kH * 3);
  for (int y = 0; y < kH; ++y)  // OSMesa's row 0 is the bottom
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) f.rgb[(size_t(y) * kW + x) * 3 + c] = buffer[(size_t(kH - 1 - y) * kW + x) * 4 + c];
  OSMesaDestroyContext(ctx);
  return f;
}

struct Agreement {
  double coverage = 0;  // pixels both draw, or both leave as background
  double close = 0;     // of the pixels both draw: max channel difference <= 24
  double mean = 0;      // mean absolute channel difference over the pixels both draw
};

Agreement compare(const std::vector<uint8_t>& gl, const std::vector<uint8_t>& ours_rgba) {
  size_t same_coverage = 0, both = 0, close = 0;
  double sum = 0;
  for (size_t p = 0; p < size_t(kW) * kH; ++p) {
    const uint8_t* a = &gl[p * 3];
    const uint8_t* b = &ours_rgba[p * 4];
    const bool bg_a = a[0] == kBackground[0] && a[1] == kBackground[1] && a[2] == kBackground[2];
    const bool bg_b = b[0] == kBackground[0] && b[1] == kBackground[1] && b[2] == kBackground[2];
    same_coverage += bg_a == bg_b;
    if (bg_a || bg_b) continue;
    ++both;
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      worst = std::max(worst, std::abs(int(a[c]) - int(b[c])));
      sum += std::abs(int(a[c]) - int(b[c]));
    }
    close += worst <= 24;
  }
  Agreement g;
  g.coverage = double(same_coverage) / (double(kW) * kH);
  g.close = both ? double(close) / double(both) : 0;
  g.mean = both ? sum / (3.0 * double(both)) : 0;
  return g;
}

}  // namespace

class GlFrames : public TexsimCli {
 protected:
  // glTF 2's base colour is sRGB (its specification); the other formats' textures linear.
  Agreement against_gl(const std::string& model, bool flip_rows = true) {
    const bool srgb = model.find("/glTF2/") != std::string::npos;
    const GlFrame gl = render_gl(model, flip_rows, srgb);
    char camera[256];
    std::snprintf(camera, sizeof camera, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,45", gl.eye[0], gl.eye[1], gl.eye[2],
                  gl.target[0], gl.target[1], gl.target[2]);
    const Result r = run("render --model " + model + " --memory cached --camera " + camera + " --width " +
                         std::to_string(kW) + " --height " + std::to_string(kH) + " --out ours.png");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    int w = 0, h = 0;
    const std::vector<uint8_t> ours = read_image(dir / "ours.png", w, h);
    EXPECT_EQ(w, kW);
    if (ours.empty() || gl.rgb.empty()) return {};
    return compare(gl.rgb, ours);
  }
};

// glTF 2.0 (top-left texture origin in the file), COLLADA and OBJ (bottom-left): texsim's frame is
// OpenGL's, pixel for pixel but for edges (coverage) and LOD/filter rounding.
TEST_F(GlFrames, TestModelsLookAsOpenGLDrawsThem) {
  for (const char* m : {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "Collada/duck.dae", "OBJ/spider.obj"}) {
    const std::string model = std::string("/usr/share/assimp/models/") + m;
    const Agreement g = against_gl(model);
    std::printf("[ gl       ] %s: coverage %.4f, pixels within 24 LSB %.4f, mean difference %.2f LSB\n", m,
                g.coverage, g.close, g.mean);
    EXPECT_GT(g.coverage, 0.999) << m;  // the same rasterization rules, culling and depth test
    EXPECT_GT(g.close, 0.999) << m;
    EXPECT_LT(g.mean, 1.0) << m;
  }
}

// The check fires: textures uploaded top row first (the usual convention mistake) disagree.
TEST_F(GlFrames, UpsideDownTexturesAreCaught) {
  const Agreement g = against_gl("/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf", false);
  std::printf("[ gl       ] upside down: coverage %.4f, pixels within 24 LSB %.4f, mean difference %.2f LSB\n",
              g.coverage, g.close, g.mean);
  EXPECT_GT(g.coverage, 0.999);  // the geometry is the same
  EXPECT_LT(g.close, 0.9);
}

// The paper's reflection mapping (render --envmap): the duck as a mirror of a cube map, drawn by
// OpenGL with a GLSL shader that reflects the view ray by the interpolated normal per pixel and
// samples a seamless samplerCube (implicit derivatives: llvmpipe's quad differences), on the faces
// texsim converts the equirectangular environment to (load_envmap, every level uploaded). texsim's
// mirror pixels agree with OpenGL's but for LOD and filter rounding; GL reflecting the reversed view
// ray (the eye's direction from the surface, a sign slip that gives -R) disagrees.
namespace {

// The mirror drawn by GL: rgb and which pixels it drew.
struct MirrorFrame {
  std::vector<uint8_t> rgb;
  std::vector<bool> drawn;
};
MirrorFrame render_gl_mirror(const std::string& path, const std::vector<tex::Pyramid>& faces, const double eye[3],
                             const double target[3], double radius, bool reversed) {
  Assimp::Importer importer;
  const aiScene* scene = importer.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                                     aiProcess_JoinIdenticalVertices | aiProcess_SortByPType |
                                                     aiProcess_GenSmoothNormals);
  EXPECT_TRUE(scene) << importer.GetErrorString();
  MirrorFrame f;
  if (!scene) return f;
  std::vector<uint8_t> buffer(size_t(kW) * kH * 4);
  OSMesaContext ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, nullptr);
  EXPECT_TRUE(ctx && OSMesaMakeCurrent(ctx, buffer.data(), GL_UNSIGNED_BYTE, kW, kH));
  glViewport(0, 0, kW, kH);
  glClearColor(0, 0, 0, 0);  // alpha 0: not drawn
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  gluPerspective(45.0, double(kW) / kH, radius * 0.05, radius * 10);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  gluLookAt(eye[0], eye[1], eye[2], target[0], target[1], target[2], 0, 1, 0);
  GLuint cube = 0;
  glGenTextures(1, &cube);
  glBindTexture(GL_TEXTURE_CUBE_MAP, cube);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int face = 0; face < 6; ++face)
    for (size_t k = 0; k < faces[size_t(face)].levels.size(); ++k) {
      const tex::Image& img = faces[size_t(face)].levels[k];
      const std::vector<uint8_t> rgba = rgba8_bytes(img);
      glTexImage2D(GLenum(GL_TEXTURE_CUBE_MAP_POSITIVE_X + face), GLint(k), GL_RGBA8, img.width, img.height, 0, GL_RGBA,
                   GL_UNSIGNED_BYTE, rgba.data());
    }
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  const GLuint program = glCreateProgram();
  glAttachShader(program, compile_shader(GL_VERTEX_SHADER, R"(#version 120
    varying vec3 world, normal;
    void main() {
      world = gl_Vertex.xyz;  // (PreTransformVertices: world space; the modelview is the view alone)
      normal = gl_Normal;
      gl_Position = gl_ModelViewProjectionMatrix * gl_Vertex;
    })"));
  glAttachShader(program, compile_shader(GL_FRAGMENT_SHADER, R"(#version 120
    uniform samplerCube env;
    uniform vec3 eye;
    uniform float sign;
    varying vec3 world, normal;
    void main() {
      vec3 r = reflect(sign * normalize(world - eye), normalize(normal));
      gl_FragColor = vec4(textureCube(env, r).rgb, 1.0);
    })"));
  glLinkProgram(program);
  glUseProgram(program);
  glUniform1i(glGetUniformLocation(program, "env"), 0);
  glUniform3f(glGetUniformLocation(program, "eye"), float(eye[0]), float(eye[1]), float(eye[2]));
  glUniform1f(glGetUniformLocation(program, "sign"), reversed ? -1.f : 1.f);
  glBegin(GL_TRIANGLES);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    for (unsigned t = 0; t < mesh->mNumFaces; ++t) {
      if (mesh->mFaces[t].mNumIndices != 3) continue;
      for (int k = 0; k < 3; ++k) {
        const unsigned i = mesh->mFaces[t].mIndices[k];
        glNormal3f(mesh->mNormals[i].x, mesh->mNormals[i].y, mesh->mNormals[i].z);
        glVertex3f(mesh->mVertices[i].x, mesh->mVertices[i].y, mesh->mVertices[i].z);
      }
    }
  }
  glEnd();
  glFinish();
  f.rgb.resize(size_t(kW) * kH * 3);
  f.drawn.resize(size_t(kW) * kH);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const uint8_t* p = &buffer[(size_t(kH - 1 - y) * kW + x) * 4];
      for (int c = 0; c < 3; ++c) f.rgb[(size_t(y) * kW + x) * 3 + c] = p[c];
      f.drawn[size_t(y) * kW + x] = p[3] != 0;
    }
  OSMesaDestroyContext(ctx);
  return f;
}

}  // namespace

TEST_F(GlFrames, ChromeDuckReflectsAsOpenGLDrawsIt) {
  const std::string model = "/usr/share/assimp/models/Collada/duck.dae";
  const std::string env = "gradient:256x128";
  std::string how;
  const std::vector<tex::Pyramid> faces = tex::load_envmap(env, tex::TextureOptions{}, how);
  const GlFrame view = render_gl(model, true, false);  // (its camera)
  double radius = 0;
  for (int c = 0; c < 3; ++c) radius += (view.eye[c] - view.target[c]) * (view.eye[c] - view.target[c]);
  radius = std::sqrt(radius) / 2.6;
  char camera[256];
  std::snprintf(camera, sizeof camera, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,45", view.eye[0], view.eye[1], view.eye[2],
                view.target[0], view.target[1], view.target[2]);
  const Result r = run("render --model " + model + " --envmap " + env + " --camera " + camera + " --width " +
                       std::to_string(kW) + " --height " + std::to_string(kH) + " --out mirror.png");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("a mirror of"), std::string::npos) << r.out;
  int w = 0, h = 0;
  const std::vector<uint8_t> ours = read_image(dir / "mirror.png", w, h);
  ASSERT_EQ(w, kW);
  for (bool reversed : {false, true}) {
    const MirrorFrame gl = render_gl_mirror(model, faces, view.eye, view.target, radius, reversed);
    size_t drawn = 0, close = 0;
    double sum = 0;
    for (size_t p = 0; p < size_t(kW) * kH; ++p) {
      if (!gl.drawn[p]) continue;
      ++drawn;
      int worst = 0;
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(gl.rgb[p * 3 + c]) - int(ours[p * 4 + size_t(c)]));
        worst = std::max(worst, d);
        sum += d;
      }
      close += worst <= 24;
    }
    const double fraction = double(close) / double(drawn), mean = sum / (3.0 * double(drawn));
    std::printf("[ gl       ] chrome duck%s: %zu mirror pixels, within 24 LSB %.4f, mean difference %.2f LSB\n",
                reversed ? " (GL planted with the view ray reversed)" : "", drawn, fraction, mean);
    EXPECT_GT(drawn, size_t(kW) * kH / 8);
    if (reversed) {
      EXPECT_LT(fraction, 0.9) << "a mirror reflecting the reversed view ray went unnoticed";
    } else {
      EXPECT_GT(fraction, 0.98);
      EXPECT_LT(mean, 3.0);
    }
  }
}
