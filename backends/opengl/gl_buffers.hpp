// Storage buffers for the generated kernels: immutable GL buffers made
// from host vectors, owned and freed with the backend.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

namespace prism::gl {

class Buffer {
 public:
  Buffer() = default;
  Buffer(const void* data, size_t bytes);  // at least 32 bytes: GL refuses empty bindings
  ~Buffer();
  Buffer(Buffer&& other) noexcept : id_(other.id_), bytes_(other.bytes_) { other.id_ = 0; }
  Buffer& operator=(Buffer&& other) noexcept;
  Buffer(const Buffer&) = delete;
  Buffer& operator=(const Buffer&) = delete;

  template <class T>
  static Buffer of(std::span<const T> items) {
    return Buffer(items.data(), items.size_bytes());
  }
  void bind(GLuint binding) const { glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, id_); }
  void read(size_t offset, size_t bytes, void* out) const { glGetNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), out); }
  void write(size_t offset, size_t bytes, const void* data) const {
    glNamedBufferSubData(id_, GLintptr(offset), GLsizeiptr(bytes), data);
  }
  size_t bytes() const { return bytes_; }
  GLuint id() const { return id_; }

 private:
  GLuint id_ = 0;
  size_t bytes_ = 0;
};

}  // namespace prism::gl
