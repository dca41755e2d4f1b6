// prism.compare (the conformance metrics of `prism conform`, on arrays) and
// prism.read_image (an image file's channels as an array).
#include "bindings.hpp"
#include "prism/conform_metrics.hpp"
#include "prism/image_file.hpp"

namespace prism::python {

namespace {

using Floats = py::array_t<float, py::array::c_style | py::array::forcecast>;

Image image_of(const Floats& rgb, const char* name) {
  if (rgb.ndim() != 3 || rgb.shape(2) != 3)
    throw py::value_error(std::string(name) + ": expected an array of shape (height, width, 3)");
  Image image;
  image.height = int(rgb.shape(0));
  image.width = int(rgb.shape(1));
  image.rgb.assign(rgb.data(), rgb.data() + rgb.size());
  return image;
}

conform::Metrics compare(const Floats& reference, const Floats& image, const std::optional<Floats>& path,
                         float threshold) {
  Image ref = image_of(reference, "reference");
  const Image test = image_of(image, "image");
  if (test.width != ref.width || test.height != ref.height)
    throw py::value_error("image: its shape differs from the reference's");
  if (path) {
    if (path->ndim() != 2 || path->shape(0) != ref.height || path->shape(1) != ref.width)
      throw py::value_error("path: expected an array of shape (height, width), as the reference's");
    ref.path.assign(path->data(), path->data() + path->size());
  }
  return conform::measure(ref, conform::stable_pixels(ref), test, threshold);
}

py::tuple read_image(const std::filesystem::path& file) {
  ImageFile read = read_image_file(file);
  std::vector<std::string> names = read.channel_names;
  const py::ssize_t h = read.height, w = read.width, c = read.channels;
  return py::make_tuple(take_as_array(std::move(read.pixels), {h, w, c}), names);
}

}  // namespace

void bind_compare(py::module_& m) {
  using M = conform::Metrics;
  py::class_<M>(m, "Metrics", R"(An image against a reference, as `prism conform` measures it.

Errors are absolute channel differences; a pixel is over when a channel
differs by more than the threshold. Stable pixels are those whose 3x3
neighbourhood shares one path signature in the reference's path AOV; the
others are edges.)")
      .def_readonly("mean_error", &M::mean_error)
      .def_readonly("rms_error", &M::rms_error)
      .def_readonly("psnr", &M::psnr)
      .def_readonly("max_error", &M::max_error)
      .def_readonly("pixels", &M::pixels)
      .def_readonly("pixels_over", &M::pixels_over)
      .def_readonly("stable_pixels", &M::stable_pixels)
      .def_readonly("stable_over", &M::stable_over)
      .def_readonly("edge_pixels", &M::edge_pixels)
      .def_readonly("edge_over", &M::edge_over)
      .def_readonly("nonfinite", &M::nonfinite, "NaN or Inf pixels in the image under test.")
      .def("__repr__", [](const M& x) {
        char text[320];
        std::snprintf(text, sizeof text,
                      "Metrics(rms_error=%.3g, max_error=%.3g, pixels_over=%ld/%ld, stable_over=%ld/%ld, "
                      "edge_over=%ld/%ld, nonfinite=%ld)",
                      x.rms_error, x.max_error, x.pixels_over, x.pixels, x.stable_over, x.stable_pixels, x.edge_over,
                      x.edge_pixels, x.nonfinite);
        return std::string(text);
      });

  m.def("compare", &compare, py::arg("reference"), py::arg("image"), py::arg("path") = py::none(),
        py::arg("threshold") = 0.016f,
        R"(The conformance metrics of `image` against `reference` (`prism conform`'s own code).

reference, image: arrays of shape (height, width, 3) (Frame.rgb). path: the
reference's path AOV (Frame.path of a render with aovs=("path",)); without
it every pixel counts as an edge. threshold: a pixel is over when a channel
differs by more (0.016, conform's cap). Returns Metrics.)");
  m.def("read_image", &read_image, py::arg("file"),
        R"(An image file's pixels as float32 (height, width, channels), and its channel names.

EXR files keep their float values (and the id / path channels `prism render
--aov` writes); 8-bit and 16-bit files are scaled to [0, 1].)");
}

}  // namespace prism::python
