#include "gl_display.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstring>
#include <string>

#include "prism/errors.hpp"

namespace prism::viewer {

namespace {

// A rectangle in window pixels (origin bottom-left, as GL counts), covered
// by a two-triangle strip; the fragment shader maps each pixel to a texel
// with integer arithmetic, flipping rows because texture row 0 holds the
// image's top row.
constexpr const char* kVertexShader = R"(#version 330 core
uniform ivec4 u_rect;      // x, y, width, height in window pixels, y from the bottom
uniform ivec2 u_viewport;
void main() {
  vec2 corner = vec2(gl_VertexID & 1, gl_VertexID >> 1);
  vec2 pixel = vec2(u_rect.xy) + corner * vec2(u_rect.zw);
  gl_Position = vec4(pixel / vec2(u_viewport) * 2.0 - 1.0, 0.0, 1.0);
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
uniform ivec4 u_rect;
uniform ivec2 u_tex_size;
uniform sampler2D u_tex;
out vec4 colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy) - u_rect.xy;
  int from_top = u_rect.w - 1 - p.y;
  ivec2 texel = ivec2(p.x * u_tex_size.x / u_rect.z, from_top * u_tex_size.y / u_rect.w);
  colour = texelFetch(u_tex, clamp(texel, ivec2(0), u_tex_size - 1), 0);
}
)";

GLuint compile(GLenum kind, const char* source) {
  GLuint shader = glCreateShader(kind);
  glShaderSource(shader, 1, &source, nullptr);
  glCompileShader(shader);
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetShaderInfoLog(shader, sizeof log, nullptr, log);
    glDeleteShader(shader);
    throw RuntimeError(std::string("viewer: display shader does not compile: ") + log);
  }
  return shader;
}

void check_gl(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) throw RuntimeError(std::string("viewer: OpenGL error ") + std::to_string(error) + " " + what);
}

}  // namespace

GlDisplay::GlDisplay() {
  GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  program_ = glCreateProgram();
  glAttachShader(program_, vs);
  glAttachShader(program_, fs);
  glLinkProgram(program_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = 0;
  glGetProgramiv(program_, GL_LINK_STATUS, &ok);
  if (!ok) {
    char log[2048] = {};
    glGetProgramInfoLog(program_, sizeof log, nullptr, log);
    glDeleteProgram(program_);
    throw RuntimeError(std::string("viewer: display shaders do not link: ") + log);
  }
  u_rect_ = glGetUniformLocation(program_, "u_rect");
  u_viewport_ = glGetUniformLocation(program_, "u_viewport");
  u_tex_size_ = glGetUniformLocation(program_, "u_tex_size");
  u_tex_ = glGetUniformLocation(program_, "u_tex");
  glGenVertexArrays(1, &vao_);  // core profile: drawing needs a bound VAO, even an empty one
  for (Texture* t : {&frame_, &overlay_}) {
    glGenTextures(1, &t->id);
    glBindTexture(GL_TEXTURE_2D, t->id);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
  }
  glBindTexture(GL_TEXTURE_2D, 0);
  check_gl("setting up the display");
}

GlDisplay::~GlDisplay() {
  glDeleteTextures(1, &frame_.id);
  glDeleteTextures(1, &overlay_.id);
  glDeleteVertexArrays(1, &vao_);
  glDeleteProgram(program_);
}

void GlDisplay::upload(Texture& texture, const Rgba8Image& image) {
  glBindTexture(GL_TEXTURE_2D, texture.id);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
  if (texture.width != image.width || texture.height != image.height) {
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, image.width, image.height, 0, GL_RGBA, GL_UNSIGNED_BYTE,
                 image.rgba.data());
    texture.width = image.width;
    texture.height = image.height;
  } else {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  }
}

void GlDisplay::draw_rect(const Texture& texture, int x, int y, int width, int height) {
  glBindTexture(GL_TEXTURE_2D, texture.id);
  glUniform4i(u_rect_, x, y, width, height);
  glUniform2i(u_tex_size_, texture.width, texture.height);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
}

void GlDisplay::draw(const Rgba8Image& frame, const Rgba8Image& overlay, int viewport_width, int viewport_height) {
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glDrawBuffer(GL_BACK);
  glViewport(0, 0, viewport_width, viewport_height);
  glDisable(GL_DITHER);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_FRAMEBUFFER_SRGB);
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glUseProgram(program_);
  glBindVertexArray(vao_);
  glActiveTexture(GL_TEXTURE0);
  glUniform1i(u_tex_, 0);
  glUniform2i(u_viewport_, viewport_width, viewport_height);
  upload(frame_, frame);
  glDisable(GL_BLEND);
  draw_rect(frame_, 0, 0, viewport_width, viewport_height);
  if (overlay.width > 0 && overlay.height > 0) {
    upload(overlay_, overlay);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    draw_rect(overlay_, 0, viewport_height - overlay.height, overlay.width, overlay.height);
    glDisable(GL_BLEND);
  }
  glBindVertexArray(0);
  glUseProgram(0);
  check_gl("drawing the frame");
}

std::vector<uint8_t> GlDisplay::read_back(int width, int height) {
  std::vector<uint8_t> bottom_up(size_t(width) * height * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  std::vector<uint8_t> top_down(bottom_up.size());
  const size_t row = size_t(width) * 4;
  check_gl("reading the back buffer");
  for (int y = 0; y < height; ++y) std::memcpy(&top_down[y * row], &bottom_up[(height - 1 - y) * row], row);
  return top_down;
}

}  // namespace prism::viewer
