// SPDX-License-Identifier: MIT
#include "core/strokes/internal/splice.h"

#include <vector>

namespace inkline::core::internal {
namespace {

// Appends next's points after the first (before the last, reversed) and its edges; with
// `bridged`, every new segment is marked bridged, else it keeps next's marks.
void append(StrokeGeometry& r_into, const StrokeGeometry& next, bool reversed, bool bridged) {
    const bool marks = bridged || !next.bridged.empty() || !r_into.bridged.empty();
    if (marks) r_into.bridged.resize(r_into.edges.size(), 0);
    if (reversed) {
        r_into.points_px.insert(r_into.points_px.end(), next.points_px.rbegin() + 1, next.points_px.rend());
        r_into.points_world.insert(r_into.points_world.end(), next.points_world.rbegin() + 1, next.points_world.rend());
        r_into.edges.insert(r_into.edges.end(), next.edges.rbegin(), next.edges.rend());
    } else {
        r_into.points_px.insert(r_into.points_px.end(), next.points_px.begin() + 1, next.points_px.end());
        r_into.points_world.insert(r_into.points_world.end(), next.points_world.begin() + 1, next.points_world.end());
        r_into.edges.insert(r_into.edges.end(), next.edges.begin(), next.edges.end());
    }
    if (bridged) {
        r_into.bridged.resize(r_into.edges.size(), 1);
    } else if (marks) {  // else nothing is bridged on either side, and the marks stay empty
        std::vector<uint8_t> b = next.bridged;
        b.resize(next.edges.size(), 0);
        if (reversed) {
            r_into.bridged.insert(r_into.bridged.end(), b.rbegin(), b.rend());
        } else {
            r_into.bridged.insert(r_into.bridged.end(), b.begin(), b.end());
        }
    }
    r_into.pure_stroke_count += next.pure_stroke_count;
}

}  // namespace

void splice(StrokeGeometry& r_into, const StrokeGeometry& next, bool reversed) {
    append(r_into, next, reversed, false);
    r_into.ends[1] = next.ends[reversed ? 0 : 1];
}

void splice_bridged(StrokeGeometry& r_into, const StrokeGeometry& gap) {
    append(r_into, gap, false, true);
    r_into.ends[1] = gap.ends[1];
}

void splice_bridged_segment(StrokeGeometry& r_into, const glm::dvec2& px, const glm::dvec3& world, uint32_t edge) {
    r_into.bridged.resize(r_into.edges.size(), 0);
    r_into.points_px.push_back(px);
    r_into.points_world.push_back(world);
    r_into.edges.push_back(edge);
    r_into.bridged.push_back(1);
}

bool orient_for_splice(StrokeGeometry& a, const glm::dvec2& pa, StrokeGeometry& b, const glm::dvec2& pb) {
    const bool a_back = a.points_px.back() == pa, b_front = b.points_px.front() == pb;
    if ((!a_back && a.points_px.front() != pa) || (!b_front && b.points_px.back() != pb)) return false;
    if (!a_back) a.reverse();
    if (!b_front) b.reverse();
    return true;
}

StrokeGeometry part_of(const StrokeGeometry& g, size_t begin, size_t end) {
    StrokeGeometry out;
    out.kind = g.kind;
    out.visible = g.visible;
    out.points_px.assign(g.points_px.begin() + std::ptrdiff_t(begin), g.points_px.begin() + std::ptrdiff_t(end) + 1);
    out.points_world.assign(g.points_world.begin() + std::ptrdiff_t(begin),
                            g.points_world.begin() + std::ptrdiff_t(end) + 1);
    out.edges.assign(g.edges.begin() + std::ptrdiff_t(begin), g.edges.begin() + std::ptrdiff_t(end));
    if (!g.bridged.empty()) {
        std::vector<uint8_t> b = g.bridged;
        b.resize(g.edges.size(), 0);
        out.bridged.assign(b.begin() + std::ptrdiff_t(begin), b.begin() + std::ptrdiff_t(end));
    }
    out.ends = {begin == 0 ? g.ends[0] : StrokeEnd::kJunction,
                end + 1 == g.points_px.size() ? g.ends[1] : StrokeEnd::kJunction};
    return out;
}

}  // namespace inkline::core::internal
