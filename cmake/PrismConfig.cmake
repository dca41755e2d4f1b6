# The installed Prism package:
#
#   find_package(Prism REQUIRED)     # -DCMAKE_PREFIX_PATH=<install prefix>
#
# Programs on the library API (prism/api.hpp: Engine, LiveScene, Renderer):
#   target_link_libraries(app PRIVATE Prism::core)  # libprism_core.so
#   target_link_libraries(app PRIVATE Prism::view)  # + prism::ViewWindow (prism/view_window.hpp)
# The Engine finds the installed plugins in <prefix>/lib/prism by itself.
#
# Primitive plugins built outside the tree:
#   prism_add_primitive_plugin(<type> SOURCES ... [SHARED <file>.shared.glsl | GLSL <file>])
# builds libprism_primitive_<type>.so into ${PRISM_PLUGIN_OUTPUT_DIR}
# (default <build>/plugins) against Prism::sdk, the header-only plugin ABI
# (prism/primitive_abi.h, prism/sdk/*.hpp; glm). Point PRISM_PLUGIN_PATH at
# that folder and the installed `prism` loads it. Also set:
#   Prism_PLUGIN_DIR   the installed plugins (<prefix>/lib/prism)
#   Prism_EXECUTABLE   the installed `prism`
include(CMakeFindDependencyMacro)
find_dependency(glm CONFIG)
include("${CMAKE_CURRENT_LIST_DIR}/PrismTargets.cmake")
include("${CMAKE_CURRENT_LIST_DIR}/PrismPrimitivePlugin.cmake")

get_filename_component(_prism_prefix "${CMAKE_CURRENT_LIST_DIR}/../../.." ABSOLUTE)
set(Prism_PLUGIN_DIR "${_prism_prefix}/lib/prism")
set(Prism_EXECUTABLE "${_prism_prefix}/bin/prism")
unset(_prism_prefix)

function(prism_add_primitive_plugin type)
  prism_primitive_plugin_library(${type} SDK Prism::sdk ${ARGN})
endfunction()
