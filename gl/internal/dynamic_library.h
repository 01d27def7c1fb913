// SPDX-License-Identifier: MIT
// A shared library opened at run time (dlopen), not at link time: a run that makes no GL context
// never maps EGL, OSMesa or what they pull in (Mesa's drivers, LLVM; about 60 MB of a run's RSS).
#pragma once

#include <string>

namespace inkline::gl::internal {

class DynamicLibrary {
  public:
    // Opens `soname` (e.g. "libEGL.so.1"); throws ContextError naming it and the loader's reason.
    explicit DynamicLibrary(const char* soname);
    ~DynamicLibrary();
    DynamicLibrary(DynamicLibrary&& other) noexcept;
    DynamicLibrary(const DynamicLibrary&) = delete;
    DynamicLibrary& operator=(const DynamicLibrary&) = delete;
    DynamicLibrary& operator=(DynamicLibrary&&) = delete;

    // Sets r_fn to the library's function `name`; throws ContextError naming both when it has none.
    template <typename Fn>
    void load(const char* name, Fn& r_fn) const {
        r_fn = reinterpret_cast<Fn>(symbol(name));
    }

    const std::string& soname() const { return soname_; }

  private:
    void* symbol(const char* name) const;

    std::string soname_;
    void* handle_ = nullptr;
};

}  // namespace inkline::gl::internal
