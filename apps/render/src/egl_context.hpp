// An OpenGL 3.3+ core context with no window and no display server, through EGL.
//
// Displays are tried in this order, the first giving a context wins:
//   1. EGL devices (EGL_EXT_device_enumeration + EGL_EXT_platform_device), hardware
//      ones before software ones (EGL_MESA_device_software: llvmpipe);
//   2. Mesa's surfaceless platform (EGL_MESA_platform_surfaceless);
//   3. the default display (eglGetDisplay(EGL_DEFAULT_DISPLAY)).
// The context is made current with no surface (EGL_KHR_surfaceless_context), else with
// a 1x1 pbuffer; the renderer draws into its own framebuffer objects either way.
#pragma once

#include <string>

#include <epoxy/egl.h>

namespace finflex::render::detail {

class EglContext {
 public:
  // Throws RenderError (kNoDevice) with one line naming every display tried and why
  // it failed.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // Makes the context current on the calling thread (if it is not already).
  // Throws RenderError (kGraphics) when EGL refuses.
  void make_current() const;
  // The same without throwing, for destructors; false when EGL refuses.
  bool try_make_current() const noexcept;
  // How the display was reached, e.g. "device 0 (software)".
  const std::string& description() const { return description_; }
  EGLDisplay display() const { return display_; }
  EGLContext context() const { return context_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  EGLSurface surface_ = EGL_NO_SURFACE;
  std::string description_;

  // Initialises `display` and creates the context on it; on failure releases what it
  // made and returns why.
  bool try_display(EGLDisplay display, std::string& why);
  void release();
};

}  // namespace finflex::render::detail
