#include "gl_program.h"

#include <string>

#include "lapis/core/error.h"

namespace lapis::viewer {

namespace {

GLuint compile(GLenum type, const char* source) {
  const GLuint s = glCreateShader(type);
  glShaderSource(s, 1, &source, nullptr);
  glCompileShader(s);
  GLint ok = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    throw Error(std::string("viewer: shader compilation failed: ") + log);
  }
  return s;
}

}  // namespace

GLuint link_program(const char* vs, const char* fs) { return link_program(vs, nullptr, fs); }

GLuint link_program(const char* vs, const char* gs, const char* fs) {
  const GLuint p = glCreateProgram();
  const GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
  const GLuint g = gs ? compile(GL_GEOMETRY_SHADER, gs) : 0;
  glAttachShader(p, v);
  if (g) glAttachShader(p, g);
  glAttachShader(p, f);
  glLinkProgram(p);
  glDeleteShader(v);
  if (g) glDeleteShader(g);
  glDeleteShader(f);
  GLint ok = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048];
    glGetProgramInfoLog(p, sizeof log, nullptr, log);
    throw Error(std::string("viewer: program link failed: ") + log);
  }
  return p;
}

}  // namespace lapis::viewer
