// The uv of each primitive, read back through the grid texture
// (shading_support.hpp): each case lands on one texel centre. The cases
// come from the primitives' folders (tests/cases/primitive_cases.hpp, `uv`),
// one test per case and backend: Backends/PrimitiveUvTest.<case>/<backend>.
#include "primitive_cases.hpp"
#include "shading_support.hpp"

namespace prism::test {
namespace {

class PrimitiveUvTest : public GridTextureTest {
 public:
  PrimitiveUvTest(std::string backend, const cases::UvCase& uv) : backend_(std::move(backend)), uv_(uv) {}
  std::string backend_name() const override { return backend_; }
  void TestBody() override {
    Image image = render_grid(uv_.camera, uv_.material_extra, uv_.object);
    EXPECT_TRUE(pixel_near(image, 0, 0, uv_.expected));
  }

 private:
  std::string backend_;
  cases::UvCase uv_;
};

// Registered before main() runs the tests, as PRISM_INSTANTIATE_BACKEND_TESTS
// would name them.
[[maybe_unused]] const bool registered = [] {
  for (const cases::PrimitiveCases* cases : cases::all_primitive_cases()) {
    for (const cases::UvCase& uv : cases->uv) {
      for (const std::string& backend : backend_names()) {
        const std::string name = uv.name + "/" + backend_param_name({backend, 0});
        testing::RegisterTest("Backends/PrimitiveUvTest", name.c_str(), nullptr, backend.c_str(), __FILE__, __LINE__,
                              [backend, uv]() -> testing::Test* { return new PrimitiveUvTest(backend, uv); });
      }
    }
  }
  return true;
}();

}  // namespace
}  // namespace prism::test
