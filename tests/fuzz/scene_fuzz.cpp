// SPDX-License-Identifier: MIT
// libFuzzer entry point for the scene parser (built by tests/fuzz/run.sh).
#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    inkline::fuzz::scene_target(data, size);
    return 0;
}
