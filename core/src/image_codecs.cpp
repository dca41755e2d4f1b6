#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "image_codecs.hpp"

namespace prism::codec {

Format format_of_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char magic[4] = {};
  if (!in.read(reinterpret_cast<char*>(magic), 4)) return Format::Other;
  if (magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G') return Format::Png;
  if (magic[0] == 0xff && magic[1] == 0xd8 && magic[2] == 0xff) return Format::Jpeg;
  if (magic[0] == 0x76 && magic[1] == 0x2f && magic[2] == 0x31 && magic[3] == 0x01) return Format::Exr;
  return Format::Other;
}

Format format_of_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".png") return Format::Png;
  if (ext == ".jpg" || ext == ".jpeg") return Format::Jpeg;
  if (ext == ".exr") return Format::Exr;
  return Format::Other;
}

int write_fully(int fd, const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    const ssize_t n = ::write(fd, bytes, size);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) return errno;
    if (n == 0) return EIO;
    bytes += n;
    size -= size_t(n);
  }
  return 0;
}

void write_all(int fd, const void* data, size_t size) {
  if (const int error = write_fully(fd, data, size)) throw CodecError(std::strerror(error));
}

}  // namespace prism::codec
