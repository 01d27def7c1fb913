// SPDX-License-Identifier: MIT
// Hostile input, readers: each case asserts the exit code, the one-line message and the state of
// every file involved afterwards (tests/support/hostile.h).
#include "tests/support/hostile.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::HostileTest;

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

class HostileReaders : public HostileTest {
  protected:
    // Runs `inkline render MESH -q [extra] -o dir/out` and expects exit 2, one line naming the
    // problem, and no file written or changed anywhere in the test's folder.
    void expect_refused(const fs::path& mesh, const std::string& needle, const std::string& extra = "",
                        const std::string& prefix = "") {
        SCOPED_TRACE(mesh.filename().string() + " " + extra);
        const auto before = test::folder_state(dir);
        const test::RunResult r = test::run_shell(prefix + test::inkline_command() + " render '" + mesh.string() +
                                                  "' -q " + extra + " -o '" + (dir / "out").string() + "'");
        test::expect_one_line_error(r, 2, needle);
        EXPECT_EQ(test::changed_entries(before, test::folder_state(dir)), std::vector<std::string>{});
    }

    void write_bytes(const fs::path& path, const std::string& bytes) { test::write_text(path, bytes); }
};

// ---- binary builders ----

template <typename T>
void append(std::string& r_out, T value, bool big_endian = false) {
    char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    if (big_endian) std::reverse(raw, raw + sizeof(T));
    r_out.append(raw, sizeof(T));
}

// A binary STL of the given triangles (9 floats each); `count` overrides the header's count.
std::string binary_stl(const std::vector<std::vector<float>>& triangles, int64_t count = -1) {
    std::string out(80, ' ');
    append<uint32_t>(out, uint32_t(count < 0 ? int64_t(triangles.size()) : count));
    for (const auto& t : triangles) {
        for (float n : {0.0f, 0.0f, 1.0f}) append(out, n);
        for (float v : t) append(out, v);
        append<uint16_t>(out, 0);
    }
    return out;
}

const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 1, 1, 0};
const std::vector<float> kTriangle2 = {0, 0, 0, 1, 1, 0, 0, 1, 0};

// A binary PLY of a unit square: `declared` vertices in the header, the square's 4 in the data.
std::string binary_ply(bool big_endian, int declared_vertices = 4, const std::vector<float>& vertex1 = {1, 0, 0},
                       const std::string& index_type = "int", int list_count = 3) {
    std::string out = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\nelement vertex " + std::to_string(declared_vertices) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face 2\nproperty list uchar " +
                      index_type + " vertex_indices\nend_header\n";
    const std::vector<std::vector<float>> vertices = {{0, 0, 0}, vertex1, {1, 1, 0}, {0, 1, 0}};
    for (const auto& v : vertices) {
        for (float c : v) append(out, c, big_endian);
    }
    for (const std::vector<int32_t>& face : {std::vector<int32_t>{0, 1, 2}, std::vector<int32_t>{0, 2, 3}}) {
        append<uint8_t>(out, uint8_t(list_count));
        for (int32_t i : face) {
            if (index_type == "float") {
                append(out, float(i), big_endian);
            } else {
                append(out, i, big_endian);
            }
        }
    }
    return out;
}

std::string ascii_ply_header(int vertices, int faces, const std::string& list = "uchar int") {
    return "ply\nformat ascii 1.0\nelement vertex " + std::to_string(vertices) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(faces) +
           "\nproperty list " + list + " vertex_indices\nend_header\n";
}
const std::string kSquareVertices = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
const std::string kSquareFaces = "3 0 1 2\n3 0 2 3\n";

const std::string kFacet =
    "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 1 1 0\n endloop\nendfacet\n";

// ---- class 5: silent misreads ----

TEST_F(HostileReaders, HexFloatInObjIsRefusedWithItsLine) {
    // Stream extraction reads "0x1p-1" as 0 and fails on the rest, so the vertex was dropped and
    // every later index pointed one vertex off. So are words it would split into two numbers.
    for (const char* word : {"0x1p-1", "0X1P+0", "-0x.8p1", "1.5.3", "1-2", "2e", "1,5"}) {
        for (int axis = 0; axis < 3; ++axis) {
            std::string coords[3] = {"0", "0", "0"};
            coords[axis] = word;
            test::write_text(dir / "hex.obj", "v 0 0 0\nv " + coords[0] + " " + coords[1] + " " + coords[2] +
                                                  "\nv 1 0 0\nv 0 1 0\nf 1 3 4\n");
            expect_refused(dir / "hex.obj", "hex.obj:2: coordinate '" + std::string(word) + "' is not a");
        }
    }
    // The same in a texture coordinate, which would fail OpenMesh's whole read without a line.
    test::write_text(dir / "vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0x1p-1 0\nf 1 2 3\n");
    expect_refused(dir / "vt.obj", "vt.obj:4: coordinate '0x1p-1' is not a decimal number");
    // CRLF line ends, comments and blanks around it change nothing.
    test::write_text(dir / "crlf.obj", "# c\r\nv 0 0 0\r\n  v\t0x10 0 0 \r\nv 1 0 0\r\nv 0 1 0\r\nf 1 3 4\r\n");
    expect_refused(dir / "crlf.obj", "crlf.obj:3: coordinate '0x10' is not a decimal number");
}

TEST_F(HostileReaders, ObjIndexTooLongForAnIntIsRefused) {
    test::write_text(dir / "idx.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4294967299\n");
    expect_refused(dir / "idx.obj", "idx.obj:4: face corner '4294967299' is not an index");
}

TEST_F(HostileReaders, PlyDeclaringMoreVerticesThanItHoldsIsRefused) {
    // ASCII: face lines would be read as vertices.
    test::write_text(dir / "more.ply", ascii_ply_header(5, 2) + kSquareVertices + kSquareFaces);
    expect_refused(dir / "more.ply", "more.ply:14: vertex 4 has 4 values");
    test::write_text(dir / "more3.ply", ascii_ply_header(6, 2) + kSquareVertices + "3 0 1 2\n");
    expect_refused(dir / "more3.ply", "more3.ply:14: vertex 4 has 4 values");
    test::write_text(dir / "short.ply", ascii_ply_header(6, 0) + kSquareVertices);
    expect_refused(dir / "short.ply", "short.ply: the file ends after 4 of 6 vertex elements");
    // Binary, both byte orders: the data runs out, or is left over. (Binary data has no lines: a
    // wrong count whose misread happens to use up the data exactly cannot be told from a file.)
    for (bool big_endian : {false, true}) {
        write_bytes(dir / "more_bin.ply", binary_ply(big_endian, 7));
        expect_refused(dir / "more_bin.ply", "more_bin.ply: the file ends inside vertex 6 of 7");
        write_bytes(dir / "more_bin.ply", binary_ply(big_endian, 4) + std::string(12, '\0'));
        expect_refused(dir / "more_bin.ply", "more_bin.ply: 12 bytes after the last element");
    }
}

TEST_F(HostileReaders, PlyHoldingMoreThanItDeclaresIsRefused) {
    test::write_text(dir / "fewer.ply", ascii_ply_header(4, 1) + kSquareVertices + kSquareFaces);
    expect_refused(dir / "fewer.ply", "fewer.ply:15: data after the last element");
    // One vertex too few declared: the last vertex line is read as a face of 0 corners... and refused.
    test::write_text(dir / "fewer_v.ply", ascii_ply_header(3, 2) + kSquareVertices + kSquareFaces);
    expect_refused(dir / "fewer_v.ply", "fewer_v.ply:13: face 0");
}

TEST_F(HostileReaders, PlyElementsMustStandOnePerLine) {
    test::write_text(dir / "split.ply", ascii_ply_header(4, 2) + "0 0\n0\n1 0 0\n1 1 0\n0 1 0\n" + kSquareFaces);
    expect_refused(dir / "split.ply", "split.ply:10: vertex 0 has too few values");
    // CRLF, tabs and a blank line between elements are fine: the square reads.
    test::write_text(dir / "crlf.ply", "ply\r\nformat ascii 1.0\r\ncomment x\r\nelement vertex 4\r\nproperty float x\r\n"
                                       "property float y\r\nproperty float z\r\nelement face 2\r\n"
                                       "property list uchar int vertex_indices\r\nend_header\r\n"
                                       "0\t0 0\r\n1 0 0\r\n\r\n1 1 0\r\n0 1 0\r\n3 0 1 2\r\n3 0 2 3\r\n");
    const test::RunResult ok = test::run_inkline("render " + (dir / "crlf.ply").string() + " -q --size 64x64 -o " +
                                                 (dir / "crlf_out").string());
    EXPECT_EQ(ok.code, 0) << ok.output;
}

TEST_F(HostileReaders, PlyFloatIndexListIsRefused) {
    for (const char* list : {"uchar float", "uchar double", "float int"}) {
        test::write_text(dir / "f.ply", ascii_ply_header(4, 2, list) + kSquareVertices + kSquareFaces);
        expect_refused(dir / "f.ply", "f.ply: face property 'vertex_indices' is a list of floating-point values");
    }
    for (bool big_endian : {false, true}) {
        write_bytes(dir / "fb.ply", binary_ply(big_endian, 4, {1, 0, 0}, "float"));
        expect_refused(dir / "fb.ply", "fb.ply: face property 'vertex_indices' is a list of floating-point values");
    }
    // A fractional value where an integer is declared.
    test::write_text(dir / "frac.ply", ascii_ply_header(4, 2) + kSquareVertices + "3 0 1 2.5\n3 0 2 3\n");
    expect_refused(dir / "frac.ply", "frac.ply:14: face 0: '2.5' is not an integer");
}

TEST_F(HostileReaders, PlyWithoutCoordinatesOrIndicesIsRefused) {
    test::write_text(dir / "noz.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                      "0 0\n1 0\n0 1\n3 0 1 2\n");
    expect_refused(dir / "noz.ply", "noz.ply: the vertex element has no property 'z'");
    test::write_text(dir / "nolist.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                         "property float z\nelement face 1\nproperty list uchar int corners\n"
                                         "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    expect_refused(dir / "nolist.ply", "nolist.ply: the face element has no 'vertex_indices' list");
}

TEST_F(HostileReaders, BinaryPlyListCountBeyondTheDataIsRefused) {
    for (bool big_endian : {false, true}) {
        write_bytes(dir / "list.ply", binary_ply(big_endian, 4, {1, 0, 0}, "int", 200));
        expect_refused(dir / "list.ply", "list.ply: face 0 of 2: its list declares 200 values; 25 bytes are left");
        // A count that fits the data but not the faces after it.
        write_bytes(dir / "list.ply", binary_ply(big_endian, 4, {1, 0, 0}, "int", 5));
        expect_refused(dir / "list.ply", "list.ply: ");
    }
}

TEST_F(HostileReaders, NanOrInfinityInBinaryStlIsRefused) {
    for (float bad : {kNan, kInf, -kInf, 3e38f}) {
        for (int k = 0; k < 9; ++k) {
            std::vector<float> t = kTriangle2;
            t[size_t(k)] = bad;
            write_bytes(dir / "nan.stl", binary_stl({kTriangle, t}));
            expect_refused(dir / "nan.stl", std::isfinite(bad) ? "nan.stl: triangle 1 has a coordinate beyond the limit"
                                                               : "nan.stl: triangle 1 has a non-finite coordinate");
        }
    }
    std::string nan_facet = kFacet;
    nan_facet.replace(nan_facet.find("vertex 1 0 0"), 12, "vertex 1 nan 0");
    test::write_text(dir / "nan_ascii.stl", "solid s\n" + kFacet + nan_facet + "endsolid s\n");
    expect_refused(dir / "nan_ascii.stl", "nan_ascii.stl:12: non-finite coordinate");
}

TEST_F(HostileReaders, NanOrInfinityInBinaryPlyIsRefused) {
    for (bool big_endian : {false, true}) {
        for (int axis = 0; axis < 3; ++axis) {
            for (float bad : {kNan, kInf}) {
                std::vector<float> v = {1, 0, 0};
                v[size_t(axis)] = bad;
                write_bytes(dir / "nan.ply", binary_ply(big_endian, 4, v));
                expect_refused(dir / "nan.ply", "nan.ply: vertex 1 has a non-finite coordinate");
            }
        }
    }
    test::write_text(dir / "nan_ascii.ply", ascii_ply_header(4, 2) + "0 0 0\n1 0 nan\n1 1 0\n0 1 0\n" + kSquareFaces);
    expect_refused(dir / "nan_ascii.ply", "nan_ascii.ply:11: vertex 1 has a non-finite coordinate");
}

TEST_F(HostileReaders, TruncatedAsciiStlIsRefused) {
    const std::string whole = "solid s\n" + kFacet + kFacet + "endsolid s\n";
    // Cut after every word before "endsolid": inside a facet, between facets, inside a number.
    size_t cuts = 0;
    for (size_t cut = 9; cut < whole.rfind("endsolid"); cut += 7) {
        test::write_text(dir / "cut.stl", whole.substr(0, cut));
        expect_refused(dir / "cut.stl", "cut.stl:");
        ++cuts;
    }
    EXPECT_GT(cuts, 20u);
    test::write_text(dir / "noend.stl", "solid s\n" + kFacet + kFacet);
    expect_refused(dir / "noend.stl", "the file ends after 2 facets without 'endsolid'");
}

TEST_F(HostileReaders, MalformedAsciiStlStructureIsRefused) {
    const std::string four = kFacet.substr(0, kFacet.find(" endloop")) + "  vertex 0 1 0\n endloop\nendfacet\n";
    test::write_text(dir / "four.stl", "solid s\n" + four + "endsolid s\n");
    expect_refused(dir / "four.stl", "four.stl:7: expected 'endloop' in facet 0 (a facet has three vertices)");
    std::string no_loop = kFacet;
    no_loop.replace(no_loop.find("outer loop"), 10, "outer");
    test::write_text(dir / "loop.stl", "solid s\n" + no_loop + "endsolid s\n");
    expect_refused(dir / "loop.stl", "loop.stl:4: expected 'loop' in facet 0, found 'vertex'");
    test::write_text(dir / "word.stl", "solid s\n" + kFacet + "facet normal 0 0 1\nouter loop\nvertex 0 0\nvertex 1 0 0\n");
    expect_refused(dir / "word.stl", "word.stl:12: 'vertex' is not a number in facet 1");
    test::write_text(dir / "notstl.stl", "hello\n");
    expect_refused(dir / "notstl.stl", "notstl.stl: not an STL file");
}

// ---- class 8: messages naming the real cause ----

TEST_F(HostileReaders, BinaryStlWithAWrongTriangleCountSaysSo) {
    for (int64_t count : {int64_t(0), int64_t(1), int64_t(3), int64_t(4000000000)}) {
        write_bytes(dir / "count.stl", binary_stl({kTriangle, kTriangle2}, count));
        expect_refused(dir / "count.stl",
                       "count.stl: binary STL header declares " + std::to_string(count) + " triangles");
    }
    // Truncated inside a triangle, and a header starting with "solid" as many exporters write it.
    std::string cut = binary_stl({kTriangle, kTriangle2});
    cut.resize(cut.size() - 7);
    cut.replace(0, 5, "solid");
    write_bytes(dir / "cut.stl", cut);
    expect_refused(dir / "cut.stl", "cut.stl: binary STL header declares 2 triangles (184 bytes), but the file has 177");
}

TEST_F(HostileReaders, UnreadableMeshSaysPermissionDenied) {
    std::string prefix;
    if (::geteuid() == 0) {
        // Root reads anything: run as nobody instead, where setpriv can.
        if (test::run_shell("command -v setpriv").code != 0) GTEST_SKIP() << "root without setpriv";
        prefix = "setpriv --reuid=65534 --regid=65534 --clear-groups ";
        fs::permissions(dir, fs::perms::all);
    }
    const std::string square_ply = ascii_ply_header(4, 2) + kSquareVertices + kSquareFaces;
    for (const auto& [name, text] : {std::pair<std::string, std::string>{"m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"},
                                     {"m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
                                     {"m.ply", square_ply},
                                     {"m.stl", "solid s\n" + kFacet + "endsolid s\n"}}) {
        test::write_text(dir / name, text);
        fs::permissions(dir / name, fs::perms::none);
        expect_refused(dir / name, name + ": cannot read: Permission denied", "", prefix);
    }
}

TEST_F(HostileReaders, FolderOrDeviceGivenAsMeshIsNamed) {
    for (const char* name : {"m.obj", "m.ply", "m.stl", "m.off"}) {
        fs::create_directory(dir / name);
        expect_refused(dir / name, std::string(name) + ": is a folder, not a mesh file");
    }
    ASSERT_EQ(::mkfifo((dir / "fifo.stl").c_str(), 0644), 0);
    expect_refused(dir / "fifo.stl", "fifo.stl: not a regular file");
}

TEST_F(HostileReaders, LibraryOutputNeverReachesTheUser) {
    // Read by OpenMesh (a leading blank declines the fast reader), with a material library that
    // does not exist and a face past the vertices: one line of inkline's own, nothing else.
    test::write_text(dir / "om.obj", "mtllib nothere.mtl\nusemtl x\n v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 7\n");
    expect_refused(dir / "om.obj", "om.obj: face 2 references a vertex that does not exist");
}

// ---- round two: what the readers skipped silently ----

// `inkline info MESH`: its output, after checking it succeeded.
std::string info_of(const fs::path& mesh) {
    const test::RunResult r = test::run_inkline("info '" + mesh.string() + "'");
    EXPECT_EQ(r.code, 0) << r.output;
    return r.output;
}

const std::string kBom = "\xef\xbb\xbf";

TEST_F(HostileReaders, ObjByteOrderMarkKeepsTheFirstVertex) {
    // The mark used to make the first line's keyword unknown: the vertex went, every index shifted.
    const std::string body = "v 5 5 5\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    test::write_text(dir / "bom.obj", kBom + body);
    test::write_text(dir / "bom_general.obj", kBom + body + " # read by the general reader\n");
    for (const char* name : {"bom.obj", "bom_general.obj"}) {
        SCOPED_TRACE(name);
        const std::string out = info_of(dir / name);
        EXPECT_NE(out.find("vertices: 4\n"), std::string::npos) << out;
        EXPECT_NE(out.find("bounds: [0, 0, 0] .. [5, 5, 5]"), std::string::npos) << out;
    }
}

TEST_F(HostileReaders, UnknownObjStatementIsRefusedWithItsLine) {
    test::write_text(dir / "cap.obj", "v 0 0 0\nV 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_refused(dir / "cap.obj", "cap.obj:2: unknown statement 'V'");
    test::write_text(dir / "cap_general.obj", " v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nvx 1 2 3\n");
    expect_refused(dir / "cap_general.obj", "cap_general.obj:5: unknown statement 'vx'");
    // Every statement of the format is still read (and ignored where it carries no geometry).
    test::write_text(dir / "all.obj",
                     "mtllib a.mtl\no thing\ng part\ns 1\nmg off\nusemtl ink\nvp 0.5\nvn 0 0 1\nvt 0 0\n"
                     "v 0 0 0\nv 1 0 0\nv 0 1 0\ncstype bezier\ndeg 3\nstep 1 1\nbmat u 1\ncurv 0 1 1 2\n"
                     "curv2 1 2\nsurf 0 1 0 1 1 2\nparm u 0 1\ntrim 0 1 1\nhole 0 1 1\nscrv 0 1 1\nsp 1\n"
                     "end\ncon 1 0 1 1 2 0 1 1\nbevel off\nc_interp off\nd_interp off\nlod 1\nmaplib a.map\n"
                     "usemap off\nshadow_obj s.obj\ntrace_obj t.obj\nctech cparm 1\nstech cparma 1 1\n"
                     "call x.mod\ncsh -ls\nl 1 2\np 1\nf 1 2 3\n");
    const std::string out = info_of(dir / "all.obj");
    EXPECT_NE(out.find("vertices: 3\nfaces: 1\n"), std::string::npos) << out;
}

TEST_F(HostileReaders, ObjTextureCoordinateProblemsNameTheTextureCoordinate) {
    test::write_text(dir / "vt.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt inf 0\nf 1 2 3\n");
    expect_refused(dir / "vt.obj", "vt.obj:4: texture coordinate 'inf' is not finite");
}

TEST_F(HostileReaders, ObjFaceLineMayEndInAComment) {
    const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3 # first\nf 2 4 3 #second\n";
    test::write_text(dir / "c.obj", body);
    test::write_text(dir / "c_general.obj", " # read by the general reader\n" + body);
    for (const char* name : {"c.obj", "c_general.obj"}) {
        SCOPED_TRACE(name);
        const std::string out = info_of(dir / name);
        EXPECT_NE(out.find("vertices: 4\nfaces: 2\n"), std::string::npos) << out;
    }
}

TEST_F(HostileReaders, ObjFaceWithARepeatedCornerIsCountedInTheWarning) {
    const std::string body = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 2\nf 3 3 3 3\n";
    test::write_text(dir / "r.obj", body);
    test::write_text(dir / "r_general.obj", " # read by the general reader\n" + body);
    for (const char* name : {"r.obj", "r_general.obj"}) {
        SCOPED_TRACE(name);
        const std::string out = info_of(dir / name);
        EXPECT_NE(out.find("faces: 1\n"), std::string::npos) << out;
        EXPECT_NE(out.find(std::string(name) + ": skipped 2 face(s) with fewer than 3"), std::string::npos) << out;
    }
}

const std::string kOffSquare = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n";

TEST_F(HostileReaders, OffNumbersThatAreNotIntegersAreRefused) {
    // strtol read the leading digits: "2.7" was vertex 2, "1.5" faces was 1.
    for (const char* word : {"2.7", "2x", "2e5", "0x2"}) {
        test::write_text(dir / "f.off", "OFF\n4 1 0\n" + kOffSquare + "3 0 1 " + word + "\n");
        expect_refused(dir / "f.off", "f.off:7: '" + std::string(word) + "' is not an integer");
    }
    test::write_text(dir / "h.off", "OFF\n4 1.5 0\n" + kOffSquare + "3 0 1 2\n");
    expect_refused(dir / "h.off", "h.off:2: '1.5' is not an integer");
    test::write_text(dir / "n.off", "OFF\n-3 1 0\n" + kOffSquare + "3 0 1 2\n");
    expect_refused(dir / "n.off", "n.off:2: the element counts must not be negative");
}

TEST_F(HostileReaders, OffHoldingMoreThanItDeclaresIsRefused) {
    test::write_text(dir / "face.off", "OFF\n4 1 0\n" + kOffSquare + "3 0 1 2\n3 0 2 3\n");
    expect_refused(dir / "face.off", "face.off:8: data after the 4 vertices and 1 faces the header declares");
    test::write_text(dir / "junk.off", "OFF\n4 1 0\n" + kOffSquare + "3 0 1 2\ngarbage here\n");
    expect_refused(dir / "junk.off", "junk.off:8: data after the 4 vertices and 1 faces the header declares");
    test::write_text(dir / "fourth.off", "OFF\n4 1 0\n0 0 0\n1 0 0 0\n1 1 0\n0 1 0\n3 0 1 2\n");
    expect_refused(dir / "fourth.off", "fourth.off:4: unexpected '0' after the vertex's three coordinates");
    // What the format allows still reads: colours after vertices of COFF and after face indices,
    // comments and blank lines at the end, counts on the header line, a byte order mark.
    test::write_text(dir / "c.off", "COFF\n4 2 0\n0 0 0 1 0 0 1\n1 0 0 1 0 0 1\n1 1 0 1 0 0 1\n0 1 0 1 0 0 1\n"
                                    "3 0 1 2 0.5 0.5 0.5\n3 0 2 3 255 0 0\n# end\n\n");
    test::write_text(dir / "bom.off", kBom + "OFF 4 2\n" + kOffSquare + "3 0 1 2\n3 0 2 3\n");
    for (const char* name : {"c.off", "bom.off"}) {
        SCOPED_TRACE(name);
        const std::string out = info_of(dir / name);
        EXPECT_NE(out.find("vertices: 4\nfaces: 2\n"), std::string::npos) << out;
    }
}

TEST_F(HostileReaders, HexFloatInAsciiPlyIsRefusedWithItsLine) {
    // strtod read "0x1p3" as 8, where OBJ and OFF refuse it.
    for (const char* word : {"0x1p3", "0X1P0", "-0x.8p1"}) {
        test::write_text(dir / "hex.ply", ascii_ply_header(4, 2) + "0 0 0\n1 0 " + word + "\n1 1 0\n0 1 0\n" + kSquareFaces);
        expect_refused(dir / "hex.ply", "hex.ply:11: vertex 1: '" + std::string(word) + "' is not a decimal number");
    }
}

TEST_F(HostileReaders, PlyByteOrderMarkIsSkipped) {
    test::write_text(dir / "bom.ply", kBom + ascii_ply_header(4, 2) + "0 0 0\n1 0 0\n1 1 3\n0 1 0\n" + kSquareFaces);
    const std::string out = info_of(dir / "bom.ply");
    EXPECT_NE(out.find("vertices: 4\nfaces: 2\n"), std::string::npos) << out;
    EXPECT_NE(out.find("bounds: [0, 0, 0] .. [1, 1, 3]"), std::string::npos) << out;
}

TEST_F(HostileReaders, HexFloatInAsciiStlIsRefusedWithItsLine) {
    for (const char* word : {"0x1p0", "0X1P0", "-0x.8p1"}) {
        std::string facet = kFacet;
        facet.replace(facet.find("vertex 1 0 0"), 12, "vertex " + std::string(word) + " 0 0");
        test::write_text(dir / "hex.stl", "solid s\n" + facet + "endsolid s\n");
        expect_refused(dir / "hex.stl", "hex.stl:5: '" + std::string(word) + "' is not a decimal number in facet 0");
    }
}

TEST_F(HostileReaders, AsciiStlByteOrderMarkIsSkipped) {
    // Read as binary before: "declares 1818521189 triangles".
    test::write_text(dir / "bom.stl", kBom + "solid s\n" + kFacet + "endsolid s\n");
    const std::string out = info_of(dir / "bom.stl");
    EXPECT_NE(out.find("vertices: 3\nfaces: 1\n"), std::string::npos) << out;
}

TEST_F(HostileReaders, UpperCaseAsciiStlKeywordsAreNamedAsSuch) {
    test::write_text(dir / "facet.stl", "solid s\nFACET normal 0 0 1\nendsolid s\n");
    expect_refused(dir / "facet.stl",
                   "facet.stl:2: expected 'facet' or 'endsolid', found 'FACET' (STL keywords are lower case)");
    test::write_text(dir / "solid.stl", "SOLID s\n" + kFacet + "endsolid s\n");
    expect_refused(dir / "solid.stl", "solid.stl: ASCII STL must start with 'solid', found 'SOLID' (STL keywords are lower case)");
    std::string facet = kFacet;
    facet.replace(facet.find("outer"), 5, "OUTER");
    test::write_text(dir / "outer.stl", "solid s\n" + facet + "endsolid s\n");
    expect_refused(dir / "outer.stl", "outer.stl:3: expected 'outer' in facet 0, found 'OUTER' (STL keywords are lower case)");
}

// ---- class 9: --max-faces while reading ----

TEST_F(HostileReaders, MaxFacesIsCheckedWhileReadingEveryFormat) {
    std::string obj, off = "OFF\n4 40 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n", ply_faces, stl = "solid s\n";
    obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
    for (int i = 0; i < 40; ++i) {
        obj += "f 1 2 3\n";
        off += "3 0 1 2\n";
        ply_faces += "3 0 1 2\n";
        stl += kFacet;
    }
    test::write_text(dir / "m.obj", obj);
    test::write_text(dir / "m_general.obj", obj + " # read by the general reader\n");
    test::write_text(dir / "m.off", off);
    test::write_text(dir / "m.ply", ascii_ply_header(4, 40) + kSquareVertices + ply_faces);
    test::write_text(dir / "m.stl", stl + "endsolid s\n");
    for (const char* name : {"m.obj", "m_general.obj", "m.off", "m.ply", "m.stl"}) {
        expect_refused(dir / name, std::string(name) + ": more than 10 faces, the limit (raise it with --max-faces)",
                       "--max-faces 10");
    }
    // A binary STL says how many triangles it holds: refused from its header.
    write_bytes(dir / "big.stl", binary_stl(std::vector<std::vector<float>>(5000, kTriangle)));
    expect_refused(dir / "big.stl", "big.stl: declares 5000 triangles, more than the limit of 100 faces",
                   "--max-faces 100");
}

}  // namespace
}  // namespace inkline
