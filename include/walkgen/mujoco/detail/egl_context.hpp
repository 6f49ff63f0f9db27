#pragma once
/// @file
/// A headless OpenGL context for MuJoCo's offscreen renderer: EGL without a window, on Mesa's
/// surfaceless platform (software rendering, no display or GPU needed), else EGL's default
/// display. Machinery of walkgen/mujoco/mujoco_robot.hpp.

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <string>

namespace walkgen {
namespace detail {

#ifndef EGL_PLATFORM_SURFACELESS_MESA
#define EGL_PLATFORM_SURFACELESS_MESA 0x31DD
#endif

/// Owns one EGL context. ok() tells whether it exists; error() says why not.
class EglContext {
 public:
  EglContext() {
    display_ = surfaceless_display();
    if (display_ == EGL_NO_DISPLAY) display_ = eglGetDisplay(EGL_DEFAULT_DISPLAY);
    if (display_ == EGL_NO_DISPLAY) {
      error_ = "no EGL display (install libegl1 and libegl-mesa0)";
      return;
    }
    EGLint major = 0;
    EGLint minor = 0;
    if (eglInitialize(display_, &major, &minor) != EGL_TRUE) {
      error_ = "eglInitialize failed (EGL error " + hex(eglGetError()) +
               "; install libegl-mesa0 and libgl1-mesa-dri)";
      display_ = EGL_NO_DISPLAY;
      return;
    }
    const EGLint config_attributes[] = {EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_ALPHA_SIZE,
                                        8,
                                        EGL_DEPTH_SIZE,
                                        24,
                                        EGL_STENCIL_SIZE,
                                        8,
                                        EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT,
                                        EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (eglChooseConfig(display_, config_attributes, &config, 1, &count) != EGL_TRUE || count < 1) {
      error_ = "no EGL configuration with RGBA8, depth 24 and desktop OpenGL";
      return;
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) {
      error_ = "EGL cannot bind desktop OpenGL";
      return;
    }
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, nullptr);
    if (context_ == EGL_NO_CONTEXT)
      error_ = "eglCreateContext failed (EGL error " + hex(eglGetError()) + ")";
  }
  ~EglContext() {
    if (context_ != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context_) {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      }
      eglDestroyContext(display_, context_);
    }
    // The display is shared by every context of the process: it is not terminated here.
  }
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  bool ok() const { return context_ != EGL_NO_CONTEXT; }
  const std::string& error() const { return error_; }

  /// Makes the context current on this thread (no surface: MuJoCo draws into its own FBO).
  bool make_current() {
    if (!ok()) return false;
    if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
      error_ = "eglMakeCurrent failed (EGL error " + hex(eglGetError()) + ")";
      return false;
    }
    return true;
  }

 private:
  static EGLDisplay surfaceless_display() {
    const auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) return EGL_NO_DISPLAY;
    return get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  }
  static std::string hex(EGLint code) {
    static const char* digits = "0123456789abcdef";
    std::string s = "0x0000";
    for (int i = 0; i < 4; ++i) s[5 - i] = digits[(code >> (4 * i)) & 0xf];
    return s;
  }

  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string error_;
};

}  // namespace detail
}  // namespace walkgen
