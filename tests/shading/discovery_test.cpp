// The backends this program runs against: what the registry finds, checked
// against PRISM_REQUIRE_BACKENDS.
#include <algorithm>

#include "test_support.hpp"

namespace prism::test {
namespace {

TEST(BackendDiscovery, FindsAtLeastOneBackend) {
  EXPECT_FALSE(backend_names().empty()) << "no libprism_backend_*.so on the search path: every "
                                           "backend-parameterised test would silently vanish";
}

TEST(BackendDiscovery, EveryRequiredBackendIsFound) {
  const auto& found = backend_names();
  for (const std::string& name : required_backends()) {
    EXPECT_NE(std::find(found.begin(), found.end(), name), found.end())
        << "PRISM_REQUIRE_BACKENDS names '" << name << "', which the registry does not find";
  }
}

}  // namespace
}  // namespace prism::test
