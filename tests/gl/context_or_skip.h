// SPDX-License-Identifier: MIT
// A GL context for a test, or exit 77 (CTest's SKIP_RETURN_CODE) when none can be created at
// all. The setup installs Mesa, so on CI every GL test runs on llvmpipe; a skip is a failure.
#pragma once

#include "gl/context.h"

#include <cstdlib>
#include <iostream>
#include <memory>

namespace inkline::test {

inline constexpr int kSkipReturnCode = 77;

// Skips only when no back-end works at all; a requested back-end that fails while another
// works throws, and the test fails.
inline std::unique_ptr<gl::Context> context_or_skip(gl::Backend backend) {
    try {
        return gl::create_context(backend);
    } catch (const gl::ContextError& e) {
        if (backend != gl::Backend::kAuto) {
            try {
                gl::create_context(gl::Backend::kAuto);
            } catch (const gl::ContextError&) {
                std::cerr << "no GL context: " << e.what() << "\n";
                std::exit(kSkipReturnCode);
            }
            throw;
        }
        std::cerr << "no GL context: " << e.what() << "\n";
        std::exit(kSkipReturnCode);
    }
}

}  // namespace inkline::test
