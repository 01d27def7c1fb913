// SPDX-License-Identifier: MIT
#include "tests/support/objects.h"

#include <cmath>
#include <numbers>

namespace inkline::test {
namespace {

class Parts final : public core::AnimatedMesh {
  public:
    explicit Parts(std::vector<Part> parts) {
        for (uint32_t o = 0; o < parts.size(); ++o) {
            const Part& part = parts[o];
            const auto base = uint32_t(mesh_.positions.size());
            mesh_.positions.insert(mesh_.positions.end(), part.mesh.positions.begin(), part.mesh.positions.end());
            for (const glm::uvec3& t : part.mesh.triangles) {
                mesh_.triangles.push_back(t + glm::uvec3(base));
                face_objects_.push_back(o);
            }
            velocity_.insert(velocity_.end(), part.mesh.positions.size(), part.velocity);
            deforms_ = deforms_ || part.velocity != glm::dvec3(0.0);
            objects_.push_back({part.name, -1});
        }
    }

    const core::Mesh& rest() const override { return mesh_; }
    bool deforms() const override { return deforms_; }
    void positions_at(int frame, std::vector<glm::vec3>& r_positions) const override {
        r_positions.resize(mesh_.positions.size());
        for (size_t v = 0; v < r_positions.size(); ++v) {
            r_positions[v] = glm::vec3(glm::dvec3(mesh_.positions[v]) + velocity_[v] * double(frame - 1));
        }
    }
    std::vector<core::MeshObject> mesh_objects() const override { return objects_; }
    std::vector<uint32_t> face_objects() const override { return face_objects_; }

  private:
    core::Mesh mesh_;
    std::vector<glm::dvec3> velocity_;
    std::vector<core::MeshObject> objects_;
    std::vector<uint32_t> face_objects_;
    bool deforms_ = false;
};

}  // namespace

std::unique_ptr<core::MeshFrames> objects_frames(std::vector<Part> parts) {
    return std::make_unique<core::MeshFrames>(std::make_shared<Parts>(std::move(parts)), "parts");
}

core::Mesh tube(int segments, int rings, double radius, double half_length) {
    core::Mesh mesh;
    for (int r = 0; r <= rings; ++r) {
        const double y = -half_length + 2.0 * half_length * r / rings;
        for (int s = 0; s < segments; ++s) {
            const double a = 2.0 * std::numbers::pi * s / segments;
            mesh.positions.emplace_back(float(radius * std::cos(a)), float(y), float(-radius * std::sin(a)));
        }
    }
    const auto at = [segments](int r, int s) { return uint32_t(r * segments + (s % segments)); };
    for (int r = 0; r < rings; ++r) {
        for (int s = 0; s < segments; ++s) {
            mesh.triangles.emplace_back(at(r, s), at(r, s + 1), at(r + 1, s + 1));
            mesh.triangles.emplace_back(at(r, s), at(r + 1, s + 1), at(r + 1, s));
        }
    }
    return mesh;
}

}  // namespace inkline::test
