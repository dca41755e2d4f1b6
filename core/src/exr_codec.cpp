// libprism_exr.so: OpenEXR through the OpenEXR library (the C++ Imf API),
// loaded on first use (see image_codecs.hpp).
#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfThreading.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>
#include <iterator>
#include <memory>
#include <mutex>
#include <vector>

#include "image_codecs.hpp"

namespace prism::codec {

namespace {

// OpenEXR writes the table of chunk offsets in ~OutputFile, where it
// swallows every error: so the stream keeps its first failure for the
// caller to check once the file object is gone.
class FdOutput : public Imf::OStream {
 public:
  explicit FdOutput(int fd) : Imf::OStream("output"), fd_(fd) {}
  void write(const char c[], int n) override {
    if (error_ == 0) error_ = write_fully(fd_, c, size_t(n));
    if (error_ != 0) throw CodecError(std::strerror(error_));
  }
  uint64_t tellp() override {
    const off_t position = ::lseek(fd_, 0, SEEK_CUR);
    return position < 0 ? 0 : uint64_t(position);
  }
  void seekp(uint64_t position) override {
    if (::lseek(fd_, off_t(position), SEEK_SET) < 0 && error_ == 0) error_ = errno;
    if (error_ != 0) throw CodecError(std::strerror(error_));
  }
  int error() const { return error_; }

 private:
  int fd_;
  int error_ = 0;
};

// OpenImageIO's channel order: by layer (the name before the last '.'),
// then R, G, B, Y, ... A, ... Z in this table's order, then by name.
int special_rank(const std::string& suffix) {
  static const char* const kSpecial[] = {"R", "Red", "G", "Green", "B", "Blue", "Y", "real", "imag", "A", "Alpha",
                                         "AR", "RA", "AG", "GA", "AB", "BA", "Z", "Depth", "Zback"};
  for (size_t i = 0; i < std::size(kSpecial); ++i)
    if (suffix == kSpecial[i]) return int(i);
  return 10000;
}

std::vector<std::string> channels_in_oiio_order(const Imf::ChannelList& list) {
  struct Named {
    std::string name, layer, suffix;
    int rank;
  };
  std::vector<Named> named;
  for (auto it = list.begin(); it != list.end(); ++it) {
    const std::string name = it.name();
    const size_t dot = name.rfind('.');
    const std::string layer = dot == std::string::npos ? "" : name.substr(0, dot);
    const std::string suffix = dot == std::string::npos ? name : name.substr(dot + 1);
    named.push_back({name, layer, suffix, special_rank(suffix)});
  }
  std::stable_sort(named.begin(), named.end(), [](const Named& a, const Named& b) {
    if (a.layer != b.layer) return a.layer < b.layer;
    if (a.rank != b.rank) return a.rank < b.rank;
    return a.suffix < b.suffix;
  });
  std::vector<std::string> names;
  for (const Named& n : named) names.push_back(n.name);
  return names;
}

class ExrReader {
 public:
  void open(const std::filesystem::path& file) {
    try {
      input_ = std::make_unique<Imf::InputFile>(file.c_str(), 0);
    } catch (const std::exception& e) {
      throw CodecError(e.what());
    }
    const Imf::Header& h = input_->header();
    if (h.hasType() && (h.type() == Imf::DEEPSCANLINE || h.type() == Imf::DEEPTILE)) throw Unsupported("deep EXR");
    const Imath::Box2i window = h.dataWindow();
    origin_ = window.min;
    header_.width = window.max.x - window.min.x + 1;
    header_.height = window.max.y - window.min.y + 1;
    header_.channel_names = channels_in_oiio_order(h.channels());
    header_.channels = int(header_.channel_names.size());
    if (header_.channels == 0) throw CodecError("the image has no pixels");
    bool any_float = false;
    for (const std::string& name : header_.channel_names) {
      const Imf::Channel& channel = *h.channels().findChannel(name);
      if (channel.xSampling != 1 || channel.ySampling != 1) throw Unsupported("subsampled EXR channels");
      if (channel.type == Imf::UINT) throw Unsupported("integer EXR channels");
      any_float = any_float || channel.type == Imf::FLOAT;
    }
    header_.format = any_float ? PixelFormat::Float : PixelFormat::Half;
  }

  const ImageFile& header() const { return header_; }

  void read(int max_channels, const RowSink& sink) {
    const int channels = std::min(header_.channels, max_channels);
    ImageFile shape = header_;
    shape.channels = channels;
    shape.channel_names.resize(size_t(channels));
    sink.header(shape);
    constexpr int kRowsPerBlock = 64;
    const size_t row_floats = size_t(header_.width) * size_t(channels);
    std::vector<float> block(row_floats * kRowsPerBlock);
    for (int y0 = 0; y0 < header_.height; y0 += kRowsPerBlock) {
      const int rows = std::min(kRowsPerBlock, header_.height - y0);
      read_block(shape.channel_names, y0, rows, block.data());
      for (int r = 0; r < rows; ++r) sink.row(y0 + r, block.data() + size_t(r) * row_floats);
    }
  }

 private:
  void read_block(const std::vector<std::string>& names, int y0, int rows, float* out) {
    const size_t channels = names.size();
    Imf::FrameBuffer frame;
    for (size_t c = 0; c < channels; ++c)
      frame.insert(names[c], Imf::Slice::Make(Imf::FLOAT, out + c, Imath::V2i(origin_.x, origin_.y + y0), header_.width,
                                              rows, channels * sizeof(float), size_t(header_.width) * channels * sizeof(float)));
    try {
      input_->setFrameBuffer(frame);
      input_->readPixels(origin_.y + y0, origin_.y + y0 + rows - 1);
    } catch (const std::exception& e) {
      throw CodecError(std::string("cannot decode: ") + e.what());
    }
  }

  std::unique_ptr<Imf::InputFile> input_;
  Imath::V2i origin_;
  ImageFile header_;
};

std::vector<std::string> channel_names_to_write(const ImageFile& image) {
  if (!image.channel_names.empty()) return image.channel_names;
  std::vector<std::string> names;
  static const char* const kDefault[] = {"R", "G", "B", "A"};
  for (int c = 0; c < image.channels; ++c) names.push_back(c < 4 ? kDefault[c] : "channel" + std::to_string(c));
  return names;
}


ImageFile exr_header(const std::filesystem::path& file) {
  ExrReader reader;
  reader.open(file);
  return reader.header();
}

void read_exr_rows(const std::filesystem::path& file, int max_channels, const RowSink& sink) {
  ExrReader reader;
  reader.open(file);
  reader.read(max_channels, sink);
}

// OpenEXR compresses blocks of scanlines in a thread pool of its own, which
// is empty unless sized. Sized once, to the threads rendering may use (TBB's
// limit, which `--threads` sets): writing a 1280x720 render took ~300 ms
// on one thread and ~200 ms on this 2-core machine's two.
int exr_threads() {
  static std::once_flag sized;
  std::call_once(sized, [] {
    Imf::setGlobalThreadCount(int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  });
  return Imf::globalThreadCount();
}

void write_exr_file(int fd, const ImageFile& image, PixelFormat storage) {
  const std::vector<std::string> names = channel_names_to_write(image);
  if (int(names.size()) != image.channels) throw CodecError("channel names do not match the channel count");
  const bool half = storage == PixelFormat::Half;
  const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
  // OpenEXR writes a channel only from a slice of its own type.
  std::vector<Imath::half> halves;
  if (half) halves.assign(image.pixels.begin(), image.pixels.end());
  char* base = half ? reinterpret_cast<char*>(halves.data()) : reinterpret_cast<char*>(const_cast<float*>(image.pixels.data()));
  const size_t value_size = half ? sizeof(Imath::half) : sizeof(float);
  Imf::Header header(image.width, image.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer frame;
  const size_t x_stride = size_t(image.channels) * value_size, y_stride = x_stride * size_t(image.width);
  for (size_t c = 0; c < names.size(); ++c) {
    header.channels().insert(names[c], Imf::Channel(type));
    frame.insert(names[c], Imf::Slice(type, base + c * value_size, x_stride, y_stride));
  }
  FdOutput stream(fd);
  try {
    Imf::OutputFile file(stream, header, exr_threads());
    file.setFrameBuffer(frame);
    file.writePixels(image.height);
  } catch (const std::exception& e) {
    throw CodecError(stream.error() ? std::strerror(stream.error()) : e.what());
  }
  if (stream.error()) throw CodecError(std::strerror(stream.error()));
}

// What the sink throws (a stop request, a bad texel) goes through to the caller.
template <typename Fn>
std::string answer(Fn fn, bool& unsupported) {
  try {
    fn();
  } catch (const CodecError& e) {
    return e.what();
  } catch (const Unsupported& e) {
    unsupported = true;
    return e.what();
  }
  return "";
}

std::string module_read_header(const std::filesystem::path& file, ImageFile& out, bool& unsupported) {
  return answer([&] { out = exr_header(file); }, unsupported);
}

std::string module_read(const std::filesystem::path& file, int max_channels, const RowSink& sink, bool& unsupported) {
  return answer([&] { read_exr_rows(file, max_channels, sink); }, unsupported);
}

std::string module_write(int fd, const ImageFile& image, PixelFormat storage) {
  bool unsupported = false;
  return answer([&] { write_exr_file(fd, image, storage); }, unsupported);
}

const ExrModule exr_module_table = {module_read_header, module_read, module_write};

}  // namespace

}  // namespace prism::codec

extern "C" __attribute__((visibility("default"))) const prism::codec::ExrModule* prism_exr_module(void) {
  return &prism::codec::exr_module_table;
}
