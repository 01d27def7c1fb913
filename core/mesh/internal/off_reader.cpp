// SPDX-License-Identifier: MIT
#include "core/mesh/internal/off_reader.h"

#include "core/error.h"
#include "core/mesh/internal/mesh_checks.h"

#include <cstdlib>
#include <fstream>
#include <string>
#include <string_view>

namespace inkline::core::internal {
namespace {

// The most corners one polygon may have; far beyond any real file, small enough to allocate.
constexpr long kMaxCorners = 1'000'000;

class OffLines {
  public:
    explicit OffLines(const std::filesystem::path& path) : path_(path), in_(path, std::ios::binary) {}

    // The next line with content, comments ('#' to the end) removed; false at the end.
    bool next(std::string& r_line) {
        while (std::getline(in_, r_line)) {
            ++number_;
            if (number_ == 1) strip_bom(r_line);
            const size_t hash = r_line.find('#');
            if (hash != std::string::npos) r_line.resize(hash);
            if (r_line.find_first_not_of(" \t\r\f\v") != std::string::npos) return true;
        }
        return false;
    }

    std::string where() const { return path_.string() + ":" + std::to_string(number_); }
    [[noreturn]] void fail(const std::string& problem) const { throw InputError(where() + ": " + problem); }

  private:
    const std::filesystem::path& path_;
    std::ifstream in_;
    size_t number_ = 0;
};

bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// The next blank-separated word at r_cursor, advancing it; empty at the end of the line.
std::string_view next_word(const char*& r_cursor) {
    while (is_blank(*r_cursor)) ++r_cursor;
    const char* begin = r_cursor;
    while (*r_cursor != '\0' && !is_blank(*r_cursor)) ++r_cursor;
    return {begin, size_t(r_cursor - begin)};
}

// Reads an integer word at r_cursor, advancing it; false when the line has no more words. A
// word that is not a whole integer ("2.7", "2x", "2e5") is refused, not read as its digits.
bool scan_integer(const OffLines& lines, const char*& r_cursor, long long& r_value) {
    const std::string_view word = next_word(r_cursor);
    if (word.empty()) return false;
    const std::string_view digits = word.substr(word[0] == '-' ? 1 : 0);
    if (digits.empty() || digits.size() > 18 || digits.find_first_not_of("0123456789") != std::string_view::npos) {
        lines.fail("'" + std::string(word.substr(0, 40)) + "' is not an integer");
    }
    r_value = std::strtoll(std::string(word).c_str(), nullptr, 10);
    return true;
}

}  // namespace

OffContents read_off(const std::filesystem::path& path, uintmax_t file_size, size_t max_triangles) {
    OffLines lines(path);
    std::string line;
    if (!lines.next(line)) throw InputError(path.string() + ": not an OFF file (no header)");

    // Header: [ST][C][N]OFF, optionally followed by the counts on the same line.
    const size_t start = line.find_first_not_of(" \t\r");
    const size_t keyword_end = line.find_first_of(" \t\r", start);
    const std::string keyword = line.substr(start, keyword_end - start);
    if (keyword.size() < 3 || keyword.compare(keyword.size() - 3, 3, "OFF") != 0 ||
        keyword.find_first_not_of("STCNOF") != std::string::npos) {
        lines.fail("not an OFF file (expected OFF, COFF, NOFF, STOFF, ... first)");
    }
    const bool plain = keyword == "OFF";
    std::string counts_text = keyword_end == std::string::npos ? "" : line.substr(keyword_end);
    if (counts_text.find("BINARY") != std::string::npos) {
        lines.fail("binary OFF is not supported; convert the mesh to PLY, STL or OBJ");
    }
    if (counts_text.find_first_not_of(" \t\r") == std::string::npos) {
        if (!lines.next(counts_text)) lines.fail("the file ends before the element counts");
    }
    const char* cursor = counts_text.c_str();
    long long vertices = 0, faces = 0, edges = 0;
    if (!scan_integer(lines, cursor, vertices) || !scan_integer(lines, cursor, faces)) {
        lines.fail("expected 'vertices faces edges' counts");
    }
    scan_integer(lines, cursor, edges);  // optional and unused, but an integer where present
    if (const std::string_view extra = next_word(cursor); !extra.empty()) {
        lines.fail("unexpected '" + std::string(extra.substr(0, 40)) + "' after the 'vertices faces edges' counts");
    }
    if (vertices < 0 || faces < 0 || edges < 0) lines.fail("the element counts must not be negative");
    // Every vertex and face line takes at least two bytes.
    if (uintmax_t(vertices) > file_size / 2 || uintmax_t(faces) > file_size / 2) {
        lines.fail("declares " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                   " faces, more than the file's " + std::to_string(file_size) + " bytes can hold");
    }

    OffContents out;
    out.mesh.positions.reserve(size_t(vertices));
    for (long long v = 0; v < vertices; ++v) {
        if (!lines.next(line)) lines.fail("the file ends after " + std::to_string(v) + " of " + std::to_string(vertices) + " vertices");
        cursor = line.c_str();
        const std::string where = lines.where();
        const double x = scan_coordinate(where, cursor), y = scan_coordinate(where, cursor), z = scan_coordinate(where, cursor);
        // Colours, normals and texture coordinates follow only where the header says so.
        if (plain) {
            if (const std::string_view extra = next_word(cursor); !extra.empty()) {
                lines.fail("unexpected '" + std::string(extra.substr(0, 40)) +
                           "' after the vertex's three coordinates (plain OFF has no more; COFF, NOFF, STOFF "
                           "... declare colours, normals, texture coordinates)");
            }
        }
        out.mesh.positions.emplace_back(float(x), float(y), float(z));
    }
    std::vector<uint32_t> corners;
    for (long long f = 0; f < faces; ++f) {
        if (!lines.next(line)) lines.fail("the file ends after " + std::to_string(f) + " of " + std::to_string(faces) + " faces");
        cursor = line.c_str();
        long long count = 0;
        if (!scan_integer(lines, cursor, count) || count < 0 || count > kMaxCorners) lines.fail("expected a face's corner count");
        corners.clear();
        for (long long c = 0; c < count; ++c) {
            long long index = 0;
            if (!scan_integer(lines, cursor, index)) lines.fail("the face has fewer indices than its count " + std::to_string(count));
            if (index < 0 || index >= vertices) {
                lines.fail("face references vertex " + std::to_string(index) + "; valid: 0.." + std::to_string(vertices - 1));
            }
            corners.push_back(uint32_t(index));
        }
        if (count < 3) {
            ++out.short_faces;
            continue;
        }
        for (size_t i = 1; i + 1 < corners.size(); ++i) {
            if (out.mesh.triangles.size() >= max_triangles) throw_face_limit(path.string(), max_triangles);
            out.mesh.triangles.emplace_back(corners[0], corners[i], corners[i + 1]);
        }
    }
    if (lines.next(line)) {
        lines.fail("data after the " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
                   " faces the header declares (is a count in the header too small?)");
    }
    return out;
}

}  // namespace inkline::core::internal
