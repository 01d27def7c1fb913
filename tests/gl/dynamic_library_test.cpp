// SPDX-License-Identifier: MIT
// EGL and OSMesa are opened only when a context is made: a run without GL maps no Mesa or LLVM,
// and a library that cannot be opened is a ContextError naming it.
#include "gl/internal/dynamic_library.h"

#include "core/visibility/raycast_visibility.h"
#include "gl/context.h"
#include "tests/gl/context_or_skip.h"
#include "tests/support/obj.h"
#include "tests/support/run.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

namespace inkline {
namespace {

std::string process_maps() {
    std::ifstream in("/proc/self/maps");
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(DynamicLibrary, MissingLibraryIsAContextErrorNamingIt) {
    try {
        gl::internal::DynamicLibrary library("libinkline-no-such-library.so.0");
        FAIL() << "opened a library that does not exist";
    } catch (const gl::ContextError& e) {
        EXPECT_NE(std::string(e.what()).find("libinkline-no-such-library.so.0"), std::string::npos) << e.what();
    }
}

TEST(DynamicLibrary, MissingFunctionIsAContextErrorNamingIt) {
    const gl::internal::DynamicLibrary library("libc.so.6");
    void (*fn)() = nullptr;
    try {
        library.load("inkline_no_such_function", fn);
        FAIL() << "resolved a function that does not exist";
    } catch (const gl::ContextError& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("libc.so.6"), std::string::npos) << what;
        EXPECT_NE(what.find("inkline_no_such_function"), std::string::npos) << what;
    }
}

TEST(DynamicLibrary, AContextMapsItsLibrary) {
    const auto context = test::context_or_skip(gl::Backend::kOsmesa);
    EXPECT_NE(process_maps().find("libOSMesa.so"), std::string::npos);
}

#ifdef INKLINE_EXE
// The libraries a GL context brings in, as the dynamic loader names them.
constexpr const char* kGlLibraries[] = {"libEGL.so", "libOSMesa.so", "libGL.so", "libLLVM"};

// The libraries the dynamic loader opened for one run of the program, linked or dlopen'd
// (LD_DEBUG=files prints "file=<name>" for each), with its output.
test::RunResult run_tracing_libraries(const std::string& args) {
    return test::run_shell("LD_DEBUG=files " + test::inkline_command() + " " + args);
}

void expect_no_gl_library(const test::RunResult& r, const std::string& what) {
    for (const char* library : kGlLibraries) {
        EXPECT_EQ(r.output.find(std::string("file=") + library), std::string::npos)
            << what << " opened " << library << ":\n" << r.output;
    }
}

TEST(DynamicLibrary, RunWithoutGlOpensNoMesa) {
    const std::filesystem::path dir = test::fresh_temp_dir("gl_dynamic_library");
    const std::string scene = std::string(INKLINE_SAMPLES) + "/torus/scene.json --frames 1 -q -o " + dir.string();

    const test::RunResult exact = run_tracing_libraries("render " + scene + " --visibility exact");
    ASSERT_EQ(exact.code, 0) << exact.output;
    expect_no_gl_library(exact, "--visibility exact");
    if (core::raycast_available()) {
        const test::RunResult raycast = run_tracing_libraries("render " + scene + " --visibility raycast");
        ASSERT_EQ(raycast.code, 0) << raycast.output;
        expect_no_gl_library(raycast, "--visibility raycast");
        // Without a GPU device node auto decides on ray casting without making a context.
        if (!gl::gpu_device_present()) {
            const test::RunResult automatic = run_tracing_libraries("render " + scene + " --visibility auto");
            ASSERT_EQ(automatic.code, 0) << automatic.output;
            expect_no_gl_library(automatic, "--visibility auto without a GPU");
        }
    }

    // The trace does see a library opened at run time: a GL run opens EGL (then OSMesa if need be),
    // whether or not it then gets a context.
    const test::RunResult with_gl = run_tracing_libraries("render " + scene + " --visibility gl");
    EXPECT_NE(with_gl.output.find("file=libEGL.so.1"), std::string::npos) << with_gl.output;
    std::filesystem::remove_all(dir);
}
#endif

}  // namespace
}  // namespace inkline
