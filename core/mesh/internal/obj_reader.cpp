// SPDX-License-Identifier: MIT
#include "core/mesh/internal/obj_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

#include "core/internal/parallel.h"
#include "core/mesh/internal/mesh_checks.h"

namespace inkline::core::internal {
namespace {

// Face indices longer than this are left to the general reader (OpenMesh reads an int).
constexpr size_t kMaxIndexDigits = 9;

// Faces of more corners than this drop repeated corners by sorting instead of pairwise.
constexpr size_t kMaxPairwiseCorners = 64;

// Texts shorter than this are read on one thread; starting another costs more.
constexpr size_t kMinParallelBytes = size_t(1) << 20;

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// The next token of a line (blank-separated), advancing r_cursor past it; empty at the end.
std::string_view next_token(const char*& r_cursor, const char* end) {
    while (r_cursor < end && is_blank(*r_cursor)) ++r_cursor;
    const char* begin = r_cursor;
    while (r_cursor < end && !is_blank(*r_cursor)) ++r_cursor;
    return {begin, size_t(r_cursor - begin)};
}

// A plain decimal number: digits, '.', an exponent; a sign only first ('-') or after the 'e'.
// Everything strtod, from_chars and OpenMesh's stream extraction read identically.
bool is_plain_number(std::string_view token) {
    if (token.empty() || token[0] == '+') return false;
    for (char c : token) {
        if (!((c >= '0' && c <= '9') || c == '.' || c == 'e' || c == 'E' || c == '-' || c == '+')) return false;
    }
    return true;
}

// A coordinate: the float OpenMesh would store (correctly rounded from the text, as its stream
// extraction does), after the double check_obj would test against kMaxCoordinate.
bool parse_coordinate(std::string_view token, float& r_value) {
    if (!is_plain_number(token)) return false;
    const char* end = token.data() + token.size();
    auto [float_end, float_error] = std::from_chars(token.data(), end, r_value);
    if (float_error != std::errc() || float_end != end) return false;
    // The float is within a relative 2^-24 of the double: far below the limit, so is the double.
    if (std::abs(double(r_value)) < 0.5 * kMaxCoordinate) return true;
    double checked = 0.0;
    auto [checked_end, checked_error] = std::from_chars(token.data(), end, checked);
    return checked_error == std::errc() && checked_end == end && std::abs(checked) <= kMaxCoordinate;
}

// An optional '-' and 1..kMaxIndexDigits digits, the whole token.
bool parse_index(std::string_view token, int64_t& r_value) {
    const bool negative = !token.empty() && token[0] == '-';
    const std::string_view digits = token.substr(negative ? 1 : 0);
    if (digits.empty() || digits.size() > kMaxIndexDigits) return false;
    int64_t value = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + (c - '0');
    }
    r_value = negative ? -value : value;
    return true;
}

// A face corner "I", "I/J", "I//K" or "I/J/K": its vertex index I (J and K are not used).
bool parse_corner(std::string_view token, int64_t& r_vertex) {
    const size_t slash = token.find('/');
    if (!parse_index(token.substr(0, slash), r_vertex)) return false;
    if (slash == std::string_view::npos) return true;
    const std::string_view rest = token.substr(slash + 1);
    const size_t second = rest.find('/');
    int64_t unused = 0;
    if (second == std::string_view::npos) return parse_index(rest, unused);
    const std::string_view texcoord = rest.substr(0, second), normal = rest.substr(second + 1);
    return (texcoord.empty() || parse_index(texcoord, unused)) && parse_index(normal, unused);
}

// OpenMesh drops repeated corners of a face, keeping the first of each, in order. Pairwise for
// the usual few corners; by sorting for a polygon of very many, where pairwise is quadratic.
void drop_repeated_corners(std::vector<uint32_t>& r_corners, std::vector<std::pair<uint32_t, uint32_t>>& r_scratch) {
    if (r_corners.size() <= kMaxPairwiseCorners) {
        size_t kept = 0;
        for (size_t i = 0; i < r_corners.size(); ++i) {
            if (std::find(r_corners.begin(), r_corners.begin() + std::ptrdiff_t(kept), r_corners[i]) ==
                r_corners.begin() + std::ptrdiff_t(kept)) {
                r_corners[kept++] = r_corners[i];
            }
        }
        r_corners.resize(kept);
        return;
    }
    r_scratch.clear();
    for (uint32_t i = 0; i < r_corners.size(); ++i) r_scratch.emplace_back(r_corners[i], i);
    std::sort(r_scratch.begin(), r_scratch.end());  // by vertex, then by place: the first comes first
    std::vector<uint8_t> keep(r_corners.size(), 0);
    for (size_t k = 0; k < r_scratch.size(); ++k) {
        if (k == 0 || r_scratch[k].first != r_scratch[k - 1].first) keep[r_scratch[k].second] = 1;
    }
    size_t kept = 0;
    for (size_t i = 0; i < r_corners.size(); ++i) {
        if (keep[i]) r_corners[kept++] = r_corners[i];
    }
    r_corners.resize(kept);
}

// One piece of the text, whole lines, read on its own: vertices_before is the number of vertex
// lines before it, which negative face indices count back from.
struct Piece {
    std::string_view text;
    size_t vertex_lines = 0;  // "v" lines in it
    size_t face_lines = 0;    // "f" lines in it
    size_t vertices_before = 0;
    ObjContents contents;
    int64_t largest_index = -1;  // checked against the final vertex count: faces may come first
    bool plain = true;
};

// Counts the lines of a piece that start with "v" or "f" and a blank, for reserving and for
// the offsets of negative indices.
void count_lines(Piece& r_piece) {
    const char* p = r_piece.text.data();
    const char* const end = p + r_piece.text.size();
    while (p < end) {
        if (p + 1 < end && is_blank(p[1])) {
            r_piece.vertex_lines += p[0] == 'v';
            r_piece.face_lines += p[0] == 'f';
        }
        const void* newline = std::memchr(p, '\n', size_t(end - p));
        p = newline ? static_cast<const char*>(newline) + 1 : end;
    }
}

void read_piece(Piece& r_piece, bool has_carriage_returns, size_t max_triangles) {
    Mesh& mesh = r_piece.contents.mesh;
    mesh.positions.reserve(r_piece.vertex_lines);
    mesh.triangles.reserve(r_piece.face_lines);
    std::vector<uint32_t> corners;
    std::vector<std::pair<uint32_t, uint32_t>> scratch;
    const char* p = r_piece.text.data();
    const char* const text_end = p + r_piece.text.size();
    auto decline = [&r_piece] { r_piece.plain = false; };
    while (p < text_end) {
        const void* newline = std::memchr(p, '\n', size_t(text_end - p));
        const char* line_end = newline ? static_cast<const char*>(newline) : text_end;
        const char* cursor = p;
        p = newline ? line_end + 1 : text_end;
        // Trailing blanks and one '\r' go; a '\r' anywhere else is left to the general reader.
        while (line_end > cursor && (is_blank(line_end[-1]) || line_end[-1] == '\r')) --line_end;
        if (has_carriage_returns && std::find(cursor, line_end, '\r') != line_end) return decline();
        if (cursor == line_end || *cursor == '#') continue;
        if (is_blank(*cursor)) return decline();  // OpenMesh trims it, check_obj would not look at it

        const std::string_view keyword = next_token(cursor, line_end);
        if (keyword == "v") {
            glm::vec3 position;
            for (int axis = 0; axis < 3; ++axis) {
                if (!parse_coordinate(next_token(cursor, line_end), position[axis])) return decline();
            }
            mesh.positions.push_back(position);
        } else if (keyword == "vt") {
            // OpenMesh fails the whole read on a texture coordinate it cannot parse.
            float unused = 0.0f;
            for (int axis = 0; axis < 2; ++axis) {
                if (!parse_coordinate(next_token(cursor, line_end), unused)) return decline();
            }
        } else if (keyword == "f") {
            // A comment may end a face line.
            const char* const hash = std::find(cursor, line_end, '#');
            if (hash != line_end) line_end = hash;
            corners.clear();
            size_t count = 0;
            for (std::string_view token = next_token(cursor, line_end); !token.empty();
                 token = next_token(cursor, line_end)) {
                int64_t index = 0;
                if (!parse_corner(token, index)) return decline();
                // OBJ counts from 1; a negative index counts back from the last vertex so far.
                if (index < 0) index += int64_t(r_piece.vertices_before + mesh.positions.size()) + 1;
                if (index <= 0) return decline();
                r_piece.largest_index = std::max(r_piece.largest_index, index - 1);
                corners.push_back(uint32_t(index - 1));
                ++count;
            }
            if (count == 0) return decline();
            drop_repeated_corners(corners, scratch);
            r_piece.contents.short_faces += corners.size() < 3;
            for (size_t i = 1; i + 1 < corners.size(); ++i) {
                if (mesh.triangles.size() >= max_triangles) {
                    r_piece.contents.over_limit = true;
                    return;
                }
                mesh.triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
            }
        } else if (keyword == "o" || keyword == "g") {
            r_piece.contents.groups.push_back({mesh.triangles.size(), keyword == "o", std::string(next_token(cursor, line_end))});
        } else if (keyword[0] != '#' && !is_obj_statement(keyword)) {
            return decline();  // check_obj names it
        }
        // Every other statement ("vn", "o", "g", "s", "usemtl", "mtllib", "l", ...) carries
        // nothing OpenMesh's reader passes on to inkline's mesh.
    }
}

}  // namespace

std::optional<ObjContents> read_plain_obj(std::string_view text, size_t max_triangles) {
    if (text.starts_with(kUtf8Bom)) text.remove_prefix(kUtf8Bom.size());
    // Bytes OpenMesh's streams treat as blanks but this reader does not, and NUL: general reader.
    for (char c : {'\v', '\f', '\0'}) {
        if (std::memchr(text.data(), c, text.size())) return std::nullopt;
    }
    const bool has_carriage_returns = std::memchr(text.data(), '\r', text.size()) != nullptr;

    // Pieces of whole lines, one per thread, read in parallel and joined in order.
    const size_t pieces_wanted =
        text.size() < kMinParallelBytes ? 1 : hardware_threads();
    std::vector<Piece> pieces;
    for (size_t begin = 0, k = 0; begin < text.size(); ++k) {
        size_t end = std::max(begin, text.size() * (k + 1) / pieces_wanted);
        end = end >= text.size() ? text.size() : text.find('\n', end);
        end = end == std::string_view::npos ? text.size() : std::min(text.size(), end + 1);
        Piece piece;
        piece.text = text.substr(begin, end - begin);
        pieces.push_back(std::move(piece));
        begin = end;
    }
    parallel_for(pieces.size(), 2, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) count_lines(pieces[i]);
    });
    for (size_t i = 1; i < pieces.size(); ++i) {
        pieces[i].vertices_before = pieces[i - 1].vertices_before + pieces[i - 1].vertex_lines;
    }
    parallel_for(pieces.size(), 2, [&](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) read_piece(pieces[i], has_carriage_returns, max_triangles);
    });

    ObjContents out;
    size_t vertices = 0, triangles = 0;
    int64_t largest_index = -1;
    for (const Piece& piece : pieces) {
        if (!piece.plain) return std::nullopt;
        if (piece.contents.over_limit) {
            // Every line before the limit was plain; those after were not all read.
            out.over_limit = true;
            return out;
        }
        vertices += piece.contents.mesh.positions.size();
        triangles += piece.contents.mesh.triangles.size();
        largest_index = std::max(largest_index, piece.largest_index);
        out.short_faces += piece.contents.short_faces;
    }
    if (largest_index >= int64_t(vertices)) return std::nullopt;
    if (triangles > max_triangles) {
        out.over_limit = true;
        return out;
    }
    if (pieces.size() == 1) {
        out.mesh = std::move(pieces[0].contents.mesh);
        out.groups = std::move(pieces[0].contents.groups);
        return out;
    }
    out.mesh.positions.reserve(vertices);
    out.mesh.triangles.reserve(triangles);
    for (Piece& piece : pieces) {
        for (ObjGroupStart& g : piece.contents.groups) {
            g.first_triangle += out.mesh.triangles.size();
            out.groups.push_back(std::move(g));
        }
        const Mesh& part = piece.contents.mesh;
        out.mesh.positions.insert(out.mesh.positions.end(), part.positions.begin(), part.positions.end());
        out.mesh.triangles.insert(out.mesh.triangles.end(), part.triangles.begin(), part.triangles.end());
        piece.contents.mesh = {};
    }
    return out;
}

void obj_objects(const ObjContents& contents, std::vector<std::string>& r_names, std::vector<uint32_t>& r_face_objects) {
    r_names.clear();
    r_face_objects.clear();
    const bool by_object = std::any_of(contents.groups.begin(), contents.groups.end(), [](const ObjGroupStart& g) { return g.is_object; });
    std::vector<const ObjGroupStart*> starts;
    for (const ObjGroupStart& g : contents.groups) {
        if (g.is_object == by_object) starts.push_back(&g);
    }
    const size_t faces = contents.mesh.triangles.size();
    std::vector<std::string> names;
    std::vector<uint32_t> face_objects(faces, 0);
    const auto id_of = [&](const std::string& name) {
        const auto it = std::find(names.begin(), names.end(), name);
        if (it != names.end()) return uint32_t(it - names.begin());
        names.push_back(name);
        return uint32_t(names.size() - 1);
    };
    size_t next = 0;
    uint32_t current = 0;
    bool named = false;
    for (size_t f = 0; f < faces; ++f) {
        while (next < starts.size() && starts[next]->first_triangle <= f) {
            current = id_of(starts[next]->name.empty() ? std::string("default") : starts[next]->name);
            named = true;
            ++next;
        }
        if (!named) {
            current = id_of("default");
            named = true;
        }
        face_objects[f] = current;
    }
    if (names.size() < 2) return;
    r_names = std::move(names);
    r_face_objects = std::move(face_objects);
}

}  // namespace inkline::core::internal
