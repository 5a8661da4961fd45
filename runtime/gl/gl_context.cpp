#include "runtime/gl/gl_context.hpp"

#include <cstring>
#include <mutex>
#include <utility>

#include <EGL/eglext.h>
#include <fmt/core.h>

namespace crtforge::gl {
namespace {

std::string egl_string(EGLDisplay display, EGLint name) {
    const char* text = eglQueryString(display, name);
    return text ? text : "";
}

// Whole-word search in a space-separated extension string.
bool in_extension_list(const std::string& list, const std::string& name) {
    for (size_t at = list.find(name); at != std::string::npos; at = list.find(name, at + 1)) {
        const bool starts = at == 0 || list[at - 1] == ' ';
        const size_t end = at + name.size();
        if (starts && (end == list.size() || list[end] == ' ')) return true;
    }
    return false;
}

Diagnostic no_gl(const std::string& what) { return make_error(fmt::format("no OpenGL through EGL: {}; {}", what, kGlPackagesHint)); }

// Guards the shared display's creation and termination.
std::mutex& display_mutex() {
    static std::mutex mutex;
    return mutex;
}
std::weak_ptr<EglDisplay>& shared_display() {
    static std::weak_ptr<EglDisplay> display;
    return display;
}

const char* api_description(GlApi api) {
    return api == GlApi::DesktopCore ? "an OpenGL 4.5 core profile context" : "an OpenGL ES 3 context";
}

}  // namespace

std::string egl_error_name(EGLint error) {
    switch (error) {
        case EGL_SUCCESS: return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP: return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW: return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
        default: return fmt::format("EGL error 0x{:04X}", error);
    }
}

// ---- EglDisplay -------------------------------------------------------------------------------

Result<std::shared_ptr<EglDisplay>> EglDisplay::open() {
    std::lock_guard lock(display_mutex());
    if (auto existing = shared_display().lock()) return existing;

    // Client extensions (EGL_NO_DISPLAY) say which platforms the EGL library knows.
    const std::string client = egl_string(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!in_extension_list(client, "EGL_MESA_platform_surfaceless")) {
        return no_gl(client.empty() ? "the EGL library reports no client extensions"
                                    : "the EGL library has no surfaceless platform (EGL_MESA_platform_surfaceless)");
    }
    const EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        return no_gl(fmt::format("eglGetPlatformDisplay(surfaceless) failed ({})", egl_error_name(eglGetError())));
    }
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) {
        return no_gl(fmt::format("eglInitialize on the surfaceless display failed ({})", egl_error_name(eglGetError())));
    }
    const std::string extensions = egl_string(display, EGL_EXTENSIONS);
    if (!in_extension_list(extensions, "EGL_KHR_surfaceless_context")) {
        eglTerminate(display);  // no engine holds it: the registry above was empty
        return no_gl("the EGL display cannot make a context current without a surface (EGL_KHR_surfaceless_context)");
    }
    std::shared_ptr<EglDisplay> out(new EglDisplay());
    out->display_ = display;
    out->extensions_ = extensions;
    out->version_ = fmt::format("{}.{}", major, minor);
    shared_display() = out;
    return out;
}

EglDisplay::~EglDisplay() {
    std::lock_guard lock(display_mutex());
    // EGL hands out one handle per platform + native display, so a display opened by another
    // thread after this one's last owner let go (but before this lock) is this very handle, alive
    // again: terminate only when nobody has re-opened it.
    if (shared_display().expired() && display_ != EGL_NO_DISPLAY) eglTerminate(display_);
}

bool EglDisplay::has_extension(const std::string& name) const { return in_extension_list(extensions_, name); }

// ---- CurrentScope -----------------------------------------------------------------------------

CurrentScope::CurrentScope(CurrentScope&& other) noexcept
    : context_(std::exchange(other.context_, nullptr)),
      previous_api_(other.previous_api_),
      previous_display_(other.previous_display_),
      previous_draw_(other.previous_draw_),
      previous_read_(other.previous_read_),
      previous_context_(other.previous_context_) {}

CurrentScope::~CurrentScope() {
    if (context_ == nullptr) return;
    if (previous_context_ == context_->context()) {  // nested: the context was already current
        eglBindAPI(previous_api_);
        return;
    }
    // Release ours first (a release applies to the bound API), then give back the caller's.
    eglBindAPI(context_->egl_api());
    eglMakeCurrent(context_->display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglBindAPI(previous_api_);
    if (previous_context_ != EGL_NO_CONTEXT) {
        eglMakeCurrent(previous_display_, previous_draw_, previous_read_, previous_context_);
    }
}

// ---- GlContext --------------------------------------------------------------------------------

EGLenum GlContext::egl_api() const { return is_es() ? EGL_OPENGL_ES_API : EGL_OPENGL_API; }

Result<CurrentScope> GlContext::make_current() const {
    CurrentScope scope;
    scope.previous_api_ = eglQueryAPI();
    scope.previous_display_ = eglGetCurrentDisplay();
    scope.previous_draw_ = eglGetCurrentSurface(EGL_DRAW);
    scope.previous_read_ = eglGetCurrentSurface(EGL_READ);
    scope.previous_context_ = eglGetCurrentContext();
    if (eglBindAPI(egl_api()) != EGL_TRUE) {
        return make_error(fmt::format("eglBindAPI failed ({})", egl_error_name(eglGetError())));
    }
    if (eglMakeCurrent(display(), EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE) {
        const EGLint error = eglGetError();
        eglBindAPI(scope.previous_api_);
        return make_error(fmt::format("cannot make the GL context current on this thread ({}){}", egl_error_name(error),
                                      error == EGL_BAD_ACCESS ? ": another thread is using this engine" : ""));
    }
    scope.context_ = this;
    return scope;
}

Result<std::unique_ptr<GlContext>> GlContext::create(GlApi api) {
    auto display = EglDisplay::open();
    if (!display) return display.error();

    std::unique_ptr<GlContext> out(new GlContext());
    out->api_ = api;
    out->display_ = std::move(display).value();
    const EGLDisplay dpy = out->display();

    const EGLenum previous_api = eglQueryAPI();
    if (eglBindAPI(out->egl_api()) != EGL_TRUE) {
        return no_gl(fmt::format("the EGL library does not offer the {} API ({})", out->is_es() ? "OpenGL ES" : "OpenGL",
                                 egl_error_name(eglGetError())));
    }

    EGLConfig config = EGL_NO_CONFIG_KHR;
    if (!out->display_->has_extension("EGL_KHR_no_config_context")) {
        const EGLint attributes[] = {EGL_RENDERABLE_TYPE, out->is_es() ? EGL_OPENGL_ES3_BIT : EGL_OPENGL_BIT, EGL_NONE};
        EGLint count = 0;
        if (eglChooseConfig(dpy, attributes, &config, 1, &count) != EGL_TRUE || count < 1) {
            eglBindAPI(previous_api);
            return no_gl(fmt::format("the EGL display has no config for {}", api_description(api)));
        }
    }

    const EGLint desktop_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 4,
                                         EGL_CONTEXT_MINOR_VERSION, 5,
                                         EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                         EGL_NONE};
    // 3.0 asks for "at least ES 3.0": Mesa hands back the newest ES 3.x it supports.
    const EGLint es_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    out->context_ = eglCreateContext(dpy, config, EGL_NO_CONTEXT, out->is_es() ? es_attributes : desktop_attributes);
    const EGLint create_error = eglGetError();
    eglBindAPI(previous_api);
    if (out->context_ == EGL_NO_CONTEXT) {
        return no_gl(fmt::format("the driver cannot create {} ({})", api_description(api), egl_error_name(create_error)));
    }

    auto scope = out->make_current();
    if (!scope) return scope.error();
    auto functions = GlFunctions::load();
    if (!functions) return functions.error();
    out->functions_ = functions.value();
    out->facts_ = query_context_facts(out->functions_);
    take_gl_errors(out->functions_);  // start clean
    if (out->facts_.renderer.empty() || out->facts_.version.empty()) {
        return no_gl(fmt::format("{} was created but reports no GL_RENDERER/GL_VERSION", api_description(api)));
    }
    return out;
}

GlContext::~GlContext() {
    if (context_ != EGL_NO_CONTEXT) {
        // A context current on this thread is only marked for deletion: release it first.
        if (eglGetCurrentContext() == context_) {
            const EGLenum previous_api = eglQueryAPI();
            eglBindAPI(egl_api());
            eglMakeCurrent(display(), EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
            eglBindAPI(previous_api);
        }
        eglDestroyContext(display(), context_);
    }
}

}  // namespace crtforge::gl
