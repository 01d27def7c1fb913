// SPDX-License-Identifier: MIT
#include "cli/farm.h"

#include "core/error.h"
#include "core/scene/frame_pattern.h"
#include "export/atomic_file.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <sys/stat.h>
#include <unistd.h>

namespace inkline::cli {
namespace {

namespace fs = std::filesystem;

// One shell word, single-quoted.
std::string quote(const std::string& word) {
    std::string out = "'";
    for (char c : word) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// One value of a `#SBATCH` line: sbatch splits those lines at whitespace and '#' outside double
// quotes, and a line ends at a newline, so control characters, '"' and '\\' are refused and a value
// with spaces, quotes or '#' is double-quoted. Throws InputError naming `what`.
std::string sbatch_word(const std::string& value, const std::string& what) {
    bool plain = !value.empty();
    for (const char c : value) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 || u == 0x7f || c == '"' || c == '\\') {
            throw InputError(what + ": a control character, '\"' or '\\' cannot be written into a Slurm #SBATCH line");
        }
        if (c == ' ' || c == '#' || c == '\'') plain = false;
    }
    return plain ? value : "\"" + value + "\"";
}

// An --sbatch value: one sbatch option that the scripts do not set themselves.
const std::string& own_sbatch_option(const std::string& option) {
    sbatch_word(option, "--sbatch");  // what no #SBATCH line can hold is named first
    if (!option.starts_with("-")) {
        throw InputError("--sbatch '" + quote_value(option) + "': expected one sbatch option, e.g. --account=lab");
    }
    for (const char* reserved : {"--array", "-a", "--output", "-o", "--error", "-e", "--job-name", "-J", "--dependency", "-d"}) {
        const std::string name = reserved;
        if (option == name || option.starts_with(name + "=") || (name.size() == 2 && option.starts_with(name))) {
            throw InputError("--sbatch '" + quote_value(option) + "': inkline farm sets " + name + " itself");
        }
    }
    return option;
}

std::string self_path() {
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    return ec ? std::string("inkline") : exe.string();
}

std::string absolute(const std::string& path) {
    std::error_code ec;
    const fs::path whole = fs::absolute(path, ec);
    if (ec) throw InputError(quote_value(path) + ": cannot resolve against the working folder: " + ec.message());
    return whole.lexically_normal().string();
}

void write_script(const fs::path& path, const std::string& text) {
    output::write_file_atomically(path, text);
    ::chmod(path.c_str(), 0755);
}

// The per-frame files a render plan writes.
std::vector<std::string> frame_files(const RenderPlan& plan, int frame) {
    std::vector<std::string> files;
    for (const std::string* pattern : {&plan.json, &plan.svg, &plan.png, &plan.preview}) {
        if (!pattern->empty()) files.push_back(core::format_frame(*pattern, frame));
    }
    if (plan.pdf_per_frame) files.push_back(core::format_frame(plan.pdf, frame));
    return files;
}

int summarize(const FarmArgs& args, const RenderPlan& plan) {
    std::ostringstream report;
    const int frames = plan.last - plan.first + 1;
    report << "inkline farm summary: frames " << plan.first << ".." << plan.last << " in " << args.chunks << " chunks\n";
    bool complete = true;
    for (int k = 1; k <= args.chunks; ++k) {
        const ChunkRange c = chunk_range(plan.first, plan.last, k, args.chunks);
        if (c.first > c.last) continue;
        std::vector<int> missing;
        for (int f = c.first; f <= c.last; ++f) {
            for (const std::string& file : frame_files(plan, f)) {
                std::error_code ec;
                if (!fs::exists(file, ec)) {
                    missing.push_back(f);
                    break;
                }
            }
        }
        report << "chunk " << k << " (frames " << c.first << "-" << c.last << "): ";
        if (missing.empty()) {
            report << "ok\n";
            continue;
        }
        complete = false;
        report << "missing frame(s)";
        for (int f : missing) report << " " << f;
        report << "; re-run: sbatch --array=" << k << " " << (fs::path(args.out_dir) / "slurm" / "render.sbatch").string()
               << "\n";
    }
    if (complete && !args.assemble_pdf.empty()) {
        // pdfunite (poppler-utils) joins the per-frame PDFs in frame order.
        std::string command = "pdfunite";
        for (int f = plan.first; f <= plan.last; ++f) command += " " + quote(core::format_frame(plan.pdf, f));
        const std::string temp = output::temporary_path_for(args.assemble_pdf).string();
        command += " " + quote(temp);
        std::error_code ec;
        fs::create_directories(fs::path(args.assemble_pdf).parent_path(), ec);
        if (ec) throw OutputError(fs::path(args.assemble_pdf).parent_path().string() + ": cannot create folder: " + ec.message());
        if (std::system(command.c_str()) == 0 && std::rename(temp.c_str(), args.assemble_pdf.c_str()) == 0) {
            report << "sequence PDF: " << args.assemble_pdf << " (" << frames << " pages)\n";
        } else {
            std::remove(temp.c_str());
            report << "sequence PDF: pdfunite failed or is missing (Debian package poppler-utils)\n";
            complete = false;
        }
    }
    report << (complete ? "complete\n" : "INCOMPLETE\n");
    output::write_file_atomically(fs::path(args.out_dir) / "slurm" / "summary.txt", report.str());
    std::fputs(report.str().c_str(), stdout);
    return complete ? 0 : kFramesMissing;
}

}  // namespace

int run_farm(const FarmArgs& args, const RenderArgs& render_in) {
    if (args.chunks < 1 || args.chunks > 100000) throw InputError("--chunks: must be 1..100000");
    // Each task gets its chunk and the farm's output folder; the same options after -- would clash.
    if (!render_in.chunk.empty()) throw InputError("render options after --: --chunk is set by inkline farm for each task");
    if (!render_in.out_dir.empty()) throw InputError("render options after --: -o is the farm's own -o");
    RenderArgs render = render_in;
    render.input = absolute(args.scene);
    render.out_dir = absolute(args.out_dir);
    RenderPlan plan = plan_render(render);
    if (plan.write_on) throw InputError("--write-on: a write-on cannot be split into chunks; render it with inkline render");
    if (!plan.pdf.empty() && !plan.pdf_per_frame) {
        throw InputError("--pdf '" + plan.pdf + "': a farm renders per-frame PDFs (a pattern such as pdf/frame_%04d.pdf); "
                         "--assemble-pdf names the multi-page result");
    }
    FarmArgs farm = args;
    farm.out_dir = render.out_dir;
    if (farm.assemble_pdf.empty() && plan.pdf_per_frame) farm.assemble_pdf = (fs::path(farm.out_dir) / "sequence.pdf").string();
    if (!farm.assemble_pdf.empty() && !plan.pdf_per_frame) throw InputError("--assemble-pdf: the render writes no per-frame PDFs");
    if (!farm.assemble_pdf.empty()) farm.assemble_pdf = absolute(farm.assemble_pdf);
    if (args.summarize) return summarize(farm, plan);

    // Every path in the scripts is absolute: jobs may start in any folder on any node.
    const fs::path dir = fs::path(farm.out_dir) / "slurm";
    const std::string exe = self_path();
    std::string render_words;
    for (const std::string& a : args.render_args) render_words += " " + quote(a);
    std::string farm_words = " --chunks " + std::to_string(args.chunks) + " -o " + quote(farm.out_dir);
    if (!farm.assemble_pdf.empty()) farm_words += " --assemble-pdf " + quote(farm.assemble_pdf);

    // Every value in a #SBATCH line goes through sbatch_word; every word of a command line is
    // shell-quoted. Nothing the user typed is written into a script otherwise.
    std::ostringstream job;
    job << "#!/bin/bash\n"
        << "# One chunk of the sequence per array task (written by inkline farm).\n"
        << "#SBATCH --job-name=inkline-render\n"
        << "#SBATCH --array=1-" << args.chunks << "\n"
        << "#SBATCH " << sbatch_word("--output=" + (dir / "logs" / "chunk-%a.log").string(), "-o") << "\n";
    const std::string cd_line = "cd " + quote(fs::current_path().string()) + "\n";  // relative paths in render options
    // The user's #SBATCH lines, the same for both jobs (an account or QOS the cluster requires
    // applies to the summary too).
    std::string directives;
    if (!args.partition.empty()) directives += "#SBATCH " + sbatch_word("--partition=" + args.partition, "--partition") + "\n";
    if (!args.time.empty()) directives += "#SBATCH " + sbatch_word("--time=" + args.time, "--time") + "\n";
    if (!args.mem.empty()) directives += "#SBATCH " + sbatch_word("--mem=" + args.mem, "--mem") + "\n";
    for (const std::string& a : args.sbatch_args) directives += "#SBATCH " + sbatch_word(own_sbatch_option(a), "--sbatch") + "\n";
    job << directives;
    job << cd_line << "exec " << quote(exe) << " render " << quote(render.input) << " --chunk slurm -q -o " << quote(render.out_dir)
        << render_words << "\n";
    write_script(dir / "render.sbatch", job.str());

    std::ostringstream summary;
    summary << "#!/bin/bash\n"
            << "# Runs after every chunk: checks each frame, names chunks to re-run, assembles the PDF.\n"
            << "#SBATCH --job-name=inkline-summary\n"
            << "#SBATCH " << sbatch_word("--output=" + (dir / "logs" / "summary.log").string(), "-o") << "\n"
            << directives;
    summary << cd_line << "exec " << quote(exe) << " farm " << quote(render.input) << farm_words << " --summarize --" << render_words
            << "\n";
    write_script(dir / "summary.sbatch", summary.str());

    std::ostringstream submit;
    submit << "#!/bin/bash\n# Submits the chunk array, then the summary once every chunk has ended.\nset -euo pipefail\n"
           << "array=$(sbatch --parsable " << quote((dir / "render.sbatch").string()) << ")\n"
           << "array=${array%%;*}\n"
           << "summary=$(sbatch --parsable --dependency=afterany:$array " << quote((dir / "summary.sbatch").string()) << ")\n"
           << "echo \"inkline farm: chunks job $array, summary job ${summary%%;*}\"\n";
    write_script(dir / "submit.sh", submit.str());
    std::error_code ec;
    fs::create_directories(dir / "logs", ec);
    if (ec) throw OutputError((dir / "logs").string() + ": cannot create folder: " + ec.message());
    std::printf("inkline farm: wrote %s (render.sbatch, summary.sbatch, submit.sh): frames %d..%d in %d chunks\n",
                dir.c_str(), plan.first, plan.last, args.chunks);
    if (!args.submit) return 0;
    const std::string command = "bash " + quote((dir / "submit.sh").string());
    if (std::system(command.c_str()) != 0) throw OutputError((dir / "submit.sh").string() + ": sbatch failed");
    return 0;
}

}  // namespace inkline::cli
