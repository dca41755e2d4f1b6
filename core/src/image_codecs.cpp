#include <dlfcn.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "image_codecs.hpp"
#include "prism/errors.hpp"

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

void write_all(int fd, const void* data, size_t size) {
  if (const int error = write_fully(fd, data, size)) throw CodecError(std::strerror(error));
}

const void* load_core_module(const std::string& file_name, const char* symbol) {
  Dl_info info{};
  std::filesystem::path path = file_name;
  if (dladdr(reinterpret_cast<void*>(&load_core_module), &info) && info.dli_fname)
    path = std::filesystem::path(info.dli_fname).parent_path() / file_name;
  void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);  // kept for the life of the process
  if (!handle) {
    const char* why = dlerror();
    throw RuntimeError("cannot load image support " + path.string() + ": " + (why ? why : "dlopen failed"));
  }
  auto entry = reinterpret_cast<const void* (*)()>(dlsym(handle, symbol));
  if (!entry) throw RuntimeError("cannot load image support: " + path.string() + " has no " + symbol);
  return entry();
}

namespace {

const ExrModule& exr_module() {
  static const auto* module = static_cast<const ExrModule*>(load_core_module("libprism_exr.so", PRISM_EXR_MODULE_SYMBOL));
  return *module;
}

// The module's answer as the exceptions the other codecs throw.
void raise(const std::string& error, bool unsupported) {
  if (unsupported) throw Unsupported(error);
  if (!error.empty()) throw CodecError(error);
}

}  // namespace

ImageFile read_exr_header(const std::filesystem::path& file) {
  ImageFile header;
  bool unsupported = false;
  raise(exr_module().read_header(file, header, unsupported), unsupported);
  return header;
}

void read_exr(const std::filesystem::path& file, int max_channels, const RowSink& sink) {
  bool unsupported = false;
  raise(exr_module().read(file, max_channels, sink, unsupported), unsupported);
}

void write_exr(int fd, const ImageFile& image, PixelFormat storage) { raise(exr_module().write(fd, image, storage), false); }

}  // namespace prism::codec
