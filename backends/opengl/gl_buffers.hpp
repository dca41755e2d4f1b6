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

// A buffer the host reads results from: persistently mapped, filled by
// copies from a storage buffer (glCopyNamedBufferSubData), read once a
// fence after the copies has signalled. On a GPU this reads from host
// memory; glGetNamedBufferSubData would stall in the driver's own copy.
class ReadbackBuffer {
 public:
  ReadbackBuffer() = default;
  explicit ReadbackBuffer(size_t bytes);
  ~ReadbackBuffer();
  ReadbackBuffer(ReadbackBuffer&& other) noexcept;
  ReadbackBuffer& operator=(ReadbackBuffer&& other) noexcept;
  ReadbackBuffer(const ReadbackBuffer&) = delete;
  ReadbackBuffer& operator=(const ReadbackBuffer&) = delete;

  // Copies `bytes` from the start of `from`; wait() returns once they are
  // here (the host may work in between).
  void start_copy(const Buffer& from, size_t bytes);
  void wait();
  const void* data() const { return mapped_; }
  size_t bytes() const { return bytes_; }

 private:
  void release();
  GLuint id_ = 0;
  size_t bytes_ = 0;
  void* mapped_ = nullptr;
  GLsync fence_ = nullptr;
};

// Two GL timestamps around a dispatch (glQueryCounter), for `bench
// --profile`; off, it makes no queries and ms() is -1.
class TimerPair {
 public:
  explicit TimerPair(bool on);
  ~TimerPair();
  TimerPair(const TimerPair&) = delete;
  TimerPair& operator=(const TimerPair&) = delete;
  void start() const;
  void stop() const;
  // The time between them on the device, once the commands have finished.
  double ms() const;

 private:
  GLuint queries_[2] = {0, 0};
};

}  // namespace prism::gl
