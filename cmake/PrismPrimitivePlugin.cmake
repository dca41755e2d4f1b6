# What building a primitive plugin takes, shared by Prism's own plugins
# (cmake/PrismPlugin.cmake) and by plugins built outside the tree against an
# installed Prism (PrismConfig.cmake, installed with this file):
#
#   prism_primitive_plugin_library(<type> SDK <sdk target> SOURCES ...
#                                  [SHARED <file>.shared.glsl | GLSL <file>])
#
# builds libprism_primitive_<type>.so into ${PRISM_PLUGIN_OUTPUT_DIR}
# (default: <build>/plugins) from an object library
# prism_primitive_<type>_objects, which tests can link directly.
# SHARED names the one source of the intersector, written in the shared
# dialect (prism/sdk/dialect.hpp): it is embedded as `kPluginGlsl` in
# "<file>.hpp" (the GPU's source) and is includable from the plugin's C++
# (PRISM_SHARED_SOURCE + prism/sdk/instantiate.hpp), the plugin folder being
# on the include path. GLSL embeds a hand-written GPU intersector the same
# way (plugins not yet written once).
include_guard(GLOBAL)
include(${CMAKE_CURRENT_LIST_DIR}/PrismEmbed.cmake)

function(prism_primitive_plugin_library type)
  cmake_parse_arguments(ARG "" "SDK;GLSL;SHARED" "SOURCES" ${ARGN})
  if(NOT ARG_SDK OR NOT ARG_SOURCES)
    message(FATAL_ERROR "prism_primitive_plugin_library(${type}): SDK and SOURCES are required")
  endif()
  set(output_dir "${PRISM_PLUGIN_OUTPUT_DIR}")
  if(NOT output_dir)
    set(output_dir "${CMAKE_BINARY_DIR}/plugins")
  endif()
  set(objects prism_primitive_${type}_objects)
  add_library(${objects} OBJECT ${ARG_SOURCES})
  target_link_libraries(${objects} PUBLIC ${ARG_SDK})
  target_compile_features(${objects} PUBLIC cxx_std_20)
  set_target_properties(${objects} PROPERTIES POSITION_INDEPENDENT_CODE ON CXX_VISIBILITY_PRESET hidden
                                              VISIBILITY_INLINES_HIDDEN ON)
  if(ARG_SHARED AND ARG_GLSL)
    message(FATAL_ERROR "prism_primitive_plugin_library(${type}): SHARED is the GLSL source too; give one of them")
  endif()
  if(ARG_SHARED)
    prism_embed_text(${objects} ${ARG_SHARED} kPluginGlsl)
    target_include_directories(${objects} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  elseif(ARG_GLSL)
    prism_embed_text(${objects} ${ARG_GLSL} kPluginGlsl)
  endif()
  add_library(prism_primitive_${type} MODULE $<TARGET_OBJECTS:${objects}>)
  target_link_libraries(prism_primitive_${type} PRIVATE ${ARG_SDK})
  set_target_properties(prism_primitive_${type} PROPERTIES PREFIX "lib" LIBRARY_OUTPUT_DIRECTORY "${output_dir}")
endfunction()
