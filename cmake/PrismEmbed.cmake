# prism_embed_text(<target> <file> <symbol>): makes the text of <file> (a
# GLSL source) available to <target> as `inline constexpr char <symbol>[]`
# from the header "<file name>.hpp" (e.g. `#include "torus.glsl.hpp"`),
# regenerated whenever the file changes. Installed with the CMake package.
include_guard(GLOBAL)
set(PRISM_EMBED_TEXT_SCRIPT "${CMAKE_CURRENT_LIST_DIR}/embed_text.cmake")

function(prism_embed_text target file symbol)
  get_filename_component(source "${file}" ABSOLUTE)
  get_filename_component(name "${file}" NAME)
  set(dir "${CMAKE_CURRENT_BINARY_DIR}/embedded")
  set(header "${dir}/${name}.hpp")
  add_custom_command(
    OUTPUT "${header}"
    COMMAND ${CMAKE_COMMAND} -DINPUT=${source} -DOUTPUT=${header} -DNAME=${symbol}
            -P ${PRISM_EMBED_TEXT_SCRIPT}
    DEPENDS "${source}" ${PRISM_EMBED_TEXT_SCRIPT}
    COMMENT "Embedding ${name}"
    VERBATIM)
  target_sources(${target} PRIVATE "${header}")
  target_include_directories(${target} PRIVATE "${dir}")
endfunction()
