// SPDX-License-Identifier: MIT
#include "core/error.h"

namespace inkline::detail {

void check_failed(const char* file, int line, const std::string& message) {
    std::ostringstream out;
    out << "internal check failed at " << file << ":" << line << ": " << message;
    throw InternalError(out.str());
}

}  // namespace inkline::detail
