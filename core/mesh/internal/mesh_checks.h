// SPDX-License-Identifier: MIT
// Checks that run before OpenMesh's readers, which trust their input: vertex lines that would be
// skipped, element counts the file cannot hold, malformed PLY headers. Found by fuzzing
// (tests/fuzz/); each check names the file and line.
#pragma once

#include "core/mesh/mesh.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace inkline::core::internal {

// Reads one coordinate at r_cursor: the next blank-separated word, which must be a whole decimal
// number (no hex floats, no "1.5.3" or "1-2" that stream extraction would split), finite and
// within kMaxCoordinate; advances the cursor past it. Throws InputError prefixed with `where`
// ("file:line") naming the word; `what` names the thing read ("vertex", "texture coordinate").
double scan_coordinate(const std::string& where, const char*& r_cursor, const char* what = "vertex");

// A whole decimal word: digits, '.', signs and an exponent only (no hex float, "inf" or "nan").
bool is_decimal_word(std::string_view word);

// The UTF-8 byte order mark some editors put before a text file's first line.
inline constexpr std::string_view kUtf8Bom = "\xef\xbb\xbf";

// True when `line` is a first line starting with a byte order mark, which is then removed.
bool strip_bom(std::string& r_line);

// Throws the InputError for a mesh with more than `limit` triangles.
[[noreturn]] void throw_face_limit(const std::string& name, size_t limit);

// OBJ: whether `keyword` starts a statement of the OBJ format ("v", "f", "usemtl", "cstype", ...).
bool is_obj_statement(std::string_view keyword);

// OBJ: names vertex lines OpenMesh would skip; returns the number of faces with < 3 corners.
size_t check_obj(const std::filesystem::path& path);

// PLY: the header's structure, and element counts the file's size can hold.
void check_ply(const std::filesystem::path& path, uintmax_t file_size);

}  // namespace inkline::core::internal
