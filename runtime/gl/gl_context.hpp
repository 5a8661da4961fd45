// The long-lived EGL objects a GL engine reuses across jobs: the surfaceless Mesa display (shared
// by every engine in the process, terminated with the last one) and one context of the requested
// API, with its function table and what it reports about itself. No window, no surface: the
// context is made current with EGL_NO_SURFACE (EGL_KHR_surfaceless_context) and renders into FBOs.
#pragma once

#include <memory>
#include <string>

#include <EGL/egl.h>

#include "crtforge/diagnostic.hpp"
#include "crtforge/runtime/gl_engine.hpp"
#include "runtime/gl/gl_functions.hpp"

namespace crtforge::gl {

// The process-wide surfaceless display. eglTerminate invalidates every context on a display, so
// it is reference-counted: engines share one and the last to go terminates it.
class EglDisplay {
public:
    static Result<std::shared_ptr<EglDisplay>> open();
    ~EglDisplay();
    EglDisplay(const EglDisplay&) = delete;
    EglDisplay& operator=(const EglDisplay&) = delete;

    EGLDisplay get() const { return display_; }
    bool has_extension(const std::string& name) const;  // display extension (EGL_EXTENSIONS)
    const std::string& version() const { return version_; }  // EGL_VERSION, e.g. "1.5"

private:
    EglDisplay() = default;
    EGLDisplay display_ = EGL_NO_DISPLAY;
    std::string extensions_, version_;
};

class GlContext;

// Makes a context current on this thread for the scope's lifetime, then gives the thread back
// the context (and bound client API) it had before.
class CurrentScope {
public:
    CurrentScope(CurrentScope&& other) noexcept;
    CurrentScope& operator=(CurrentScope&&) = delete;
    CurrentScope(const CurrentScope&) = delete;
    ~CurrentScope();

private:
    friend class GlContext;
    CurrentScope() = default;

    const GlContext* context_ = nullptr;  // null once moved from
    EGLenum previous_api_ = EGL_NONE;
    EGLDisplay previous_display_ = EGL_NO_DISPLAY;
    EGLSurface previous_draw_ = EGL_NO_SURFACE, previous_read_ = EGL_NO_SURFACE;
    EGLContext previous_context_ = EGL_NO_CONTEXT;
};

class GlContext {
public:
    static Result<std::unique_ptr<GlContext>> create(GlApi api);
    ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    GlApi api() const { return api_; }
    bool is_es() const { return api_ == GlApi::Es; }
    EGLenum egl_api() const;
    EGLDisplay display() const { return display_->get(); }
    EGLContext context() const { return context_; }

    // Fails with the EGL error when the context cannot be made current on this thread (for
    // example while another thread has it).
    Result<CurrentScope> make_current() const;

    // Valid after create(); use them only inside a CurrentScope.
    const GlFunctions& functions() const { return functions_; }
    const GlContextFacts& facts() const { return facts_; }

private:
    GlContext() = default;

    GlApi api_ = GlApi::DesktopCore;
    std::shared_ptr<EglDisplay> display_;
    EGLContext context_ = EGL_NO_CONTEXT;
    GlFunctions functions_;
    GlContextFacts facts_;
};

// "EGL_BAD_MATCH" and friends, for messages.
std::string egl_error_name(EGLint error);

// The hint appended to every "no GL here" error.
inline constexpr const char* kGlPackagesHint =
    "install the Debian packages libegl1, libgl1-mesa-dri and libegl-mesa0 (Mesa's EGL and llvmpipe)";

}  // namespace crtforge::gl
