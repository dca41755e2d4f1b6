#include "gl_buffers.hpp"

#include <algorithm>
#include <string>

#include "prism/errors.hpp"

namespace prism::gl {

Buffer::Buffer(const void* data, size_t bytes) : bytes_(std::max<size_t>(bytes, 32)) {
  glCreateBuffers(1, &id_);
  std::vector<unsigned char> padded;
  if (bytes < bytes_) {  // too small (or empty): pad so the binding is legal
    padded.assign(bytes_, 0);
    if (bytes) std::copy_n(static_cast<const unsigned char*>(data), bytes, padded.begin());
    data = padded.data();
  }
  glNamedBufferStorage(id_, GLsizeiptr(bytes_), data, GL_DYNAMIC_STORAGE_BIT);
  if (GLenum error = glGetError(); error != GL_NO_ERROR) {
    glDeleteBuffers(1, &id_);
    id_ = 0;
    throw RuntimeError("OpenGL cannot allocate a " + std::to_string(bytes_) + "-byte buffer" +
                       (error == GL_OUT_OF_MEMORY ? " (out of memory)" : ""));
  }
}

Buffer::~Buffer() {
  if (id_) glDeleteBuffers(1, &id_);
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    if (id_) glDeleteBuffers(1, &id_);
    id_ = other.id_;
    bytes_ = other.bytes_;
    other.id_ = 0;
  }
  return *this;
}

}  // namespace prism::gl
