// A headless OpenGL 4.5 core context through EGL: no window, no X server.
// It tries each EGL device (EGL_EXT_platform_device: what a GPU driver
// offers headless), then Mesa's surfaceless platform (llvmpipe here), and
// keeps the first that gives a 4.5 core context.
#pragma once

#include <EGL/egl.h>

#include <string>

namespace prism::gl {

class EglContext {
 public:
  // Throws prism::RuntimeError with every platform's reason when none works.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6, EGL surfaceless"
  const std::string& description() const { return description_; }
  // Vendor, renderer and version strings: what a cached program binary depends on.
  const std::string& driver_identity() const { return driver_identity_; }
  // A CPU renderer (llvmpipe), not a GPU: it takes smaller tiles.
  bool software() const { return software_; }

  // Makes this context current for the guard's lifetime and restores the
  // caller's EGL context afterwards (prism view keeps its own window context).
  class Current {
   public:
    explicit Current(const EglContext& context);
    ~Current();
    Current(const Current&) = delete;
    Current& operator=(const Current&) = delete;

   private:
    EGLDisplay display_;
    EGLSurface draw_, read_;
    EGLContext context_;
  };

 private:
  bool try_display(EGLDisplay display, const std::string& platform, std::string& why);
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string description_;
  std::string driver_identity_;
  bool software_ = false;
};

}  // namespace prism::gl
