// SPDX-License-Identifier: MIT
#include "core/mesh/internal/stl_reader.h"

#include "core/error.h"
#include "core/mesh/internal/mesh_checks.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cctype>
#include <cstring>
#include <string_view>
#include <unordered_map>

namespace inkline::core::internal {
namespace {

constexpr size_t kBinaryHeaderBytes = 84;    // 80-byte comment and a 32-bit triangle count
constexpr size_t kBinaryTriangleBytes = 50;  // normal, three corners (12 floats) and 2 spare bytes

// Joins corners at the same position into one vertex, as every STL reader does.
class VertexIndex {
  public:
    explicit VertexIndex(Mesh& r_mesh) : mesh_(r_mesh) {}

    uint32_t index_of(const glm::vec3& p) {
        Key key{};
        for (int axis = 0; axis < 3; ++axis) {
            const float v = p[axis] == 0.0f ? 0.0f : p[axis];  // -0 and +0 are the same place
            key[size_t(axis)] = std::bit_cast<uint32_t>(v);
        }
        const auto [it, added] = index_.try_emplace(key, uint32_t(mesh_.positions.size()));
        if (added) mesh_.positions.push_back(p);
        return it->second;
    }

  private:
    using Key = std::array<uint32_t, 3>;
    struct Hash {
        size_t operator()(const Key& k) const {
            uint64_t h = 1469598103934665603ull;
            for (uint32_t v : k) h = (h ^ v) * 1099511628211ull;
            return size_t(h ^ (h >> 29));
        }
    };
    Mesh& mesh_;
    std::unordered_map<Key, uint32_t, Hash> index_;
};

class StlReader {
  public:
    StlReader(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles)
        : name_(path.string()), bytes_(bytes), max_triangles_(max_triangles), vertices_(out_.mesh) {}

    StlContents read() {
        const bool solid = starts_with_solid();
        if (bytes_.size() >= kBinaryHeaderBytes) {
            uint32_t count = 0;
            std::memcpy(&count, bytes_.data() + 80, 4);
            if constexpr (std::endian::native == std::endian::big) count = __builtin_bswap32(count);
            const uint64_t expected = kBinaryHeaderBytes + uint64_t(count) * kBinaryTriangleBytes;
            if (expected == bytes_.size()) {
                read_binary(count);
                return std::move(out_);
            }
            if (!solid && starts_with_upper_case_solid() && is_text()) fail_upper_case_solid();
            if (!solid || !is_text()) {
                fail("binary STL header declares " + std::to_string(count) + " triangles (" +
                     std::to_string(expected) + " bytes), but the file has " + std::to_string(bytes_.size()) +
                     " bytes (truncated or damaged)");
            }
        }
        if (!solid && starts_with_upper_case_solid() && is_text()) fail_upper_case_solid();
        if (!solid) fail("not an STL file (neither 'solid ...' text nor a binary STL of 84 + 50 x N bytes)");
        if (!is_text()) fail("ASCII STL with binary bytes in it (damaged?)");
        read_ascii();
        return std::move(out_);
    }

  private:
    [[noreturn]] void fail(const std::string& problem) const { throw InputError(name_ + ": " + problem); }
    [[noreturn]] void fail_at_line(const std::string& problem) const {
        throw InputError(name_ + ":" + std::to_string(line_) + ": " + problem);
    }

    // Where the text starts: after a UTF-8 byte order mark, if any.
    size_t text_begin() const { return std::string_view(bytes_).starts_with(kUtf8Bom) ? kUtf8Bom.size() : 0; }

    bool starts_with_solid() const {
        const size_t first = bytes_.find_first_not_of(" \t\r\n", text_begin());
        return first != std::string::npos && bytes_.compare(first, 5, "solid") == 0;
    }
    [[noreturn]] void fail_upper_case_solid() const {
        fail("ASCII STL must start with 'solid', found 'SOLID' (STL keywords are lower case)");
    }
    bool starts_with_upper_case_solid() const {
        const size_t first = bytes_.find_first_not_of(" \t\r\n", text_begin());
        return first != std::string::npos && bytes_.compare(first, 5, "SOLID") == 0;
    }

    // " (STL keywords are lower case)" when `got` is `wanted` in other letter case.
    static std::string case_note(std::string_view got, std::string_view wanted) {
        const bool same = got.size() == wanted.size() &&
                          std::equal(got.begin(), got.end(), wanted.begin(), [](char a, char b) {
                              return std::tolower(static_cast<unsigned char>(a)) == b;
                          });
        return same ? " (STL keywords are lower case)" : "";
    }
    bool is_text() const {
        return std::none_of(bytes_.begin(), bytes_.end(), [](char c) {
            const auto u = static_cast<unsigned char>(c);
            return u < 0x20 && c != '\t' && c != '\n' && c != '\r' && c != '\f' && c != '\v';
        });
    }

    void add_triangle(const glm::vec3 (&corners)[3]) {
        const uint32_t a = vertices_.index_of(corners[0]), b = vertices_.index_of(corners[1]),
                       c = vertices_.index_of(corners[2]);
        if (a == b || b == c || a == c) {
            ++out_.collapsed;
            return;
        }
        if (out_.mesh.triangles.size() >= max_triangles_) throw_face_limit(name_, max_triangles_);
        out_.mesh.triangles.emplace_back(a, b, c);
    }

    static bool valid(double v) { return std::isfinite(v) && std::abs(v) <= kMaxCoordinate; }

    void read_binary(uint32_t count) {
        if (count > max_triangles_) {
            fail("declares " + std::to_string(count) + " triangles, more than the limit of " +
                 std::to_string(max_triangles_) + " faces (raise it with --max-faces)");
        }
        out_.mesh.triangles.reserve(count);
        const char* p = bytes_.data() + kBinaryHeaderBytes;
        for (uint32_t t = 0; t < count; ++t, p += kBinaryTriangleBytes) {
            glm::vec3 corners[3];
            for (int k = 0; k < 9; ++k) {
                uint32_t bits = 0;
                std::memcpy(&bits, p + 12 + 4 * k, 4);
                if constexpr (std::endian::native == std::endian::big) bits = __builtin_bswap32(bits);
                const float v = std::bit_cast<float>(bits);
                if (!valid(v)) {
                    fail("triangle " + std::to_string(t) + (std::isfinite(v) ? " has a coordinate beyond the limit of 1e18"
                                                                              : " has a non-finite coordinate"));
                }
                corners[k / 3][k % 3] = v;
            }
            add_triangle(corners);
        }
    }

    // ---- ASCII ----

    // The next blank-separated word, counting lines; empty at the end of the file.
    std::string_view word() {
        while (at_ < bytes_.size() && std::isspace(static_cast<unsigned char>(bytes_[at_]))) {
            if (bytes_[at_] == '\n') ++line_;
            ++at_;
        }
        const size_t begin = at_;
        while (at_ < bytes_.size() && !std::isspace(static_cast<unsigned char>(bytes_[at_]))) ++at_;
        return std::string_view(bytes_).substr(begin, at_ - begin);
    }
    void skip_rest_of_line() {
        while (at_ < bytes_.size() && bytes_[at_] != '\n') ++at_;
    }
    void expect(std::string_view wanted, const std::string& context) {
        const std::string_view got = word();
        if (got.empty()) fail_at_line("the file ends " + context + " (truncated?)");
        if (got != wanted) {
            fail_at_line("expected '" + std::string(wanted) + "' " + context + ", found '" +
                         std::string(got.substr(0, 40)) + "'" + case_note(got, wanted));
        }
    }
    double number(const std::string& context, bool coordinate) {
        const std::string_view got = word();
        if (got.empty()) fail_at_line("the file ends " + context + " (truncated?)");
        const std::string text(got.substr(0, 60));
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (end == text.c_str() || *end != '\0' || got.size() > 60) fail_at_line("'" + text + "' is not a number " + context);
        // As for every format: stream readers take "0x1p0" as 0 and fail on the rest.
        if (std::isfinite(v) && !is_decimal_word(got)) {
            fail_at_line("'" + text + "' is not a decimal number " + context + " (hex floats are not read)");
        }
        if (coordinate && !valid(v)) {
            fail_at_line(std::isfinite(v) ? "coordinate beyond the limit of 1e18" : "non-finite coordinate");
        }
        return v;
    }

    void read_ascii() {
        at_ = text_begin();
        line_ = 1;
        size_t facets = 0;
        bool in_solid = false;
        for (std::string_view w = word(); !w.empty(); w = word()) {
            if (!in_solid) {
                if (w != "solid") {
                    fail_at_line("expected 'solid', found '" + std::string(w.substr(0, 40)) + "'" + case_note(w, "solid"));
                }
                skip_rest_of_line();  // the solid's name
                in_solid = true;
                continue;
            }
            if (w == "endsolid") {
                skip_rest_of_line();
                in_solid = false;
                continue;
            }
            if (w != "facet") {
                fail_at_line("expected 'facet' or 'endsolid', found '" + std::string(w.substr(0, 40)) + "'" +
                             case_note(w, "facet") + case_note(w, "endsolid"));
            }
            const std::string context = "in facet " + std::to_string(facets);
            expect("normal", context);
            for (int k = 0; k < 3; ++k) number(context, false);
            expect("outer", context);
            expect("loop", context);
            glm::vec3 corners[3];
            for (int c = 0; c < 3; ++c) {
                expect("vertex", context);
                for (int axis = 0; axis < 3; ++axis) corners[c][axis] = float(number(context, true));
            }
            expect("endloop", context + " (a facet has three vertices)");
            expect("endfacet", context);
            add_triangle(corners);
            ++facets;
        }
        if (in_solid) {
            fail_at_line("the file ends after " + std::to_string(facets) + " facets without 'endsolid' (truncated?)");
        }
    }

    std::string name_;
    const std::string& bytes_;
    size_t max_triangles_;
    StlContents out_;
    VertexIndex vertices_;
    size_t at_ = 0;
    size_t line_ = 1;
};

}  // namespace

StlContents read_stl(const std::filesystem::path& path, const std::string& bytes, size_t max_triangles) {
    return StlReader(path, bytes, max_triangles).read();
}

}  // namespace inkline::core::internal
