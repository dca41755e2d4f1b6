# `cmake --install build --prefix P` installs, beside bin/prism, lib/ and
# lib/prism/ (the plugins), the public headers and a CMake package:
#   P/include/prism/primitive_abi.h, P/include/prism/sdk/*.hpp (the plugin ABI)
#   P/include/prism/api.hpp and what it includes (the library API),
#     image_io.hpp (write_image), view_window.hpp (apps/prism: Prism::view)
#   P/include/prism/backend_fingerprint.hpp and what it includes (a backend's
#     descriptor and the layout fingerprint the registry checks)
#   P/lib/cmake/Prism/PrismConfig.cmake (find_package(Prism)), exporting
#   Prism::sdk, Prism::core, Prism::view and prism_add_primitive_plugin()
#   (cmake/PrismConfig.cmake).
include(CMakePackageConfigHelpers)

set_target_properties(prism_sdk PROPERTIES EXPORT_NAME sdk)
install(TARGETS prism_sdk EXPORT PrismTargets)
install(FILES ${PROJECT_SOURCE_DIR}/core/include/prism/primitive_abi.h DESTINATION include/prism)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/prism/sdk DESTINATION include/prism)

# The library API: libprism_core.so as Prism::core (its include folder and
# glm come through Prism::sdk). The Engine finds the installed plugins in
# lib/prism beside it, so a program linking it needs no PRISM_PLUGIN_PATH.
set_target_properties(prism_core PROPERTIES EXPORT_NAME core)
target_compile_features(prism_core PUBLIC cxx_std_20)  # api.hpp: std::span, designated initializers
install(TARGETS prism_core EXPORT PrismTargets LIBRARY DESTINATION lib)
install(FILES
  ${PROJECT_SOURCE_DIR}/core/include/prism/api.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/backend.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/stats_keys.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/errors.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/scene.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/image_io.hpp
  DESTINATION include/prism)
# A backend's descriptor (prism::backend_desc) and the layout fingerprint the
# registry checks it by, with the headers of the types it covers.
install(FILES
  ${PROJECT_SOURCE_DIR}/core/include/prism/backend_fingerprint.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/layout_fingerprint.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/cancel.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/cpu_render.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/geometry.hpp
  ${PROJECT_SOURCE_DIR}/core/include/prism/registry.hpp
  DESTINATION include/prism)

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
