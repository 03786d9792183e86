// The GL reference tests' shader compile (Mesa through OSMesa): a failed compile is a test failure
// with the GLSL log. Include after the GL headers (GL_GLEXT_PROTOTYPES defined).
#pragma once
#include <gtest/gtest.h>

#include <vector>

#include "model/image.h"

inline GLuint compile_shader(GLenum kind, const char* text) {
  const GLuint s = glCreateShader(kind);
  glShaderSource(s, 1, &text, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[1024] = {};
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    ADD_FAILURE() << "GLSL: " << log;
  }
  return s;
}

// The RGBA8 bytes of an image's texels (8-bit channels), row after row, for glTexImage*.
inline std::vector<uint8_t> rgba8_bytes(const tex::Image& img) {
  std::vector<uint8_t> out;
  out.reserve(img.texels.size() * 4);
  for (const tex::Texel& t : img.texels)
    for (int c = 0; c < 4; ++c) out.push_back(uint8_t(t[size_t(c)]));
  return out;
}
