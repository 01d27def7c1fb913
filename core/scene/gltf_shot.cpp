// SPDX-License-Identifier: MIT
#include "core/scene/gltf_shot.h"

#include "core/error.h"
#include "core/internal/key_table.h"
#include "core/mesh/mesh_io.h"
#include "core/scene/scene.h"

#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/gtx/quaternion.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <numeric>

namespace inkline::core {
namespace {

using Bytes = std::vector<unsigned char>;

// Vertices of one object closer than this fraction of its bounding box's diagonal, with the
// same skin weights and morph offsets, are one vertex (docs/gltf.md, "Welding").
constexpr double kWeldFraction = 1e-6;

// A camera's eye stays within this in every coordinate, as a scene file's must (docs/scene.md).
constexpr double kMaxEyeCoordinate = 1e19;

// The narrowest vertical field of view drawn, degrees (as in a scene file).
constexpr double kMinFovDeg = 1e-3;

// The most influences a vertex may have (JOINTS_n/WEIGHTS_n sets times four).
constexpr size_t kMaxInfluenceSets = 16;

[[noreturn]] void fail(const std::string& file, const std::string& where, const std::string& what) {
    throw InputError(file + ": " + where + ": " + what);
}

std::string at(const char* array, size_t index) { return std::string(array) + "[" + std::to_string(index) + "]"; }

// ---------------------------------------------------------------------------------------------
// Accessors: every read is checked against the buffer it reads from.

size_t component_size(int type) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
        default: return 0;
    }
}

size_t component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR: return 1;
        case TINYGLTF_TYPE_VEC2: return 2;
        case TINYGLTF_TYPE_VEC3: return 3;
        case TINYGLTF_TYPE_VEC4: return 4;
        case TINYGLTF_TYPE_MAT2: return 4;
        case TINYGLTF_TYPE_MAT3: return 9;
        case TINYGLTF_TYPE_MAT4: return 16;
        default: return 0;
    }
}

// One component as a double: floats as they are, integers normalised (glTF 2.0, 3.11) or not.
double read_component(const unsigned char* p, int type, bool normalized) {
    switch (type) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT: {
            float f;
            std::memcpy(&f, p, 4);
            return f;
        }
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const auto v = int8_t(p[0]);
            return normalized ? std::max(double(v) / 127.0, -1.0) : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? double(p[0]) / 255.0 : double(p[0]);
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            int16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? std::max(double(v) / 32767.0, -1.0) : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return normalized ? double(v) / 65535.0 : double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
            uint32_t v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        case TINYGLTF_COMPONENT_TYPE_INT: {
            int32_t v;
            std::memcpy(&v, p, 4);
            return double(v);
        }
        default: return 0.0;
    }
}

class Reader {
  public:
    Reader(const tinygltf::Model& model, std::string file) : model_(model), file_(std::move(file)) {}

    const std::string& file() const { return file_; }

    // Accessor `index` as count x components doubles, sparse substitution applied. `what` names
    // the user in messages; `types` lists the accepted glTF types, `components` the accepted
    // component types (empty: any).
    std::vector<double> read(int index, const std::string& what, std::initializer_list<int> types,
                             std::initializer_list<int> components = {}) const {
        if (index < 0 || size_t(index) >= model_.accessors.size()) {
            fail(file_, what, "accessor " + std::to_string(index) + " does not exist");
        }
        const tinygltf::Accessor& a = model_.accessors[size_t(index)];
        const std::string where = at("accessors", size_t(index));
        if (std::find(types.begin(), types.end(), a.type) == types.end()) fail(file_, where, "has the wrong type for " + what);
        if (components.size() > 0 && std::find(components.begin(), components.end(), a.componentType) == components.end()) {
            fail(file_, where, "has the wrong component type for " + what);
        }
        const size_t width = component_count(a.type), size = component_size(a.componentType);
        if (width == 0 || size == 0) fail(file_, where, "unknown type or component type");
        if (a.count > (size_t(1) << 31) / width) fail(file_, where, "count " + std::to_string(a.count) + " is too large");
        std::vector<double> out(a.count * width, 0.0);
        if (a.bufferView >= 0) {
            const View v = view(a.bufferView, where);
            const size_t element = width * size;
            const size_t stride = v.stride != 0 ? v.stride : element;
            if (a.count > 0) {
                const size_t last = a.byteOffset + (a.count - 1) * stride + element;
                if (a.byteOffset > v.length || last > v.length || last < a.byteOffset) {
                    fail(file_, where, "reads past the end of its bufferView");
                }
            }
            for (size_t i = 0; i < a.count; ++i) {
                const unsigned char* p = v.data + a.byteOffset + i * stride;
                for (size_t c = 0; c < width; ++c) out[i * width + c] = read_component(p + c * size, a.componentType, a.normalized);
            }
        }
        if (a.sparse.isSparse) apply_sparse(a, where, width, size, out);
        for (size_t i = 0; i < out.size(); ++i) {
            if (!std::isfinite(out[i])) {
                fail(file_, where,
                     "element " + std::to_string(i / width) + " (read as " + what + ") is NaN or infinite");
            }
        }
        return out;
    }

    // Indices (unsigned integer scalars).
    std::vector<uint32_t> read_indices(int index, const std::string& what) const {
        const std::vector<double> v = read(index, what, {TINYGLTF_TYPE_SCALAR},
                                           {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT});
        return std::vector<uint32_t>(v.begin(), v.end());
    }

    size_t count(int index) const {
        return index >= 0 && size_t(index) < model_.accessors.size() ? model_.accessors[size_t(index)].count : 0;
    }

  private:
    struct View {
        const unsigned char* data;
        size_t length, stride;
    };

    View view(int index, const std::string& where) const {
        if (index < 0 || size_t(index) >= model_.bufferViews.size()) fail(file_, where, "bufferView " + std::to_string(index) + " does not exist");
        const tinygltf::BufferView& v = model_.bufferViews[size_t(index)];
        const std::string vwhere = at("bufferViews", size_t(index));
        if (v.buffer < 0 || size_t(v.buffer) >= model_.buffers.size()) fail(file_, vwhere, "buffer " + std::to_string(v.buffer) + " does not exist");
        const Bytes& data = model_.buffers[size_t(v.buffer)].data;
        if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset) {
            fail(file_, vwhere, "lies outside its buffer (" + std::to_string(data.size()) + " bytes)");
        }
        return {data.data() + v.byteOffset, v.byteLength, v.byteStride};
    }

    void apply_sparse(const tinygltf::Accessor& a, const std::string& where, size_t width, size_t size,
                      std::vector<double>& r_out) const {
        const size_t n = size_t(std::max(a.sparse.count, 0));
        if (a.sparse.count < 0 || n > a.count) fail(file_, where, "sparse count exceeds the accessor's count");
        const int itype = a.sparse.indices.componentType;
        const size_t isize = component_size(itype);
        if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            fail(file_, where, "sparse indices must be unsigned integers");
        }
        const View iv = view(a.sparse.indices.bufferView, where + ".sparse.indices");
        const View vv = view(a.sparse.values.bufferView, where + ".sparse.values");
        const auto ioff = size_t(std::max(a.sparse.indices.byteOffset, 0));
        const auto voff = size_t(std::max(a.sparse.values.byteOffset, 0));
        if (ioff > iv.length || n * isize > iv.length - ioff) fail(file_, where, "sparse indices read past their bufferView");
        if (voff > vv.length || n * width * size > vv.length - voff) fail(file_, where, "sparse values read past their bufferView");
        for (size_t k = 0; k < n; ++k) {
            const auto i = size_t(read_component(iv.data + ioff + k * isize, itype, false));
            if (i >= a.count) fail(file_, where, "sparse index " + std::to_string(i) + " is out of range");
            for (size_t c = 0; c < width; ++c) {
                r_out[i * width + c] = read_component(vv.data + voff + (k * width + c) * size, a.componentType, a.normalized);
            }
        }
    }

    const tinygltf::Model& model_;
    std::string file_;
};

// ---------------------------------------------------------------------------------------------
// Animation.

struct Trs {
    glm::dvec3 t{0.0};
    glm::dquat r{1.0, 0.0, 0.0, 0.0};
    glm::dvec3 s{1.0};
};

enum class Path : uint8_t { kTranslation, kRotation, kScale, kWeights };
enum class Interpolation : uint8_t { kStep, kLinear, kCubic };

struct Channel {
    int node = 0;
    Path path = Path::kTranslation;
    Interpolation interpolation = Interpolation::kLinear;
    std::vector<double> times;   // increasing
    std::vector<double> values;  // per key: width values (cubic: in-tangent, value, out-tangent)
    size_t width = 3;
};

// The channel's value at a time, width values.
std::vector<double> sample(const Channel& c, double time) {
    const size_t n = c.times.size(), w = c.width;
    const size_t stride = c.interpolation == Interpolation::kCubic ? 3 * w : w;
    const size_t offset = c.interpolation == Interpolation::kCubic ? w : 0;
    auto value = [&](size_t key) {
        return std::vector<double>(c.values.begin() + long(key * stride + offset), c.values.begin() + long(key * stride + offset + w));
    };
    if (time <= c.times.front() || n == 1) return value(0);
    if (time >= c.times.back()) return value(n - 1);
    const size_t k = size_t(std::upper_bound(c.times.begin(), c.times.end(), time) - c.times.begin()) - 1;
    const double t0 = c.times[k], t1 = c.times[k + 1], dt = t1 - t0;
    const double u = dt > 0.0 ? (time - t0) / dt : 0.0;
    std::vector<double> out(w);
    if (c.interpolation == Interpolation::kStep) return value(k);
    if (c.interpolation == Interpolation::kCubic) {
        const double u2 = u * u, u3 = u2 * u;
        const double h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
        for (size_t i = 0; i < w; ++i) {
            const double p0 = c.values[k * stride + w + i], m0 = c.values[k * stride + 2 * w + i] * dt;
            const double p1 = c.values[(k + 1) * stride + w + i], m1 = c.values[(k + 1) * stride + i] * dt;
            out[i] = h00 * p0 + h10 * m0 + h01 * p1 + h11 * m1;
        }
        return out;
    }
    const std::vector<double> a = value(k), b = value(k + 1);
    if (c.path == Path::kRotation) {
        const glm::dquat qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
        const glm::dquat q = glm::slerp(glm::normalize(qa), glm::normalize(qb), u);
        return {q.x, q.y, q.z, q.w};
    }
    for (size_t i = 0; i < w; ++i) out[i] = a[i] + (b[i] - a[i]) * u;
    return out;
}

glm::dmat4 matrix_of(const Trs& trs) {
    return glm::translate(glm::dmat4(1.0), trs.t) * glm::mat4_cast(trs.r) * glm::scale(glm::dmat4(1.0), trs.s);
}

// ---------------------------------------------------------------------------------------------
// Geometry of one object before welding.

struct Influence {
    uint32_t joint;  // index into the skin's joints
    double weight;
};

struct ObjectGeometry {
    int node = 0;
    int skin = -1;
    std::vector<glm::dvec3> positions;               // per source vertex, object space
    std::vector<std::vector<glm::dvec3>> targets;    // per morph target, per source vertex
    std::vector<double> default_weights;             // mesh.weights or node.weights
    std::vector<std::vector<Influence>> influences;  // per source vertex (skinned)
    std::vector<glm::uvec3> triangles;               // source vertex indices
};

std::string lower_extension(const std::filesystem::path& path) {
    std::string e = path.extension().string();
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

// tinygltf's file access, kept to plain relative files next to the glTF file.
bool file_exists(const std::string& path, void*) {
    std::error_code ec;
    return std::filesystem::is_regular_file(path, ec);
}
std::string expand_path(const std::string& path, void*) { return path; }
bool read_whole_file(Bytes* out, std::string* err, const std::string& path, void*) {
    try {
        const std::string bytes = read_input_file(path);
        out->assign(bytes.begin(), bytes.end());
        return true;
    } catch (const InputError& e) {
        if (err) *err += e.what();
        return false;
    }
}
bool refuse_write(std::string* err, const std::string&, const Bytes&, void*) {
    if (err) *err += "writing is not allowed";
    return false;
}
// Images are never needed for lines.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's message up to its first line break, quoted as any value in a message.
std::string first_line(const std::string& text) { return quote_value(text.substr(0, text.find('\n')), 200); }

}  // namespace

struct GltfShot::Impl {
    std::string file;
    GltfOptions options;
    tinygltf::Model model;
    std::vector<int> parent;            // per node; -1 for a root
    std::vector<int> order;             // nodes of the scene, parents before children
    std::vector<Trs> rest_trs;          // per node
    std::vector<bool> has_matrix;       // per node: a fixed matrix instead of TRS
    std::vector<glm::dmat4> fixed;      // per node with has_matrix
    std::vector<Channel> channels;      // of the chosen animations
    std::vector<ObjectGeometry> geometry;
    std::vector<std::vector<glm::dmat4>> inverse_bind;  // per skin, per joint
    std::vector<uint32_t> weld_of;      // per object, per source vertex, concatenated: welded vertex
    std::vector<uint32_t> source_of;    // per welded vertex: one source vertex (concatenated)
    std::vector<size_t> source_base;    // per object: its first source vertex
    std::vector<GltfObject> objects;
    std::vector<uint32_t> face_objects;
    std::optional<GltfCamera> camera;
    std::vector<GltfCamera> cameras;  // every camera of the scene, in scene order
    Mesh rest;
    bool deforms = false;
    std::optional<std::pair<double, double>> time_range;
    std::vector<std::string> warnings;

    void load(const std::filesystem::path& path);
    void build_hierarchy(int scene);
    void read_animations();
    void read_objects();
    void read_skins();
    void orient_mirrored();
    void weld();
    void compact();
    void choose_camera();
    std::vector<glm::dmat4> world_at(double time, std::vector<std::vector<double>>* r_weights) const;
    void evaluate(double time, std::vector<glm::vec3>& r_positions) const;
};

void GltfShot::Impl::load(const std::filesystem::path& path) {
    const std::string bytes = read_input_file(path);
    tinygltf::TinyGLTF loader;
    loader.SetImageLoader(skip_image, nullptr);
    loader.SetFsCallbacks({file_exists, expand_path, read_whole_file, refuse_write, nullptr});
    std::string err, warn;
    const std::string base = path.parent_path().string();
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) fail(file, "file", "is larger than 4 GiB");
    bool ok = false;
    if (bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0) {
        ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                         unsigned(bytes.size()), base);
    } else {
        ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
    }
    if (!ok) {
        // tinygltf quotes the whole data URI it cannot decode; the buffer is what to name.
        if (err.find("Failed to decode 'uri'") != std::string::npos && err.find("in Buffer") != std::string::npos) {
            fail(file, "buffers", "a buffer's data URI is not valid base64");
        }
        throw InputError(
            file + ": cannot read as glTF 2.0: " + (err.empty() ? std::string("unknown error") : first_line(err)));
    }
    // tinygltf reads on past what it can skip (an animation channel without a target node, say),
    // telling it in err, a line each: up to three of them, in one warning.
    if (!err.empty()) {
        std::string told;
        size_t lines = 0;
        for (size_t at = 0; at < err.size();) {
            size_t end = err.find('\n', at);
            if (end == std::string::npos) end = err.size();
            std::string line = err.substr(at, end - at);
            at = end + 1;
            while (!line.empty() && (line.back() == '.' || line.back() == ' ' || line.back() == '\r')) line.pop_back();
            if (line.empty()) continue;
            if (lines++ < 3) told += (told.empty() ? "" : "; ") + quote_value(line, 160);
        }
        if (lines > 3) told += "; and " + std::to_string(lines - 3) + " more";
        if (!told.empty()) warnings.push_back(file + ": skipped in reading: " + told);
    }
    if (model.asset.version.rfind("2.", 0) != 0) {
        fail(file, "asset.version", "is '" + quote_value(model.asset.version) + "': only glTF 2.x is read");
    }
    for (const std::string& required : model.extensionsRequired) {
        if (required == "KHR_mesh_quantization" || required == "KHR_materials_unlit" ||
            required.rfind("KHR_texture", 0) == 0 || required.rfind("KHR_materials", 0) == 0) {
            continue;  // changes nothing that lines depend on, or only what the reader handles
        }
        fail(file, "extensionsRequired", "'" + quote_value(required) + "' is not supported");
    }
}

void GltfShot::Impl::build_hierarchy(int scene_index) {
    const size_t n = model.nodes.size();
    parent.assign(n, -1);
    for (size_t i = 0; i < n; ++i) {
        for (const int c : model.nodes[i].children) {
            if (c < 0 || size_t(c) >= n) fail(file, at("nodes", i), "child " + std::to_string(c) + " does not exist");
            if (parent[size_t(c)] != -1 || size_t(c) == i) {
                fail(file, at("nodes", size_t(c)), "has more than one parent (the node hierarchy must be a tree)");
            }
            parent[size_t(c)] = int(i);
        }
    }
    // A cycle leaves nodes that no root reaches; they are found while walking from the roots.
    int chosen = scene_index >= 0 ? scene_index : (model.defaultScene >= 0 ? model.defaultScene : 0);
    if (model.scenes.empty()) {
        if (scene_index > 0) fail(file, "scenes", "the file has no scenes");
        chosen = -1;
    } else if (size_t(chosen) >= model.scenes.size()) {
        fail(file, "scenes", "scene " + std::to_string(chosen) + " does not exist (the file has " +
                                 std::to_string(model.scenes.size()) + ")");
    }
    std::vector<int> roots;
    if (chosen >= 0) {
        roots = model.scenes[size_t(chosen)].nodes;
    } else {
        for (size_t i = 0; i < n; ++i) {
            if (parent[i] == -1) roots.push_back(int(i));
        }
    }
    std::vector<uint8_t> seen(n, 0);
    for (const int r : roots) {
        if (r < 0 || size_t(r) >= n) fail(file, "scenes", "node " + std::to_string(r) + " does not exist");
        if (parent[size_t(r)] != -1) fail(file, at("nodes", size_t(r)), "is a scene root and also a child");
        std::vector<int> stack{r};
        while (!stack.empty()) {
            const int v = stack.back();
            stack.pop_back();
            if (seen[size_t(v)]) fail(file, at("nodes", size_t(v)), "is reached twice (a cycle in the node hierarchy)");
            seen[size_t(v)] = 1;
            order.push_back(v);
            const auto& children = model.nodes[size_t(v)].children;
            for (auto it = children.rbegin(); it != children.rend(); ++it) stack.push_back(*it);
        }
    }
    for (size_t i = 0; i < n; ++i) {
        // A node in a cycle has a parent but no root above it.
        if (!seen[i] && parent[i] != -1) {
            int v = int(i);
            for (size_t steps = 0; steps <= n && v != -1; ++steps) v = parent[size_t(v)];
            if (v != -1) fail(file, at("nodes", i), "is part of a cycle in the node hierarchy");
        }
    }
    rest_trs.assign(n, {});
    has_matrix.assign(n, false);
    fixed.assign(n, glm::dmat4(1.0));
    for (size_t i = 0; i < n; ++i) {
        const tinygltf::Node& node = model.nodes[i];
        const std::string where = at("nodes", i);
        auto finite = [&](const std::vector<double>& v, const char* key) {
            for (const double x : v) {
                if (!std::isfinite(x)) fail(file, where + "." + key, "is not finite");
            }
        };
        finite(node.translation, "translation");
        finite(node.rotation, "rotation");
        finite(node.scale, "scale");
        finite(node.matrix, "matrix");
        finite(node.weights, "weights");
        if (node.matrix.size() == 16) {
            has_matrix[i] = true;
            fixed[i] = glm::make_mat4(node.matrix.data());
        } else if (!node.matrix.empty()) {
            fail(file, where + ".matrix", "must have 16 values");
        }
        Trs& trs = rest_trs[i];
        if (node.translation.size() == 3) trs.t = glm::make_vec3(node.translation.data());
        if (node.scale.size() == 3) trs.s = glm::make_vec3(node.scale.data());
        if (node.rotation.size() == 4) {
            trs.r = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
            if (!(glm::length(trs.r) > 1e-12)) fail(file, where + ".rotation", "is not a rotation (zero length)");
            trs.r = glm::normalize(trs.r);
        }
    }
}

void GltfShot::Impl::read_animations() {
    const Reader reader(model, file);
    std::vector<size_t> chosen;
    if (options.animation.empty()) {
        for (size_t a = 0; a < model.animations.size(); ++a) chosen.push_back(a);
    } else {
        for (size_t a = 0; a < model.animations.size(); ++a) {
            if (model.animations[a].name == options.animation || std::to_string(a) == options.animation) chosen.push_back(a);
        }
        if (chosen.empty()) {
            std::string names;
            for (size_t a = 0; a < model.animations.size() && a < 8; ++a) {
                names += (a ? ", " : "") + (model.animations[a].name.empty() ? std::to_string(a) : "'" + quote_value(model.animations[a].name) + "'");
            }
            fail(file, "animations", "no animation named '" + quote_value(options.animation) + "' (the file has " +
                                         (names.empty() ? std::string("none") : names) + ")");
        }
        chosen.erase(chosen.begin() + 1, chosen.end());  // the first of that name
    }
    for (const size_t a : chosen) {
        const tinygltf::Animation& anim = model.animations[a];
        for (size_t c = 0; c < anim.channels.size(); ++c) {
            const tinygltf::AnimationChannel& ch = anim.channels[c];
            const std::string where = at("animations", a) + "." + at("channels", c);
            if (ch.target_node < 0) continue;  // no target: ignored, as the specification says
            if (size_t(ch.target_node) >= model.nodes.size()) fail(file, where, "targets node " + std::to_string(ch.target_node) + ", which does not exist");
            if (ch.sampler < 0 || size_t(ch.sampler) >= anim.samplers.size()) fail(file, where, "sampler " + std::to_string(ch.sampler) + " does not exist");
            const tinygltf::AnimationSampler& s = anim.samplers[size_t(ch.sampler)];
            const std::string swhere = at("animations", a) + "." + at("samplers", size_t(ch.sampler));
            Channel out;
            out.node = ch.target_node;
            if (ch.target_path == "translation") {
                out.path = Path::kTranslation;
            } else if (ch.target_path == "rotation") {
                out.path = Path::kRotation;
                out.width = 4;
            } else if (ch.target_path == "scale") {
                out.path = Path::kScale;
            } else if (ch.target_path == "weights") {
                out.path = Path::kWeights;
            } else {
                warnings.push_back(file + ": " + where + ": path '" + quote_value(ch.target_path) + "' ignored");
                continue;
            }
            if (s.interpolation == "STEP") {
                out.interpolation = Interpolation::kStep;
            } else if (s.interpolation == "CUBICSPLINE") {
                out.interpolation = Interpolation::kCubic;
            } else if (s.interpolation == "LINEAR" || s.interpolation.empty()) {
                out.interpolation = Interpolation::kLinear;
            } else {
                fail(file, swhere, "unknown interpolation '" + quote_value(s.interpolation) + "'");
            }
            out.times = reader.read(s.input, swhere + ".input", {TINYGLTF_TYPE_SCALAR}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
            if (out.times.empty()) fail(file, swhere + ".input", "has no keys");
            for (size_t k = 1; k < out.times.size(); ++k) {
                if (!(out.times[k] > out.times[k - 1])) fail(file, swhere + ".input", "times must increase (key " + std::to_string(k) + ")");
            }
            const int type = out.path == Path::kRotation ? TINYGLTF_TYPE_VEC4
                             : out.path == Path::kWeights ? TINYGLTF_TYPE_SCALAR
                                                          : TINYGLTF_TYPE_VEC3;
            out.values = reader.read(s.output, swhere + ".output", {type});
            const size_t keys = out.times.size() * (out.interpolation == Interpolation::kCubic ? 3 : 1);
            if (out.path == Path::kWeights) {
                if (out.values.size() % keys != 0 || out.values.empty()) fail(file, swhere + ".output", "has a value count that does not match its keys");
                out.width = out.values.size() / keys;
            } else if (out.values.size() != keys * out.width) {
                fail(file, swhere + ".output", "has " + std::to_string(out.values.size() / out.width) + " values for " +
                                                   std::to_string(keys) + " keys");
            }
            if (out.path == Path::kRotation) {
                for (size_t k = 0; k < out.values.size(); k += 4) {
                    const double len = glm::length(glm::dvec4(out.values[k], out.values[k + 1], out.values[k + 2], out.values[k + 3]));
                    const bool tangent = out.interpolation == Interpolation::kCubic && (k / 4) % 3 != 1;
                    if (!tangent && !(len > 1e-12)) fail(file, swhere + ".output", "rotation " + std::to_string(k / 4) + " has zero length");
                }
            }
            const double t0 = out.times.front(), t1 = out.times.back();
            time_range = time_range ? std::pair(std::min(time_range->first, t0), std::max(time_range->second, t1)) : std::pair(t0, t1);
            channels.push_back(std::move(out));
        }
    }
}

void GltfShot::Impl::read_skins() {
    const Reader reader(model, file);
    inverse_bind.resize(model.skins.size());
    for (size_t s = 0; s < model.skins.size(); ++s) {
        const tinygltf::Skin& skin = model.skins[s];
        const std::string where = at("skins", s);
        if (skin.joints.empty()) fail(file, where, "has no joints");
        for (const int j : skin.joints) {
            if (j < 0 || size_t(j) >= model.nodes.size()) fail(file, where, "joint node " + std::to_string(j) + " does not exist");
        }
        std::vector<glm::dmat4>& ibm = inverse_bind[s];
        ibm.assign(skin.joints.size(), glm::dmat4(1.0));
        if (skin.inverseBindMatrices >= 0) {
            const std::vector<double> m = reader.read(skin.inverseBindMatrices, where + ".inverseBindMatrices",
                                                      {TINYGLTF_TYPE_MAT4}, {TINYGLTF_COMPONENT_TYPE_FLOAT});
            if (m.size() < 16 * skin.joints.size()) fail(file, where + ".inverseBindMatrices", "has fewer matrices than joints");
            for (size_t j = 0; j < skin.joints.size(); ++j) ibm[j] = glm::make_mat4(m.data() + 16 * j);
        }
    }
}

void GltfShot::Impl::read_objects() {
    const Reader reader(model, file);
    size_t faces = 0;
    // Primitives without a surface, and triangle lists whose count is no multiple of 3: counted,
    // and told once with the first of each.
    size_t skipped = 0, ragged = 0;
    std::string first_skipped, first_ragged;
    for (const int n : order) {
        const tinygltf::Node& node = model.nodes[size_t(n)];
        if (node.mesh < 0) continue;
        if (size_t(node.mesh) >= model.meshes.size()) fail(file, at("nodes", size_t(n)), "mesh " + std::to_string(node.mesh) + " does not exist");
        if (node.skin >= 0 && size_t(node.skin) >= model.skins.size()) fail(file, at("nodes", size_t(n)), "skin " + std::to_string(node.skin) + " does not exist");
        const tinygltf::Mesh& mesh = model.meshes[size_t(node.mesh)];
        const std::string mwhere = at("meshes", size_t(node.mesh));
        ObjectGeometry g;
        g.node = n;
        g.skin = node.skin;
        size_t target_count = 0;
        bool first_primitive = true;
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& prim = mesh.primitives[p];
            const std::string where = mwhere + "." + at("primitives", p);
            const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                if (skipped++ == 0) first_skipped = where;
                continue;  // points and lines have no surface to draw lines of
            }
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) fail(file, where, "has no POSITION");
            const std::vector<double> positions = reader.read(pos->second, where + ".POSITION", {TINYGLTF_TYPE_VEC3});
            const size_t count = positions.size() / 3;
            const size_t base = g.positions.size();
            for (size_t v = 0; v < count; ++v) g.positions.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
            // Morph targets: every primitive of a mesh has the same number.
            if (first_primitive) {
                target_count = prim.targets.size();
                g.targets.resize(target_count);
            } else if (prim.targets.size() != target_count) {
                fail(file, where, "has " + std::to_string(prim.targets.size()) + " morph targets, the mesh's first primitive " +
                                      std::to_string(target_count));
            }
            first_primitive = false;
            for (size_t t = 0; t < target_count; ++t) {
                std::vector<glm::dvec3>& offsets = g.targets[t];
                offsets.resize(base + count, glm::dvec3(0.0));
                const auto it = prim.targets[t].find("POSITION");
                if (it == prim.targets[t].end()) continue;
                const std::vector<double> d = reader.read(it->second, where + "." + at("targets", t) + ".POSITION", {TINYGLTF_TYPE_VEC3});
                if (d.size() != positions.size()) fail(file, where + "." + at("targets", t), "has a different vertex count from POSITION");
                for (size_t v = 0; v < count; ++v) offsets[base + v] = {d[3 * v], d[3 * v + 1], d[3 * v + 2]};
            }
            // Skin influences, from every JOINTS_n/WEIGHTS_n pair.
            if (node.skin >= 0) {
                const size_t joints = model.skins[size_t(node.skin)].joints.size();
                g.influences.resize(base + count);
                for (size_t set = 0; set < kMaxInfluenceSets; ++set) {
                    const auto j = prim.attributes.find("JOINTS_" + std::to_string(set));
                    const auto w = prim.attributes.find("WEIGHTS_" + std::to_string(set));
                    if (j == prim.attributes.end() && w == prim.attributes.end()) break;
                    if (j == prim.attributes.end() || w == prim.attributes.end()) fail(file, where, "JOINTS_" + std::to_string(set) + " and WEIGHTS_" + std::to_string(set) + " must come together");
                    const std::vector<double> jv = reader.read(j->second, where + ".JOINTS_" + std::to_string(set), {TINYGLTF_TYPE_VEC4},
                                                               {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
                    const std::vector<double> wv = reader.read(w->second, where + ".WEIGHTS_" + std::to_string(set), {TINYGLTF_TYPE_VEC4});
                    if (jv.size() != 4 * count || wv.size() != 4 * count) fail(file, where, "JOINTS_" + std::to_string(set) + " or WEIGHTS_" + std::to_string(set) + " has a different vertex count from POSITION");
                    for (size_t v = 0; v < count; ++v) {
                        for (size_t k = 0; k < 4; ++k) {
                            const double weight = wv[4 * v + k];
                            if (weight == 0.0) continue;
                            const auto joint = uint32_t(jv[4 * v + k]);
                            if (joint >= joints) fail(file, where + ".JOINTS_" + std::to_string(set), "joint " + std::to_string(joint) + " of vertex " + std::to_string(v) + " is out of range (the skin has " + std::to_string(joints) + ")");
                            g.influences[base + v].push_back({joint, weight});
                        }
                    }
                }
            }
            // Triangles.
            std::vector<uint32_t> indices;
            if (prim.indices >= 0) {
                indices = reader.read_indices(prim.indices, where + ".indices");
                for (size_t i = 0; i < indices.size(); ++i) {
                    if (indices[i] >= count) fail(file, where + ".indices", "index " + std::to_string(indices[i]) + " is out of range (" + std::to_string(count) + " vertices)");
                }
            } else {
                indices.resize(count);
                std::iota(indices.begin(), indices.end(), 0u);
            }
            const auto add = [&](uint32_t a, uint32_t b, uint32_t c) {
                g.triangles.push_back({uint32_t(base) + a, uint32_t(base) + b, uint32_t(base) + c});
            };
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                if (indices.size() % 3 != 0 && ragged++ == 0) first_ragged = where;
                for (size_t i = 0; i + 2 < indices.size(); i += 3) add(indices[i], indices[i + 1], indices[i + 2]);
            } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                for (size_t i = 0; i + 2 < indices.size(); ++i) {
                    if (i % 2 == 0) add(indices[i], indices[i + 1], indices[i + 2]);
                    else add(indices[i + 1], indices[i], indices[i + 2]);
                }
            } else {
                for (size_t i = 1; i + 1 < indices.size(); ++i) add(indices[0], indices[i], indices[i + 1]);
            }
            if (g.triangles.size() + faces > options.max_faces) {
                throw InputError(file + ": more than " + std::to_string(options.max_faces) + " faces (raise the limit with --max-faces)");
            }
        }
        if (g.triangles.empty()) continue;
        g.default_weights = !node.weights.empty() ? node.weights : mesh.weights;
        if (!g.default_weights.empty() && g.default_weights.size() != target_count) {
            warnings.push_back(file + ": " + (!node.weights.empty() ? at("nodes", size_t(n)) : mwhere) + ": " +
                               std::to_string(g.default_weights.size()) + " morph weight(s) for " +
                               std::to_string(target_count) +
                               " targets; a missing weight is 0, an extra one is ignored");
        }
        g.default_weights.resize(target_count, 0.0);
        faces += g.triangles.size();
        GltfObject object;
        object.name = node.name.empty() ? "node " + std::to_string(n) : node.name;
        object.node = n;
        object.first_face = uint32_t(faces - g.triangles.size());
        object.faces = uint32_t(g.triangles.size());
        objects.push_back(object);
        geometry.push_back(std::move(g));
    }
    if (skipped > 0) {
        warnings.push_back(file + ": " + std::to_string(skipped) +
                           " primitive(s) of points or lines skipped, having no surface (the first: " + first_skipped +
                           ")");
    }
    if (ragged > 0) {
        warnings.push_back(
            file + ": " + std::to_string(ragged) +
            " triangle list(s) whose index count is no multiple of 3; their last indices are ignored (the first: " +
            first_ragged + ")");
    }
    if (objects.empty()) throw InputError(file + ": the scene has no triangles to draw");
}

// glTF 2.0 (meshes): the sign of the determinant of a node's world transform sets its
// triangles' winding, counterclockwise where it is positive and clockwise where a mirroring scale
// makes it negative. A mirrored object's triangles are turned to counterclockwise, so that every
// face of the frame's mesh faces out as the file means it: stippling and hatching draw on the
// faces turned to the camera, and the brush and the tone take the light from the faces' sides.
// The sign is read at the first frame; an object whose scale keys mirror it at some times and not
// at others keeps that winding, with a warning.
void GltfShot::Impl::orient_mirrored() {
    const double start = time_range ? time_range->first : 0.0;
    auto mirrored_at = [&](double time) {
        const std::vector<glm::dmat4> world = world_at(time, nullptr);
        std::vector<bool> mirrored(geometry.size());
        for (size_t o = 0; o < geometry.size(); ++o) {
            mirrored[o] = glm::determinant(glm::dmat3(world[size_t(geometry[o].node)])) < 0.0;
        }
        return mirrored;
    };
    const std::vector<bool> mirrored = mirrored_at(start);
    for (size_t o = 0; o < geometry.size(); ++o) {
        if (!mirrored[o]) continue;
        for (glm::uvec3& t : geometry[o].triangles) std::swap(t.y, t.z);
    }
    // Only a scale channel with a value of zero or below can change the sign: then every key
    // time of such a channel is looked at.
    std::vector<double> times;
    for (const Channel& c : channels) {
        if (c.path != Path::kScale) continue;
        if (std::none_of(c.values.begin(), c.values.end(), [](double v) { return !(v > 0.0); })) continue;
        times.insert(times.end(), c.times.begin(), c.times.end());
    }
    std::sort(times.begin(), times.end());
    times.erase(std::unique(times.begin(), times.end()), times.end());
    std::vector<bool> warned(geometry.size(), false);
    for (const double time : times) {
        const std::vector<bool> now = mirrored_at(time);
        for (size_t o = 0; o < geometry.size(); ++o) {
            if (now[o] == mirrored[o] || warned[o]) continue;
            warned[o] = true;
            warnings.push_back(
                file + ": " + at("nodes", size_t(objects[o].node)) + " ('" + quote_value(objects[o].name) +
                "') is mirrored at some times and not at others; its faces keep the winding of the first frame");
        }
    }
}

// Welds the source vertices of each object that share a position (within kWeldFraction of its
// size) and move alike (the same skin influences and morph offsets), so that a seam where an
// exporter split vertices is no boundary.
void GltfShot::Impl::weld() {
    size_t total = 0;
    source_base.clear();
    for (const ObjectGeometry& g : geometry) {
        source_base.push_back(total);
        total += g.positions.size();
    }
    weld_of.assign(total, 0);
    source_of.clear();
    for (size_t o = 0; o < geometry.size(); ++o) {
        const ObjectGeometry& g = geometry[o];
        Bounds b;
        for (const glm::dvec3& p : g.positions) b.add(p);
        const double cell = std::max(kWeldFraction * 2.0 * b.radius(), 1e-300);
        const auto key_of = [&](const glm::dvec3& p) {
            const glm::dvec3 q = glm::floor((p - b.min) / cell);
            return std::array<int64_t, 3>{int64_t(q.x), int64_t(q.y), int64_t(q.z)};
        };
        // A cell's key: its coordinates (0 .. 1 / kWeldFraction, and a neighbour's one beyond)
        // in 21 bits each; the top bit stays clear, so no key is KeyTable's empty one.
        static_assert(1.0 / kWeldFraction + 2.0 < double(1 << 21));
        const auto pack = [](int64_t x, int64_t y, int64_t z) {
            const auto part = [](int64_t v) { return uint64_t(v + 1) & 0x1fffffu; };
            return part(x) | (part(y) << 21) | (part(z) << 42);
        };
        // Each cell's kept vertices in the order kept: the first and last, the others linked.
        struct Kept {
            uint32_t first = UINT32_MAX, last = UINT32_MAX;
        };
        internal::KeyTable<Kept> cells(g.positions.size());
        std::vector<uint32_t> next_kept(g.positions.size(), UINT32_MAX);
        const auto same_motion = [&](uint32_t a, uint32_t c) {
            for (const auto& t : g.targets) {
                if (glm::length(t[a] - t[c]) > cell) return false;
            }
            if (!g.influences.empty()) {
                const auto& ia = g.influences[a];
                const auto& ic = g.influences[c];
                if (ia.size() != ic.size()) return false;
                for (size_t k = 0; k < ia.size(); ++k) {
                    if (ia[k].joint != ic[k].joint || std::abs(ia[k].weight - ic[k].weight) > 1e-6) return false;
                }
            }
            return true;
        };
        for (uint32_t v = 0; v < g.positions.size(); ++v) {
            const auto k = key_of(g.positions[v]);
            uint32_t found = UINT32_MAX;
            for (int64_t dx = -1; dx <= 1 && found == UINT32_MAX; ++dx) {
                for (int64_t dy = -1; dy <= 1 && found == UINT32_MAX; ++dy) {
                    for (int64_t dz = -1; dz <= 1 && found == UINT32_MAX; ++dz) {
                        const Kept* kept = cells.find(pack(k[0] + dx, k[1] + dy, k[2] + dz));
                        if (!kept) continue;
                        for (uint32_t u = kept->first; u != UINT32_MAX; u = next_kept[u]) {
                            if (glm::length(g.positions[u] - g.positions[v]) <= cell && same_motion(u, v)) {
                                found = u;
                                break;
                            }
                        }
                    }
                }
            }
            if (found != UINT32_MAX) {
                weld_of[source_base[o] + v] = weld_of[source_base[o] + found];
            } else {
                weld_of[source_base[o] + v] = uint32_t(source_of.size());
                source_of.push_back(uint32_t(source_base[o] + v));
                Kept& kept = cells[pack(k[0], k[1], k[2])];
                (kept.first == UINT32_MAX ? kept.first : next_kept[kept.last]) = v;
                kept.last = v;
            }
        }
    }
    rest.triangles.clear();
    face_objects.clear();
    for (size_t o = 0; o < geometry.size(); ++o) {
        for (const glm::uvec3& t : geometry[o].triangles) {
            rest.triangles.push_back({weld_of[source_base[o] + t.x], weld_of[source_base[o] + t.y], weld_of[source_base[o] + t.z]});
            face_objects.push_back(uint32_t(o));
        }
    }
}

// Keeps only what evaluation reads: per object, the data of its welded vertices (one source
// vertex each), in welded order, so source_of becomes the identity; the file's buffers go.
void GltfShot::Impl::compact() {
    std::vector<size_t> welded_base(geometry.size(), 0);
    size_t w = 0;
    for (size_t o = 0; o < geometry.size(); ++o) {
        ObjectGeometry& g = geometry[o];
        welded_base[o] = w;
        std::vector<uint32_t> kept;
        for (; w < source_of.size() && source_of[w] < source_base[o] + g.positions.size(); ++w) {
            kept.push_back(uint32_t(source_of[w] - source_base[o]));
        }
        const auto pick = [&](auto& values) {
            std::remove_reference_t<decltype(values)> out;
            out.reserve(kept.size());
            for (const uint32_t v : kept) out.push_back(std::move(values[v]));
            values = std::move(out);
        };
        pick(g.positions);
        for (auto& t : g.targets) pick(t);
        if (!g.influences.empty()) pick(g.influences);
        g.triangles = {};
    }
    source_base = std::move(welded_base);
    for (size_t i = 0; i < source_of.size(); ++i) source_of[i] = uint32_t(i);
    weld_of = {};
    model.buffers = {};
    model.bufferViews = {};
    model.accessors = {};
    model.images = {};
}

// World matrices of every node at a time; the morph weights of every node when asked.
std::vector<glm::dmat4> GltfShot::Impl::world_at(double time, std::vector<std::vector<double>>* r_weights) const {
    std::vector<Trs> trs = rest_trs;
    std::vector<bool> animated(model.nodes.size(), false);
    if (r_weights) {
        r_weights->assign(model.nodes.size(), {});
        for (size_t i = 0; i < model.nodes.size(); ++i) {
            const tinygltf::Node& node = model.nodes[i];
            if (!node.weights.empty()) (*r_weights)[i] = node.weights;
            else if (node.mesh >= 0 && size_t(node.mesh) < model.meshes.size()) (*r_weights)[i] = model.meshes[size_t(node.mesh)].weights;
        }
    }
    for (const Channel& c : channels) {
        const std::vector<double> v = sample(c, time);
        Trs& t = trs[size_t(c.node)];
        switch (c.path) {
            case Path::kTranslation: t.t = {v[0], v[1], v[2]}; break;
            case Path::kScale: t.s = {v[0], v[1], v[2]}; break;
            case Path::kRotation: {
                const glm::dquat q(v[3], v[0], v[1], v[2]);
                t.r = glm::length(q) > 1e-12 ? glm::normalize(q) : glm::dquat(1.0, 0.0, 0.0, 0.0);
                break;
            }
            case Path::kWeights:
                if (r_weights) (*r_weights)[size_t(c.node)] = v;
                break;
        }
        if (c.path != Path::kWeights) animated[size_t(c.node)] = true;
    }
    std::vector<glm::dmat4> world(model.nodes.size(), glm::dmat4(1.0));
    for (const int n : order) {
        const size_t i = size_t(n);
        // A node with a matrix is not animated (glTF 2.0, 5.25); an animated one uses its TRS.
        const glm::dmat4 local = has_matrix[i] && !animated[i] ? fixed[i] : matrix_of(trs[i]);
        world[i] = parent[i] >= 0 ? world[size_t(parent[i])] * local : local;
    }
    return world;
}

void GltfShot::Impl::evaluate(double time, std::vector<glm::vec3>& r_positions) const {
    std::vector<std::vector<double>> weights;
    const std::vector<glm::dmat4> world = world_at(time, &weights);
    r_positions.resize(source_of.size());
    std::vector<glm::dmat4> joint_matrices;
    size_t o = 0;
    size_t next_object_base = geometry.size() > 1 ? source_base[1] : SIZE_MAX;
    // Each welded vertex from its representative source vertex.
    int prepared_for = -1;
    for (size_t w = 0; w < source_of.size(); ++w) {
        const size_t s = source_of[w];
        while (s >= next_object_base) {
            ++o;
            next_object_base = o + 1 < geometry.size() ? source_base[o + 1] : SIZE_MAX;
        }
        const ObjectGeometry& g = geometry[o];
        const size_t v = s - source_base[o];
        glm::dvec3 p = g.positions[v];
        const std::vector<double>& wts = weights[size_t(g.node)];
        for (size_t t = 0; t < g.targets.size(); ++t) {
            const double wt = t < wts.size() ? wts[t] : 0.0;
            if (wt != 0.0) p += wt * g.targets[t][v];
        }
        if (g.skin >= 0 && !g.influences[v].empty()) {
            if (prepared_for != int(o)) {
                const tinygltf::Skin& skin = model.skins[size_t(g.skin)];
                joint_matrices.resize(skin.joints.size());
                for (size_t j = 0; j < skin.joints.size(); ++j) {
                    joint_matrices[j] = world[size_t(skin.joints[j])] * inverse_bind[size_t(g.skin)][j];
                }
                prepared_for = int(o);
            }
            glm::dmat4 m(0.0);
            for (const Influence& in : g.influences[v]) m += in.weight * joint_matrices[in.joint];
            p = glm::dvec3(m * glm::dvec4(p, 1.0));
        } else {
            p = glm::dvec3(world[size_t(g.node)] * glm::dvec4(p, 1.0));
        }
        r_positions[w] = glm::vec3(p);
        const glm::vec3& q = r_positions[w];
        if (!(std::abs(q.x) <= kMaxCoordinate && std::abs(q.y) <= kMaxCoordinate && std::abs(q.z) <= kMaxCoordinate)) {
            const float c = std::abs(q.x) <= kMaxCoordinate ? std::abs(q.y) <= kMaxCoordinate ? q.z : q.y : q.x;
            throw InputError(file + ": " + at("nodes", size_t(g.node)) + " ('" + quote_value(objects[o].name) +
                             "'): at time " + std::to_string(time) + " s a vertex coordinate (" + std::to_string(c) +
                             ") is beyond the limit of 1e18");
        }
    }
}

void GltfShot::Impl::choose_camera() {
    for (const int n : order) {
        const int c = model.nodes[size_t(n)].camera;
        if (c < 0) continue;
        if (size_t(c) >= model.cameras.size()) fail(file, at("nodes", size_t(n)), "camera " + std::to_string(c) + " does not exist");
        const tinygltf::Camera& cam = model.cameras[size_t(c)];
        GltfCamera entry;
        entry.name = !cam.name.empty()                      ? cam.name
                     : !model.nodes[size_t(n)].name.empty() ? model.nodes[size_t(n)].name
                                                            : at("cameras", size_t(c));
        entry.node = n;
        entry.index = size_t(c);
        entry.orthographic = cam.type == "orthographic";
        cameras.push_back(entry);
    }
    // By name first (the camera's or its node's), then by index in the file's cameras.
    int node = -1;
    for (const GltfCamera& entry : cameras) {
        const tinygltf::Camera& c = model.cameras[entry.index];
        if (options.camera.empty() || c.name == options.camera ||
            model.nodes[size_t(entry.node)].name == options.camera) {
            node = entry.node;
            break;
        }
    }
    for (size_t k = 0; k < cameras.size() && node < 0; ++k) {
        if (std::to_string(cameras[k].index) == options.camera) node = cameras[k].node;
    }
    if (node < 0) {
        if (options.camera.empty()) return;
        std::string names;
        for (size_t k = 0; k < cameras.size() && k < 8; ++k) {
            names += (k ? ", " : "") + std::string("'") + quote_value(cameras[k].name) + "' (" +
                     std::to_string(cameras[k].index) + ")";
        }
        if (cameras.size() > 8) names += ", ...";
        fail(file, "cameras",
             "no camera named '" + quote_value(options.camera) + "' in the scene (it has " +
                 (names.empty() ? std::string("none") : names) + ")");
    }
    const auto index = size_t(model.nodes[size_t(node)].camera);
    const tinygltf::Camera& c = model.cameras[index];
    const std::string where = at("cameras", index);
    GltfCamera out = *std::find_if(cameras.begin(), cameras.end(), [&](const GltfCamera& e) { return e.node == node; });
    if (c.type == "perspective") {
        const tinygltf::PerspectiveCamera& p = c.perspective;
        if (!(p.yfov > 0.0 && p.yfov < 3.14159)) fail(file, where + ".perspective.yfov", "must be above 0 and below pi");
        if (!(p.znear > 0.0) || !std::isfinite(p.znear)) fail(file, where + ".perspective.znear", "must be above 0");
        if (p.aspectRatio != 0.0 && !(p.aspectRatio > 0.0 && std::isfinite(p.aspectRatio))) fail(file, where + ".perspective.aspectRatio", "must be above 0");
        if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(p.zfar))) fail(file, where + ".perspective.zfar", "must be above znear");
        out.yfov = p.yfov;
        out.aspect = p.aspectRatio;
        out.znear = p.znear;
        if (p.zfar != 0.0) out.zfar = p.zfar;
    } else if (c.type == "orthographic") {
        const tinygltf::OrthographicCamera& p = c.orthographic;
        if (!(p.xmag != 0.0 && std::isfinite(p.xmag)) || !(p.ymag != 0.0 && std::isfinite(p.ymag))) {
            fail(file, where + ".orthographic", "xmag and ymag must be finite and not zero");
        }
        if (!(p.znear >= 0.0) || !(p.zfar > p.znear) || !std::isfinite(p.zfar)) fail(file, where + ".orthographic", "needs 0 <= znear < zfar");
        out.orthographic = true;
        out.xmag = std::abs(p.xmag);
        out.ymag = std::abs(p.ymag);
        out.aspect = out.xmag / out.ymag;
        out.znear = p.znear;
        out.zfar = p.zfar;
    } else {
        fail(file, where + ".type", "must be perspective or orthographic");
    }
    camera = out;
}

GltfShot::GltfShot(const std::filesystem::path& path, const GltfOptions& options) : impl_(std::make_unique<Impl>()) {
    Impl& m = *impl_;
    m.file = quote_value(path.string(), 160);
    m.options = options;
    if (!(options.fps > 0.0 && options.fps <= 1e6)) throw InputError("fps must be above 0 and at most 1e6");
    m.load(path);
    m.build_hierarchy(options.scene);
    m.read_skins();
    m.read_objects();
    m.read_animations();
    m.orient_mirrored();
    m.weld();
    m.compact();
    m.choose_camera();
    // Geometry moves when a channel drives a node above an object, a skin's joint, or weights.
    std::vector<bool> moved(m.model.nodes.size(), false);
    for (const Channel& c : m.channels) moved[size_t(c.node)] = true;
    std::vector<bool> below_moved(m.model.nodes.size(), false);
    for (const int n : m.order) {
        below_moved[size_t(n)] = moved[size_t(n)] || (m.parent[size_t(n)] >= 0 && below_moved[size_t(m.parent[size_t(n)])]);
    }
    for (const ObjectGeometry& g : m.geometry) {
        if (below_moved[size_t(g.node)]) m.deforms = true;
        if (g.skin >= 0) {
            for (const int j : m.model.skins[size_t(g.skin)].joints) m.deforms = m.deforms || below_moved[size_t(j)];
        }
    }
    const double start = m.time_range ? m.time_range->first : 0.0;
    m.evaluate(start, m.rest.positions);
}

GltfShot::~GltfShot() = default;

const Mesh& GltfShot::rest() const { return impl_->rest; }
bool GltfShot::deforms() const { return impl_->deforms; }
std::vector<std::string> GltfShot::warnings() const { return impl_->warnings; }
double GltfShot::fps() const { return impl_->options.fps; }
const std::vector<GltfObject>& GltfShot::objects() const { return impl_->objects; }
std::vector<uint32_t> GltfShot::face_objects() const { return impl_->face_objects; }

std::vector<MeshObject> GltfShot::mesh_objects() const {
    std::vector<MeshObject> out;
    for (const GltfObject& o : impl_->objects) out.push_back({o.name, o.node});
    return out;
}
const std::optional<GltfCamera>& GltfShot::camera() const { return impl_->camera; }
const std::vector<GltfCamera>& GltfShot::cameras() const { return impl_->cameras; }

std::vector<std::string> GltfShot::animations() const {
    std::vector<std::string> out;
    for (size_t a = 0; a < impl_->model.animations.size(); ++a) {
        const std::string& name = impl_->model.animations[a].name;
        out.push_back(name.empty() ? at("animations", a) : name);
    }
    return out;
}

void GltfShot::positions_at(int frame, std::vector<glm::vec3>& r_positions) const {
    impl_->evaluate(double(frame) / impl_->options.fps, r_positions);
}

void GltfShot::positions_at_time(double seconds, std::vector<glm::vec3>& r_positions) const {
    impl_->evaluate(seconds, r_positions);
}

std::optional<std::pair<int, int>> GltfShot::frame_range() const {
    if (!impl_->time_range) return std::nullopt;
    const double fps = impl_->options.fps;
    const double first = std::round(impl_->time_range->first * fps), last = std::round(impl_->time_range->second * fps);
    if (!(first >= -1e9 && last <= 1e9)) {
        throw InputError(impl_->file + ": animations: key times span more frames than can be drawn");
    }
    return std::pair(int(first), int(last));
}

GltfCameraView GltfShot::camera_view_at(int frame) const {
    const Impl& m = *impl_;
    INKLINE_CHECK(m.camera.has_value());
    const std::vector<glm::dmat4> world = m.world_at(double(frame) / m.options.fps, nullptr);
    const glm::dmat4& w = world[size_t(m.camera->node)];
    GltfCameraView view;
    view.eye = glm::dvec3(w[3]);
    const glm::dvec3 forward = -glm::dvec3(w[2]), up = glm::dvec3(w[1]);
    if (!(glm::length(forward) > 1e-12) || !(glm::length(up) > 1e-12) || !std::isfinite(glm::length(view.eye))) {
        throw InputError(m.file + ": " + at("nodes", size_t(m.camera->node)) + ": the camera's transform at frame " +
                         std::to_string(frame) + " is degenerate");
    }
    for (int i = 0; i < 3; ++i) {
        if (!(std::abs(view.eye[i]) <= kMaxEyeCoordinate)) {
            throw InputError(m.file + ": " + at("nodes", size_t(m.camera->node)) + ": the camera at frame " +
                             std::to_string(frame) + " is beyond the coordinate limit of 1e19");
        }
    }
    view.forward = glm::normalize(forward);
    view.up = glm::normalize(up);
    return view;
}

std::string GltfShot::file() const { return impl_->file; }

namespace {
std::string shot_file(const GltfShot& shot) { return shot.file(); }
}  // namespace

bool is_gltf_path(const std::filesystem::path& path) {
    const std::string e = lower_extension(path);
    return e == ".gltf" || e == ".glb";
}

void apply_gltf_camera(const GltfShot& shot, Scene& r_scene, int first, int last, bool image_given) {
    if (r_scene.given.camera) return;
    const std::optional<GltfCamera>& cam = shot.camera();
    if (!cam) {
        // No camera in the file: a bare mesh's view, still when the shot is animated, framing
        // where the shot's geometry goes over the frames drawn (read at up to kFitFrames of them,
        // evenly, the first and last included), so that nothing that moves leaves the image.
        Bounds bounds = bounds_of(shot.rest().positions);
        if (shot.frame_range() && shot.deforms() && last > first) {
            constexpr int kFitFrames = 32;
            const int steps = std::min(last - first, kFitFrames - 1);
            std::vector<glm::vec3> positions;
            for (int k = 0; k <= steps; ++k) {
                shot.positions_at(first + int((int64_t(last) - first) * k / steps), positions);
                const Bounds at = bounds_of(positions);
                if (at.valid) bounds.add(at.min), bounds.add(at.max);
            }
        }
        r_scene.camera = default_turntable_scene(r_scene.mesh.path, bounds).camera;
        if (shot.frame_range()) r_scene.camera.orbit.reset();
        return;
    }
    const double aspect = cam->aspect > 0.0 ? cam->aspect : double(r_scene.image.width) / r_scene.image.height;
    if (!image_given && cam->aspect > 0.0) {
        constexpr int kLongSide = 1024;
        r_scene.image = aspect >= 1.0 ? ImageSize{kLongSide, std::max(1, int(std::lround(kLongSide / aspect)))}
                                      : ImageSize{std::max(1, int(std::lround(kLongSide * aspect))), kLongSide};
    }
    const double image_aspect = double(r_scene.image.width) / r_scene.image.height;
    // Vertical half-extent at unit distance (perspective) or in world units (orthographic), then
    // refitted to the image: the camera's longer side maps to the image's longer side.
    double half_y = cam->orthographic ? cam->ymag : std::tan(cam->yfov / 2.0);
    const double half_long = aspect >= 1.0 ? half_y * aspect : half_y;
    half_y = image_aspect >= 1.0 ? half_long / image_aspect : half_long;

    const Bounds bounds = bounds_of(shot.rest().positions);
    const double size = std::max(bounds.radius(), 1e-30);
    r_scene.camera = {};
    for (int frame = first; frame <= last; ++frame) {
        const GltfCameraView view = shot.camera_view_at(frame);
        CameraPose pose;
        pose.up = view.up;
        pose.eye = view.eye;
        pose.target = view.eye + view.forward * size;
        if (cam->orthographic) {
            pose.ortho_height = 2.0 * half_y;
            if (!(*pose.ortho_height >= kMinOrthoHeight)) {
                throw InputError(shot_file(shot) + ": the orthographic camera's view height (" +
                                 std::to_string(*pose.ortho_height) +
                                 " at this image size) is below the limit of 1e-18");
            }
            r_scene.camera.per_frame[frame] = pose;
            continue;
        }
        pose.fov_y_deg = glm::degrees(2.0 * std::atan(half_y));
        if (!(pose.fov_y_deg >= kMinFovDeg)) {
            throw InputError(shot_file(shot) + ": the camera's field of view (" + std::to_string(pose.fov_y_deg) +
                             " degrees at this image size) is below the limit of 0.001 degrees");
        }
        r_scene.camera.per_frame[frame] = pose;
    }
    // Both kinds clip at the camera's planes, as Blender renders them; an orthographic znear of
    // 0 keeps everything in front of the camera.
    r_scene.camera.near = cam->znear;
    if (cam->zfar) r_scene.camera.far = *cam->zfar;
}

}  // namespace inkline::core
