// SPDX-License-Identifier: MIT
#include "core/mesh/mesh_io.h"

#include "core/error.h"
#include "tests/support/obj.h"
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>

namespace inkline {
namespace {

namespace fs = std::filesystem;

class MeshIo : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    std::string error_of(const fs::path& path) {
        try {
            core::load_mesh(path);
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }
};

TEST_F(MeshIo, ReadsEveryFormatToTheSameTriangles) {
    // A unit square split into two triangles, written as OBJ, OFF, PLY (ascii) and STL (ascii).
    test::write_text(dir / "q.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    test::write_text(dir / "q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    test::write_text(dir / "q.ply",
                     "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                     "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    test::write_text(dir / "q.stl",
                     "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
                     "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
                     "vertex 0 1 0\nendloop\nendfacet\nendsolid q\n");
    for (const char* name : {"q.obj", "q.off", "q.ply", "q.stl"}) {
        const core::LoadedMesh loaded = core::load_mesh(dir / name);
        EXPECT_EQ(loaded.mesh.triangles.size(), 2u) << name;
        EXPECT_EQ(loaded.mesh.positions.size(), 4u) << name;
        for (const auto& t : loaded.mesh.triangles) {
            EXPECT_GT(core::face_normal(loaded.mesh.positions, t).z, 0.0) << name << ": winding kept";
        }
    }
}

TEST_F(MeshIo, RoundTripsAGeneratedMesh) {
    const core::Mesh torus = test::torus(1.0, 0.3, 16, 8);
    test::write_obj(dir / "torus.obj", torus);
    const core::LoadedMesh loaded = core::load_mesh(dir / "torus.obj");
    EXPECT_EQ(loaded.mesh.triangles, torus.triangles);
    ASSERT_EQ(loaded.mesh.positions.size(), torus.positions.size());
    EXPECT_NEAR(loaded.mesh.positions[5].x, torus.positions[5].x, 1e-6);
}

TEST_F(MeshIo, MissingFileNamesTheFile) {
    const std::string error = error_of(dir / "nope.obj");
    EXPECT_NE(error.find("nope.obj"), std::string::npos);
    EXPECT_NE(error.find("not found"), std::string::npos);
}

TEST_F(MeshIo, EmptyFileIsAnError) {
    test::write_text(dir / "empty.obj", "");
    EXPECT_NE(error_of(dir / "empty.obj").find("empty"), std::string::npos);
}

TEST_F(MeshIo, MeshWithoutFacesIsAnError) {
    test::write_text(dir / "points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    EXPECT_NE(error_of(dir / "points.obj").find("no faces"), std::string::npos);
}

TEST_F(MeshIo, OutOfRangeIndexIsAnError) {
    test::write_text(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n");
    const std::string error = error_of(dir / "bad.obj");
    EXPECT_NE(error.find("bad.obj"), std::string::npos);
    EXPECT_NE(error.find("references a vertex that does not exist"), std::string::npos) << error;
}

TEST_F(MeshIo, NonFiniteCoordinateNamesTheLine) {
    for (const char* value : {"nan", "inf", "-INF"}) {
        test::write_text(dir / "bad.obj", std::string("v 0 0 0\nv ") + value + " 0 0\nv 0 1 0\nv 1 1 0\nf 1 3 4\n");
        const std::string error = error_of(dir / "bad.obj");
        EXPECT_NE(error.find("bad.obj:2: vertex has a non-finite coordinate"), std::string::npos) << error;
    }
}

TEST_F(MeshIo, NonFiniteOffCoordinateNamesTheLine) {
    test::write_text(dir / "nan.off", "OFF\n# comment\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
    const std::string error = error_of(dir / "nan.off");
    EXPECT_NE(error.find("nan.off:5: vertex has a non-finite coordinate"), std::string::npos) << error;
}

TEST_F(MeshIo, AstronomicalCoordinateIsAnError) {
    test::write_text(dir / "big.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string error = error_of(dir / "big.obj");
    EXPECT_NE(error.find("big.obj:2: coordinate"), std::string::npos) << error;
    EXPECT_NE(error.find("exceeds the limit"), std::string::npos) << error;
}

TEST_F(MeshIo, CoordinateLimitHoldsForTheTextNotItsFloat) {
    // 1.00000001e18 rounds to a float below the limit, but the text is above it.
    test::write_text(dir / "over.obj", "v 0 0 0\nv 1.00000001e18 0 0\nv 0 1 0\nf 1 2 3\n");
    const std::string error = error_of(dir / "over.obj");
    EXPECT_NE(error.find("over.obj:2: coordinate"), std::string::npos) << error;
    test::write_text(dir / "at.obj", "v 0 0 0\nv -1e18 0 0\nv 0 4e17 0\nf 1 2 3\n");
    const core::LoadedMesh at = core::load_mesh(dir / "at.obj");
    EXPECT_EQ(at.mesh.positions[1].x, -1e18f);
    EXPECT_EQ(at.mesh.positions[2].y, 4e17f);
}

TEST_F(MeshIo, ZeroAndOutOfRangeRelativeIndicesAreErrors) {
    for (const char* face : {"f 0 1 2", "f -5 -2 -1", "f 1 2 4"}) {
        test::write_text(dir / "idx.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + face + "\n");
        const std::string error = error_of(dir / "idx.obj");
        EXPECT_NE(error.find("references a vertex that does not exist"), std::string::npos) << face << ": " << error;
    }
    // Valid relative indices still work.
    test::write_text(dir / "rel.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
    EXPECT_EQ(core::load_mesh(dir / "rel.obj").mesh.triangles.size(), 1u);
}

TEST_F(MeshIo, ShortFacesAreSkippedWithAWarning) {
    test::write_text(dir / "short.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\nf 1 2 3\n");
    const core::LoadedMesh loaded = core::load_mesh(dir / "short.obj");
    EXPECT_EQ(loaded.mesh.triangles.size(), 1u);
    ASSERT_EQ(loaded.warnings.size(), 1u);
    EXPECT_NE(loaded.warnings[0].find("fewer than 3 vertices"), std::string::npos);
}

TEST_F(MeshIo, BinaryGarbageIsAnError) {
    std::string garbage;
    uint32_t x = 12345;
    for (int i = 0; i < 4096; ++i) {
        x = x * 1664525u + 1013904223u;
        garbage.push_back(char(x >> 24));
    }
    for (const char* name : {"garbage.obj", "garbage.off", "garbage.ply", "garbage.stl"}) {
        test::write_text(dir / name, garbage);
        EXPECT_NE(error_of(dir / name).find(name), std::string::npos) << name;
    }
}

// Found by the fuzz seed corpus: OpenMesh reserved memory for the declared counts first.
TEST_F(MeshIo, HeaderCountsBeyondTheFileSizeAreRefused_fuzz_huge_counts) {
    test::write_text(dir / "huge.off", "OFF\n99999999 99999999 0\n0 0 0\n");
    EXPECT_NE(error_of(dir / "huge.off").find("more than the file's"), std::string::npos);
    // The fuzzer's variants: separators on the keyword line, and a face claiming 2e9 corners.
    test::write_text(dir / "sep.off", "OFF\x1c\x1c\x1c\n99999999 9-\nproperty 0 0\nt ");
    EXPECT_NE(error_of(dir / "sep.off").find("sep.off:1: not an OFF file"), std::string::npos) << error_of(dir / "sep.off");
    test::write_text(dir / "counts.off", "OFF\n99999999 9\n0 0 0\n");
    EXPECT_NE(error_of(dir / "counts.off").find("counts.off:2: declares 99999999 vertices"), std::string::npos)
        << error_of(dir / "counts.off");
    test::write_text(dir / "corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n");
    EXPECT_NE(error_of(dir / "corners.off").find("corners.off:6: expected a face's corner count"), std::string::npos)
        << error_of(dir / "corners.off");
    test::write_text(dir / "binary.off", "OFF BINARY\n");
    EXPECT_NE(error_of(dir / "binary.off").find("binary OFF is not supported"), std::string::npos);
    test::write_text(dir / "huge.ply",
                     "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\n"
                     "property float y\nproperty float z\nend_header\n");
    EXPECT_NE(error_of(dir / "huge.ply").find("more than the file's"), std::string::npos);
}

// Found by tests/fuzz/run.sh: OpenMesh's PLY reader crashed on a property before any element.
TEST_F(MeshIo, MalformedPlyHeaderIsRefused_fuzz_crash_2c8c58c8) {
    test::write_text(dir / "p.ply", "ply\nformat ascii 1.0\nelemex\nproperty float y\nelement face 2\n"
                                    "property list uchar int vertex_indices\nend_header\n0 0 0\n");
    EXPECT_NE(error_of(dir / "p.ply").find("p.ply:3: malformed PLY header"), std::string::npos) << error_of(dir / "p.ply");
    test::write_text(dir / "q.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n");
    EXPECT_NE(error_of(dir / "q.ply").find("q.ply:3: malformed PLY header: a property before any element"),
              std::string::npos);
}

// Found by tests/fuzz/run.sh: OpenMesh's PLY header loop never ends once a numeric token fails.
TEST_F(MeshIo, PlyHeaderWithABadVersionIsRefused_fuzz_hang) {
    test::write_text(dir / "v.ply", std::string("ply\nformat ascii \x01\x01") + "0\nelement vertex 3\nproperty float x\n"
                                    "end_header\n0\n1\n2\n");
    EXPECT_NE(error_of(dir / "v.ply").find("v.ply:2: malformed PLY header: unsupported version"), std::string::npos)
        << error_of(dir / "v.ply");
    test::write_text(dir / "c.ply", "ply\nformat ascii 1.0\nelement vertex 9999999999\nproperty float x\nend_header\n");
    EXPECT_NE(error_of(dir / "c.ply").find("c.ply:3: malformed PLY header"), std::string::npos) << error_of(dir / "c.ply");
}

// Found by tests/fuzz/run.sh: OpenMesh's OBJ reader asserts on a face corner that is no index.
TEST_F(MeshIo, ObjFaceCornersMustBeIndices_fuzz_crash_631a40f6) {
    for (const char* face : {"f - / 1", "f 1 2 x", "f 1/ 2 3", "f 1//2/3 2 3", " \tf /01", "f", "  f  "}) {
        test::write_text(dir / "c.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\n") + face + "\n");
        EXPECT_NE(error_of(dir / "c.obj").find("c.obj:4: face"), std::string::npos) << face << ": " << error_of(dir / "c.obj");
    }
    test::write_text(dir / "ok.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 -1/1\n");
    EXPECT_EQ(core::load_mesh(dir / "ok.obj").mesh.triangles.size(), 1u);
}

// Found by tests/fuzz/run.sh: OpenMesh collects as many corners as a face list's count says.
TEST_F(MeshIo, PlyFaceListCountsMustFitTheirLine_fuzz_oom_39421bb9) {
    const std::string header = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\nelement face 1\nproperty list int int vertex_indices\nend_header\n"
                               "0 0 0\n1 0 0\n0 1 0\n";
    test::write_text(dir / "l.ply", header + "2000000000 0 1 2\n");
    EXPECT_NE(error_of(dir / "l.ply").find("l.ply: a face list (element 0) declares '2000000000' values"), std::string::npos)
        << error_of(dir / "l.ply");
    // OpenMesh reads ASCII PLY token by token: elements need not stand one per line.
    test::write_text(dir / "tokens.ply", header.substr(0, header.size() - 18) + "0 0 0 1 0 0 0 1 0 -2 0 1\n");
    EXPECT_NE(error_of(dir / "tokens.ply").find("declares '-2' values"), std::string::npos) << error_of(dir / "tokens.ply");
    // Found by the fuzzer: a CR alone after end_header put the data on the header's last line.
    test::write_text(dir / "cr.ply", header.substr(0, header.find("end_header") + 10) + "\r0 0 0 1 0 0 0 1 0 -2 0 1\n");
    EXPECT_NE(error_of(dir / "cr.ply").find("data on the end_header line"), std::string::npos) << error_of(dir / "cr.ply");
    test::write_text(dir / "glued.ply", header.substr(0, header.size() - 18) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2-1\n");
    EXPECT_NE(error_of(dir / "glued.ply").find("face 0: '2-1' is not a number"), std::string::npos) << error_of(dir / "glued.ply");
    test::write_text(dir / "ok.ply", header + "3 0 1 2\n");
    EXPECT_EQ(core::load_mesh(dir / "ok.ply").mesh.triangles.size(), 1u);
    test::write_text(dir / "b.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                                    "property list uint int vertex_indices\nend_header\n" + std::string(16, '\0'));
    EXPECT_NE(error_of(dir / "b.ply").find("binary PLY with uint list counts is not supported"), std::string::npos)
        << error_of(dir / "b.ply");
}

TEST_F(MeshIo, UnknownExtensionIsAnError) {
    test::write_text(dir / "mesh.xyz", "garbage");
    EXPECT_NE(error_of(dir / "mesh.xyz").find("cannot read"), std::string::npos);
}

// A binary STL of two triangles of a unit square, written by hand.
std::string square_binary_stl() {
    std::string out = "solid written by a tool that starts binary headers with solid" + std::string(18, ' ');
    out.resize(80, ' ');
    const uint32_t count = 2;
    out.append(reinterpret_cast<const char*>(&count), 4);
    for (const std::array<float, 12>& t : {std::array<float, 12>{0, 0, 1, 0, 0, 0, 1, 0, 0, 1, 1, 0},
                                           std::array<float, 12>{0, 0, 1, 0, 0, 0, 1, 1, 0, 0, 1, 0}}) {
        out.append(reinterpret_cast<const char*>(t.data()), 48);
        out.append(2, '\0');
    }
    return out;
}

// The unit square as binary PLY in either byte order, with properties and an element inkline
// does not use, of every size.
std::string square_binary_ply(bool big_endian) {
    std::string out = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                      " 1.0\ncomment c\nelement vertex 4\nproperty double x\nproperty float y\nproperty short z\n"
                      "property uchar red\nelement face 2\nproperty list uchar uint vertex_indices\nproperty float q\n"
                      "element edge 1\nproperty int a\nproperty ushort b\nend_header\n";
    auto put = [&](auto value) {
        char raw[sizeof(value)];
        std::memcpy(raw, &value, sizeof(value));
        if (big_endian) std::reverse(raw, raw + sizeof(value));
        out.append(raw, sizeof(value));
    };
    for (const std::array<int, 3>& v : {std::array<int, 3>{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}) {
        put(double(v[0]));
        put(float(v[1]));
        put(int16_t(v[2]));
        put(uint8_t(7));
    }
    for (const std::array<uint32_t, 3>& f : {std::array<uint32_t, 3>{0, 1, 2}, {0, 2, 3}}) {
        put(uint8_t(3));
        for (uint32_t i : f) put(i);
        put(0.5f);
    }
    put(int32_t(0));
    put(uint16_t(1));
    return out;
}

TEST_F(MeshIo, BinaryPlyAndStlReadAsTheSquare) {
    test::write_text(dir / "le.ply", square_binary_ply(false));
    test::write_text(dir / "be.ply", square_binary_ply(true));
    test::write_text(dir / "b.stl", square_binary_stl());
    for (const char* name : {"le.ply", "be.ply", "b.stl"}) {
        const core::LoadedMesh loaded = core::load_mesh(dir / name);
        EXPECT_EQ(loaded.mesh.triangles.size(), 2u) << name;
        EXPECT_EQ(loaded.mesh.positions.size(), 4u) << name << ": STL corners at one place share a vertex";
        EXPECT_TRUE(loaded.warnings.empty()) << name;
        for (const auto& t : loaded.mesh.triangles) {
            EXPECT_GT(core::face_normal(loaded.mesh.positions, t).z, 0.0) << name;
        }
    }
}

// A binary file ends exactly where its data does: every shorter prefix is refused.
TEST_F(MeshIo, EveryTruncationOfABinaryMeshIsRefused) {
    for (const auto& [name, whole] : {std::pair<std::string, std::string>{"t.stl", square_binary_stl()},
                                      {"le.ply", square_binary_ply(false)},
                                      {"be.ply", square_binary_ply(true)}}) {
        for (size_t cut = 1; cut < whole.size(); ++cut) {
            test::write_text(dir / name, whole.substr(0, cut));
            EXPECT_NE(error_of(dir / name).find(name), std::string::npos) << name << " cut at " << cut;
        }
    }
}

// ASCII PLY and STL cut at any line end before their last element are refused.
TEST_F(MeshIo, EveryTruncationOfAnAsciiMeshAtALineEndIsRefused) {
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
    const std::string facet = "facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n";
    const std::string stl = "solid s\n" + facet + facet + "endsolid s\n";
    for (const auto& [name, whole] : {std::pair<std::string, std::string>{"a.ply", ply}, {"a.stl", stl}}) {
        ASSERT_NO_THROW(core::load_mesh((test::write_text(dir / name, whole), dir / name)));
        for (size_t cut = whole.find('\n'); cut + 1 < whole.size(); cut = whole.find('\n', cut + 1)) {
            test::write_text(dir / name, whole.substr(0, cut + 1));
            EXPECT_NE(error_of(dir / name).find(name), std::string::npos) << name << " cut at " << cut;
            test::write_text(dir / name, whole.substr(0, cut));  // and without the line end
            EXPECT_NE(error_of(dir / name).find(name), std::string::npos) << name << " cut at " << cut;
        }
    }
}

TEST_F(MeshIo, FaceLimitStopsReadingEveryFormat) {
    test::write_text(dir / "q.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
    test::write_text(dir / "q.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
    test::write_text(dir / "q.ply", square_binary_ply(false));
    test::write_text(dir / "q.stl", square_binary_stl());
    for (const char* name : {"q.obj", "q.off", "q.ply", "q.stl"}) {
        EXPECT_EQ(core::load_mesh(dir / name, {2}).mesh.triangles.size(), 2u) << name << ": at the limit";
        try {
            core::load_mesh(dir / name, {1});
            ADD_FAILURE() << name << ": over the limit but read";
        } catch (const InputError& e) {
            const std::string message = e.what();
            const std::string file = (dir / name).string();
            EXPECT_TRUE(message.find(file + ": more than 1 faces, the limit") == 0 ||
                        message.find(file + ": declares 2 triangles, more than the limit of 1 faces") == 0)
                << message;
        }
    }
}

TEST_F(MeshIo, CoordinatesBeyondFloatRangeInTheGeneralObjReaderAreRefused) {
    // Values beyond float range pass check_obj's double test but not OpenMesh's float read.
    for (const char* line : {"v 0 1e39 0", "v 0 0 -1e39"}) {
        test::write_text(dir / "f.obj", std::string(" # general reader\nv 0 0 0\n") + line + "\nv 0 1 0\nf 1 2 3\n");
        EXPECT_NE(error_of(dir / "f.obj").find("f.obj:3: coordinate"), std::string::npos) << error_of(dir / "f.obj");
    }
}

}  // namespace
}  // namespace inkline
