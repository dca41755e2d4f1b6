# Declaring plugins. A primitive plugin is one folder under plugins/ that calls
#   prism_add_primitive_plugin(<type> SOURCES ... [SHARED <file> | GLSL <file>] [TESTS ...])
# and builds libprism_primitive_<type>.so into the plugin folder, exactly as
# a plugin outside the tree does against the installed package
# (cmake/PrismPrimitivePlugin.cmake), plus its install rule, its tests and
# its cases for the suites (<type>_cases.cpp, prism_add_primitive_cases). The
# tests link the same sources directly (the object library), so they
# exercise exactly the code the shared object exports.
include(${CMAKE_CURRENT_LIST_DIR}/PrismPrimitivePlugin.cmake)

function(prism_add_primitive_plugin type)
  cmake_parse_arguments(ARG "" "GLSL;SHARED" "SOURCES;TESTS" ${ARGN})
  set(objects prism_primitive_${type}_objects)
  set(gpu_source "")
  if(ARG_SHARED)
    set(gpu_source SHARED ${ARG_SHARED})
  elseif(ARG_GLSL)
    set(gpu_source GLSL ${ARG_GLSL})
  endif()
  prism_primitive_plugin_library(${type} SDK prism_sdk SOURCES ${ARG_SOURCES} ${gpu_source})
  prism_hot_code(${objects})
  prism_profile_guided(${objects})
  prism_add_primitive_cases(${type})
  if(PRISM_PLUGIN_IS_EXAMPLE)  # built for a test only (tests/sdk): not installed, in no suite's list
    return()
  endif()
  install(TARGETS prism_primitive_${type} LIBRARY DESTINATION lib/prism)
  set_property(GLOBAL APPEND PROPERTY PRISM_PLUGIN_TARGETS prism_primitive_${type})
  if(PRISM_BUILD_TESTS AND ARG_TESTS)
    set(test prism_primitive_${type}_test)
    add_executable(${test} ${ARG_TESTS} $<TARGET_OBJECTS:${objects}>)
    target_link_libraries(${test} PRIVATE prism_sdk prism_test_support prism_test_main)
    gtest_discover_tests(${test} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS unit)
    prism_add_to_unit_suite(${test})
  endif()
endfunction()

# A plugin's test cases: <type>_cases.cpp beside its CMakeLists.txt, when
# there is one (tests/cases/primitive_cases.hpp), becomes
# libprism_cases_<type>.so beside the plugin, where the suites find it; no
# suite lists the types. Not installed.
function(prism_add_primitive_cases type)
  set(source ${CMAKE_CURRENT_SOURCE_DIR}/${type}_cases.cpp)
  if(NOT PRISM_BUILD_TESTS OR NOT EXISTS ${source})
    return()
  endif()
  set(output_dir "${PRISM_PLUGIN_OUTPUT_DIR}")
  add_library(prism_cases_${type} MODULE ${source})
  target_link_libraries(prism_cases_${type} PRIVATE prism_case_kit)
  set_target_properties(prism_cases_${type} PROPERTIES PREFIX "lib" LIBRARY_OUTPUT_DIRECTORY "${output_dir}")
  set_property(GLOBAL APPEND PROPERTY PRISM_CASES_TARGETS prism_cases_${type})
  if(NOT PRISM_PLUGIN_IS_EXAMPLE)
    set_property(GLOBAL APPEND PROPERTY PRISM_CASES_TYPES ${type})
  endif()
endfunction()

# A backend is one folder under backends/ calling
#   prism_add_backend(<name> SOURCES ... [LIBS ...])
function(prism_add_backend name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_library(prism_backend_${name} MODULE ${ARG_SOURCES})
  target_link_libraries(prism_backend_${name} PRIVATE prism_core ${ARG_LIBS})
  prism_hot_code(prism_backend_${name})
  prism_link_time_optimised(prism_backend_${name})
  prism_profile_guided(prism_backend_${name})
  set_target_properties(prism_backend_${name} PROPERTIES
    PREFIX "lib" LIBRARY_OUTPUT_DIRECTORY ${PRISM_PLUGIN_OUTPUT_DIR})
  install(TARGETS prism_backend_${name} LIBRARY DESTINATION lib/prism)
  set_property(GLOBAL APPEND PROPERTY PRISM_PLUGIN_TARGETS prism_backend_${name})
endfunction()

# Test programs labelled unit or shading register here; the target
# prism_unit_suite builds just them and every plugin (the sanitizer run).
function(prism_add_to_unit_suite target)
  set_property(GLOBAL APPEND PROPERTY PRISM_UNIT_TEST_TARGETS ${target})
endfunction()

function(prism_define_unit_suite)
  get_property(tests GLOBAL PROPERTY PRISM_UNIT_TEST_TARGETS)
  get_property(plugins GLOBAL PROPERTY PRISM_PLUGIN_TARGETS)
  get_property(cases GLOBAL PROPERTY PRISM_CASES_TARGETS)
  add_custom_target(prism_unit_suite DEPENDS ${tests} ${plugins} ${cases} prism_oiio)
endfunction()

# Adds every subfolder of the calling folder that has a CMakeLists.txt, in
# name order: adding a plugin, backend or test folder edits no list. The glob
# is CONFIGURE_DEPENDS, so a plain `cmake --build` sees a new folder (its
# CMakeLists.txt) and re-runs CMake by itself.
function(prism_add_subfolders)
  file(GLOB lists CONFIGURE_DEPENDS RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/*/CMakeLists.txt)
  list(SORT lists)
  foreach(list_file ${lists})
    get_filename_component(child ${list_file} DIRECTORY)
    add_subdirectory(${child})
  endforeach()
endfunction()
