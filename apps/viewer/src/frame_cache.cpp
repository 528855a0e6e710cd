#include "frame_cache.h"

#include "gl_program.h"

namespace lapis::viewer {
namespace {

// A triangle covering the viewport, its texture coordinates from gl_VertexID: no buffers.
constexpr const char* kVertex = R"(#version 330 core
out vec2 uv;
void main() {
  vec2 p = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);
  uv = p;
  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)";
constexpr const char* kFragment = R"(#version 330 core
in vec2 uv;
uniform sampler2D picture;
out vec4 color;
void main() { color = texture(picture, uv); }
)";

}  // namespace

FrameCache::FrameCache() {
  program_ = link_program(kVertex, kFragment);
  glGenVertexArrays(1, &vao_);
  glGenTextures(1, &texture_);
  glGenFramebuffers(1, &framebuffer_);
}

FrameCache::~FrameCache() {
  glDeleteFramebuffers(1, &framebuffer_);
  glDeleteTextures(1, &texture_);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

bool FrameCache::draw(std::uint64_t signature, int width, int height) {
  if (!valid_ || signature != signature_ || width != width_ || height != height_) return false;
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, texture_);
  glUniform1i(glGetUniformLocation(program_, "picture"), 0);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glEnable(GL_DEPTH_TEST);
  return true;
}

void FrameCache::store(std::uint64_t signature, int width, int height) {
  GLint drawn = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
  if (width != width_ || height != height_) {
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_, 0);
    width_ = width, height_ = height;
  }
  while (glGetError() != GL_NO_ERROR) {
  }
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(drawn));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(drawn));
  signature_ = signature;
  valid_ = glGetError() == GL_NO_ERROR;  // else every frame draws the scene, as without a cache
}

}  // namespace lapis::viewer
