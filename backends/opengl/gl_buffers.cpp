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

ReadbackBuffer::ReadbackBuffer(size_t bytes) : bytes_(std::max<size_t>(bytes, 32)) {
  constexpr GLbitfield kMap = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
  glCreateBuffers(1, &id_);
  glNamedBufferStorage(id_, GLsizeiptr(bytes_), nullptr, kMap | GL_CLIENT_STORAGE_BIT);
  if (glGetError() == GL_NO_ERROR) mapped_ = glMapNamedBufferRange(id_, 0, GLsizeiptr(bytes_), kMap);
  if (!mapped_) {
    release();
    throw RuntimeError("OpenGL cannot allocate a " + std::to_string(bytes) + "-byte readback buffer");
  }
}

ReadbackBuffer::~ReadbackBuffer() { release(); }

void ReadbackBuffer::release() {
  if (fence_) glDeleteSync(fence_);
  fence_ = nullptr;
  if (id_) glDeleteBuffers(1, &id_);  // unmaps too
  id_ = 0;
  mapped_ = nullptr;
}

ReadbackBuffer::ReadbackBuffer(ReadbackBuffer&& other) noexcept
    : id_(other.id_), bytes_(other.bytes_), mapped_(other.mapped_), fence_(other.fence_) {
  other.id_ = 0;
  other.mapped_ = nullptr;
  other.fence_ = nullptr;
}

ReadbackBuffer& ReadbackBuffer::operator=(ReadbackBuffer&& other) noexcept {
  if (this != &other) {
    release();
    id_ = other.id_;
    bytes_ = other.bytes_;
    mapped_ = other.mapped_;
    fence_ = other.fence_;
    other.id_ = 0;
    other.mapped_ = nullptr;
    other.fence_ = nullptr;
  }
  return *this;
}

void ReadbackBuffer::start_copy(const Buffer& from, size_t bytes) {
  wait();
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the shaders' writes, before the copy reads them
  glCopyNamedBufferSubData(from.id(), id_, 0, 0, GLsizeiptr(bytes));
  glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
  fence_ = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  glFlush();  // the commands start now, while the host works
}

void ReadbackBuffer::wait() {
  if (!fence_) return;
  GLenum status = GL_TIMEOUT_EXPIRED;
  while (status == GL_TIMEOUT_EXPIRED) status = glClientWaitSync(fence_, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000);
  glDeleteSync(fence_);
  fence_ = nullptr;
  if (status == GL_WAIT_FAILED) throw RuntimeError("OpenGL: waiting for the render's results failed");
}

TimerPair::TimerPair(bool on) {
  if (on) glGenQueries(2, queries_);
}

TimerPair::~TimerPair() {
  if (queries_[0]) glDeleteQueries(2, queries_);
}

void TimerPair::start() const {
  if (queries_[0]) glQueryCounter(queries_[0], GL_TIMESTAMP);
}

void TimerPair::stop() const {
  if (queries_[0]) glQueryCounter(queries_[1], GL_TIMESTAMP);
}

double TimerPair::ms() const {
  if (!queries_[0]) return -1.0;
  GLuint64 begin = 0, end = 0;
  glGetQueryObjectui64v(queries_[0], GL_QUERY_RESULT, &begin);
  glGetQueryObjectui64v(queries_[1], GL_QUERY_RESULT, &end);
  return double(end - begin) * 1e-6;
}

}  // namespace prism::gl
