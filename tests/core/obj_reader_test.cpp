// SPDX-License-Identifier: MIT
#include "core/mesh/internal/obj_reader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "core/error.h"
#include "core/mesh/mesh_io.h"
#include "tests/support/obj.h"
#include "tests/support/shapes.h"

namespace inkline {
namespace {

namespace fs = std::filesystem;

// A line with a leading blank is one the fast reader always hands to the general reader
// (check_obj + OpenMesh), and one both of those ignore: appended to a file, it yields the
// general reader's result for the same content.
constexpr const char* kForceGeneralReader = "\n #\n";

class ObjReader : public ::testing::Test {
  protected:
    fs::path dir = test::fresh_temp_dir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    void TearDown() override { fs::remove_all(dir); }

    // Checks that the fast reader gives exactly the general reader's mesh and skipped-face
    // count, or declines what the general reader refuses. Returns whether it accepted.
    bool agrees(const std::string& text, const std::string& label) {
        SCOPED_TRACE(label);
        const std::optional<core::internal::ObjContents> fast = core::internal::read_plain_obj(text);
        const fs::path general_file = dir / "general.obj";
        test::write_text(general_file, text + kForceGeneralReader);
        std::optional<core::LoadedMesh> general;
        try {
            general = core::load_mesh(general_file);
        } catch (const InputError&) {
        }
        if (!fast) return false;
        if (fast->mesh.triangles.empty()) {
            // load_mesh refuses a mesh without faces, whichever reader read it.
            EXPECT_FALSE(general.has_value());
            return true;
        }
        EXPECT_TRUE(general.has_value()) << "the fast reader accepted what the general reader refuses";
        if (!general) return true;
        EXPECT_EQ(fast->mesh.triangles, general->mesh.triangles);
        EXPECT_EQ(fast->mesh.positions.size(), general->mesh.positions.size());
        if (fast->mesh.positions.size() == general->mesh.positions.size()) {
            // Bit for bit: the same float from the same text.
            size_t differing = 0;
            for (size_t i = 0; i < fast->mesh.positions.size(); ++i) {
                differing += fast->mesh.positions[i] != general->mesh.positions[i];
            }
            EXPECT_EQ(differing, 0u);
        }
        const std::string expected_warning =
            fast->short_faces ? ": skipped " + std::to_string(fast->short_faces) + " face(s) with fewer than 3 vertices"
                              : "";
        const std::string warning = general->warnings.empty() ? "" : general->warnings[0];
        EXPECT_EQ(warning.empty(), expected_warning.empty()) << warning;
        if (!expected_warning.empty()) {
            EXPECT_NE(warning.find(expected_warning), std::string::npos) << warning;
        }
        return true;
    }
};

TEST_F(ObjReader, GeneratedMeshesReadAsTheGeneralReaderReadsThem) {
    for (const auto& [name, mesh] :
         {std::pair{"torus", test::torus(1.0, 0.3, 24, 12)}, std::pair{"sphere", test::uv_sphere(16, 8, 1.0)}}) {
        const fs::path file = dir / "m.obj";
        test::write_obj(file, mesh);
        EXPECT_TRUE(agrees(test::read_text(file), name)) << name << ": declined";
    }
}

TEST_F(ObjReader, NumbersRoundAsTheGeneralReaderRoundsThem) {
    // Coordinates at full double precision, halfway cases of float rounding, exponents.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> uniform(-3.0, 3.0);
    std::string text;
    char buffer[64];
    for (int i = 0; i < 3000; ++i) {
        const double v = uniform(rng) * std::pow(10.0, double(int(rng() % 13) - 6));
        std::snprintf(buffer, sizeof buffer, i % 3 == 0 ? "%.17g" : i % 3 == 1 ? "%.9e" : "%.6f", v);
        text += (i % 3 == 0 ? "v " : " ") + std::string(buffer) + (i % 3 == 2 ? "\n" : "");
    }
    text += "v .5 -.25 1.\nv 3E+2 1e-3 -0\nv 16777217 0.1000000000000000055511151231257827 1.00000005960464477539\n";
    text += "f 1 2 3\n";
    EXPECT_TRUE(agrees(text, "numbers"));
}

TEST_F(ObjReader, FaceFormsMatchTheGeneralReader) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\n";
    const std::pair<const char*, std::string> cases[] = {
        {"slashes",
         vertices + "vt 0 0\nvt 1 0\nvt 1 1\nvn 0 0 1\nf 1/1 2/2 3/3\nf 1/1/1 3/3/1 4/2/1\nf 1//1 2//1 5//1\n"},
        {"negative", vertices + "f -5 -4 -3\nv 2 2 2\nf -1 -2 -3 -4\n"},
        {"polygons", vertices + "f 1 2 3 4 5\n"},
        {"repeated corners", vertices + "f 1 2 2 3\nf 1 1 2\nf 4 4 4\n"},
        {"short faces", vertices + "f 1 2\nf 3\nf 1 2 3\n"},
        {"faces first", "f 1 2 3\n" + vertices},
        {"comments and groups", "# made by hand\no thing\ng part\ns off\nusemtl ink\nmtllib none.mtl\n" + vertices +
                                    "l 1 2\nvp 0.5\nf 1 2 3\n"},
        {"CRLF, tabs, trailing blanks", "v 0 0 0\r\nv\t1 0 0  \r\nv 1\t1 0\r\n\r\nf 1 2 3\t\r\n"},
        {"no final newline", vertices + "f 1 2 3"},
        {"extra numbers", "v 0 0 0 1 0 0\nv 1 0 0 0.5\nv 1 1 0\nf 1 2 3\n"},
        {"byte order mark", "\xef\xbb\xbf" + vertices + "f 1 2 3\n"},
        {"comments after faces", vertices + "f 1 2 3 # first\nf 1 3 4 #second\nf 1 1 2 # repeated\n"},
    };
    for (const auto& [name, text] : cases) EXPECT_TRUE(agrees(text, name)) << name << ": declined";
}

TEST_F(ObjReader, UnknownStatementsAreLeftToTheGeneralReaderWhichRefusesThem) {
    // OpenMesh skips an unknown keyword: "V" would drop a vertex and shift every later index.
    const std::string text = "v 0 0 0\nV 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    EXPECT_FALSE(core::internal::read_plain_obj(text).has_value());
    test::write_text(dir / "v.obj", text);
    try {
        core::load_mesh(dir / "v.obj");
        ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("v.obj:2: unknown statement 'V'"), std::string::npos) << e.what();
    }
}

TEST_F(ObjReader, LongPolygonsDropRepeatedCornersAsTheGeneralReaderDoes) {
    // Over 64 corners the repeats are found by sorting: same corners kept, same order.
    std::string text;
    for (int i = 0; i < 300; ++i) {
        const double a = 6.283185307179586 * i / 300.0;
        text += "v " + std::to_string(std::cos(a)) + " " + std::to_string(std::sin(a)) + " 0\n";
    }
    text += "f";
    for (int i = 0; i < 1000; ++i) text += " " + std::to_string(1 + (i * 7) % 300);
    text += "\nf";
    for (int i = 0; i < 200; ++i) text += " " + std::to_string(i % 3 == 0 ? 1 : 2 + i);
    text += "\n";
    EXPECT_TRUE(agrees(text, "long polygons"));
}

TEST_F(ObjReader, DeclinesWhatItCannotReadExactly) {
    const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
    const std::pair<const char*, std::string> cases[] = {
        {"out of range", vertices + "f 1 2 4\n"},
        {"zero index", vertices + "f 0 1 2\n"},
        {"negative beyond the start", vertices + "f -1 -2 -4\n"},
        {"nan", "v nan 0 0\n" + vertices + "f 1 2 3\n"},
        {"inf", "v 0 inf 0\n" + vertices + "f 1 2 3\n"},
        {"plus sign", "v +1 0 0\n" + vertices + "f 1 2 3\n"},
        {"hex", "v 0x1p3 0 0\n" + vertices + "f 1 2 3\n"},
        {"astronomical", "v 1e19 0 0\n" + vertices + "f 1 2 3\n"},
        {"two numbers", "v 1 0\n" + vertices + "f 1 2 3\n"},
        {"leading blank", " v 1 0 0\n" + vertices + "f 1 2 3\n"},
        {"bad texture coordinate", vertices + "vt x y\nf 1 2 3\n"},
        {"garbage corner", vertices + "f 1 2 3x\n"},
        {"empty face", vertices + "f\nf 1 2 3\n"},
        {"lone carriage return", vertices + "f 1 2\r3\n"},
        {"form feed", vertices + "f 1 2 3\f\n"},
        {"long index", vertices + "f 1 2 0000000003\n"},
    };
    for (const auto& [name, text] : cases) {
        EXPECT_FALSE(agrees(text, name)) << name << ": accepted";
    }
}

TEST_F(ObjReader, FuzzCorpusObjInputsAgreeWithTheGeneralReader) {
    // tests/fuzz/targets.cpp reads a corpus file as OBJ when its first byte is 0 mod 4.
    size_t obj_inputs = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(INKLINE_FUZZ_CORPUS) / "mesh")) {
        std::ifstream in(entry.path(), std::ios::binary);
        const std::string data{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        if (data.empty() || uint8_t(data[0]) % 4 != 0) continue;
        ++obj_inputs;
        agrees(data.substr(1), entry.path().filename().string());
    }
    EXPECT_GT(obj_inputs, 0u);
}

// "o" groups name objects; without any "o", "g" groups (by their first name) do; triangles before
// the first are "default"; a name that comes back is the same object; one name is no objects.
TEST_F(ObjReader, GroupsBecomeObjects) {
    const auto objects_of = [](const std::string& text, std::vector<std::string>& r_names) {
        const std::optional<core::internal::ObjContents> obj = core::internal::read_plain_obj(text);
        EXPECT_TRUE(obj.has_value());
        std::vector<uint32_t> faces;
        core::internal::obj_objects(*obj, r_names, faces);
        EXPECT_TRUE(faces.empty() || faces.size() == obj->mesh.triangles.size());
        return faces;
    };
    const std::string v = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    std::vector<std::string> names;
    EXPECT_EQ(objects_of(v + "o A\nf 1 2 3\ng skin\nf 2 4 3\no B\nf 1 2 4 3\no A\nf 1 3 4\n", names),
              (std::vector<uint32_t>{0, 0, 1, 1, 0}));
    EXPECT_EQ(names, (std::vector<std::string>{"A", "B"}));
    EXPECT_EQ(objects_of(v + "f 1 2 3\ng left side\nf 2 4 3\n", names), (std::vector<uint32_t>{0, 1}));
    EXPECT_EQ(names, (std::vector<std::string>{"default", "left"}));
    EXPECT_TRUE(objects_of(v + "o Only\nf 1 2 3\nf 2 4 3\n", names).empty());
    EXPECT_TRUE(names.empty());
    // Read in parallel pieces, the groups keep their triangles.
    std::string big = v;
    // (over the 1 MiB above which the reader splits the text).
    for (int k = 0; k < 160000; ++k) big += (k % 40000 == 0 ? "o part" + std::to_string(k / 40000) + "\n" : "") + "f 1 2 3 # padding\n";
    const std::vector<uint32_t> faces = objects_of(big, names);
    ASSERT_GT(big.size(), size_t(1) << 21);
    ASSERT_EQ(faces.size(), 160000u);
    EXPECT_EQ(names.size(), 4u);
    for (size_t f = 0; f < faces.size(); ++f) ASSERT_EQ(faces[f], f / 40000) << f;
}

}  // namespace
}  // namespace inkline
