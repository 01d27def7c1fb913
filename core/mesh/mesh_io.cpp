// SPDX-License-Identifier: MIT
#include "core/mesh/mesh_io.h"

#include "core/error.h"
#include "core/mesh/internal/mesh_checks.h"
#include "core/mesh/internal/obj_reader.h"
#include "core/mesh/internal/off_reader.h"
#include "core/mesh/internal/ply_reader.h"
#include "core/mesh/internal/stl_reader.h"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>

namespace inkline::core {
namespace {

using OpenMesh::FaceHandle;
using OpenMesh::HalfedgeHandle;
using OpenMesh::VertexHandle;


// Collects OpenMesh's reader output as a triangle soup. OpenMesh's own mesh kernel refuses
// non-manifold faces; inkline draws those too, so it keeps the soup and builds its own edge table.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
  public:
    // Every vertex and face takes at least two bytes of any file format, so a reader that
    // produces more than max_elements of either is following a lying header: refused before
    // memory grows past a small multiple of the file size.
    SoupImporter(LoadedMesh& r_out, uintmax_t file_size, size_t max_triangles)
        : out_(r_out), max_elements_(file_size / 2 + 16), max_triangles_(max_triangles) {}

    std::optional<std::string> error;  // the first fatal problem, reported after reading

    VertexHandle add_vertex(const OpenMesh::Vec3f& p) override {
        return add_vertex(OpenMesh::Vec3d(p[0], p[1], p[2]));
    }
    VertexHandle add_vertex(const OpenMesh::Vec3d& p) override {
        // Each coordinate on its own: std::max drops a NaN that is not first.
        const bool finite = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
        const bool within = finite && std::abs(p[0]) <= kMaxCoordinate && std::abs(p[1]) <= kMaxCoordinate &&
                            std::abs(p[2]) <= kMaxCoordinate;
        if (!error && !within) {
            error = "vertex " + std::to_string(out_.mesh.positions.size() + 1) +
                    (finite ? " has a coordinate beyond the limit of 1e18" : " has a non-finite coordinate");
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
            if (out_.mesh.triangles.size() >= max_triangles_) throw FaceLimit();
            out_.mesh.triangles.emplace_back(corners[0].idx(), corners[i].idx(),
                                             corners[i + 1].idx());
        }
        return FaceHandle(int(out_.mesh.triangles.size()) - 1);
    }

    size_t short_faces() const { return short_faces_; }

    // Thrown through OpenMesh's reader when the mesh passes the face limit.
    struct FaceLimit {};

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
    size_t max_triangles_;
    size_t polygons_ = 0;
    size_t short_faces_ = 0;
};

// OpenMesh reports through global streams; inkline reports through its own errors instead.
void silence_openmesh_streams() {
    omlog().disable();
    omout().disable();
    omerr().disable();
}

// Checks shared by every format once the mesh is read.
void finish(const std::string& name, size_t short_faces, LoadedMesh& r_out) {
    if (r_out.mesh.triangles.empty()) throw InputError(name + ": mesh has no faces");
    if (short_faces > 0) {
        r_out.warnings.push_back(name + ": skipped " + std::to_string(short_faces) + " face(s) with fewer than 3 vertices");
    }
}

// Opens a file for reading after the checks every input gets; its size in r_size.
std::unique_ptr<FILE, int (*)(FILE*)> open_input(const std::filesystem::path& path, uintmax_t& r_size) {
    const std::string name = path.string();
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) throw InputError(name + ": file not found");
    if (ec) throw InputError(name + ": cannot read: " + ec.message());
    if (status.type() == std::filesystem::file_type::directory) throw InputError(name + ": is a folder, not a mesh file");
    if (status.type() != std::filesystem::file_type::regular) {
        throw InputError(name + ": not a regular file (a device, FIFO or socket), not a mesh file");
    }
    // Opened before anything else, so that an unreadable file says why.
    std::unique_ptr<FILE, int (*)(FILE*)> file(std::fopen(path.c_str(), "rb"), std::fclose);
    if (!file) throw InputError(name + ": cannot read: " + std::strerror(errno));
    r_size = std::filesystem::file_size(path, ec);
    if (ec) throw InputError(name + ": cannot read: " + ec.message());
    if (r_size == 0) throw InputError(name + ": file is empty");
    return file;
}

std::string read_all(const std::filesystem::path& path, FILE* file, uintmax_t file_size) {
    const std::string name = path.string();
    std::string bytes;
    try {
        bytes.resize(size_t(file_size));
    } catch (const std::bad_alloc&) {
        throw InputError(name + ": too large to load into memory");
    }
    if (std::fread(bytes.data(), 1, bytes.size(), file) != bytes.size()) {
        throw InputError(name + ": cannot read: " + (std::ferror(file) ? std::strerror(errno) : "the file shrank while being read"));
    }
    return bytes;
}

}  // namespace

std::string read_input_file(const std::filesystem::path& path) {
    uintmax_t size = 0;
    const auto file = open_input(path, size);
    return read_all(path, file.get(), size);
}

LoadedMesh load_mesh(const std::filesystem::path& path, const MeshLimits& limits) {
    const std::string name = path.string();
    uintmax_t file_size = 0;
    const auto file = open_input(path, file_size);

    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    if (extension != ".obj" && extension != ".off" && extension != ".ply" && extension != ".stl") {
        throw InputError(name + ": cannot read '" + extension + "' files (supported: .obj .off .ply .stl)");
    }
    const size_t max_faces = limits.max_faces;
    if (extension == ".off") {
        internal::OffContents off = internal::read_off(path, file_size, max_faces);
        LoadedMesh out{std::move(off.mesh), {}};
        finish(name, off.short_faces, out);
        return out;
    }

    std::string bytes = read_all(path, file.get(), file_size);
    if (extension == ".ply") {
        internal::check_ply(path, file_size);
        internal::PlyContents ply = internal::read_ply(path, bytes, max_faces);
        LoadedMesh out{std::move(ply.mesh), {}};
        finish(name, ply.short_faces, out);
        return out;
    }
    if (extension == ".stl") {
        internal::StlContents stl = internal::read_stl(path, bytes, max_faces);
        LoadedMesh out{std::move(stl.mesh), {}};
        finish(name, 0, out);
        if (stl.collapsed > 0) {
            out.warnings.push_back(name + ": skipped " + std::to_string(stl.collapsed) +
                                   " triangle(s) with two corners at the same position");
        }
        return out;
    }

    // OBJ. Plain text, the usual form of big meshes, is read in one pass; anything else goes
    // through check_obj and OpenMesh below, which also report what is wrong with it.
    if (std::optional<internal::ObjContents> obj = internal::read_plain_obj(bytes, max_faces)) {
        if (obj->over_limit) internal::throw_face_limit(name, max_faces);
        LoadedMesh out;
        internal::obj_objects(*obj, out.object_names, out.face_objects);
        out.mesh = std::move(obj->mesh);
        finish(name, obj->short_faces, out);
        return out;
    }
    // OpenMesh would read a byte order mark as part of the first line's keyword and skip it.
    const bool bom = std::string_view(bytes).starts_with(internal::kUtf8Bom);
    if (bom) {
        bytes.erase(0, internal::kUtf8Bom.size());
    } else {
        bytes = std::string();
    }
    const size_t short_faces = internal::check_obj(path);

    silence_openmesh_streams();
    LoadedMesh out;
    SoupImporter importer(out, file_size, max_faces);
    OpenMesh::IO::Options options;
    bool ok = false;
    try {
        if (bom) {
            // Filled through str(): built from the moved string, the stream lost the file's first
            // line to OpenMesh in the sanitizer build.
            std::istringstream text;
            text.str(bytes);
            ok = OpenMesh::IO::IOManager().read(text, "obj", importer, options);
        } else {
            ok = OpenMesh::IO::IOManager().read(name, importer, options);
        }
    } catch (const SoupImporter::FaceLimit&) {
        internal::throw_face_limit(name, max_faces);
    } catch (const std::bad_alloc&) {
        throw InputError(name + ": too large to load into memory");
    } catch (const InputError& e) {
        throw InputError(name + ": " + e.what());
    } catch (const std::exception& e) {
        throw InputError(name + ": cannot read: " + e.what());
    }
    if (importer.error) throw InputError(name + ": " + *importer.error);
    if (!ok) throw InputError(name + ": cannot read as OBJ (the file may be damaged)");
    finish(name, std::max(short_faces, importer.short_faces()), out);
    return out;
}

Mesh mesh_from_arrays(std::span<const double> coordinates, std::span<const int64_t> indices,
                      const std::string& coordinates_name, const std::string& indices_name, const MeshLimits& limits) {
    if (coordinates.size() % 3 != 0) throw InputError(coordinates_name + ": expected rows of 3 coordinates (x, y, z)");
    if (indices.size() % 3 != 0) throw InputError(indices_name + ": expected rows of 3 vertex indices (triangles)");
    if (coordinates.empty()) throw InputError(coordinates_name + ": no vertices");
    if (indices.empty()) throw InputError(indices_name + ": no triangles");
    const size_t vertices = coordinates.size() / 3, triangles = indices.size() / 3;
    if (vertices > std::numeric_limits<uint32_t>::max()) {
        throw InputError(coordinates_name + ": " + std::to_string(vertices) + " vertices exceed the limit of 2^32 - 1");
    }
    if (triangles > limits.max_faces) {
        throw InputError(indices_name + ": " + std::to_string(triangles) + " triangles exceed the limit of " +
                         std::to_string(limits.max_faces));
    }
    Mesh mesh;
    mesh.positions.resize(vertices);
    for (size_t v = 0; v < vertices; ++v) {
        for (int k = 0; k < 3; ++k) {
            const double c = coordinates[3 * v + size_t(k)];
            if (!std::isfinite(c) || std::abs(c) > kMaxCoordinate) {
                throw InputError(coordinates_name + "[" + std::to_string(v) + "]: coordinate " + std::to_string(c) +
                                 (std::isfinite(c) ? " is beyond 1e18" : " is not finite"));
            }
            mesh.positions[v][k] = float(c);
        }
    }
    mesh.triangles.resize(triangles);
    for (size_t t = 0; t < triangles; ++t) {
        for (int k = 0; k < 3; ++k) {
            const int64_t i = indices[3 * t + size_t(k)];
            if (i < 0 || uint64_t(i) >= vertices) {
                throw InputError(indices_name + "[" + std::to_string(t) + "]: vertex index " + std::to_string(i) +
                                 " out of range (" + std::to_string(vertices) + " vertices)");
            }
            mesh.triangles[t][k] = uint32_t(i);
        }
    }
    return mesh;
}

}  // namespace inkline::core
