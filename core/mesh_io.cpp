// SPDX-License-Identifier: MIT
#include "core/mesh_io.h"

#include "core/error.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

namespace inkline::core {
namespace {

using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;

// Coordinates beyond this magnitude are refused: their squares still fit a double comfortably,
// and no real scene needs them (float meshes lose all precision long before).
constexpr double kMaxCoordinate = 1e18;

// Collects OpenMesh's reader output as a triangle soup. OpenMesh's own mesh kernel refuses
// non-manifold faces; inkline draws those too, so it keeps the soup and builds its own edge table.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
  public:
    // Every vertex and face takes at least two bytes of any file format, so a reader that
    // produces more than max_elements of either is following a lying header: refused before
    // memory grows past a small multiple of the file size.
    SoupImporter(LoadedMesh& r_out, uintmax_t file_size) : out_(r_out), max_elements_(file_size / 2 + 16) {}

    std::optional<std::string> error;  // the first fatal problem, reported after reading

    VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
        return add_vertex(OpenMesh::Vec3d(p[0], p[1], p[2]));
    }
    VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
        const double largest = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])});
        if (!error && !(largest <= kMaxCoordinate)) {  // also catches NaN
            error = "vertex " + std::to_string(out_.mesh.positions.size() + 1) +
                    (std::isfinite(largest) ? " has a coordinate beyond the limit of 1e18"
                                            : " has a non-finite coordinate");
        }
        if (out_.mesh.positions.size() >= max_elements_) throw_too_many("vertices");
        out_.mesh.positions.emplace_back(float(p[0]), float(p[1]), float(p[2]));
        return VertexHandle(int(out_.mesh.positions.size()) - 1);
    }
    VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }

    FaceHandle add_face(const VHandles& corners) override {
        if (++polygons_ > max_elements_) throw_too_many("faces");
        if (corners.size() < 3) {
            ++short_faces_;
            return FaceHandle();
        }
        const auto n_vertices = out_.mesh.positions.size();
        for (const VertexHandle& v : corners) {
            if (v.idx() < 0 || size_t(v.idx()) >= n_vertices) {
                if (!error) {
                    error = "face " + std::to_string(polygons_) +
                            " references a vertex that does not exist (index " + std::to_string(v.idx() + 1) +
                            " after resolving relative indices; valid: 1.." + std::to_string(n_vertices) + ")";
                }
                return FaceHandle();
            }
        }
        // Fan triangulation keeps the polygon's winding.
        for (size_t i = 1; i + 1 < corners.size(); ++i) {
            out_.mesh.triangles.emplace_back(corners[0].idx(), corners[i].idx(),
                                             corners[i + 1].idx());
        }
        return FaceHandle(int(out_.mesh.triangles.size()) - 1);
    }

    size_t short_faces() const { return short_faces_; }

    // Attributes inkline does not use are accepted and dropped.
    HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
    FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
    void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
    void set_face_texindex(FaceHandle, int) override {}
    void set_point(VertexHandle v, const OpenMesh::Vec3f& p) override {
        if (v.idx() >= 0 && size_t(v.idx()) < out_.mesh.positions.size())
            out_.mesh.positions[size_t(v.idx())] = glm::vec3(p[0], p[1], p[2]);
    }
    void set_halfedge(VertexHandle, HalfedgeHandle) override {}
    void set_normal(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(VertexHandle, const OpenMesh::Vec3d&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
    void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
    void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_next(HalfedgeHandle, HalfedgeHandle) override {}
    void set_face(HalfedgeHandle, FaceHandle) override {}
    void request_face_texcoords2D() override {}
    void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
    void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
    void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
    void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec3f&) override {}
    void set_color(OpenMesh::EdgeHandle, const OpenMesh::Vec4f&) override {}
    void set_status(OpenMesh::EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
    void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
    void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
    void add_texture_information(int, std::string) override {}

    bool is_triangle_mesh() const override { return false; }
    size_t n_vertices() const override { return out_.mesh.positions.size(); }
    size_t n_faces() const override { return out_.mesh.triangles.size(); }
    size_t n_edges() const override { return 0; }

  private:
    [[noreturn]] void throw_too_many(const char* what) const {
        throw InputError(std::string("declares more ") + what + " than the file's size can hold");
    }

    LoadedMesh& out_;
    uintmax_t max_elements_;
    size_t polygons_ = 0;
    size_t short_faces_ = 0;
};

// Reads one coordinate with strtod, which also accepts "nan" and "inf", so they can be named.
double scan_coordinate(const std::string& where, const char*& r_cursor) {
    char* end = nullptr;
    const double value = std::strtod(r_cursor, &end);
    if (end == r_cursor) throw InputError(where + ": vertex needs three numbers");
    if (!std::isfinite(value)) throw InputError(where + ": vertex has a non-finite coordinate");
    if (std::abs(value) > kMaxCoordinate) {
        throw InputError(where + ": coordinate " + std::to_string(value) + " exceeds the limit of 1e18");
    }
    r_cursor = end;
    return value;
}

// OpenMesh's text readers silently skip a vertex line they cannot parse ("v nan 0 0", or a value
// beyond float range), which shifts every later index. This pass finds such lines first and
// names them. OBJ: every "v" line. OFF: the vertex block after the counts.
// Returns the number of OBJ faces with fewer than 3 corners, which OpenMesh drops unreported.
size_t check_text_vertices(const std::filesystem::path& path, const std::string& extension) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    size_t number = 0;
    auto where = [&] { return path.string() + ":" + std::to_string(number); };
    if (extension == ".obj") {
        size_t short_faces = 0;
        while (std::getline(in, line)) {
            ++number;
            if (line.size() < 2 || (line[1] != ' ' && line[1] != '\t')) continue;
            if (line[0] == 'f') {
                std::istringstream corners(line.substr(2));
                std::string corner;
                int count = 0;
                while (corners >> corner) ++count;
                short_faces += count < 3;
            }
            if (line[0] != 'v') continue;
            const char* cursor = line.c_str() + 2;
            for (int axis = 0; axis < 3; ++axis) scan_coordinate(where(), cursor);
        }
        return short_faces;
    }
    // OFF: header keyword, then "nv nf ne", then nv vertex lines; '#' starts a comment.
    long vertices = -1;
    bool header = false;
    while (std::getline(in, line)) {
        ++number;
        const size_t hash = line.find('#');
        if (hash != std::string::npos) line.resize(hash);
        if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
        if (!header) {
            header = true;
            if (line.find("OFF") != std::string::npos) {
                if (line.find("BINARY") != std::string::npos) return 0;  // binary: checked on import
                const size_t after = line.find("OFF") + 3;
                if (line.find_first_not_of(" \t\r", after) == std::string::npos) continue;
                line = line.substr(after);
            }
        }
        const char* cursor = line.c_str();
        if (vertices < 0) {
            char* end = nullptr;
            vertices = std::strtol(cursor, &end, 10);
            if (end == cursor || vertices < 0) return 0;  // not an OFF layout this pass knows
            continue;
        }
        if (vertices-- == 0) return 0;
        for (int axis = 0; axis < 3; ++axis) scan_coordinate(where(), cursor);
    }
    return 0;
}

// OpenMesh's OFF and PLY readers reserve memory for the element counts a header declares before
// reading any element. A header claiming more elements than the file could hold is refused
// here, before it can exhaust memory. Each element needs at least this many bytes.
constexpr uintmax_t kMinTextVertexBytes = 6;  // "0 0 0\n"
constexpr uintmax_t kMinTextFaceBytes = 8;    // "3 0 1 2\n"
constexpr uintmax_t kMinBinaryVertexBytes = 12;
constexpr uintmax_t kMinBinaryFaceBytes = 13;

struct PlyCounts {
    uintmax_t vertices = 0;
    uintmax_t faces = 0;
    bool binary = false;
};

// OpenMesh's PLY reader trusts the header's structure (a property before any element crashes
// it), so the header is checked line by line first: "ply", one "format", then "element NAME N",
// "property TYPE NAME", "property list TYPE TYPE NAME", "comment" and "obj_info" lines, up to
// "end_header".
PlyCounts check_ply_header(const std::filesystem::path& path) {
    static const std::set<std::string> kTypes = {"char",  "uchar",  "short",  "ushort",  "int",    "uint",
                                                 "float", "double", "int8",   "uint8",   "int16",  "uint16",
                                                 "int32", "uint32", "float32", "float64"};
    constexpr int kMaxHeaderLines = 1000;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    PlyCounts counts;
    bool have_format = false, in_element = false;
    for (int number = 1; number <= kMaxHeaderLines && std::getline(in, line); ++number) {
        if (!line.empty() && line.back() == '\r') line.pop_back();
        auto fail = [&](const std::string& problem) {
            throw InputError(path.string() + ":" + std::to_string(number) + ": malformed PLY header: " + problem);
        };
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (number == 1) {
            if (keyword != "ply") fail("the file must start with 'ply'");
            continue;
        }
        if (keyword == "end_header") {
            if (!have_format) fail("no format line");
            return counts;
        }
        if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
        if (keyword == "format") {
            std::string format, version;
            if (!(words >> format >> version) ||
                (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")) {
                fail("unknown format");
            }
            have_format = true;
            counts.binary = format != "ascii";
        } else if (keyword == "element") {
            std::string name, count_text, extra;
            if (!(words >> name >> count_text) || (words >> extra) ||
                count_text.find_first_not_of("0123456789") != std::string::npos || count_text.size() > 12) {
                fail("expected 'element NAME COUNT'");
            }
            const uintmax_t count = std::stoull(count_text);
            if (name == "vertex") counts.vertices = count;
            if (name == "face") counts.faces = count;
            in_element = true;
        } else if (keyword == "property") {
            if (!in_element) fail("a property before any element");
            std::string type, name, extra;
            if (!(words >> type)) fail("expected a property type");
            if (type == "list") {
                std::string count_type, item_type;
                if (!(words >> count_type >> item_type >> name) || !kTypes.count(count_type) || !kTypes.count(item_type))
                    fail("expected 'property list TYPE TYPE NAME'");
            } else if (!kTypes.count(type) || !(words >> name)) {
                fail("expected 'property TYPE NAME'");
            }
            if (words >> extra) fail("unexpected words after the property name");
        } else {
            fail("unknown keyword '" + keyword + "'");
        }
    }
    throw InputError(path.string() + ": malformed PLY header: no end_header in the first " +
                     std::to_string(kMaxHeaderLines) + " lines");
}

// A face of an ASCII OFF file starts with its corner count; OpenMesh collects that many corners
// before reading them, so an absurd count would allocate without bound. Faces follow the
// vertex lines; each corner takes at least two bytes ("0 ").
void check_off_face_sizes(std::istream& in, uintmax_t vertices, uintmax_t faces, uintmax_t file_size,
                          const std::filesystem::path& path) {
    if (vertices > file_size || faces > file_size) return;  // refused by the caller
    std::string line;
    std::getline(in, line);  // rest of the counts line
    for (uintmax_t read = 0; read < vertices && std::getline(in, line);) {
        if (line.find_first_not_of(" \t\r") != std::string::npos && line[line.find_first_not_of(" \t\r")] != '#') ++read;
    }
    for (uintmax_t read = 0; read < faces && std::getline(in, line);) {
        std::istringstream words(line);
        long long corners = 0;
        if (!(words >> corners)) continue;
        ++read;
        if (corners < 0 || uintmax_t(corners) > file_size / 2) {
            throw InputError(path.string() + ": a face declares " + std::to_string(corners) +
                             " corners, more than the file can hold");
        }
    }
}

void check_declared_counts(const std::filesystem::path& path, const std::string& extension, uintmax_t file_size) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    uintmax_t vertices = 0, faces = 0;
    bool binary = false;
    if (extension == ".ply") {
        const PlyCounts counts = check_ply_header(path);
        vertices = counts.vertices;
        faces = counts.faces;
        binary = counts.binary;
    } else if (extension == ".off") {
        // The counts are read as OpenMesh reads them: the keyword line, then stream tokens.
        std::string keyword_line;
        std::getline(in, keyword_line);
        binary = keyword_line.find("BINARY") != std::string::npos;
        if (binary) {
            uint32_t counts[3] = {0, 0, 0};
            in.read(reinterpret_cast<char*>(counts), sizeof counts);
            vertices = counts[0];
            faces = counts[1];
        } else {
            in.seekg(0);
            std::string keyword;
            in >> keyword;
            const bool counts_on_keyword_line = keyword_line.find_first_of("0123456789") != std::string::npos &&
                                                keyword.find("OFF") != std::string::npos;
            if (!counts_on_keyword_line) {
                in.seekg(0);
                std::getline(in, keyword_line);
            }
            long long v = 0, f = 0;
            if (in >> v >> f) {
                vertices = uintmax_t(std::max(v, 0LL));
                faces = uintmax_t(std::max(f, 0LL));
                if (v < 0 || f < 0) throw InputError(path.string() + ": negative element counts in the header");
            }
            check_off_face_sizes(in, vertices, faces, file_size, path);
        }
    }
    const uintmax_t needed = binary ? vertices * kMinBinaryVertexBytes + faces * kMinBinaryFaceBytes
                                    : vertices * kMinTextVertexBytes + faces * kMinTextFaceBytes;
    if (vertices > file_size || faces > file_size || needed > file_size) {
        throw InputError(path.string() + ": header declares " + std::to_string(vertices) + " vertices and " +
                         std::to_string(faces) + " faces, more than the file's " + std::to_string(file_size) +
                         " bytes can hold");
    }
}

// OpenMesh reports through global streams; inkline reports through its own errors instead.
void silence_openmesh_streams() {
    omlog().disable();
    omout().disable();
    omerr().disable();
}

}  // namespace

LoadedMesh load_mesh(const std::filesystem::path& path) {
    const std::string name = path.string();
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw InputError(name + ": file not found");
    if (std::filesystem::is_directory(path, ec)) throw InputError(name + ": is a folder, not a mesh file");
    const uintmax_t file_size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name + ": cannot read: " + ec.message());
    if (file_size == 0) throw InputError(name + ": file is empty");

    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    size_t short_faces = 0;
    if (extension == ".off" || extension == ".ply") check_declared_counts(path, extension, file_size);
    if (extension == ".obj" || extension == ".off") short_faces = check_text_vertices(path, extension);

    silence_openmesh_streams();
    LoadedMesh out;
    SoupImporter importer(out, file_size);
    OpenMesh::IO::Options options;
    bool ok = false;
    try {
        ok = OpenMesh::IO::IOManager().read(name, importer, options);
    } catch (const std::bad_alloc&) {
        throw InputError(name + ": too large to load into memory");
    } catch (const InputError& e) {
        throw InputError(name + ": " + e.what());
    } catch (const std::exception& e) {
        throw InputError(name + ": cannot read: " + e.what());
    }
    if (importer.error) throw InputError(name + ": " + *importer.error);
    if (!ok) {
        throw InputError(name + ": cannot read as a mesh (supported: .obj .off .ply .stl; "
                                "the file may be damaged)");
    }
    if (out.mesh.triangles.empty()) throw InputError(name + ": mesh has no faces");
    short_faces = std::max(short_faces, importer.short_faces());
    if (short_faces > 0) {
        out.warnings.push_back(name + ": skipped " + std::to_string(short_faces) +
                               " face(s) with fewer than 3 vertices");
    }
    return out;
}

}  // namespace inkline::core
