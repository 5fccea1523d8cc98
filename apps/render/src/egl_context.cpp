#include "egl_context.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "render/error.hpp"

namespace finflex::render::detail {

namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t length = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
    const bool starts = p == list || p[-1] == ' ';
    const bool ends = p[length] == ' ' || p[length] == '\0';
    if (starts && ends) return true;
  }
  return false;
}

std::string egl_error_name(EGLint error) {
  switch (error) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    default:
      return "EGL error " + std::to_string(error);
  }
}

std::string last_egl_error() { return egl_error_name(eglGetError()); }

// libepoxy loads libEGL.so.1 and libGL.so.1 (desktop GL entry points) itself and ends
// the process when one is missing: check first, so that the caller gets an exception.
void require_library(const char* name) {
  static std::mutex mutex;
  static std::map<std::string, void*> loaded;
  const std::lock_guard<std::mutex> lock(mutex);
  if (loaded.count(name) != 0) return;
  void* handle = dlopen(name, RTLD_NOW | RTLD_GLOBAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    throw RenderError(ErrorCode::kNoDevice, "egl",
                      std::string("no EGL display can be initialised: ") + name +
                          " cannot be loaded (" + (why ? why : "unknown reason") +
                          "); install the EGL and GL libraries (libegl1, libgl1, a driver)");
  }
  loaded.emplace(name, handle);  // kept for the life of the process, as epoxy keeps it
}

// EGL displays are one per device and process: two renderers on the same device share
// it, so it is terminated when the last one goes.
std::mutex display_mutex;
std::map<EGLDisplay, int> display_users;

bool acquire_display(EGLDisplay display) {
  const std::lock_guard<std::mutex> lock(display_mutex);
  EGLint major = 0;
  EGLint minor = 0;
  if (display_users[display] == 0 && !eglInitialize(display, &major, &minor)) {
    display_users.erase(display);
    return false;
  }
  ++display_users[display];
  return true;
}

void release_display(EGLDisplay display) {
  const std::lock_guard<std::mutex> lock(display_mutex);
  if (--display_users[display] == 0) {
    display_users.erase(display);
    eglTerminate(display);
  }
}

struct Candidate {
  EGLDisplay display;
  std::string description;
};

std::vector<Candidate> device_displays(std::vector<std::string>& tried) {
  std::vector<Candidate> candidates;
  EGLint count = 0;
  if (!eglQueryDevicesEXT(0, nullptr, &count) || count <= 0) {
    tried.push_back("EGL devices: none");
    return candidates;
  }
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  eglQueryDevicesEXT(count, devices.data(), &count);
  std::vector<Candidate> software;
  for (EGLint i = 0; i < count; ++i) {
    const EGLDeviceEXT device = devices[static_cast<std::size_t>(i)];
    const bool is_software =
        has_extension(eglQueryDeviceStringEXT(device, EGL_EXTENSIONS), "EGL_MESA_device_software");
    const std::string name =
        "device " + std::to_string(i) + (is_software ? " (software)" : " (hardware)");
    const EGLDisplay display = eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY) {
      tried.push_back(name + ": no display (" + last_egl_error() + ")");
      continue;
    }
    (is_software ? software : candidates).push_back({display, name});
  }
  candidates.insert(candidates.end(), software.begin(), software.end());
  return candidates;
}

std::vector<Candidate> candidate_displays(std::vector<std::string>& tried) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::vector<Candidate> candidates;
  if (has_extension(client, "EGL_EXT_device_enumeration") &&
      has_extension(client, "EGL_EXT_platform_device")) {
    candidates = device_displays(tried);
  } else {
    tried.push_back("EGL devices: EGL_EXT_device_enumeration or EGL_EXT_platform_device missing");
  }
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    const EGLDisplay display =
        eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY) {
      candidates.push_back({display, "surfaceless"});
    } else {
      tried.push_back("surfaceless: no display (" + last_egl_error() + ")");
    }
  } else {
    tried.push_back("surfaceless: EGL_MESA_platform_surfaceless missing");
  }
  const EGLDisplay fallback = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  if (fallback != EGL_NO_DISPLAY) {
    candidates.push_back({fallback, "default display"});
  } else {
    tried.push_back("default display: none");
  }
  return candidates;
}

}  // namespace

EglContext::EglContext() {
  // NVIDIA's driver waits for the GPU by spinning a core (its default __GL_YIELD); a
  // short sleep instead leaves the cores to the work beside the drawing (the farm's
  // simulation threads: 48 frames/s instead of 37 on the H200 machine,
  // docs/rendering.md "On the GPU machine"). Set before the driver loads; a value the
  // caller set stays. Other drivers ignore it.
  setenv("__GL_YIELD", "USLEEP", 0);
  require_library("libEGL.so.1");
  require_library("libGL.so.1");
  std::vector<std::string> tried;
  for (const Candidate& candidate : candidate_displays(tried)) {
    std::string why;
    if (try_display(candidate.display, why)) {
      description_ = candidate.description;
      return;
    }
    tried.push_back(candidate.description + ": " + why);
  }
  std::string message = "no EGL device or display could be initialised with OpenGL 3.3 core";
  for (std::size_t i = 0; i < tried.size(); ++i) message += (i == 0 ? " (" : "; ") + tried[i];
  if (!tried.empty()) message += ")";
  throw RenderError(ErrorCode::kNoDevice, "egl", message);
}

EglContext::~EglContext() { release(); }

bool EglContext::try_display(EGLDisplay display, std::string& why) {
  if (!acquire_display(display)) {
    why = "eglInitialize failed (" + last_egl_error() + ")";
    return false;
  }
  display_ = display;
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!eglBindAPI(EGL_OPENGL_API)) {
    why = "no desktop OpenGL (" + last_egl_error() + ")";
    release();
    return false;
  }
  // A config is needed only for a pbuffer; Mesa's device displays have none and take
  // EGL_NO_CONFIG_KHR.
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE,
                                      EGL_PBUFFER_BIT,
                                      EGL_RENDERABLE_TYPE,
                                      EGL_OPENGL_BIT,
                                      EGL_RED_SIZE,
                                      8,
                                      EGL_GREEN_SIZE,
                                      8,
                                      EGL_BLUE_SIZE,
                                      8,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint config_count = 0;
  if (!eglChooseConfig(display, config_attributes, &config, 1, &config_count)) config_count = 0;
  const bool configless = has_extension(extensions, "EGL_KHR_no_config_context");
  if (config_count == 0 && !configless) {
    why = "no OpenGL pbuffer config and no EGL_KHR_no_config_context";
    release();
    return false;
  }
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                       3,
                                       EGL_CONTEXT_MINOR_VERSION,
                                       3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                       EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  context_ = eglCreateContext(display, config_count > 0 ? config : EGL_NO_CONFIG_KHR,
                              EGL_NO_CONTEXT, context_attributes);
  if (context_ == EGL_NO_CONTEXT) {
    why = "no OpenGL 3.3 core context (" + last_egl_error() + ")";
    release();
    return false;
  }
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    if (config_count == 0) {
      why = "neither EGL_KHR_surfaceless_context nor a pbuffer config";
      release();
      return false;
    }
    const EGLint pbuffer_attributes[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display, config, pbuffer_attributes);
    if (surface_ == EGL_NO_SURFACE) {
      why = "no pbuffer (" + last_egl_error() + ")";
      release();
      return false;
    }
  }
  if (!eglMakeCurrent(display, surface_, surface_, context_)) {
    why = "eglMakeCurrent failed (" + last_egl_error() + ")";
    release();
    return false;
  }
  return true;
}

bool EglContext::try_make_current() const noexcept {
  return eglGetCurrentContext() == context_ ||
         eglMakeCurrent(display_, surface_, surface_, context_) == EGL_TRUE;
}

void EglContext::make_current() const {
  if (!try_make_current()) {
    throw RenderError(ErrorCode::kGraphics, "egl",
                      "eglMakeCurrent failed (" + last_egl_error() + ")");
  }
}

void EglContext::release() {
  if (display_ == EGL_NO_DISPLAY) return;
  if (eglGetCurrentContext() == context_) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  }
  if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
  if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
  release_display(display_);
  surface_ = EGL_NO_SURFACE;
  context_ = EGL_NO_CONTEXT;
  display_ = EGL_NO_DISPLAY;
}

}  // namespace finflex::render::detail
