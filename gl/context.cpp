// SPDX-License-Identifier: MIT
#include "gl/context.h"

#include "core/error.h"

#define EGL_EGLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/gl.h>
#include <GL/osmesa.h>

#include <sys/resource.h>

#include <filesystem>
#include <string>
#include <vector>

namespace inkline::gl {
namespace {

class EglContext final : public Context {
  public:
    EglContext(EGLDisplay display, EGLContext context) : display_(display), context_(context) {}
    ~EglContext() override {
        eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        eglDestroyContext(display_, context_);
        eglTerminate(display_);
    }
    Backend backend() const override { return Backend::kEgl; }
    const char* backend_name() const override { return "egl"; }
    GlProc proc_address(const char* name) const override { return eglGetProcAddress(name); }

  private:
    EGLDisplay display_;
    EGLContext context_;
};

class OsmesaContext final : public Context {
  public:
    explicit OsmesaContext(OSMesaContext context) : context_(context), buffer_(4, 0) {
        // OSMesa needs a bound colour buffer; rendering itself goes to framebuffer objects.
        OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, 1, 1);
    }
    ~OsmesaContext() override { OSMesaDestroyContext(context_); }
    Backend backend() const override { return Backend::kOsmesa; }
    const char* backend_name() const override { return "osmesa"; }
    GlProc proc_address(const char* name) const override { return OSMesaGetProcAddress(name); }

  private:
    OSMesaContext context_;
    std::vector<unsigned char> buffer_;
};

// Tries the surfaceless platform, then every EGL device; returns nullptr with a reason.
std::unique_ptr<Context> try_egl(std::string& r_reason) {
    std::vector<EGLDisplay> displays;
    const char* extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    const std::string ext = extensions ? extensions : "";
    if (ext.find("EGL_MESA_platform_surfaceless") != std::string::npos) {
        displays.push_back(eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr));
    }
    if (ext.find("EGL_EXT_platform_device") != std::string::npos) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        auto query = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        if (query && query(8, devices, &count)) {
            for (EGLint i = 0; i < count; ++i)
                displays.push_back(eglGetPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr));
        }
    }
    if (displays.empty()) displays.push_back(eglGetDisplay(EGL_DEFAULT_DISPLAY));

    for (EGLDisplay display : displays) {
        if (display == EGL_NO_DISPLAY) continue;
        EGLint major = 0, minor = 0;
        if (!eglInitialize(display, &major, &minor)) continue;
        const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
        EGLConfig config = nullptr;
        EGLint n = 0;
        const bool have_config = eglChooseConfig(display, config_attribs, &config, 1, &n) && n > 0;
        if (!eglBindAPI(EGL_OPENGL_API)) {
            eglTerminate(display);
            continue;
        }
        const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                          EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                          EGL_NONE};
        EGLContext context = eglCreateContext(display, have_config ? config : EGL_NO_CONFIG_KHR,
                                              EGL_NO_CONTEXT, context_attribs);
        if (context == EGL_NO_CONTEXT) {
            eglTerminate(display);
            continue;
        }
        if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
            eglDestroyContext(display, context);
            eglTerminate(display);
            continue;
        }
        return std::make_unique<EglContext>(display, context);
    }
    r_reason = "EGL: no display gave an OpenGL 3.3 core context";
    return nullptr;
}

std::unique_ptr<Context> try_osmesa(std::string& r_reason) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 24, OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE, OSMESA_CONTEXT_MAJOR_VERSION, 3,
                           OSMESA_CONTEXT_MINOR_VERSION, 3, 0};
    OSMesaContext context = OSMesaCreateContextAttribs(attribs, nullptr);
    if (!context) {
        r_reason = "OSMesa: could not create an OpenGL 3.3 core context";
        return nullptr;
    }
    return std::make_unique<OsmesaContext>(context);
}

}  // namespace

Backend parse_backend(const std::string& name) {
    if (name == "auto") return Backend::kAuto;
    if (name == "egl") return Backend::kEgl;
    if (name == "osmesa") return Backend::kOsmesa;
    throw inkline::InputError("--gl '" + inkline::quote_value(name) + "': expected auto, egl or osmesa");
}

std::string Context::renderer() const {
    const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    return s ? s : "";
}

std::string Context::version() const {
    const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    return s ? s : "";
}

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
