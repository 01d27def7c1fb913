// SPDX-License-Identifier: MIT
#include "gl/internal/dynamic_library.h"

#include "gl/context.h"

#include <dlfcn.h>

#include <utility>

namespace inkline::gl::internal {

DynamicLibrary::DynamicLibrary(const char* soname) : soname_(soname) {
    // RTLD_NODELETE: Mesa registers exit handlers and LLVM has static destructors, so closing
    // the handle must not unmap them while the process runs; a second open is then only a count.
    handle_ = ::dlopen(soname, RTLD_NOW | RTLD_LOCAL | RTLD_NODELETE);
    if (!handle_) {
        const char* reason = ::dlerror();
        throw ContextError("cannot load " + soname_ + " (" + (reason ? reason : "unknown reason") + ")");
    }
}

DynamicLibrary::~DynamicLibrary() {
    if (handle_) ::dlclose(handle_);
}

DynamicLibrary::DynamicLibrary(DynamicLibrary&& other) noexcept
    : soname_(std::move(other.soname_)), handle_(std::exchange(other.handle_, nullptr)) {}

void* DynamicLibrary::symbol(const char* name) const {
    void* address = ::dlsym(handle_, name);
    if (!address) throw ContextError(soname_ + " has no function " + name);
    return address;
}

}  // namespace inkline::gl::internal
