// SPDX-License-Identifier: MIT
#include "core/mesh/internal/mesh_checks.h"

#include "core/error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

namespace inkline::core::internal {
namespace {

// Each element needs at least this many bytes: an ASCII vertex "0 0 0\n", face "3 0 1 2\n";
// a binary vertex three floats, a face a count byte and three indices.
constexpr uintmax_t kMinTextVertexBytes = 6;
constexpr uintmax_t kMinTextFaceBytes = 8;
constexpr uintmax_t kMinBinaryVertexBytes = 12;
constexpr uintmax_t kMinBinaryFaceBytes = 13;

struct PlyCounts {
    uintmax_t vertices = 0;
    uintmax_t faces = 0;
    bool binary = false;
};

// OpenMesh's PLY reader reserves memory for the declared counts before reading any element.
void check_counts(const std::filesystem::path& path, const PlyCounts& c, uintmax_t file_size) {
    const uintmax_t needed = c.binary ? c.vertices * kMinBinaryVertexBytes + c.faces * kMinBinaryFaceBytes
                                      : c.vertices * kMinTextVertexBytes + c.faces * kMinTextFaceBytes;
    if (c.vertices > file_size || c.faces > file_size || needed > file_size) {
        throw InputError(path.string() + ": header declares " + std::to_string(c.vertices) + " vertices and " +
                         std::to_string(c.faces) + " faces, more than the file's " + std::to_string(file_size) +
                         " bytes can hold");
    }
}

// A signed decimal integer of at most 9 digits (OpenMesh reads an int; ten digits may overflow it).
bool is_index(std::string_view s) {
    if (!s.empty() && s[0] == '-') s.remove_prefix(1);
    return !s.empty() && s.size() <= 9 && s.find_first_not_of("0123456789") == std::string_view::npos;
}

// An OBJ face corner: v, v/vt, v//vn or v/vt/vn.
bool is_obj_corner(std::string_view corner) {
    const size_t first = corner.find('/');
    if (first == std::string_view::npos) return is_index(corner);
    if (!is_index(corner.substr(0, first))) return false;
    const std::string_view rest = corner.substr(first + 1);
    const size_t second = rest.find('/');
    if (second == std::string_view::npos) return is_index(rest);
    const std::string_view texture = rest.substr(0, second);
    return (texture.empty() || is_index(texture)) && is_index(rest.substr(second + 1));
}

}  // namespace

// The statements of the OBJ format (geometry, free-form, grouping, display and render
// attributes). OpenMesh skips any other word silently: a mistyped "V" would drop a vertex and
// shift every later index, so anything else is refused.
bool is_obj_statement(std::string_view keyword) {
    static const std::set<std::string_view> kStatements = {
        "v",     "vt",      "vn",       "vp",       "vc",       "f",        "l",         "p",    "o",
        "g",     "s",       "mg",       "usemtl",   "mtllib",   "cstype",   "deg",       "bmat", "step",
        "curv",  "curv2",   "surf",     "parm",     "trim",     "hole",     "scrv",      "sp",   "end",
        "con",   "bevel",   "c_interp", "d_interp", "lod",      "maplib",   "usemap",    "shadow_obj",
        "trace_obj", "ctech", "stech",  "call",     "csh"};
    return kStatements.count(keyword) > 0;
}

// Reads one coordinate: a whole decimal word, so that strtod here and OpenMesh's stream
// extraction (which stops at the first character it cannot take and reads the rest as the next
// number) agree on it; "nan" and "inf" are named as such.
bool is_decimal_word(std::string_view word) {
    return word.find_first_not_of("0123456789.eE+-") == std::string_view::npos;
}

bool strip_bom(std::string& r_line) {
    if (r_line.compare(0, kUtf8Bom.size(), kUtf8Bom) != 0) return false;
    r_line.erase(0, kUtf8Bom.size());
    return true;
}

double scan_coordinate(const std::string& where, const char*& r_cursor, const char* what) {
    const char* begin = r_cursor;
    while (*begin == ' ' || *begin == '\t' || *begin == '\r' || *begin == '\f' || *begin == '\v') ++begin;
    const char* end_of_word = begin;
    while (*end_of_word != '\0' && !std::isspace(static_cast<unsigned char>(*end_of_word))) ++end_of_word;
    if (end_of_word == begin) {
        throw InputError(where + ": " + what + (std::string_view(what) == "vertex" ? " needs three numbers" : " needs two numbers"));
    }
    const std::string word(begin, std::min<size_t>(size_t(end_of_word - begin), 40));
    char* end = nullptr;
    const double value = std::strtod(begin, &end);
    if (end != end_of_word) {
        throw InputError(where + ": coordinate '" + word + "' is not a number");
    }
    if (!std::isfinite(value)) {
        throw InputError(where + ": " + (std::string_view(what) == "vertex" ? "vertex has a non-finite coordinate"
                                                                            : std::string(what) + " '" + word + "' is not finite"));
    }
    if (!is_decimal_word(std::string_view(begin, size_t(end_of_word - begin)))) {
        throw InputError(where + ": coordinate '" + word + "' is not a decimal number (hex floats are not read)");
    }
    if (std::abs(value) > kMaxCoordinate) {
        throw InputError(where + ": coordinate " + word + " exceeds the limit of 1e18");
    }
    r_cursor = end_of_word;
    return value;
}

void throw_face_limit(const std::string& name, size_t limit) {
    throw InputError(name + ": more than " + std::to_string(limit) + " faces, the limit (raise it with --max-faces)");
}

// OpenMesh's OBJ reader silently skips a vertex line it cannot parse ("v nan 0 0", or a value
// beyond float range), which shifts every later index, and drops faces of fewer than 3 corners
// unreported. This pass names such vertex lines and counts those faces.
size_t check_obj(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::string line;
    size_t number = 0, short_faces = 0;
    while (std::getline(in, line)) {
        ++number;
        if (number == 1) strip_bom(line);  // load_mesh hands OpenMesh the text without it
        const std::string where = path.string() + ":" + std::to_string(number);
        // Split the keyword as OpenMesh does: stream extraction, so any leading whitespace.
        std::istringstream words(line);
        std::string keyword;
        if (!(words >> keyword) || keyword[0] == '#') continue;
        if (!is_obj_statement(keyword)) {
            throw InputError(where + ": unknown statement '" + keyword.substr(0, 40) + "'");
        }
        if (keyword == "f") {
            std::string corner;
            int count = 0;
            std::set<std::string> distinct;  // vertex indices as written: OpenMesh drops repeats
            while (words >> corner && corner[0] != '#') {  // a comment may end the line
                ++count;
                distinct.insert(corner.substr(0, corner.find('/')));
                // OpenMesh's reader asserts (aborts) on a corner that is not an index.
                if (!is_obj_corner(corner)) {
                    throw InputError(where + ": face corner '" + corner +
                                     "' is not an index (expected v, v/vt, v//vn or v/vt/vn)");
                }
            }
            // ... and on a face without corners.
            if (count == 0) throw InputError(where + ": face without corners");
            short_faces += distinct.size() < 3;
        } else if (keyword == "v") {
            std::string rest;
            std::getline(words, rest);
            const char* cursor = rest.c_str();
            for (int axis = 0; axis < 3; ++axis) scan_coordinate(where, cursor);
        } else if (keyword == "vt") {
            // OpenMesh fails the whole read on a texture coordinate it cannot parse.
            std::string rest;
            std::getline(words, rest);
            const char* cursor = rest.c_str();
            for (int axis = 0; axis < 2; ++axis) scan_coordinate(where, cursor, "texture coordinate");
        }
    }
    return short_faces;
}

namespace {

struct PlyElement {
    std::string name;
    uintmax_t count = 0;
    std::vector<std::string> lists;  // per property: the list's count type, or "" for a scalar
};

void require_number(const std::filesystem::path& path, const std::string& element, uintmax_t index,
                    const std::string& token) {
    char* end = nullptr;
    std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') {
        throw InputError(path.string() + ": " + element + " " + std::to_string(index) + ": '" + token +
                         "' is not a number");
    }
}

// OpenMesh collects a list's values before handing them on, as many as its count says. ASCII
// PLY is read the way OpenMesh reads it, token by token in header order, and each list count
// must fit the bytes left in the file (a value takes at least two); binary files may use 8-bit
// list counts only, which bound it.
void check_ply_lists(const std::filesystem::path& path, std::istream& in, const std::vector<PlyElement>& elements,
                     bool binary, uintmax_t file_size) {
    for (const PlyElement& element : elements) {
        for (const std::string& count_type : element.lists) {
            if (binary && !count_type.empty() && count_type != "uchar" && count_type != "char" &&
                count_type != "uint8" && count_type != "int8") {
                throw InputError(path.string() + ": binary PLY with " + count_type +
                                 " list counts is not supported (8-bit counts, as in 'property list uchar int "
                                 "vertex_indices', are)");
            }
        }
    }
    if (binary) return;
    std::string token;
    for (const PlyElement& element : elements) {
        for (uintmax_t i = 0; i < element.count; ++i) {
            for (const std::string& count_type : element.lists) {
                if (!(in >> token)) return;  // a short file: OpenMesh's reader reports it
                // OpenMesh's >> would split "2-1" into two numbers; only whole numbers keep both
                // readings of the file the same.
                require_number(path, element.name, i, token);
                if (count_type.empty()) continue;
                char* end = nullptr;
                const long long n = std::strtoll(token.c_str(), &end, 10);
                const std::streamoff at = in.tellg();
                const uintmax_t left = at < 0 ? 0 : file_size - std::min<uintmax_t>(file_size, uintmax_t(at));
                if (*end != '\0' || n < 0 || uintmax_t(n) > left / 2 + 1) {
                    throw InputError(path.string() + ": a " + element.name + " list (element " + std::to_string(i) +
                                     ") declares '" + token + "' values; " + std::to_string(left) +
                                     " bytes are left in the file");
                }
                for (long long k = 0; k < n && (in >> token); ++k) require_number(path, element.name, i, token);
            }
        }
    }
}

}  // namespace

// OpenMesh's PLY reader trusts the header's structure (a property before any element crashes
// it), so the header is checked line by line first: "ply", one "format", then "element NAME N",
// "property TYPE NAME", "property list TYPE TYPE NAME", "comment" and "obj_info" lines, up to
// "end_header".
void check_ply(const std::filesystem::path& path, uintmax_t file_size) {
    static const std::set<std::string> kTypes = {"char",  "uchar",  "short",  "ushort",  "int",    "uint",
                                                 "float", "double", "int8",   "uint8",   "int16",  "uint16",
                                                 "int32", "uint32", "float32", "float64"};
    constexpr int kMaxHeaderLines = 1000;
    std::ifstream in(path, std::ios::binary);
    std::string line;
    PlyCounts counts;
    bool have_format = false, in_element = false;
    std::vector<PlyElement> elements;
    for (int number = 1; number <= kMaxHeaderLines && std::getline(in, line); ++number) {
        if (number == 1) strip_bom(line);
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
            // The checks below read the data from the next line on, as the format requires.
            std::string trailing;
            if (words >> trailing) fail("data on the end_header line (it must end the line)");
            check_counts(path, counts, file_size);
            check_ply_lists(path, in, elements, counts.binary, file_size);
            return;
        }
        if (keyword == "comment" || keyword == "obj_info" || keyword.empty()) continue;
        if (keyword == "format") {
            std::string format, version;
            if (!(words >> format >> version) ||
                (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")) {
                fail("unknown format");
            }
            // OpenMesh reads the version with >> and, should that fail, loops on its header forever.
            if (version != "1.0") fail("unsupported version '" + version + "' (expected 1.0)");
            have_format = true;
            counts.binary = format != "ascii";
        } else if (keyword == "element") {
            std::string name, count_text, extra;
            if (!(words >> name >> count_text) || (words >> extra) ||
                count_text.find_first_not_of("0123456789") != std::string::npos || count_text.size() > 10 ||
                std::stoull(count_text) > 0xffffffffull) {
                // A count beyond 32 bits fails OpenMesh's unsigned read, with the same endless loop.
                fail("expected 'element NAME COUNT' with a count below 2^32");
            }
            const uintmax_t count = std::stoull(count_text);
            if (name == "vertex") counts.vertices = count;
            if (name == "face") counts.faces = count;
            elements.push_back({name, count, {}});
            in_element = true;
        } else if (keyword == "property") {
            if (!in_element) fail("a property before any element");
            std::string type, name, extra;
            if (!(words >> type)) fail("expected a property type");
            if (type == "list") {
                std::string count_type, item_type;
                if (!(words >> count_type >> item_type >> name) || !kTypes.count(count_type) || !kTypes.count(item_type))
                    fail("expected 'property list TYPE TYPE NAME'");
                elements.back().lists.push_back(count_type);
            } else if (!kTypes.count(type) || !(words >> name)) {
                fail("expected 'property TYPE NAME'");
            } else {
                elements.back().lists.push_back("");
            }
            if (words >> extra) fail("unexpected words after the property name");
        } else {
            fail("unknown keyword '" + keyword + "'");
        }
    }
    throw InputError(path.string() + ": malformed PLY header: no end_header in the first " +
                     std::to_string(kMaxHeaderLines) + " lines");
}

}  // namespace inkline::core::internal
