#include "egl_context.hpp"

#include <EGL/eglext.h>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <cstdlib>
#include <cstring>
#include <vector>

#include "prism/errors.hpp"

namespace prism::gl {

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string egl_error_text(EGLint code) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "EGL error 0x%04x", code);
  return buffer;
}

const char* gl_string(GLenum name) {
  const char* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "?";
}

struct Candidate {
  EGLDisplay display;
  std::string platform;
  bool software;  // the EGL device says it is a software renderer (EGL_MESA_device_software)
};

// EGL displays to try, each with the platform's name, in order of preference.
std::vector<Candidate> candidate_displays(std::string& why) {
  std::vector<Candidate> displays;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  const char* forced = std::getenv("PRISM_EGL_PLATFORM");  // "device" or "surfaceless"
  auto wanted = [&](const char* name) { return !forced || std::strcmp(forced, name) == 0; };
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) {
    why += "no eglGetPlatformDisplayEXT; ";
    return displays;
  }
  if (wanted("device") && has_extension(client, "EGL_EXT_platform_device")) {
    auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query && query(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        const char* extensions = device_string ? device_string(devices[i], EGL_EXTENSIONS) : nullptr;
        if (d != EGL_NO_DISPLAY)
          displays.push_back({d, "EGL device " + std::to_string(i), has_extension(extensions, "EGL_MESA_device_software")});
      }
    }
    if (count == 0) why += "EGL device platform: no devices; ";
  }
  if (wanted("surfaceless") && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY) displays.push_back({d, "EGL surfaceless", false});
  } else if (wanted("surfaceless")) {
    why += "no EGL_MESA_platform_surfaceless; ";
  }
  return displays;
}

}  // namespace

EglContext::EglContext() {
  std::string why;
  for (const Candidate& c : candidate_displays(why)) {
    if (!try_display(c.display, c.platform, why)) continue;
    // Mesa's software rasterisers, also where the platform does not say so (surfaceless).
    const std::string renderer = driver_identity_.substr(driver_identity_.find('|') + 1);
    software_ = c.software || renderer.starts_with("llvmpipe") || renderer.starts_with("softpipe");
    return;
  }
  if (why.empty()) why = "no EGL platform offered a display";
  throw RuntimeError("no OpenGL 4.5 core context via EGL: " + why.substr(0, why.find_last_not_of("; ") + 1));
}

bool EglContext::try_display(EGLDisplay display, const std::string& platform, std::string& why) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why += platform + ": eglInitialize failed (" + egl_error_text(eglGetError()) + "); ";
    return false;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context") || !has_extension(extensions, "EGL_KHR_no_config_context")) {
    why += platform + ": no surfaceless, config-less contexts; ";
    eglTerminate(display);
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why += platform + ": no desktop OpenGL API; ";
    eglTerminate(display);
    return false;
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    why += platform + ": no OpenGL 4.5 core context (" + egl_error_text(eglGetError()) + "); ";
    eglTerminate(display);
    return false;
  }
  display_ = display;
  context_ = context;
  GLint gl_major = 0, gl_minor = 0;
  {
    Current current(*this);
    glGetIntegerv(GL_MAJOR_VERSION, &gl_major);
    glGetIntegerv(GL_MINOR_VERSION, &gl_minor);
    description_ = std::string(gl_string(GL_RENDERER)) + ", OpenGL " + gl_string(GL_VERSION) + ", " + platform;
    driver_identity_ = std::string(gl_string(GL_VENDOR)) + "|" + gl_string(GL_RENDERER) + "|" + gl_string(GL_VERSION);
  }
  if (gl_major * 10 + gl_minor >= 45) return true;
  why += platform + ": context is OpenGL " + std::to_string(gl_major) + "." + std::to_string(gl_minor) + "; ";
  eglDestroyContext(display, context);
  context_ = EGL_NO_CONTEXT;
  return false;
}

EglContext::~EglContext() {
  if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
  // The display is not terminated: EGL displays are per process and other
  // contexts (another backend instance, a viewer) may share it.
}

EglContext::Current::Current(const EglContext& context)
    : display_(eglGetCurrentDisplay()),
      draw_(eglGetCurrentSurface(EGL_DRAW)),
      read_(eglGetCurrentSurface(EGL_READ)),
      context_(eglGetCurrentContext()) {
  if (!eglMakeCurrent(context.display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context.context_))
    throw RuntimeError("cannot make the OpenGL context current (" + egl_error_text(eglGetError()) + ")");
}

EglContext::Current::~Current() {
  if (context_ != EGL_NO_CONTEXT) {
    eglMakeCurrent(display_, draw_, read_, context_);
  } else {
    eglMakeCurrent(eglGetCurrentDisplay(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
}

}  // namespace prism::gl
