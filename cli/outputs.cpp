// SPDX-License-Identifier: MIT
#include "cli/outputs.h"

#include "core/error.h"
#include "core/scene/frame_pattern.h"
#include "export/atomic_file.h"

#include <algorithm>
#include <climits>
#include <cstdint>
#include <functional>
#include <unordered_map>

#include <sys/stat.h>

namespace inkline::cli {
namespace {

namespace fs = std::filesystem;

// One output option and its pattern (or single file).
struct OutputPattern {
    const char* option;
    const std::string* pattern;
    bool per_frame;
    int last;  // the last frame it is written for
};

// Output names with their folder resolved through links, so that "a/x.svg" and "b/../a/x.svg"
// compare equal. Folders are resolved once each.
class CanonicalNames {
  public:
    std::string operator()(const fs::path& name) {
        const std::string folder = name.parent_path().string();
        auto it = folders_.find(folder);
        if (it == folders_.end()) {
            std::error_code ec;
            // A folder that cannot be resolved (the working folder was removed) is compared as
            // written; writing there fails later as an output error.
            const fs::path given = folder.empty() ? fs::path(".") : fs::path(folder);
            fs::path resolved = fs::weakly_canonical(given, ec);
            if (ec) resolved = given.lexically_normal();
            it = folders_.emplace(folder, resolved.string()).first;
        }
        return (fs::path(it->second) / name.filename()).string();
    }

  private:
    std::unordered_map<std::string, std::string> folders_;
};

// Refuses a name the system cannot create: a part over NAME_MAX bytes or a path over PATH_MAX.
void check_name_length(const std::string& name) {
    if (name.size() >= PATH_MAX) {
        throw OutputError(quote_value(name) + ": path longer than " + std::to_string(PATH_MAX - 1) + " bytes");
    }
    for (const fs::path& part : fs::path(name)) {
        if (part.native().size() > NAME_MAX) {
            throw OutputError(quote_value(name) + ": a file or folder name longer than " + std::to_string(NAME_MAX) +
                              " bytes");
        }
    }
}

}  // namespace

Outputs resolve_outputs(const RenderArgs& args, int frame_count, int written_count) {
    Outputs out{args.json_pattern, args.svg_pattern, args.png_pattern, args.preview_pattern, args.pdf_path, false,
                args.animated_svg};
    out.pdf_per_frame = !out.pdf.empty() && core::has_frame_field(out.pdf);
    const bool any_explicit =
        !out.json.empty() || !out.svg.empty() || !out.png.empty() || !out.preview.empty() || !out.pdf.empty();
    if (!args.out_dir.empty() || !any_explicit) {
        const fs::path dir = args.out_dir.empty() ? fs::path("out") : fs::path(args.out_dir);
        if (out.json.empty()) out.json = (dir / "json" / "frame_%04d.json").string();
        if (out.svg.empty()) out.svg = (dir / "svg" / "frame_%04d.svg").string();
    }
    for (const std::string* pattern : {&out.json, &out.svg, &out.png, &out.preview, &out.animated_svg}) {
        const int count = pattern == &out.animated_svg ? frame_count : written_count;
        if (!pattern->empty() && count > 1 && !core::has_frame_field(*pattern)) {
            throw InputError("output pattern '" + quote_value(*pattern) + "' has no frame field such as %04d but " +
                             std::to_string(count) + " frames are " + (count == frame_count ? "rendered" : "written"));
        }
    }
    return out;
}

void check_outputs(const Outputs& outputs, int first, int last, int written_last, const std::vector<InputFile>& inputs) {
    struct Known {
        output::FileIdentity id;
        const InputFile* input;
    };
    std::vector<Known> input_ids;
    for (const InputFile& input : inputs) {
        if (const auto id = output::file_identity(input.path)) input_ids.push_back({*id, &input});
    }

    const std::vector<OutputPattern> patterns = {
        {"--json", &outputs.json, true, written_last},
        {"--svg", &outputs.svg, true, written_last},
        {"--png", &outputs.png, true, written_last},
        {"--preview", &outputs.preview, true, written_last},
        {"--pdf", &outputs.pdf, outputs.pdf_per_frame, written_last},
        {"--animated-svg", &outputs.animated_svg, true, last},
    };
    // Every output name as a hash of its canonical form, with where it came from; equal hashes
    // are compared by name afterwards.
    struct Named {
        uint64_t hash;
        uint32_t pattern;
        int frame;
    };
    std::vector<Named> named;
    CanonicalNames canonical;
    for (uint32_t p = 0; p < patterns.size(); ++p) {
        const OutputPattern& out = patterns[p];
        if (out.pattern->empty()) continue;
        const int begin = out.per_frame ? first : out.last, end = out.last;
        for (int frame = begin; frame <= end; ++frame) {
            // The name as the writer will reach it, once missing folders are made.
            const std::string given = out.per_frame ? core::format_frame(*out.pattern, frame) : *out.pattern;
            check_name_length(given);
            const fs::path name = canonical(given);
            struct stat target {};  // what the name leads to, links followed
            if (::stat(name.c_str(), &target) == 0) {
                const output::FileIdentity id{target.st_dev, target.st_ino};
                for (const Known& k : input_ids) {
                    if (id == k.id) {
                        throw InputError(given + ": " + out.option + " would replace the " + k.input->role +
                                         " it reads (" + k.input->path.string() + ")");
                    }
                }
                // Devices and FIFOs are written in place, not replaced: several outputs may share one.
                if (!S_ISREG(target.st_mode)) continue;
                if ((target.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0) {
                    throw OutputError(given + ": is read-only; not replaced (make it writable or remove it)");
                }
            }
            named.push_back({std::hash<std::string>{}(name.string()), p, frame});
        }
    }

    std::sort(named.begin(), named.end(), [](const Named& a, const Named& b) { return a.hash < b.hash; });
    const auto name_of = [&](const Named& n) {
        const OutputPattern& out = patterns[n.pattern];
        return out.per_frame ? core::format_frame(*out.pattern, n.frame) : *out.pattern;
    };
    for (size_t i = 1; i < named.size(); ++i) {
        for (size_t j = i; j-- > 0 && named[j].hash == named[i].hash;) {
            const std::string a = name_of(named[j]), b = name_of(named[i]);
            if (canonical(a) != canonical(b)) continue;
            const OutputPattern &pa = patterns[named[j].pattern], &pb = patterns[named[i].pattern];
            const std::string where = pa.option == pb.option
                                          ? std::string(pa.option) + " frames " + std::to_string(named[j].frame) +
                                                " and " + std::to_string(named[i].frame)
                                          : std::string(pa.option) + " and " + pb.option;
            throw InputError(b + ": " + where + " would write the same file");
        }
    }
}

}  // namespace inkline::cli
