# `cmake --install build --prefix P` installs, beside bin/prism, lib/ and
# lib/prism/ (the plugins), the public headers and a CMake package:
#   P/include/prism/: the folder include/prism/ of the tree as it stands,
#     every file of it and nothing else (the test installed_headers):
#     the plugin ABI (primitive_abi.h, sdk/), the library API (api.hpp,
#     image_io.hpp, view_window.hpp for Prism::view) and a backend's
#     descriptor with the layout fingerprint the registry checks
#     (backend_fingerprint.hpp), each with the headers it includes. The
#     core's other headers (core/internal/prism/) are not installed.
#   P/lib/cmake/Prism/PrismConfig.cmake (find_package(Prism)), exporting
#   Prism::sdk, Prism::core, Prism::view and prism_add_primitive_plugin()
#   (cmake/PrismConfig.cmake).
include(CMakePackageConfigHelpers)

install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/prism DESTINATION include COMPONENT headers)

set_target_properties(prism_sdk PROPERTIES EXPORT_NAME sdk)
install(TARGETS prism_sdk EXPORT PrismTargets)

# The library API: libprism_core.so as Prism::core (its include folder and
# glm come through Prism::sdk). The Engine finds the installed plugins in
# lib/prism beside it, so a program linking it needs no PRISM_PLUGIN_PATH.
set_target_properties(prism_core PROPERTIES EXPORT_NAME core)
target_compile_features(prism_core PUBLIC cxx_std_20)  # api.hpp: std::span, designated initializers
install(TARGETS prism_core EXPORT PrismTargets LIBRARY DESTINATION lib)

install(EXPORT PrismTargets NAMESPACE Prism:: DESTINATION lib/cmake/Prism)

write_basic_package_version_file(${PROJECT_BINARY_DIR}/PrismConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMajorVersion)
install(FILES
  ${PROJECT_SOURCE_DIR}/cmake/PrismConfig.cmake
  ${PROJECT_BINARY_DIR}/PrismConfigVersion.cmake
  ${PROJECT_SOURCE_DIR}/cmake/PrismPrimitivePlugin.cmake
  ${PROJECT_SOURCE_DIR}/cmake/PrismEmbed.cmake
  ${PROJECT_SOURCE_DIR}/cmake/embed_text.cmake
  DESTINATION lib/cmake/Prism)
