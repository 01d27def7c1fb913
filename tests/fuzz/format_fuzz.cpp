// SPDX-License-Identifier: MIT
// libFuzzer entry point for one mesh reader, chosen at compile time by INKLINE_FUZZ_EXTENSION
// (".obj", ".off", ".ply" or ".stl"; built by tests/fuzz/run.sh).
#include "tests/fuzz/targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    inkline::fuzz::mesh_format_target(INKLINE_FUZZ_EXTENSION, data, size);
    return 0;
}
