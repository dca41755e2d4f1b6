// Compiling the generated kernel into a GL program, through an on-disk
// cache of program binaries (glGetProgramBinary) keyed by a hash of the
// source and the driver, so a second render of the same scene compiles
// nothing. A cache file that is truncated, corrupt or refused by the driver
// (stale after a driver update) is detected, rebuilt and rewritten.
#pragma once

#include <filesystem>
#include <map>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

namespace prism::gl {

struct ProgramStats {
  int compile_calls = 0;  // glCompileShader calls made by Prism
  int link_calls = 0;     // glLinkProgram calls made by Prism
  std::string cache;      // hit, miss, corrupt, stale, unsupported, disabled
  std::filesystem::path cache_file;
  double ms = 0.0;
};

// Returns a linked compute program for `source`. Throws RuntimeError with the
// driver's log (and where the generated source was saved) when it fails.
GLuint build_program(const std::string& source, const std::string& driver_identity, ProgramStats& stats);

}  // namespace prism::gl
