#include "gl_program.hpp"

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "kernel_source.hpp"
#include "prism/cancel.hpp"
#include "prism/errors.hpp"
#include "program_cache.hpp"
#include "prism/status.hpp"

namespace prism::gl {

namespace {

namespace fs = std::filesystem;

// Cache file: this header, then the binary. The checksum covers the binary,
// the key guards against a hash-named file holding another program.
struct CacheHeader {
  char magic[8];  // "PRISMGLB"
  uint32_t version;
  uint32_t format;  // the driver's binary format enum
  uint64_t length;
  uint64_t checksum;  // FNV-1a 64 of the binary
  char key[16];
};
constexpr uint32_t kCacheVersion = 1;

bool linked(GLuint program) {
  GLint ok = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  return ok == GL_TRUE;
}

std::string program_log(GLuint program) {
  GLint length = 0;
  glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetProgramInfoLog(program, length, nullptr, log.data());
  return log.c_str();
}

std::string shader_log(GLuint shader) {
  GLint length = 0;
  glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
  std::string log(size_t(std::max(length, 1)), '\0');
  glGetShaderInfoLog(shader, length, nullptr, log.data());
  return log.c_str();
}

std::string save_failed_source(const std::string& source, const std::string& key) {
  return gpu::save_failed_source("opengl", source, key);
}

GLuint compile_and_link(const std::string& source, const std::string& key, ProgramStats& stats) {
  GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
  const char* text = source.c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  ++stats.compile_calls;
  GLint ok = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    std::string log = shader_log(shader);
    glDeleteShader(shader);
    const std::string blame = gpu::blame_compile_error(source, log);
    throw RuntimeError("the generated GLSL kernel does not compile" + (blame.empty() ? "" : ": error in " + blame) +
                       " (source saved to " + save_failed_source(source, key) + ", line numbers refer to it):\n" + log);
  }
  GLuint program = glCreateProgram();
  glAttachShader(program, shader);
  glProgramParameteri(program, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  glLinkProgram(program);
  ++stats.link_calls;
  glDetachShader(program, shader);
  glDeleteShader(shader);
  if (!linked(program)) {
    std::string log = program_log(program);
    glDeleteProgram(program);
    throw RuntimeError("the generated GLSL kernel does not link (source saved to " +
                       save_failed_source(source, key) + "):\n" + log);
  }
  return program;
}

// Loads a cached binary; 0 with stats.cache set to why when it cannot.
GLuint load_cached(const fs::path& file, const std::string& key, ProgramStats& stats) {
  const std::optional<std::string> bytes = gpu::read_cache_file(file);
  if (!bytes) {
    stats.cache = "miss";
    return 0;
  }
  CacheHeader header{};
  if (bytes->size() < sizeof header) {
    stats.cache = "corrupt";
    return 0;
  }
  std::memcpy(&header, bytes->data(), sizeof header);
  const char* data = bytes->data() + sizeof header;
  const size_t length = bytes->size() - sizeof header;
  if (std::memcmp(header.magic, "PRISMGLB", 8) != 0 || header.version != kCacheVersion || header.length != length ||
      std::memcmp(header.key, key.data(), sizeof header.key) != 0 || header.checksum != gpu::fnv1a64(data, length)) {
    stats.cache = "corrupt";
    return 0;
  }
  GLuint program = glCreateProgram();
  glProgramBinary(program, header.format, data, GLsizei(length));
  while (glGetError() != GL_NO_ERROR) {
  }
  if (!linked(program)) {  // the driver refuses it: another driver version wrote it
    glDeleteProgram(program);
    stats.cache = "stale";
    return 0;
  }
  stats.cache = "hit";
  return program;
}

void store_cached(GLuint program, const fs::path& file, const std::string& key) {
  GLint length = 0;
  glGetProgramiv(program, GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) return;
  std::vector<char> binary(static_cast<size_t>(length));
  GLenum format = 0;
  glGetProgramBinary(program, length, nullptr, &format, binary.data());
  if (glGetError() != GL_NO_ERROR) return;
  CacheHeader header{};
  std::memcpy(header.magic, "PRISMGLB", 8);
  header.version = kCacheVersion;
  header.format = format;
  header.length = binary.size();
  header.checksum = gpu::fnv1a64(binary.data(), binary.size());
  std::memcpy(header.key, key.data(), sizeof header.key);
  std::string content(reinterpret_cast<const char*>(&header), sizeof header);
  content.append(binary.data(), binary.size());
  gpu::write_cache_file(file, content);
}

}  // namespace

GLuint build_program(const std::string& source, const std::string& driver_identity, ProgramStats& stats) {
  auto start = std::chrono::steady_clock::now();
  const std::string key = gpu::hash_hex(source + '\n' + driver_identity);
  GLint formats = 0;
  glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
  const fs::path dir = gpu::program_cache_dir("opengl");
  GLuint program = 0;
  if (formats <= 0) {
    stats.cache = "unsupported";
  } else if (dir.empty()) {
    stats.cache = "disabled";
  } else {
    stats.cache_file = dir / (key + ".bin");
    program = load_cached(stats.cache_file, key, stats);
  }
  if (program == 0) {
    notify_status(gpu::compile_notice("opengl", stats.cache));
    {
      const UninterruptibleWork compiling;
      program = compile_and_link(source, key, stats);
    }
    if (!stats.cache_file.empty()) store_cached(program, stats.cache_file, key);
  }
  stats.ms += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return program;
}

}  // namespace prism::gl
