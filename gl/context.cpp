// SPDX-License-Identifier: MIT
#include "gl/context.h"

#include "core/error.h"
#include "gl/internal/dynamic_library.h"

// EGL and OSMesa are opened at run time (gl/internal/dynamic_library.h): no prototypes, so that
// nothing here can call them through a link-time symbol.
#define EGL_EGL_PROTOTYPES 0
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/osmesa.h>

#include <sys/resource.h>

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace inkline::gl {
namespace {

constexpr const char* kEglLibrary = "libEGL.so.1";        // libglvnd's, or Mesa's own
constexpr const char* kOsmesaLibrary = "libOSMesa.so.8";  // Mesa's Gallium OSMesa

// The EGL 1.5 functions the context uses, from kEglLibrary.
struct Egl {
    internal::DynamicLibrary library;
    PFNEGLQUERYSTRINGPROC QueryString = nullptr;
    PFNEGLGETPROCADDRESSPROC GetProcAddress = nullptr;
    PFNEGLGETPLATFORMDISPLAYPROC GetPlatformDisplay = nullptr;
    PFNEGLGETDISPLAYPROC GetDisplay = nullptr;
    PFNEGLINITIALIZEPROC Initialize = nullptr;
    PFNEGLTERMINATEPROC Terminate = nullptr;
    PFNEGLCHOOSECONFIGPROC ChooseConfig = nullptr;
    PFNEGLBINDAPIPROC BindAPI = nullptr;
    PFNEGLCREATECONTEXTPROC CreateContext = nullptr;
    PFNEGLDESTROYCONTEXTPROC DestroyContext = nullptr;
    PFNEGLMAKECURRENTPROC MakeCurrent = nullptr;

    // Opens kEglLibrary; throws ContextError when it or one of the functions is missing.
    Egl() : library(kEglLibrary) {
        library.load("eglQueryString", QueryString);
        library.load("eglGetProcAddress", GetProcAddress);
        library.load("eglGetPlatformDisplay", GetPlatformDisplay);
        library.load("eglGetDisplay", GetDisplay);
        library.load("eglInitialize", Initialize);
        library.load("eglTerminate", Terminate);
        library.load("eglChooseConfig", ChooseConfig);
        library.load("eglBindAPI", BindAPI);
        library.load("eglCreateContext", CreateContext);
        library.load("eglDestroyContext", DestroyContext);
        library.load("eglMakeCurrent", MakeCurrent);
    }
};

// The OSMesa functions the context uses, from kOsmesaLibrary.
struct Osmesa {
    internal::DynamicLibrary library;
    decltype(&OSMesaCreateContextAttribs) CreateContextAttribs = nullptr;
    decltype(&OSMesaMakeCurrent) MakeCurrent = nullptr;
    decltype(&OSMesaDestroyContext) DestroyContext = nullptr;
    decltype(&OSMesaGetProcAddress) GetProcAddress = nullptr;

    // Opens kOsmesaLibrary; throws ContextError when it or one of the functions is missing.
    Osmesa() : library(kOsmesaLibrary) {
        library.load("OSMesaCreateContextAttribs", CreateContextAttribs);
        library.load("OSMesaMakeCurrent", MakeCurrent);
        library.load("OSMesaDestroyContext", DestroyContext);
        library.load("OSMesaGetProcAddress", GetProcAddress);
    }
};

class EglContext final : public Context {
  public:
    EglContext(Egl egl, EGLDisplay display, EGLContext context)
        : egl_(std::move(egl)), display_(display), context_(context) {}
    ~EglContext() override {
        egl_.MakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        egl_.DestroyContext(display_, context_);
        egl_.Terminate(display_);
    }
    Backend backend() const override { return Backend::kEgl; }
    const char* backend_name() const override { return "egl"; }
    GlProc proc_address(const char* name) const override { return egl_.GetProcAddress(name); }

  private:
    Egl egl_;
    EGLDisplay display_;
    EGLContext context_;
};

class OsmesaContext final : public Context {
  public:
    OsmesaContext(Osmesa osmesa, OSMesaContext context) : osmesa_(std::move(osmesa)), context_(context), buffer_(4, 0) {
        // OSMesa needs a bound colour buffer; rendering itself goes to framebuffer objects.
        osmesa_.MakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1);
    }
    ~OsmesaContext() override { osmesa_.DestroyContext(context_); }
    Backend backend() const override { return Backend::kOsmesa; }
    const char* backend_name() const override { return "osmesa"; }
    GlProc proc_address(const char* name) const override { return osmesa_.GetProcAddress(name); }

  private:
    Osmesa osmesa_;
    OSMesaContext context_;
    std::vector<unsigned char> buffer_;
};

// Tries the surfaceless platform, then every EGL device; returns nullptr with a reason.
std::unique_ptr<Context> try_egl(std::string& r_reason) {
    std::optional<Egl> loaded;
    try {
        loaded.emplace();
    } catch (const ContextError& e) {
        r_reason = std::string("EGL: ") + e.what();
        return nullptr;
    }
    const Egl& egl = *loaded;
    std::vector<EGLDisplay> displays;
    const char* extensions = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const std::string ext = extensions ? extensions : "";
    if (ext.find("EGL_MESA_platform_surfaceless") != std::string::npos) {
        displays.push_back(egl.GetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
    if (ext.find("EGL_EXT_platform_device") != std::string::npos) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(egl.GetProcAddress("eglQueryDevicesEXT"));
        if (query && query(8, devices, &count)) {
            for (EGLint i = 0; i < count; ++i)
                displays.push_back(egl.GetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
        }
    }
    if (displays.empty()) displays.push_back(egl.GetDisplay(EGL_DEFAULT_DISPLAY));

    for (EGLDisplay display : displays) {
        if (display == EGL_NO_DISPLAY) continue;
        EGLint major = 0, minor = 0;
        if (!egl.Initialize(display, &major, &minor)) continue;
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint n = 0;
        const bool have_config = egl.ChooseConfig(display, config_attribs, &config, 1, &n) && n > 0;
        if (!egl.BindAPI(EGL_OPENGL_API)) {
            egl.Terminate(display);
            continue;
        }
        const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                          EGL_NONE};
        EGLContext context = egl.CreateContext(display, have_config ? config : EGL_NO_CONFIG_KHR,
                                               EGL_NO_CONTEXT, context_attribs);
        if (context == EGL_NO_CONTEXT) {
            egl.Terminate(display);
            continue;
        }
        if (!egl.MakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            egl.DestroyContext(display, context);
            egl.Terminate(display);
            continue;
        }
        return std::make_unique<EglContext>(std::move(*loaded), display, context);
    }
    r_reason = "EGL: no display gave an OpenGL 3.3 core context";
    return nullptr;
}

std::unique_ptr<Context> try_osmesa(std::string& r_reason) {
    std::optional<Osmesa> osmesa;
    try {
        osmesa.emplace();
    } catch (const ContextError& e) {
        r_reason = std::string("OSMesa: ") + e.what();
        return nullptr;
    }
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                           OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    OSMesaContext context = osmesa->CreateContextAttribs(attribs, nullptr);
    if (!context) {
        r_reason = "OSMesa: could not create an OpenGL 3.3 core context";
        return nullptr;
    }
    return std::make_unique<OsmesaContext>(std::move(*osmesa), context);
}

// glGetString(name) through the context's entry point; "" when there is none.
std::string gl_string(const Context& context, GLenum name) {
    const auto get_string = reinterpret_cast<decltype(&glGetString)>(context.proc_address("glGetString"));
    const GLubyte* s = get_string ? get_string(name) : nullptr;
    return s ? reinterpret_cast<const char*>(s) : "";
}

}  // namespace

Backend parse_backend(const std::string& name) {
    if (name == "auto") return Backend::kAuto;
    if (name == "egl") return Backend::kEgl;
    if (name == "osmesa") return Backend::kOsmesa;
    throw inkline::InputError("--gl '" + inkline::quote_value(name) + "': expected auto, egl or osmesa");
}

std::string Context::renderer() const { return gl_string(*this, GL_RENDERER); }

std::string Context::version() const { return gl_string(*this, GL_VERSION); }

bool Context::is_software() const {
    if (backend() == Backend::kOsmesa) return true;
    const std::string r = renderer();
    for (const char* name : {"llvmpipe", "softpipe", "swrast", "Software Rasterizer"}) {
        if (r.find(name) != std::string::npos) return true;
    }
    return false;
}

bool gpu_device_present() {
    namespace fs = std::filesystem;
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator("/dev/dri", ec)) {
        if (entry.path().filename().string().starts_with("renderD")) return true;
    }
    return fs::exists("/dev/nvidia0", ec) || fs::exists("/dev/nvidiactl", ec);
}

std::unique_ptr<Context> create_context(Backend backend) {
    // Mesa's drivers (llvmpipe's JIT above all) map hundreds of MB as they start and crash, rather
    // than fail, when they cannot: under a smaller address-space limit no context is started.
    constexpr rlim_t kMinAddressSpace = rlim_t(1536) << 20;
    struct rlimit limit {};
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY && limit.rlim_cur < kMinAddressSpace) {
        throw OutOfMemory("OpenGL needs at least 1536 MiB of address space; the limit (ulimit -v) is " +
                          std::to_string(limit.rlim_cur >> 20) + " MiB");
    }
    std::string egl_reason, osmesa_reason;
    if (backend == Backend::kAuto || backend == Backend::kEgl) {
        if (auto context = try_egl(egl_reason)) return context;
        if (backend == Backend::kEgl) throw ContextError(egl_reason);
    }
    if (auto context = try_osmesa(osmesa_reason)) return context;
    throw ContextError(backend == Backend::kAuto ? egl_reason + "; " + osmesa_reason : osmesa_reason);
}

}  // namespace inkline::gl
