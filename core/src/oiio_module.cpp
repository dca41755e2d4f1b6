// libprism_oiio.so: the only code that includes OpenImageIO.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <memory>

#include "image_module.hpp"

namespace prism {
namespace {

PixelFormat format_of(OIIO::TypeDesc type) {
  switch (type.basetype) {
    case OIIO::TypeDesc::UINT8: return PixelFormat::UInt8;
    case OIIO::TypeDesc::UINT16: return PixelFormat::UInt16;
    case OIIO::TypeDesc::HALF: return PixelFormat::Half;
    case OIIO::TypeDesc::FLOAT: return PixelFormat::Float;
    default: return PixelFormat::Other;
  }
}

OIIO::TypeDesc type_of(PixelFormat format) {
  switch (format) {
    case PixelFormat::UInt8: return OIIO::TypeDesc::UINT8;
    case PixelFormat::UInt16: return OIIO::TypeDesc::UINT16;
    case PixelFormat::Half: return OIIO::TypeDesc::HALF;
    default: return OIIO::TypeDesc::FLOAT;
  }
}

// Opens `file` and reads its header; `error` says why when it returns null.
std::unique_ptr<OIIO::ImageInput> open_input(const std::filesystem::path& file, std::string& error) {
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);  // straight alpha, as the scene format wants
  auto input = OIIO::ImageInput::open(file.string(), &config);
  if (!input) {
    error = OIIO::geterror();
    if (error.empty()) error = "not a readable image";
    return nullptr;
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    error = "the image has no pixels";
    return nullptr;
  }
  return input;
}

void copy_header(const OIIO::ImageSpec& spec, ImageFile& out) {
  out.width = spec.width;
  out.height = spec.height;
  out.channels = spec.nchannels;
  out.channel_names = spec.channelnames;
  out.format = format_of(spec.format);
}

std::string read_header(const std::filesystem::path& file, ImageFile& out) {
  std::string error;
  auto input = open_input(file, error);
  if (!input) return error;
  copy_header(input->spec(), out);
  return "";
}

std::string read(const std::filesystem::path& file, size_t max_pixels, int max_channels, ImageFile& out) {
  std::string error;
  auto input = open_input(file, error);
  if (!input) return error;
  const OIIO::ImageSpec& spec = input->spec();
  if (size_t(spec.width) * size_t(spec.height) > max_pixels)
    return "the image has " + std::to_string(size_t(spec.width) * size_t(spec.height)) + " pixels, more than the limit of " +
           std::to_string(max_pixels);
  copy_header(spec, out);
  out.channels = std::min(spec.nchannels, max_channels);
  if (out.channel_names.size() > size_t(out.channels)) out.channel_names.resize(size_t(out.channels));
  out.pixels.resize(size_t(spec.width) * spec.height * size_t(out.channels));
  if (!input->read_image(0, 0, 0, out.channels, OIIO::TypeDesc::FLOAT, out.pixels.data()))
    return "cannot decode: " + input->geterror();
  return "";
}

std::string write(const std::filesystem::path& file, const ImageFile& image, PixelFormat storage) {
  auto output = OIIO::ImageOutput::create(file.string());
  if (!output) return OIIO::geterror();
  OIIO::ImageSpec spec(image.width, image.height, image.channels, type_of(storage));
  if (!image.channel_names.empty()) spec.channelnames = image.channel_names;
  if (storage == PixelFormat::UInt8 || storage == PixelFormat::UInt16) {
    spec.attribute("oiio:UnassociatedAlpha", 1);  // write the values as given, never divided by alpha
    spec.attribute("oiio:ColorSpace", "sRGB");
  } else {
    spec.attribute("compression", "zip");
  }
  // Values convert from float to the stored type on write (quantised for integer formats).
  if (!output->open(file.string(), spec) || !output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()) ||
      !output->close())
    return output->geterror();
  return "";
}

const ImageModule module = {read, read_header, write};

}  // namespace
}  // namespace prism

extern "C" __attribute__((visibility("default"))) const prism::ImageModule* prism_image_module(void) {
  return &prism::module;
}
