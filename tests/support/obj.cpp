// SPDX-License-Identifier: MIT
#include "tests/support/obj.h"

#include <fstream>
#include <sstream>
#include <unistd.h>

namespace inkline::test {

void write_obj(const std::filesystem::path& path, const core::Mesh& mesh) {
    std::filesystem::create_directories(path.parent_path());
    std::ofstream out(path);
    out.precision(9);
    for (const auto& p : mesh.positions) out << "v " << p.x << " " << p.y << " " << p.z << "\n";
    for (const auto& t : mesh.triangles) out << "f " << t.x + 1 << " " << t.y + 1 << " " << t.z + 1 << "\n";
}

void write_text(const std::filesystem::path& path, const std::string& text) {
    if (!path.parent_path().empty()) std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << text;
}

std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::filesystem::path fresh_temp_dir(const std::string& name) {
    const auto dir = std::filesystem::temp_directory_path() /
                     ("inkline_test_" + name + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

}  // namespace inkline::test
