// SPDX-License-Identifier: MIT
// glTF shots built in code: world-space positions against hand-computed ones for the hierarchy,
// each sampler kind, morph targets and skins; cameras; .gltf and .glb alike; welding; broken
// files refused with one line naming the element.
#include "core/scene/gltf_shot.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/gtc/constants.hpp>
#include <glm/trigonometric.hpp>
#include <string>

#include "core/error.h"
#include "core/mesh/topology.h"
#include "core/scene/scene.h"
#include "tests/support/gltf.h"
#include "tests/support/shapes.h"

namespace inkline {
namespace {

namespace fs = std::filesystem;
using test::GltfBuilder;

class GltfShotTest : public ::testing::Test {
  protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() / ("inkline_gltf_test_" + std::to_string(::getpid()) + "_" +
                                            ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::create_directories(dir_);
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path write(const GltfBuilder& b, const std::string& name, const std::string& bin = "") {
        const fs::path p = dir_ / name;
        b.write(p, bin);
        return p;
    }
    core::GltfShot load(const GltfBuilder& b, const core::GltfOptions& options = {}) {
        return core::GltfShot(write(b, "shot.gltf"), options);
    }
    // The InputError message of loading `b`, or "" when it loads.
    std::string error_of(const GltfBuilder& b, const std::string& name = "shot.gltf") {
        try {
            core::GltfShot shot(write(b, name));
        } catch (const InputError& e) {
            return e.what();
        }
        return "";
    }

    fs::path dir_;
};

// One triangle in the z = 0 plane.
const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

void expect_near(const glm::vec3& a, const glm::dvec3& b, double tol = 1e-5) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Adds an animation channel on `node` with the given times, values and interpolation.
void animate(GltfBuilder& b, int node, const std::string& path, const std::vector<float>& times,
             const std::vector<float>& values, const std::string& interpolation, const std::string& type) {
    const int input = b.floats(times, "SCALAR");
    const int output = b.floats(values, type);
    auto& doc = b.json();
    if (!doc.contains("animations")) doc["animations"] = nlohmann::json::array({{{"channels", nlohmann::json::array()}, {"samplers", nlohmann::json::array()}}});
    auto& anim = doc["animations"][0];
    anim["samplers"].push_back({{"input", input}, {"output", output}, {"interpolation", interpolation}});
    anim["channels"].push_back({{"sampler", anim["samplers"].size() - 1}, {"target", {{"node", node}, {"path", path}}}});
}

TEST_F(GltfShotTest, HierarchyPlacesEachInstanceThroughItsParents) {
    GltfBuilder b;
    const int parent = b.node("parent");
    const int child = b.mesh_node("child", kTriangle, {0, 1, 2});
    b.add_child(parent, child);
    auto& nodes = b.json()["nodes"];
    nodes[size_t(parent)]["translation"] = {10, 0, 0};
    nodes[size_t(parent)]["rotation"] = {0, 0, std::sin(glm::quarter_pi<double>()), std::cos(glm::quarter_pi<double>())};  // 90 deg about z
    nodes[size_t(child)]["scale"] = {2, 2, 2};
    nodes[size_t(child)]["translation"] = {0, 1, 0};
    b.finish_scene();
    const core::GltfShot shot = load(b);
    const auto& p = shot.rest().positions;
    ASSERT_EQ(p.size(), 3u);
    // child: (x, y) -> (2x, 2y + 1); parent: rotate 90 deg about z, (x, y) -> (-y, x), then +10 in x.
    expect_near(p[0], {10 - 1, 0, 0});
    expect_near(p[1], {10 - 1, 2, 0});
    expect_near(p[2], {10 - 3, 0, 0});
    ASSERT_EQ(shot.objects().size(), 1u);
    EXPECT_EQ(shot.objects()[0].name, "child");
    EXPECT_FALSE(shot.deforms());
    EXPECT_FALSE(shot.frame_range().has_value());
}

TEST_F(GltfShotTest, MatrixNodesAndSharedMeshesGiveOneObjectPerInstance) {
    GltfBuilder b;
    const int a = b.mesh_node("a", kTriangle, {0, 1, 2});
    const int c = b.node("b");
    b.json()["nodes"][size_t(c)]["mesh"] = 0;  // the same mesh again
    b.json()["nodes"][size_t(c)]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 5, 6, 7, 1};
    (void)a;
    b.finish_scene();
    const core::GltfShot shot = load(b);
    ASSERT_EQ(shot.objects().size(), 2u);
    ASSERT_EQ(shot.rest().triangles.size(), 2u);
    EXPECT_EQ(shot.face_objects()[1], 1u);
    expect_near(shot.rest().positions[3], {5, 6, 7});
}

// The cube's triangles, wound counterclockwise seen from outside, as a glTF mesh; every node
// named in `nodes` gets an instance of it.
void add_cube_mesh(GltfBuilder& b) {
    const core::Mesh cube = test::cube(0.5);
    std::vector<float> positions;
    for (const glm::vec3& p : cube.positions) positions.insert(positions.end(), {p.x, p.y, p.z});
    std::vector<uint32_t> indices;
    for (const glm::uvec3& t : cube.triangles) indices.insert(indices.end(), {t.x, t.y, t.z});
    b.mesh_node("plain", positions, indices);
}

// Faces of each object whose normal points towards the object's middle (none on a closed
// convex object facing out).
std::vector<size_t> inward_faces(const core::GltfShot& shot) {
    const core::Mesh& mesh = shot.rest();
    std::vector<size_t> inward;
    for (const core::GltfObject& o : shot.objects()) {
        glm::dvec3 middle(0.0);
        for (uint32_t f = o.first_face; f < o.first_face + o.faces; ++f) {
            for (int k = 0; k < 3; ++k) middle += glm::dvec3(mesh.positions[mesh.triangles[f][k]]) / (3.0 * o.faces);
        }
        size_t count = 0;
        for (uint32_t f = o.first_face; f < o.first_face + o.faces; ++f) {
            const glm::uvec3 t = mesh.triangles[f];
            const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
            if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - middle) < 0.0) ++count;
        }
        inward.push_back(count);
    }
    return inward;
}

TEST_F(GltfShotTest, MirroredNodesTurnTheirTrianglesToFaceOut) {
    GltfBuilder b;
    add_cube_mesh(b);
    auto& nodes = b.json()["nodes"];
    auto instance = [&](const std::string& name) {
        const int n = b.node(name);
        nodes[size_t(n)]["mesh"] = 0;
        return n;
    };
    nodes[size_t(instance("mirrored"))]["scale"] = {-1, 1, 1};
    const int flip = b.node("flip");
    nodes[size_t(flip)]["scale"] = {1, -2, 1};
    b.add_child(flip, instance("mirrored by its parent"));
    const int flop = b.node("flop");
    nodes[size_t(flop)]["scale"] = {1, 1, -1};
    const int twice = instance("mirrored twice");
    nodes[size_t(twice)]["scale"] = {-1, 1, 1};
    b.add_child(flop, twice);
    nodes[size_t(instance("matrix"))]["matrix"] = {0, 0, 3, 0, 0, 1, 0, 0,
                                                   1, 0, 0, 0, 4, 0, 0, 1};  // x and z swapped: a mirror
    b.finish_scene();

    const core::GltfShot shot = load(b);
    ASSERT_EQ(shot.objects().size(), 5u);
    EXPECT_EQ(inward_faces(shot), std::vector<size_t>(5, 0));
    EXPECT_TRUE(shot.warnings().empty());

    // A scale key that turns the cube inside out on the way: the first frame's winding is kept,
    // and a warning names the node.
    GltfBuilder c;
    add_cube_mesh(c);
    animate(c, 0, "scale", {0.0f, 1.0f}, {1, 1, 1, -1, 1, 1}, "LINEAR", "VEC3");
    c.finish_scene();
    const core::GltfShot turning = load(c);
    EXPECT_EQ(inward_faces(turning), std::vector<size_t>{0});
    ASSERT_EQ(turning.warnings().size(), 1u);
    EXPECT_NE(turning.warnings()[0].find("nodes[0] ('plain') is mirrored at some times and not at others"),
              std::string::npos)
        << turning.warnings()[0];
}

TEST_F(GltfShotTest, EachSamplerKindInterpolatesAsTheSpecificationSays) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    animate(b, n, "translation", {1.0f, 2.0f}, {0, 0, 0, 4, 0, 0}, "LINEAR", "VEC3");
    core::GltfOptions options;
    options.fps = 10.0;  // frame 15 is t = 1.5 s
    {
        const core::GltfShot shot = load(b, options);
        EXPECT_TRUE(shot.deforms());
        ASSERT_TRUE(shot.frame_range());
        EXPECT_EQ(shot.frame_range()->first, 10);
        EXPECT_EQ(shot.frame_range()->second, 20);
        std::vector<glm::vec3> p;
        shot.positions_at(15, p);
        expect_near(p[0], {2, 0, 0});
        shot.positions_at(0, p);  // before the first key: the first value
        expect_near(p[0], {0, 0, 0});
        shot.positions_at(99, p);  // after the last: the last value
        expect_near(p[0], {4, 0, 0});
    }
    b.json()["animations"][0]["samplers"][0]["interpolation"] = "STEP";
    {
        const core::GltfShot shot = load(b, options);
        std::vector<glm::vec3> p;
        shot.positions_at(19, p);
        expect_near(p[0], {0, 0, 0});
        shot.positions_at(20, p);
        expect_near(p[0], {4, 0, 0});
    }
}

TEST_F(GltfShotTest, CubicSplineUsesTangentsScaledByTheKeyInterval) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    // Keys at t = 0 and 2: value 0 with out-tangent 1, value 1 with in-tangent 0 (x only).
    animate(b, n, "translation", {0.0f, 2.0f},
            {0, 0, 0, 0, 0, 0, 1, 0, 0,   // in-tangent, value, out-tangent of key 0
             0, 0, 0, 1, 0, 0, 0, 0, 0},  // of key 1
            "CUBICSPLINE", "VEC3");
    core::GltfOptions options;
    options.fps = 4.0;  // frame 2 is t = 0.5, s = 0.25
    const core::GltfShot shot = load(b, options);
    std::vector<glm::vec3> p;
    shot.positions_at(2, p);
    const double s = 0.25, dt = 2.0;
    const double h10 = s * s * s - 2 * s * s + s, h01 = -2 * s * s * s + 3 * s * s;
    expect_near(p[0], {h10 * 1.0 * dt + h01 * 1.0, 0, 0});
}

TEST_F(GltfShotTest, RotationKeysAreSlerped) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    const float h = float(std::sin(glm::quarter_pi<double>()));
    animate(b, n, "rotation", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0, h, h}, "LINEAR", "VEC4");  // 0 to 90 deg about z
    core::GltfOptions options;
    options.fps = 2.0;
    const core::GltfShot shot = load(b, options);
    std::vector<glm::vec3> p;
    shot.positions_at(1, p);  // halfway: 45 degrees
    expect_near(p[1], {std::cos(glm::quarter_pi<double>()), std::sin(glm::quarter_pi<double>()), 0});
}

TEST_F(GltfShotTest, MorphTargetsUseDefaultAndAnimatedWeights) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    const int target = b.floats({0, 0, 1, 0, 0, 0, 0, 0, 0}, "VEC3");
    b.json()["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", target}}};
    b.json()["meshes"][0]["weights"] = {0.5};
    b.finish_scene();
    {
        const core::GltfShot shot = load(b);
        expect_near(shot.rest().positions[0], {0, 0, 0.5});
    }
    animate(b, n, "weights", {0.0f, 1.0f}, {0.0f, 1.0f}, "LINEAR", "SCALAR");
    core::GltfOptions options;
    options.fps = 4.0;
    const core::GltfShot shot = load(b, options);
    EXPECT_TRUE(shot.deforms());
    std::vector<glm::vec3> p;
    shot.positions_at(1, p);
    expect_near(p[0], {0, 0, 0.25});
}

TEST_F(GltfShotTest, SkinsBlendJointMatricesWithMoreThanFourInfluences) {
    GltfBuilder b;
    const int mesh_node = b.mesh_node("skinned", kTriangle, {0, 1, 2});
    std::vector<int> joints;
    for (int j = 0; j < 5; ++j) joints.push_back(b.node("joint" + std::to_string(j)));
    // Joint j moves by (j, 0, 0); vertex 0 is split 0.2 over all five: it moves by 2 in x.
    for (int j = 0; j < 5; ++j) b.json()["nodes"][size_t(joints[size_t(j)])]["translation"] = {j, 0, 0};
    const std::vector<uint8_t> j0 = {0, 1, 2, 3, 1, 0, 0, 0, 2, 0, 0, 0};
    const std::vector<uint8_t> j1 = {4, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const std::vector<float> w0 = {0.2f, 0.2f, 0.2f, 0.2f, 1, 0, 0, 0, 1, 0, 0, 0};
    const std::vector<float> w1 = {0.2f, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    auto& attributes = b.json()["meshes"][0]["primitives"][0]["attributes"];
    attributes["JOINTS_0"] = b.accessor(b.view(j0.data(), j0.size()), 5121, 3, "VEC4");
    attributes["JOINTS_1"] = b.accessor(b.view(j1.data(), j1.size()), 5121, 3, "VEC4");
    attributes["WEIGHTS_0"] = b.floats(w0, "VEC4");
    attributes["WEIGHTS_1"] = b.floats(w1, "VEC4");
    b.json()["skins"] = {{{"joints", joints}}};
    b.json()["nodes"][size_t(mesh_node)]["skin"] = 0;
    b.json()["nodes"][size_t(mesh_node)]["translation"] = {100, 0, 0};  // ignored for a skinned mesh
    b.finish_scene();
    const core::GltfShot shot = load(b);
    const auto& p = shot.rest().positions;
    expect_near(p[0], {2, 0, 0});
    expect_near(p[1], {1 + 1, 0, 0});
    expect_near(p[2], {2, 1, 0});
}

TEST_F(GltfShotTest, GlbAndExternalBuffersReadAsTheEmbeddedForm) {
    GltfBuilder b;
    b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    const core::GltfShot embedded(write(b, "a.gltf"));
    const core::GltfShot binary(write(b, "b.glb"));
    const core::GltfShot external(write(b, "c.gltf", "c.bin"));
    EXPECT_EQ(embedded.rest().positions, binary.rest().positions);
    EXPECT_EQ(embedded.rest().positions, external.rest().positions);
    EXPECT_EQ(embedded.rest().triangles, binary.rest().triangles);
}

TEST_F(GltfShotTest, StripsFansSparseAndNormalizedAttributes) {
    GltfBuilder b;
    // A quad as a strip (4 vertices, 2 triangles), positions as normalised unsigned bytes.
    const std::vector<uint8_t> quad = {0, 0, 0, 0, 255, 0, 0, 0, 0, 255, 0, 0, 255, 255, 0, 0};
    const int pos = b.accessor(b.view(quad.data(), quad.size(), 4), 5121, 4, "VEC3", true);
    b.json()["accessors"][size_t(pos)]["min"] = {0, 0, 0};
    b.json()["accessors"][size_t(pos)]["max"] = {1, 1, 0};
    b.json()["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"mode", 5}}}}});
    // A fan of 4 vertices whose positions come from a sparse accessor over zeros.
    const std::vector<uint32_t> sparse_idx = {1, 2, 3};
    const std::vector<float> sparse_val = {2, 0, 0, 2, 1, 0, 2, 2, 0};
    const int fan = b.accessor(-1, 5126, 4, "VEC3");
    b.json()["accessors"][size_t(fan)]["sparse"] = {{"count", 3},
                                                    {"indices", {{"bufferView", b.view(sparse_idx.data(), 12)}, {"componentType", 5125}}},
                                                    {"values", {{"bufferView", b.view(sparse_val.data(), 36)}}}};
    b.json()["accessors"][size_t(fan)]["min"] = {0, 0, 0};
    b.json()["accessors"][size_t(fan)]["max"] = {2, 2, 0};
    b.json()["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", fan}}}, {"mode", 6}}}}});
    const int s = b.node("strip"), f = b.node("fan");
    b.json()["nodes"][size_t(s)]["mesh"] = 0;
    b.json()["nodes"][size_t(f)]["mesh"] = 1;
    b.finish_scene();
    const core::GltfShot shot = load(b);
    ASSERT_EQ(shot.rest().triangles.size(), 4u);
    const auto& p = shot.rest().positions;
    expect_near(p[3], {1, 1, 0});
    expect_near(p[7], {2, 2, 0});
    // Strip winding alternates so both triangles face +z.
    for (const glm::uvec3& t : shot.rest().triangles) EXPECT_GT(core::face_normal(p, t).z, 0.0);
}

TEST_F(GltfShotTest, SplitVerticesAreWeldedSoASeamIsNoBoundary) {
    GltfBuilder b;
    // Two triangles of a square, each with its own copies of the shared corners (as an exporter
    // splits at a UV seam or a hard edge).
    b.mesh_node("square", {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 1, 2, 3, 4, 5});
    b.finish_scene();
    const core::GltfShot shot = load(b);
    EXPECT_EQ(shot.rest().positions.size(), 4u);
    const core::EdgeTable table = core::build_edge_table(shot.rest());
    const core::MeshReport report = core::describe_mesh(shot.rest(), table);
    EXPECT_EQ(report.boundary_edges, 4u);  // the diagonal is shared
}

TEST_F(GltfShotTest, PerspectiveCameraSetsAspectFieldAndPose) {
    GltfBuilder b;
    b.mesh_node("tri", kTriangle, {0, 1, 2});
    const int cam = b.node("CamNode");
    b.json()["cameras"] = {{{"type", "perspective"}, {"name", "Lens"},
                            {"perspective", {{"yfov", 0.5}, {"aspectRatio", 2.0}, {"znear", 0.1}, {"zfar", 100}}}}};
    b.json()["nodes"][size_t(cam)]["camera"] = 0;
    b.json()["nodes"][size_t(cam)]["translation"] = {0, 0, 5};
    b.finish_scene();
    const core::GltfShot shot = load(b);
    ASSERT_TRUE(shot.camera());
    EXPECT_EQ(shot.camera()->name, "Lens");
    core::Scene scene;
    core::apply_gltf_camera(shot, scene, 1, 1, false);
    EXPECT_EQ(scene.image.width, 1024);
    EXPECT_EQ(scene.image.height, 512);
    const core::CameraPose& pose = scene.camera.per_frame.at(1);
    EXPECT_NEAR(pose.eye.z, 5.0, 1e-12);
    EXPECT_LT(pose.target.z, 5.0);  // looks down -z
    EXPECT_NEAR(pose.fov_y_deg, glm::degrees(0.5), 1e-9);
    // A square image: the camera's long side (horizontal) maps to the image's width.
    core::Scene square;
    square.image = {800, 800};
    core::apply_gltf_camera(shot, square, 1, 1, true);
    const double half_x = 2.0 * std::tan(0.25);
    EXPECT_NEAR(square.camera.per_frame.at(1).fov_y_deg, glm::degrees(2.0 * std::atan(half_x)), 1e-9);
}

TEST_F(GltfShotTest, OrthographicCameraKeepsItsViewHeightAndPlanes) {
    GltfBuilder b;
    b.mesh_node("tri", kTriangle, {0, 1, 2});
    const int cam = b.node("Ortho");
    b.json()["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 2.0}, {"ymag", 1.0}, {"znear", 0.5}, {"zfar", 50}}}}};
    b.json()["nodes"][size_t(cam)]["camera"] = 0;
    b.json()["nodes"][size_t(cam)]["translation"] = {0, 0, 5};
    b.finish_scene();
    const core::GltfShot shot = load(b);
    core::Scene scene;
    core::apply_gltf_camera(shot, scene, 1, 1, false);
    EXPECT_EQ(scene.image.width, 1024);
    EXPECT_EQ(scene.image.height, 512);
    const core::CameraPose& pose = scene.camera.per_frame.at(1);
    EXPECT_EQ(pose.eye, glm::dvec3(0, 0, 5));
    ASSERT_TRUE(pose.ortho_height.has_value());
    EXPECT_DOUBLE_EQ(*pose.ortho_height, 2.0);  // twice ymag
    EXPECT_EQ(scene.camera.near, 0.5);
    EXPECT_EQ(scene.camera.far, 50.0);

    // Points a unit right and half a unit up land at the same pixels at every depth: xmag and
    // ymag are half the view's width and height.
    const core::Camera camera = core::camera_at(scene, 1, core::bounds_of(shot.rest().positions));
    const core::Projection projection(camera, scene.image, glm::dmat4(1.0));
    EXPECT_TRUE(projection.orthographic());
    for (const double z : {4.0, 0.0, -40.0}) {
        const glm::dvec2 px = projection.pixel({1.0, 0.5, z});
        EXPECT_NEAR(px.x, 768.0, 1e-9);
        EXPECT_NEAR(px.y, 128.0, 1e-9);
        EXPECT_TRUE(projection.in_front(projection.clip({1.0, 0.5, z})));
        EXPECT_NEAR(projection.depth(projection.clip({1.0, 0.5, z})), 5.0 - z, 1e-9);
    }
    // Behind the near plane, and behind the camera, nothing is drawn.
    EXPECT_FALSE(projection.in_front(projection.clip({0.0, 0.0, 4.7})));
    EXPECT_FALSE(projection.in_front(projection.clip({0.0, 0.0, 6.0})));
}

// Without a camera: a bare mesh's turntable, held still when the shot is animated; a scene's own
// camera is kept.
TEST_F(GltfShotTest, ShotsWithoutCameraGetTheTurntableView) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    core::Scene still;
    core::apply_gltf_camera(load(b), still, 1, 48, false);
    EXPECT_TRUE(still.camera.orbit.has_value());
    EXPECT_TRUE(still.camera.per_frame.empty());
    animate(b, n, "translation", {0.0f, 1.0f}, {0, 0, 0, 30, 0, 0}, "LINEAR", "VEC3");
    core::Scene animated;
    const core::GltfShot moving = load(b);
    core::apply_gltf_camera(moving, animated, 0, 24, false);
    EXPECT_FALSE(animated.camera.orbit.has_value());
    // The view frames where the triangle goes, not only where it starts: it slides 30 units to
    // the right over the second, and every frame's corners are in the image.
    for (int frame = 0; frame <= 24; ++frame) {
        std::vector<glm::vec3> positions;
        moving.positions_at(frame, positions);
        const core::Projection projection(core::camera_at(animated, frame, core::bounds_of(positions)), animated.image,
                                          glm::dmat4(1.0));
        for (const glm::vec3& p : positions) {
            const glm::dvec2 px = projection.pixel(glm::dvec3(p));
            EXPECT_TRUE(projection.inside_image(px)) << "frame " << frame << ": " << px.x << ", " << px.y;
        }
    }
    core::Scene given;
    given.given.camera = true;
    given.camera.pose.eye = {7, 7, 7};
    core::apply_gltf_camera(load(b), given, 0, 24, false);
    EXPECT_EQ(given.camera.pose.eye, glm::dvec3(7, 7, 7));
}

TEST_F(GltfShotTest, NamedAnimationAndCameraAreChosenOrRefused) {
    GltfBuilder b;
    const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.finish_scene();
    animate(b, n, "translation", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0}, "LINEAR", "VEC3");
    b.json()["animations"][0]["name"] = "Walk";
    core::GltfOptions options;
    options.animation = "Walk";
    EXPECT_TRUE(load(b, options).deforms());
    options.animation = "Run";
    try {
        load(b, options);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("no animation named 'Run' (the file has 'Walk')"), std::string::npos) << e.what();
    }
    options.animation.clear();
    options.camera = "Nope";
    EXPECT_THROW(load(b, options), InputError);
}

// Cameras by the camera's name, its node's, or its index in the file's cameras (names first);
// every camera of the scene listed, an unnamed one as cameras[i]; a name that matches none is
// refused with the list.
TEST_F(GltfShotTest, CamerasAreChosenByNameOrIndex) {
    GltfBuilder b;
    b.mesh_node("tri", kTriangle, {0, 1, 2});
    b.json()["cameras"] = {
        {{"type", "perspective"}, {"perspective", {{"yfov", 0.7}, {"znear", 0.1}}}},
        {{"type", "orthographic"}, {"orthographic", {{"xmag", 2}, {"ymag", 1}, {"znear", 0}, {"zfar", 50}}}},
        {{"type", "perspective"}, {"name", "Close"}, {"perspective", {{"yfov", 0.3}, {"znear", 0.1}}}}};
    for (int c = 0; c < 3; ++c) {
        const int n = b.node(c == 1 ? "Side" : "");
        b.json()["nodes"][size_t(n)]["camera"] = c;
        b.json()["nodes"][size_t(n)]["translation"] = {0, 0, 5 + c};
    }
    b.finish_scene();
    core::GltfOptions options;
    const core::GltfShot first = load(b, options);
    ASSERT_EQ(first.cameras().size(), 3u);
    EXPECT_EQ(first.cameras()[0].name, "cameras[0]");
    EXPECT_EQ(first.cameras()[1].name, "Side");
    EXPECT_TRUE(first.cameras()[1].orthographic);
    EXPECT_EQ(first.cameras()[2].name, "Close");
    EXPECT_EQ(first.camera()->index, 0u);
    for (const auto& [asked, index] :
         std::vector<std::pair<std::string, size_t>>{{"1", 1}, {"Side", 1}, {"Close", 2}, {"2", 2}}) {
        options.camera = asked;
        const core::GltfShot shot = load(b, options);
        EXPECT_EQ(shot.camera()->index, index) << asked;
        EXPECT_EQ(shot.camera()->orthographic, index == 1) << asked;
    }
    options.camera = "3";
    try {
        load(b, options);
        FAIL() << "no error";
    } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find(
                      "no camera named '3' in the scene (it has 'cameras[0]' (0), 'Side' (1), 'Close' (2))"),
                  std::string::npos)
            << e.what();
    }
}

// What can be drawn is drawn, with one warning each: primitives of points and lines (no
// surface), a triangle list whose count is no multiple of 3, default weights that do not match
// the morph targets in number, what the reader skipped (an animation channel without a node).
TEST_F(GltfShotTest, OddButDrawablePartsAreDrawnWithAWarning) {
    GltfBuilder b;
    b.mesh_node("tri", kTriangle, {0, 1, 2, 0, 1});  // two indices too many
    auto& prims = b.json()["meshes"][0]["primitives"];
    prims.push_back(prims[0]);
    prims[1]["mode"] = 1;  // LINES
    prims.push_back(prims[0]);
    prims[2]["mode"] = 0;  // POINTS
    prims[0]["targets"] = {{{"POSITION", b.floats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3")}}};
    b.json()["meshes"][0]["weights"] = {0.5, 0.25};
    b.finish_scene();
    animate(b, 0, "translation", {0.0f, 1.0f}, {0, 0, 0, 1, 0, 0}, "LINEAR", "VEC3");
    b.json()["animations"][0]["channels"][0]["target"].erase("node");  // as an old exporter wrote "id"
    const core::GltfShot shot = load(b);
    EXPECT_EQ(shot.rest().triangles.size(), 1u);
    expect_near(shot.rest().positions[0], {0, 0, 0.5});
    const std::vector<std::string> w = shot.warnings();
    ASSERT_EQ(w.size(), 4u);
    // What the reader skips comes first, in its words.
    EXPECT_NE(w[0].find("shot.gltf: skipped in reading: 'node' property is missing; `node` field is missing in "
                        "animation.channels.target"),
              std::string::npos)
        << w[0];
    EXPECT_NE(w[1].find("meshes[0]: 2 morph weight(s) for 1 targets"), std::string::npos) << w[1];
    EXPECT_NE(
        w[2].find("2 primitive(s) of points or lines skipped, having no surface (the first: meshes[0].primitives[1])"),
        std::string::npos)
        << w[2];
    EXPECT_NE(w[3].find("1 triangle list(s) whose index count is no multiple of 3"), std::string::npos) << w[3];
    EXPECT_FALSE(shot.deforms());
}

TEST_F(GltfShotTest, BrokenFilesAreRefusedWithOneLineNamingTheElement) {
    const auto base = [] {
        GltfBuilder b;
        b.mesh_node("tri", kTriangle, {0, 1, 2});
        b.finish_scene();
        return b;
    };
    const auto expect_error = [&](GltfBuilder b, const std::string& part, const std::string& name = "shot.gltf") {
        const std::string message = error_of(b, name);
        EXPECT_NE(message.find(part), std::string::npos) << "message: " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    };
    {
        GltfBuilder b = base();
        b.json()["meshes"][0]["primitives"][0]["indices"] = 99;
        expect_error(b, "indices");
    }
    {
        GltfBuilder b = base();
        b.json()["accessors"][1]["count"] = 1000;  // the index accessor reads past its view
        expect_error(b, "accessors[1]: reads past the end of its bufferView");
    }
    {
        GltfBuilder b;
        b.mesh_node("tri", kTriangle, {0, 1, 7});
        b.finish_scene();
        expect_error(b, "index 7 is out of range (3 vertices)");
    }
    {
        GltfBuilder b;
        b.mesh_node("tri", kTriangle, {0, 1, 2});
        const int other = b.node("other");
        b.add_child(0, other);
        b.add_child(other, 0);
        b.finish_scene();
        expect_error(b, "is part of a cycle in the node hierarchy");
    }
    {
        GltfBuilder b = base();
        b.json()["skins"] = {{{"joints", {42}}}};
        b.json()["nodes"][0]["skin"] = 0;
        expect_error(b, "skins[0]: joint node 42 does not exist");
    }
    {
        GltfBuilder b = base();
        const float nan = std::nanf("");
        animate(b, 0, "translation", {0.0f, 1.0f}, {0, 0, 0, nan, 0, 0}, "LINEAR", "VEC3");
        expect_error(b, "element 1 (read as animations[0].samplers[0].output) is NaN or infinite");
    }
    {
        GltfBuilder b = base();
        const fs::path p = dir_ / "missing.gltf";
        b.write(p, "missing.bin");
        fs::remove(dir_ / "missing.bin");
        try {
            core::GltfShot shot(p);
            FAIL() << "no error";
        } catch (const InputError& e) {
            const std::string m = e.what();
            EXPECT_NE(m.find("missing.gltf"), std::string::npos) << m;
            EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        }
    }
    {
        GltfBuilder b = base();
        b.json()["asset"]["version"] = "1.0";
        expect_error(b, "shot.gltf: asset.version: is '1.0': only glTF 2.x is read");
    }
    {
        GltfBuilder b = base();
        const std::string text = b.gltf_text();
        const size_t comma = text.find("base64,");
        ASSERT_NE(comma, std::string::npos);
        std::string broken = text;
        broken[comma + 8] = '!';
        std::ofstream(dir_ / "b64.gltf") << broken;
        try {
            core::GltfShot shot(dir_ / "b64.gltf");
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("b64.gltf: buffers: a buffer's data URI is not valid base64"),
                      std::string::npos)
                << e.what();
        }
    }
    {
        std::ofstream(dir_ / "junk.glb") << "glTF this is not a binary container";
        EXPECT_THROW(core::GltfShot(dir_ / "junk.glb"), InputError);
        std::ofstream(dir_ / "junk.gltf") << "{ not json";
        EXPECT_THROW(core::GltfShot(dir_ / "junk.gltf"), InputError);
        EXPECT_THROW(core::GltfShot(dir_ / "absent.gltf"), InputError);
    }
}

// Values that pass the file's own checks but not inkline's limits: coordinates beyond 1e18 (as
// for mesh files), a camera beyond 1e19, a field of view below 0.001 degrees.
TEST_F(GltfShotTest, ValuesBeyondTheDrawingLimitsAreRefused) {
    {
        GltfBuilder b;
        b.mesh_node("far", {0, 0, 0, 1e30f, 0, 0, 0, 1, 0}, {0, 1, 2});
        b.finish_scene();
        const std::string m = error_of(b);
        EXPECT_NE(m.find("nodes[0] ('far'): at time 0.000000 s a vertex coordinate"), std::string::npos) << m;
        EXPECT_NE(m.find("is beyond the limit of 1e18"), std::string::npos) << m;
    }
    {
        GltfBuilder b;
        const int n = b.mesh_node("tri", kTriangle, {0, 1, 2});
        b.json()["nodes"][size_t(n)]["scale"] = {1e20, 1, 1};  // a node transform takes it there
        b.finish_scene();
        const std::string m = error_of(b);
        EXPECT_NE(m.find("is beyond the limit of 1e18"), std::string::npos) << m;
    }
    const auto with_camera = [](nlohmann::json camera, std::vector<double> translation) {
        GltfBuilder b;
        b.mesh_node("tri", kTriangle, {0, 1, 2});
        const int cam = b.node("cam");
        b.json()["cameras"] = {camera};
        b.json()["nodes"][size_t(cam)]["camera"] = 0;
        b.json()["nodes"][size_t(cam)]["translation"] = translation;
        b.finish_scene();
        return b;
    };
    {
        const GltfBuilder b = with_camera({{"type", "perspective"}, {"perspective", {{"yfov", 0.5}, {"znear", 0.1}}}}, {0, 0, 1e25});
        const core::GltfShot shot(write(b, "far_camera.gltf"));
        core::Scene scene;
        try {
            core::apply_gltf_camera(shot, scene, 1, 1, false);
            FAIL() << "no error";
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find("beyond the coordinate limit of 1e19"), std::string::npos) << e.what();
        }
    }
    {
        const GltfBuilder b = with_camera({{"type", "perspective"}, {"perspective", {{"yfov", 1e-9}, {"znear", 0.1}}}}, {0, 0, 5});
        const core::GltfShot shot(write(b, "narrow.gltf"));
        core::Scene scene;
        EXPECT_THROW(core::apply_gltf_camera(shot, scene, 1, 1, false), InputError);
    }
    {
        // An orthographic camera on a shot near the coordinate limit keeps its eye within 1e19.
        GltfBuilder b = with_camera({{"type", "orthographic"}, {"orthographic", {{"xmag", 1e17}, {"ymag", 1e17}, {"znear", 0}, {"zfar", 1e18}}}},
                                    {0, 0, 1e17});
        b.json()["nodes"][0]["scale"] = {1e17, 1e17, 1e17};
        const core::GltfShot shot(write(b, "huge.gltf"));
        core::Scene scene;
        core::apply_gltf_camera(shot, scene, 1, 1, false);
        const core::CameraPose& pose = scene.camera.per_frame.at(1);
        EXPECT_LE(std::abs(pose.eye.z), 1e19);
        EXPECT_GE(pose.fov_y_deg, 1e-3);
    }
}

TEST_F(GltfShotTest, SceneJsonNamesAGltfFile) {
    const core::Scene scene = core::parse_scene(
        R"({"mesh": "shot.glb", "gltf": {"animation": "Walk", "camera": "Cam", "scene": 1}, "fps": 30, "frames": [1, 5]})",
        dir_ / "scene.json");
    ASSERT_TRUE(scene.gltf);
    EXPECT_EQ(scene.gltf->animation, "Walk");
    EXPECT_EQ(scene.gltf->camera, "Cam");
    EXPECT_EQ(scene.gltf->scene, 1);
    EXPECT_EQ(scene.fps, 30.0);
    EXPECT_TRUE(scene.given.frames);
    EXPECT_FALSE(scene.given.camera);
    EXPECT_THROW(core::parse_scene(R"({"mesh": "a.obj", "gltf": {}})", dir_ / "scene.json"), InputError);
    EXPECT_THROW(core::parse_scene(R"({"mesh": "a.glb", "fps": 0})", dir_ / "scene.json"), InputError);
}

}  // namespace
}  // namespace inkline
