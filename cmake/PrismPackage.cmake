# `cmake --install build --prefix P` installs, beside bin/prism, lib/ and
# lib/prism/ (the plugins), the plugin ABI's headers and a CMake package:
#   P/include/prism/primitive_abi.h, P/include/prism/sdk/*.hpp
#   P/lib/cmake/Prism/PrismConfig.cmake (find_package(Prism)), exporting
#   Prism::sdk and prism_add_primitive_plugin() (cmake/PrismConfig.cmake).
include(CMakePackageConfigHelpers)

set_target_properties(prism_sdk PROPERTIES EXPORT_NAME sdk)
install(TARGETS prism_sdk EXPORT PrismTargets)
install(FILES ${PROJECT_SOURCE_DIR}/core/include/prism/primitive_abi.h DESTINATION include/prism)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/core/include/prism/sdk DESTINATION include/prism)
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
