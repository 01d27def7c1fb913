// SPDX-License-Identifier: MIT
// libFuzzer entry point for in-code meshes of the Python module (built by tests/fuzz/run.sh).
#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    inkline::fuzz::mesh_arrays_target(data, size);
    return 0;
}
