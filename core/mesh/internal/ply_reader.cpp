// SPDX-License-Identifier: MIT
#include "core/mesh/internal/ply_reader.h"

#include "core/error.h"
#include "core/mesh/internal/mesh_checks.h"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

namespace inkline::core::internal {
namespace {

enum class Kind { kSigned, kUnsigned, kFloat };

struct Type {
    Kind kind = Kind::kFloat;
    int size = 4;  // bytes in binary files
};

std::optional<Type> type_named(const std::string& name) {
    if (name == "char" || name == "int8") return Type{Kind::kSigned, 1};
    if (name == "uchar" || name == "uint8") return Type{Kind::kUnsigned, 1};
    if (name == "short" || name == "int16") return Type{Kind::kSigned, 2};
    if (name == "ushort" || name == "uint16") return Type{Kind::kUnsigned, 2};
    if (name == "int" || name == "int32") return Type{Kind::kSigned, 4};
    if (name == "uint" || name == "uint32") return Type{Kind::kUnsigned, 4};
    if (name == "float" || name == "float32") return Type{Kind::kFloat, 4};
    if (name == "double" || name == "float64") return Type{Kind::kFloat, 8};
    return std::nullopt;
}

// What a property is for in inkline's mesh.
enum class Role { kNone, kX, kY, kZ, kCorners };

struct Property {
    std::string name;
    Type type;         // of the value, or of a list's items
    bool list = false;
    Type count_type;   // a list's count
    Role role = Role::kNone;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> properties;
};

struct Header {
    std::vector<Element> elements;
    bool binary = false;
    bool big_endian = false;
    size_t data_begin = 0;   // byte offset of the first data byte
    size_t data_line = 0;    // line number of the first data line (ASCII)
    uint64_t vertices = 0;
};

class PlyReader {
  public:
    PlyReader(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles)
        : name_(path.string()), bytes_(bytes), max_triangles_(max_triangles) {}

    PlyContents read() {
        read_header();
        for (Element& element : header_.elements) check_roles(element);
        out_.mesh.positions.assign(size_t(header_.vertices), glm::vec3(0.0f));
        if (header_.binary) {
            read_binary();
        } else {
            read_ascii();
        }
        return std::move(out_);
    }

  private:
    [[noreturn]] void fail(const std::string& problem) const { throw InputError(name_ + ": " + problem); }
    [[noreturn]] void fail_at_line(const std::string& problem) const {
        throw InputError(name_ + ":" + std::to_string(line_) + ": " + problem);
    }
    std::string element_name(const Element& e, uint64_t i) const { return e.name + " " + std::to_string(i); }

    // check_ply has checked the structure already; this reads it.
    void read_header() {
        size_t at = 0, number = 0;
        while (at < bytes_.size()) {
            const size_t newline = bytes_.find('\n', at);
            if (newline == std::string::npos) fail("malformed PLY header: no end_header");
            std::string line = bytes_.substr(at, newline - at);
            at = newline + 1;
            ++number;
            if (number == 1) strip_bom(line);
            if (!line.empty() && line.back() == '\r') line.pop_back();
            std::istringstream words(line);
            std::string keyword;
            words >> keyword;
            if (keyword == "end_header") {
                header_.data_begin = at;
                header_.data_line = number + 1;
                return;
            }
            if (keyword == "format") {
                std::string format;
                words >> format;
                header_.binary = format != "ascii";
                header_.big_endian = format == "binary_big_endian";
            } else if (keyword == "element") {
                Element e;
                words >> e.name >> e.count;
                if (e.name == "vertex") {
                    if (has_vertex_element_) fail("more than one vertex element");
                    has_vertex_element_ = true;
                    header_.vertices = e.count;
                }
                if (e.name == "face") {
                    if (has_face_element_) fail("more than one face element");
                    has_face_element_ = true;
                }
                header_.elements.push_back(std::move(e));
            } else if (keyword == "property" && !header_.elements.empty()) {
                Property p;
                std::string type;
                words >> type;
                if (type == "list") {
                    std::string count_type, item_type;
                    words >> count_type >> item_type;
                    p.list = true;
                    p.count_type = type_named(count_type).value_or(Type{});
                    p.type = type_named(item_type).value_or(Type{});
                } else {
                    p.type = type_named(type).value_or(Type{});
                }
                words >> p.name;
                header_.elements.back().properties.push_back(std::move(p));
            }
        }
        fail("malformed PLY header: no end_header");
    }

    // Marks the properties the mesh is made of and refuses what cannot be read as meant.
    void check_roles(Element& element) {
        if (element.name == "vertex") {
            const char* axes[] = {"x", "y", "z"};
            for (int axis = 0; axis < 3; ++axis) {
                Property* found = nullptr;
                for (Property& p : element.properties) {
                    if (p.name != axes[axis]) continue;
                    if (found) fail("the vertex element declares property '" + p.name + "' twice");
                    found = &p;
                }
                if (!found) fail("the vertex element has no property '" + std::string(axes[axis]) + "'");
                if (found->list) fail("vertex property '" + found->name + "' is a list, not a number");
                found->role = Role(int(Role::kX) + axis);
            }
        } else if (element.name == "face") {
            Property* found = nullptr;
            for (Property& p : element.properties) {
                if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
                if (found) fail("the face element declares its vertex list twice");
                found = &p;
            }
            if (!found) {
                if (element.count > 0) fail("the face element has no 'vertex_indices' list");
                return;
            }
            if (!found->list) fail("face property '" + found->name + "' is not a list");
            if (found->type.kind == Kind::kFloat || found->count_type.kind == Kind::kFloat) {
                fail("face property '" + found->name + "' is a list of floating-point values; vertex indices must be "
                     "integers (e.g. 'property list uchar int vertex_indices')");
            }
            found->role = Role::kCorners;
        }
    }

    void store_coordinate(uint64_t vertex, Role role, double value) {
        if (!std::isfinite(value) || std::abs(value) > kMaxCoordinate) {
            const std::string problem = "vertex " + std::to_string(vertex) +
                                        (std::isfinite(value) ? " has a coordinate beyond the limit of 1e18"
                                                              : " has a non-finite coordinate");
            if (header_.binary) fail(problem);
            fail_at_line(problem);
        }
        out_.mesh.positions[size_t(vertex)][int(role) - int(Role::kX)] = float(value);
    }

    void add_face(uint64_t face) {
        for (uint64_t index : corners_) {
            if (index >= header_.vertices) {
                const std::string problem = "face " + std::to_string(face) + " references vertex " +
                                            std::to_string(index) + "; valid: 0.." +
                                            (header_.vertices ? std::to_string(header_.vertices - 1) : "(none)");
                if (header_.binary) fail(problem);
                fail_at_line(problem);
            }
        }
        if (corners_.size() < 3) {
            ++out_.short_faces;
            return;
        }
        for (size_t i = 1; i + 1 < corners_.size(); ++i) {
            if (out_.mesh.triangles.size() >= max_triangles_) throw_face_limit(name_, max_triangles_);
            out_.mesh.triangles.emplace_back(uint32_t(corners_[0]), uint32_t(corners_[i]), uint32_t(corners_[i + 1]));
        }
    }

    // ---- ASCII: one element per line ----

    // The next line with content; false at the end of the file.
    bool next_line(std::vector<std::string_view>& r_tokens) {
        while (at_ < bytes_.size()) {
            const size_t newline = bytes_.find('\n', at_);
            const size_t end = newline == std::string::npos ? bytes_.size() : newline;
            const std::string_view line(bytes_.data() + at_, end - at_);
            at_ = newline == std::string::npos ? bytes_.size() : newline + 1;
            ++line_;
            r_tokens.clear();
            size_t i = 0;
            while (i < line.size()) {
                while (i < line.size() && is_space(line[i])) ++i;
                const size_t begin = i;
                while (i < line.size() && !is_space(line[i])) ++i;
                if (i > begin) r_tokens.push_back(line.substr(begin, i - begin));
            }
            if (!r_tokens.empty()) return true;
        }
        return false;
    }
    static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

    // A token read as a value of `type`: integers must be whole and in range.
    double ascii_value(std::string_view token, const Type& type, const std::string& what) const {
        const std::string text(token);
        char* end = nullptr;
        if (type.kind == Kind::kFloat) {
            const double value = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0') fail_at_line(what + ": '" + text + "' is not a number");
            // As for every format: stream readers take "0x1p3" as 0 and fail on the rest.
            if (std::isfinite(value) && !is_decimal_word(token)) {
                fail_at_line(what + ": '" + text + "' is not a decimal number (hex floats are not read)");
            }
            return value;
        }
        errno = 0;
        const long long value = std::strtoll(text.c_str(), &end, 10);
        if (end == text.c_str() || *end != '\0' || errno == ERANGE) {
            fail_at_line(what + ": '" + text + "' is not an integer");
        }
        const int bits = type.size * 8;
        const bool fits = type.kind == Kind::kSigned
                              ? value >= -(1ll << (bits - 1)) && value < (1ll << (bits - 1))
                              : value >= 0 && value < (1ll << bits);
        if (!fits) fail_at_line(what + ": '" + text + "' is out of range for its type");
        return double(value);
    }

    void read_ascii() {
        at_ = header_.data_begin;
        line_ = header_.data_line - 1;
        std::vector<std::string_view> tokens;
        for (const Element& element : header_.elements) {
            for (uint64_t i = 0; i < element.count; ++i) {
                if (!next_line(tokens)) {
                    fail("the file ends after " + std::to_string(i) + " of " + std::to_string(element.count) + " " +
                         element.name + " elements (truncated, or the header's count is wrong)");
                }
                const std::string what = element_name(element, i);
                size_t t = 0;
                auto take = [&]() -> std::string_view {
                    if (t >= tokens.size()) {
                        fail_at_line(what + " has too few values for its " + std::to_string(element.properties.size()) +
                                     " properties (elements stand one per line)");
                    }
                    return tokens[t++];
                };
                for (const Property& p : element.properties) {
                    if (!p.list) {
                        const double value = ascii_value(take(), p.type, what);
                        if (p.role != Role::kNone && p.role != Role::kCorners) store_coordinate(i, p.role, value);
                        continue;
                    }
                    const double count = ascii_value(take(), p.count_type, what);
                    if (count < 0 || count > double(tokens.size() - t)) {
                        fail_at_line(what + ": its list declares " + std::to_string(int64_t(count)) + " values; the line has " +
                                     std::to_string(tokens.size() - t));
                    }
                    if (p.role == Role::kCorners) corners_.clear();
                    for (size_t k = 0; k < size_t(count); ++k) {
                        const double value = ascii_value(take(), p.type, what);
                        if (p.role == Role::kCorners) {
                            if (value < 0) fail_at_line(what + " references vertex " + std::to_string(int64_t(value)));
                            corners_.push_back(uint64_t(value));
                        }
                    }
                    if (p.role == Role::kCorners) add_face(i);
                }
                if (t != tokens.size()) {
                    fail_at_line(what + " has " + std::to_string(tokens.size()) + " values, more than its properties take (" +
                                 std::to_string(t) + "); elements stand one per line");
                }
            }
        }
        if (next_line(tokens)) {
            fail_at_line("data after the last element the header declares (is a count in the header too small?)");
        }
    }

    // ---- binary ----

    double binary_value(const Type& type, const std::string& what) {
        if (bytes_.size() - at_ < size_t(type.size)) {
            fail("the file ends inside " + what + " (truncated, or the header's counts are wrong)");
        }
        unsigned char raw[8];
        std::memcpy(raw, bytes_.data() + at_, size_t(type.size));
        at_ += size_t(type.size);
        const bool swap = header_.big_endian != (std::endian::native == std::endian::big);
        if (swap) {
            for (int k = 0; k < type.size / 2; ++k) std::swap(raw[k], raw[type.size - 1 - k]);
        }
        switch (type.kind) {
            case Kind::kFloat:
                if (type.size == 4) {
                    float f;
                    std::memcpy(&f, raw, 4);
                    return f;
                } else {
                    double d;
                    std::memcpy(&d, raw, 8);
                    return d;
                }
            case Kind::kSigned:
                if (type.size == 1) return int8_t(raw[0]);
                if (type.size == 2) {
                    int16_t v;
                    std::memcpy(&v, raw, 2);
                    return v;
                } else {
                    int32_t v;
                    std::memcpy(&v, raw, 4);
                    return v;
                }
            case Kind::kUnsigned:
                if (type.size == 1) return raw[0];
                if (type.size == 2) {
                    uint16_t v;
                    std::memcpy(&v, raw, 2);
                    return v;
                } else {
                    uint32_t v;
                    std::memcpy(&v, raw, 4);
                    return v;
                }
        }
        return 0.0;
    }

    void read_binary() {
        at_ = header_.data_begin;
        for (const Element& element : header_.elements) {
            for (uint64_t i = 0; i < element.count; ++i) {
                const std::string what = element_name(element, i) + " of " + std::to_string(element.count);
                for (const Property& p : element.properties) {
                    if (!p.list) {
                        const double value = binary_value(p.type, what);
                        if (p.role != Role::kNone && p.role != Role::kCorners) store_coordinate(i, p.role, value);
                        continue;
                    }
                    const double count = binary_value(p.count_type, what);
                    const size_t left = bytes_.size() - at_;
                    if (count < 0 || count * p.type.size > double(left)) {
                        fail(what + ": its list declares " + std::to_string(int64_t(count)) + " values; " +
                             std::to_string(left) + " bytes are left in the file");
                    }
                    if (p.role == Role::kCorners) corners_.clear();
                    for (size_t k = 0; k < size_t(count); ++k) {
                        const double value = binary_value(p.type, what);
                        if (p.role == Role::kCorners) {
                            if (value < 0) fail(what + " references vertex " + std::to_string(int64_t(value)));
                            corners_.push_back(uint64_t(value));
                        }
                    }
                    if (p.role == Role::kCorners) add_face(i);
                }
            }
        }
        if (at_ != bytes_.size()) {
            fail(std::to_string(bytes_.size() - at_) +
                 " bytes after the last element the header declares (is a count in the header too small?)");
        }
    }

    std::string name_;
    const std::string& bytes_;
    size_t max_triangles_;
    Header header_;
    bool has_vertex_element_ = false, has_face_element_ = false;
    PlyContents out_;
    std::vector<uint64_t> corners_;
    size_t at_ = 0;    // the next byte to read
    size_t line_ = 0;  // the line just read (ASCII)
};

}  // namespace

PlyContents read_ply(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles) {
    return PlyReader(path, bytes, max_triangles).read();
}

}  // namespace inkline::core::internal
