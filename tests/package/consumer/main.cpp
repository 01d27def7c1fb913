// SPDX-License-Identifier: MIT
// inkline_consumer SCENE FRAME OUT: one frame of a scene through the installed inkline library's
// pipeline, with ray-cast visibility, written as polylines JSON; the same bytes as
// `inkline render SCENE --frames FRAME:FRAME --json OUT --visibility raycast` (stats.ms aside).
#include <inkline/core/mesh/mesh_frames.h>
#include <inkline/core/pipeline/frame_pipeline.h>
#include <inkline/core/scene/scene.h>
#include <inkline/core/version.h>
#include <inkline/export/json.h>

#include <cstdio>
#include <exception>
#include <fstream>
#include <string>

namespace core = inkline::core;

int main(int argc, char** argv) {
    if (argc != 4) {
        std::fprintf(stderr, "usage: inkline_consumer SCENE FRAME OUT (inkline %s)\n",
                     std::string(inkline::kVersion).c_str());
        return 2;
    }
    try {
        const core::Scene scene = core::load_scene(argv[1]);
        const int frame = std::stoi(argv[2]);
        core::MeshFrames meshes(scene.mesh, scene.first_frame);
        // A run of one frame, as `--frames N:N` is: feature edges by brute force, no tracker.
        core::FramePipeline pipeline(scene, meshes, core::make_cpu_occlusion(core::VisibilityMode::kRaycast),
                                     {.frame_count = 1});
        const core::FrameResult result = pipeline.run(frame);
        std::ofstream out(argv[3], std::ios::binary);
        out << inkline::output::polylines_json(result.lines, &result.strokes);
        if (!out.flush()) {
            std::fprintf(stderr, "inkline_consumer: %s: cannot write\n", argv[3]);
            return 3;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "inkline_consumer: %s\n", e.what());
        return 2;
    }
    return 0;
}
