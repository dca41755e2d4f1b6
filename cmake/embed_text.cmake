# Script mode (cmake -P): writes INPUT's text into OUTPUT as a C++ header
#   inline constexpr char NAME[] = R"prism_text(...)prism_text";
# Used to carry GLSL sources inside the shared objects that own them.
file(READ "${INPUT}" text)
string(FIND "${text}" ")prism_text\"" clash)
if(NOT clash EQUAL -1)
  message(FATAL_ERROR "${INPUT} contains the raw-string delimiter )prism_text\"")
endif()
set(content "// Generated from ${INPUT} by cmake/embed_text.cmake; do not edit.\n#pragma once\n\ninline constexpr char ${NAME}[] = R\"prism_text(${text})prism_text\";\n")
if(EXISTS "${OUTPUT}")
  file(READ "${OUTPUT}" old)
  if(old STREQUAL content)
    return()
  endif()
endif()
file(WRITE "${OUTPUT}" "${content}")
