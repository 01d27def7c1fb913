// SPDX-License-Identifier: MIT
// Headless OpenGL contexts: EGL (surfaceless or device platform) first, OSMesa as fallback.
// No window system is needed; on a CPU-only machine Mesa's llvmpipe provides the renderer.
// libEGL.so.1 and libOSMesa.so.8 are opened (dlopen) only when a context is made: a process that
// makes none maps no Mesa driver or LLVM.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

namespace inkline::gl {

// No GL context could be created with the requested back-end(s).
class ContextError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

enum class Backend { kAuto, kEgl, kOsmesa };

// A GL entry point as the platform returns it; cast to its PFNGL...PROC type before calling.
using GlProc = void (*)();

// Parses "auto", "egl" or "osmesa"; throws InputError otherwise.
Backend parse_backend(const std::string& name);

// An OpenGL context made current on the calling thread for its lifetime.
class Context {
  public:
    virtual ~Context() = default;
    virtual Backend backend() const = 0;           // kEgl or kOsmesa
    virtual const char* backend_name() const = 0;  // "egl" or "osmesa"
    // Address of a GL entry point in this context (eglGetProcAddress, OSMesaGetProcAddress);
    // nullptr when the platform does not know it.
    virtual GlProc proc_address(const char* name) const = 0;
    std::string renderer() const;                   // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
    std::string version() const;                    // GL_VERSION
    // True for Mesa's software rasterisers (llvmpipe, softpipe, swrast) and OSMesa.
    bool is_software() const;
};

// Whether the machine shows a GPU device node (/dev/dri/renderD*, /dev/nvidia*): without one, any
// context is a software renderer, and no context need be made to find that out.
bool gpu_device_present();

// Creates a context; kAuto tries EGL, then OSMesa. Throws ContextError naming what was tried,
// and the library when one cannot be opened.
std::unique_ptr<Context> create_context(Backend backend);

}  // namespace inkline::gl
