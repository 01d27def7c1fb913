// SPDX-License-Identifier: MIT
// Hostile input, camera: each case asserts the exit code, the one-line message and the state of
// every file involved afterwards (tests/support/hostile.h).
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::HostileTest;

}  // namespace
}  // namespace inkline
