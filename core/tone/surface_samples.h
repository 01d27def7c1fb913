// SPDX-License-Identifier: MIT
// A nested blue-noise set of points on a mesh's surface, built only where it is asked for.
//
// Level k's points keep at least r_k from every point of levels 0..k (hierarchical dart throwing,
// r_k shrinking by sqrt(2) a level, so that each level about doubles the density). Every point
// has a rank: the density (points per unit area) from which it is taken, spread at random over
// its level's share (density(k - 1), density(k)]. The points of rank below any density are then
// spread evenly at about that density, and a higher density takes the same points and more.
//
// Levels are built lazily, tile by tile: tiles are cubes of side 8 r_k, and a tile holds the same
// points whenever it is built and whatever was built before it. Its candidates come from a hash
// of (seed, level, face), for a face no wider than a tile (each tile takes those inside it), or
// of (seed, level, tile, face), spread over the face's part in the tile; they are tried in the
// order of their ids, against the lower levels within r_k and against the neighbouring tiles of
// its level that come before it in a fixed order of eight phases (the parity of the tile's
// coordinates: tiles of one phase lie a tile apart, farther than r_k, so they never meet). A view
// that needs a small part of the surface at a fine level builds that part and a margin of a few
// tiles a level around it; what a frame draws never depends on the frames before it. Levels can
// also be built on the whole surface at once (build_everywhere): the same points, faster a point.
//
// Points are anchored on faces by barycentric coordinates and follow the mesh as it deforms; their
// distribution is that of the mesh the set was built on.
#pragma once

#include "core/mesh/mesh.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace inkline::core {

class SurfaceSamples {
  public:
    struct Sample {
        uint64_t id = 0;             // the same point of the surface in every build (a 63-bit hash)
        double rank = 0.0;           // points per unit area from which it is taken
        float b1 = 0.0f, b2 = 0.0f;  // barycentric coordinates of corners 1 and 2 (corner 0: 1 - b1 - b2)
    };
    // A face's part in a box: a convex polygon by barycentric coordinates (b1, b2) of its corners.
    struct Part {
        std::array<glm::dvec2, 9> b{};
        size_t count = 0;
    };

    SurfaceSamples(const Mesh& mesh, uint64_t seed);
    SurfaceSamples(SurfaceSamples&&) noexcept;
    SurfaceSamples& operator=(SurfaceSamples&&) noexcept;
    ~SurfaceSamples();

    // Points per unit area of levels 0..level on a plane (calibrated: docs/tone.md); 0 below level 0.
    static double density(int level, double first_radius);
    double density(int level) const { return density(level, radius_[0]); }
    // The least level whose density reaches `density`, at most levels() - 1.
    int level_for(double density) const;
    // Levels this mesh can have: the tiles' coordinates must fit their keys.
    int levels() const { return int(radius_.size()); }
    // A level's spacing r_k.
    double radius(int level) const { return radius_[size_t(level)]; }

    // Builds level `level` over the tiles that face f's box meets.
    void build_face(uint32_t face, int level);
    // Builds levels 0..last over the whole surface at once: the same points as tile by tile, at a
    // fraction of the cost a point.
    void build_everywhere(int last);
    // Builds one tile of a level: `at` as tiles_over gives it.
    void build_tile(int level, const glm::ivec3& at);
    // Sorts the faces' samples by rank after building; on_face asks for it.
    void finish();
    // Drops every sample built (they come back the same when built again).
    void clear();

    // Calls visit(at) for every tile of the level that the box [lo, hi] meets (object space of the
    // mesh it was built on).
    template <typename Visit>
    void tiles_over(int level, const glm::dvec3& lo, const glm::dvec3& hi, Visit visit) const {
        const glm::ivec3 a = tile_of(level, lo), b = tile_of(level, hi);
        for (int z = a.z; z <= b.z; ++z) {
            for (int y = a.y; y <= b.y; ++y) {
                for (int x = a.x; x <= b.x; ++x) visit(glm::ivec3(x, y, z));
            }
        }
    }
    // The box of a tile.
    void tile_box(int level, const glm::ivec3& at, glm::dvec3& r_lo, glm::dvec3& r_hi) const;
    // The most tiles of the level that face f's box spans along an axis.
    int tiles_across(uint32_t face, int level) const;
    // Face f's box (object space of the mesh it was built on).
    void face_box(uint32_t face, glm::dvec3& r_lo, glm::dvec3& r_hi) const;
    // Whether face f's plane passes through the box [lo, hi].
    bool plane_meets(uint32_t face, const glm::dvec3& lo, const glm::dvec3& hi) const;
    // Face f's part in the box [lo, hi]; count 0 where they do not meet.
    Part part_in_box(uint32_t face, const glm::dvec3& lo, const glm::dvec3& hi) const;
    // The area of a part of face f (object units squared, on the mesh it was built on).
    double part_area(uint32_t face, const Part& part) const;

    // The samples built on a face, by rank (after finish()).
    std::span<const Sample> on_face(uint32_t face) const {
        return {samples_.data() + offsets_[face], offsets_[face + 1] - offsets_[face]};
    }
    // Samples built so far.
    size_t size() const { return size_; }
    // Faces of the mesh it was built on.
    size_t faces() const { return face_area_.size(); }
    // Surface area of the mesh it was built on (object units squared) and of one face.
    double area() const { return area_; }
    double face_area(uint32_t face) const { return face_area_[face]; }

  private:
    struct Tile {
        uint32_t begin = 0, count = 0;  // its points: points_[level][begin, begin + count)
        bool built = false;
    };
    struct Level;  // its tiles by key, and their points
    // Faces by their boxes, for the faces a tile meets.
    struct BoxNode {
        glm::vec3 lo{0.0f}, hi{0.0f};
        uint32_t first = 0, count = 0;  // its faces: box_faces_[first, first + count)
        uint32_t right = 0;             // an inner node's second child (its first follows it); 0 for a leaf
    };

    glm::ivec3 tile_of(int level, const glm::dvec3& p) const;
    static uint64_t tile_key(const glm::ivec3& at);
    uint32_t tile_index(int level, const glm::ivec3& at);
    // Builds a tile (and what it is tested against) unless built; its index in its level.
    uint32_t build(int level, const glm::ivec3& at);
    struct Candidate;
    // The faces whose boxes meet the box [lo, hi] (in no particular order).
    void faces_meeting(const glm::dvec3& lo, const glm::dvec3& hi, std::vector<uint32_t>& r_faces) const;
    // A level's candidates on a face's part in a tile (key), and on a whole face (the same for
    // every tile it meets).
    void part_candidates(int level, uint64_t key, uint32_t face, const Part& part, std::vector<Candidate>& r_out) const;
    void face_candidates(int level, uint32_t face, std::vector<Candidate>& r_out) const;
    // Files a tile's points: those of its candidates kept.
    void file(int level, uint32_t index, std::span<const Candidate> kept);
    uint32_t build_boxes(uint32_t first, uint32_t count, std::vector<glm::vec3>& centres);

    std::vector<glm::vec3> corners_;  // three per face, the mesh's positions when built
    std::vector<double> face_area_;
    std::vector<float> face_extent_;  // the largest side of each face's box
    double area_ = 0.0;
    glm::dvec3 origin_{0.0};      // below the mesh's box by a level-0 tile: tile coordinates stay positive
    std::vector<double> radius_;  // per level: its spacing r_k
    uint64_t seed_ = 1;
    std::vector<Level> levels_;
    std::vector<BoxNode> box_nodes_;
    std::vector<uint32_t> box_faces_;
    // The samples by face, each face's by rank (offsets_: per face, where its samples begin), and
    // those built since the last finish(), with their faces.
    std::vector<Sample> samples_;
    std::vector<size_t> offsets_;
    std::vector<std::pair<uint32_t, Sample>> fresh_;
    size_t size_ = 0;
};

}  // namespace inkline::core
