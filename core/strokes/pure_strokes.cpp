// SPDX-License-Identifier: MIT
#include "core/strokes/pure_strokes.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <utility>

#include "core/internal/point_grid.h"
#include "core/internal/union_find.h"
#include "core/strokes/internal/splice.h"
#include "core/strokes/stroke_path.h"

namespace inkline::core {
namespace {

constexpr size_t kNone = size_t(-1);
// Cell size (px) of the grid that finds segments near a stroke end.
constexpr double kGridCellPx = 8.0;

// A polyline with arc lengths, for points at a given arc (clamped, or wrapped on a loop).
class ArcPolyline {
  public:
    ArcPolyline(std::vector<glm::dvec2> points, bool closed) : points_(std::move(points)), closed_(closed) {
        arc_.assign(points_.size(), 0.0);
        for (size_t i = 1; i < points_.size(); ++i) arc_[i] = arc_[i - 1] + glm::length(points_[i] - points_[i - 1]);
    }
    double length() const { return arc_.back(); }
    double arc(size_t i) const { return arc_[i]; }
    glm::dvec2 at(double a) const {
        const double total = length();
        if (closed_ && total > 0.0) a -= std::floor(a / total) * total;
        a = std::clamp(a, 0.0, total);
        const auto it = std::upper_bound(arc_.begin(), arc_.end(), a);
        if (it == arc_.end()) return points_.back();
        const size_t s = it == arc_.begin() ? 0 : size_t(it - arc_.begin()) - 1;
        const double seg = arc_[s + 1] - arc_[s];
        return points_[s] + (points_[s + 1] - points_[s]) * (seg > 0.0 ? (a - arc_[s]) / seg : 0.0);
    }

  private:
    std::vector<glm::dvec2> points_;
    std::vector<double> arc_;
    bool closed_;
};

double angle_deg(const glm::dvec2& a, const glm::dvec2& b) {
    const double la = glm::length(a), lb = glm::length(b);
    if (la <= 0.0 || lb <= 0.0) return 0.0;
    return glm::degrees(std::acos(std::clamp(glm::dot(a, b) / (la * lb), -1.0, 1.0)));
}

// Turn at every kept point of the back-tracking-free path, for each chord window.
struct Turns {
    std::vector<size_t> kept;        // exact indices
    std::vector<double> arc;         // arc of each kept point on the cleaned path
    std::vector<double> wide, fine;  // turn (deg) at window kTurnWindowPx / kCornerScalePx
};

Turns measure_turns(const std::vector<glm::dvec2>& points, bool closed, double wide_px, double fine_px) {
    Turns t;
    t.kept = remove_backtracking(points, closed);
    std::vector<glm::dvec2> cleaned;
    for (size_t k : t.kept) cleaned.push_back(points[k]);
    const ArcPolyline path(cleaned, closed);
    t.wide.assign(t.kept.size(), 0.0);
    t.fine.assign(t.kept.size(), 0.0);
    for (size_t j = 0; j < t.kept.size(); ++j) t.arc.push_back(path.arc(j));
    const size_t last = closed ? t.kept.size() - 1 : t.kept.size();  // a loop's seam is counted once
    for (size_t j = 0; j < last; ++j) {
        const double a = t.arc[j];
        if (!closed && (j == 0 || j + 1 == t.kept.size())) continue;
        const glm::dvec2 p = cleaned[j];
        t.wide[j] = angle_deg(p - path.at(a - wide_px), path.at(a + wide_px) - p);
        t.fine[j] = angle_deg(p - path.at(a - fine_px), path.at(a + fine_px) - p);
    }
    return t;
}

// Exact indices of the corners of a polyline: kept points turning sharply at both scales, the
// sharpest first, none within kTurnWindowPx of a sharper one. Ascending.
std::vector<size_t> find_corners(const Polyline& line, double turn_angle_deg) {
    if (line.points_px.size() < 3) return {};
    const Turns t = measure_turns(line.points_px, line.closed, kTurnWindowPx, kCornerScalePx);
    std::vector<size_t> candidates;
    for (size_t j = 0; j < t.kept.size(); ++j) {
        if (t.wide[j] > turn_angle_deg && t.fine[j] > turn_angle_deg) candidates.push_back(j);
    }
    std::stable_sort(candidates.begin(), candidates.end(), [&](size_t a, size_t b) { return t.wide[a] > t.wide[b]; });
    const double total = t.arc.back();
    std::vector<size_t> accepted;
    for (size_t j : candidates) {
        bool near = false;
        for (size_t k : accepted) {
            double d = std::abs(t.arc[j] - t.arc[k]);
            if (line.closed) d = std::min(d, total - d);
            near = near || d < kTurnWindowPx;
        }
        if (!near) accepted.push_back(j);
    }
    std::vector<size_t> corners;
    for (size_t j : accepted) corners.push_back(t.kept[j]);
    std::sort(corners.begin(), corners.end());
    return corners;
}

// A pure stroke while ends are typed and linked.
struct Piece {
    StrokeGeometry geometry;
    std::array<bool, 2> polyline_end{false, false};  // the end is an end of its polyline
    std::array<glm::dvec2, 2> direction{};           // unit chord into the stroke at each end
    double length = 0.0;
};

// Copies exact points [begin, end] of a polyline; on a loop, indices wrap past the seam.
Piece cut(const Polyline& line, size_t begin, size_t end) {
    Piece piece;
    StrokeGeometry& g = piece.geometry;
    g.kind = line.kind;
    g.visible = line.visible;
    const size_t segments = line.points_px.size() - 1;
    for (size_t i = begin; i <= end; ++i) {
        const size_t k = line.closed && i > segments ? i - segments : i;
        g.points_px.push_back(line.points_px[k]);
        g.points_world.push_back(line.points_world[k]);
        if (i < end) g.edges.push_back(line.edges[k % segments]);
    }
    return piece;
}

void finish(Piece& piece) {
    const StrokeGeometry& g = piece.geometry;
    const ArcPolyline path(g.points_px, false);
    piece.length = path.length();
    const double reach = std::min(kTurnWindowPx, piece.length);
    const glm::dvec2 d0 = path.at(reach) - g.points_px.front();
    const glm::dvec2 d1 = path.at(piece.length - reach) - g.points_px.back();
    piece.direction[0] = glm::length(d0) > 0.0 ? glm::normalize(d0) : glm::dvec2(0.0);
    piece.direction[1] = glm::length(d1) > 0.0 ? glm::normalize(d1) : glm::dvec2(0.0);
}

// Splits one polyline at its corners.
void split_polyline(const Polyline& line, double turn_angle_deg, std::vector<Piece>& out, size_t& corners) {
    const size_t last = line.points_px.size() - 1;
    const std::vector<size_t> at = find_corners(line, turn_angle_deg);
    corners += at.size();
    if (line.closed && at.empty()) {
        Piece piece = cut(line, 0, last);
        piece.geometry.closed = true;
        piece.geometry.ends = {StrokeEnd::kLoop, StrokeEnd::kLoop};
        finish(piece);
        out.push_back(std::move(piece));
        return;
    }
    std::vector<std::pair<size_t, size_t>> ranges;
    if (line.closed) {
        for (size_t i = 0; i < at.size(); ++i) {
            const size_t next = i + 1 < at.size() ? at[i + 1] : at[0] + last;
            ranges.emplace_back(at[i], next);
        }
    } else {
        size_t begin = 0;
        for (size_t k : at) ranges.emplace_back(begin, k), begin = k;
        ranges.emplace_back(begin, last);
    }
    for (size_t r = 0; r < ranges.size(); ++r) {
        Piece piece = cut(line, ranges[r].first, ranges[r].second);
        piece.polyline_end = {!line.closed && r == 0, !line.closed && r + 1 == ranges.size()};
        piece.geometry.ends = {StrokeEnd::kCorner, StrokeEnd::kCorner};
        finish(piece);
        out.push_back(std::move(piece));
    }
}

struct EndRef {
    size_t piece;
    int end;
    glm::dvec2 p;
};

// Segments of all pieces on a grid (by their bounding boxes), to find what passes near a stroke end.
class SegmentGrid {
  public:
    explicit SegmentGrid(const std::vector<Piece>& pieces) : pieces_(pieces), grid_(kGridCellPx) {
        for (size_t p = 0; p < pieces.size(); ++p) {
            const auto& pts = pieces[p].geometry.points_px;
            for (size_t s = 0; s + 1 < pts.size(); ++s)
                grid_.add_box(glm::min(pts[s], pts[s + 1]), glm::max(pts[s], pts[s + 1]), {p, s});
        }
        grid_.sort();
    }

    // True when a segment of a piece other than `self` passes within radius of p.
    bool passes_near(const glm::dvec2& p, double radius, size_t self) const {
        return grid_.any_in_box(p - radius, p + radius, [&](const std::pair<size_t, size_t>& ps) {
            const auto [piece, segment] = ps;
            if (piece == self) return false;
            const auto& pts = pieces_[piece].geometry.points_px;
            return distance_to_segment(p, pts[segment], pts[segment + 1]) <= radius;
        });
    }

  private:
    const std::vector<Piece>& pieces_;
    internal::PointGrid<std::pair<size_t, size_t>> grid_;  // (piece, segment)
};

// Groups polyline ends that touch (within kTouchPx): union-find over a sweep in x.
std::vector<std::vector<size_t>> touching_groups(const std::vector<EndRef>& ends) {
    internal::UnionFind<size_t> touching(ends.size());
    std::vector<size_t> order(ends.size());
    std::iota(order.begin(), order.end(), size_t(0));
    std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
        return std::tie(ends[a].p.x, ends[a].p.y, a) < std::tie(ends[b].p.x, ends[b].p.y, b);
    });
    // Ends at the same point (thousands where a fan of edges meets) touch: one of them sweeps.
    size_t kept = 0;
    for (size_t k = 0; k < order.size(); ++k) {
        if (kept > 0 && ends[order[kept - 1]].p == ends[order[k]].p) {
            touching.unite(order[kept - 1], order[k]);
        } else {
            order[kept++] = order[k];
        }
    }
    order.resize(kept);
    for (size_t i = 0; i < order.size(); ++i) {
        for (size_t j = i + 1; j < order.size() && ends[order[j]].p.x - ends[order[i]].p.x <= kTouchPx; ++j) {
            if (glm::length(ends[order[i]].p - ends[order[j]].p) <= kTouchPx) touching.unite(order[i], order[j]);
        }
    }
    std::vector<std::vector<size_t>> groups(ends.size());
    // Groups by their root, the least end in each: in order of their first end.
    for (size_t i = 0; i < ends.size(); ++i) groups[touching.find(i)].push_back(i);
    std::erase_if(groups, [](const std::vector<size_t>& g) { return g.empty(); });
    return groups;
}

// Junctions up to this many ends are searched pair by pair.
constexpr size_t kSmallJunction = 32;

// A junction of many ends (a fan of thousands of edges meeting in one vertex): the ends on a grid
// of cells 2 * kJoinPx wide, in each cell sorted by the angle of their direction, so that the
// smoothest continuation of an end is found among the few that point nearly opposite to it. It
// picks the same end as the pair-by-pair search: the least turn, on a tie the first in `order`.
class Junction {
  public:
    // Only ends with finite positions and nonzero, finite directions are sorted by angle.
    static bool fits(const std::vector<EndRef>& members, const std::vector<Piece>& pieces) {
        return std::all_of(members.begin(), members.end(), [&](const EndRef& m) {
            const glm::dvec2 d = pieces[m.piece].direction[size_t(m.end)];
            return std::isfinite(m.p.x) && std::isfinite(m.p.y) && std::isfinite(d.x) && std::isfinite(d.y) &&
                   glm::length(d) > 0.0;
        });
    }

    Junction(const std::vector<EndRef>& members, const std::vector<size_t>& order, const std::vector<Piece>& pieces)
        : rank_(members.size()), cell_(members.size()), angle_(members.size()), target_(members.size()) {
        for (size_t r = 0; r < order.size(); ++r) rank_[order[r]] = r;
        for (size_t m = 0; m < members.size(); ++m) {
            const glm::dvec2 d = pieces[members[m].piece].direction[size_t(members[m].end)];
            cell_[m] = cell(members[m].p);
            angle_[m] = glm::degrees(std::atan2(d.y, d.x));
            target_[m] = glm::degrees(std::atan2(-d.y, -d.x));
            cells_[cell_[m]].insert({angle_[m], m});
        }
    }

    // The end that `joins` and turns least (`turn`), among those not yet removed; kNone if none.
    // Only ends that turn at most max_turn_deg can join.
    template <typename Joins, typename Turn>
    size_t smoothest(size_t i, double max_turn_deg, Joins&& joins, Turn&& turn) const {
        size_t best = kNone;
        double best_turn = 0.0;
        auto consider = [&](size_t j) {
            if (j == i || !joins(j)) return;
            const double t = turn(j);
            if (best == kNone || t < best_turn || (t == best_turn && rank_[j] < rank_[best])) best = j, best_turn = t;
        };
        // Angles from atan2 and turns from acos differ by far less than this margin (deg).
        constexpr double kMarginDeg = 1e-3;
        auto reach = [&] { return (best == kNone ? max_turn_deg : std::min(best_turn, max_turn_deg)) + kMarginDeg; };
        auto off = [&](double angle) { return std::abs(std::remainder(angle - target_[i], 360.0)); };
        for (int64_t dx = -1; dx <= 1; ++dx) {
            for (int64_t dy = -1; dy <= 1; ++dy) {
                const auto found = cells_.find({cell_[i].first + dx, cell_[i].second + dy});
                if (found == cells_.end() || found->second.empty()) continue;
                const auto& ring = found->second;
                const auto start = ring.lower_bound({target_[i], size_t(0)});
                auto it = start;
                for (size_t n = 0; n < ring.size(); ++n) {  // counter-clockwise from the target
                    if (it == ring.end()) it = ring.begin();
                    if (off(it->first) > reach()) break;
                    consider(it->second);
                    ++it;
                }
                it = start;
                for (size_t n = 0; n < ring.size(); ++n) {  // clockwise
                    if (it == ring.begin()) it = ring.end();
                    --it;
                    if (off(it->first) > reach()) break;
                    consider(it->second);
                }
            }
        }
        return best;
    }

    void remove(size_t m) { cells_[cell_[m]].erase({angle_[m], m}); }

  private:
    using Cell = std::pair<int64_t, int64_t>;
    static Cell cell(const glm::dvec2& p) {
        constexpr double kCell = 2.0 * kJoinPx;
        return {int64_t(std::floor(std::clamp(p.x, -1e8, 1e8) / kCell)),
                int64_t(std::floor(std::clamp(p.y, -1e8, 1e8) / kCell))};
    }

    std::vector<size_t> rank_;
    std::vector<Cell> cell_;
    std::vector<double> angle_, target_;
    std::map<Cell, std::set<std::pair<double, size_t>>> cells_;
};

struct Link {
    size_t piece = kNone;
    int end = 0;
};

class Linker {
  public:
    Linker(std::vector<Piece>& pieces, double turn_angle_deg)
        : pieces_(pieces), turn_(turn_angle_deg), links_(pieces.size()) {}

    // Turn (deg) of a path arriving at the junction through end a and leaving through end b.
    double turn(const EndRef& a, const EndRef& b) const {
        return angle_deg(-pieces_[a.piece].direction[size_t(a.end)], pieces_[b.piece].direction[size_t(b.end)]);
    }

    bool can_join(const EndRef& a, const EndRef& b) const {
        const StrokeGeometry& ga = pieces_[a.piece].geometry;
        const StrokeGeometry& gb = pieces_[b.piece].geometry;
        if (a.piece == b.piece && a.end == b.end) return false;
        return ga.kind == gb.kind && ga.visible == gb.visible && glm::length(a.p - b.p) <= kJoinPx &&
               turn(a, b) <= turn_;
    }

    // One junction: the longest stroke takes its smoothest continuation, then the next longest
    // of those left; the ends left over are typed.
    void resolve(const std::vector<EndRef>& members, bool t_junction, size_t& r_links) {
        std::vector<size_t> order(members.size());
        std::iota(order.begin(), order.end(), size_t(0));
        std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
            return pieces_[members[a].piece].length > pieces_[members[b].piece].length;
        });
        std::vector<uint8_t> linked(members.size(), 0);
        std::optional<Junction> big;
        if (members.size() > kSmallJunction && Junction::fits(members, pieces_)) big.emplace(members, order, pieces_);
        for (size_t i : order) {
            if (linked[i]) continue;
            size_t best = kNone;
            if (big) {
                best = big->smoothest(
                    i, turn_, [&](size_t j) { return can_join(members[i], members[j]); },
                    [&](size_t j) { return turn(members[i], members[j]); });
            } else {
                for (size_t j : order) {
                    if (j == i || linked[j] || !can_join(members[i], members[j])) continue;
                    if (best == kNone || turn(members[i], members[j]) < turn(members[i], members[best])) best = j;
                }
            }
            if (best == kNone) continue;
            if (big) big->remove(i), big->remove(best);
            linked[i] = linked[best] = 1;
            links_[members[i].piece][size_t(members[i].end)] = {members[best].piece, members[best].end};
            links_[members[best].piece][size_t(members[best].end)] = {members[i].piece, members[i].end};
            ++r_links;
        }
        for (size_t i = 0; i < members.size(); ++i) {
            if (linked[i]) continue;
            StrokeEnd type = StrokeEnd::kJunction;
            if (members.size() == 1) type = t_junction ? StrokeEnd::kJunction : StrokeEnd::kFree;
            if (members.size() == 2 && turn(members[0], members[1]) > turn_) type = StrokeEnd::kCorner;
            pieces_[members[i].piece].geometry.ends[size_t(members[i].end)] = type;
        }
    }

    // Joins linked pieces into strokes, in order of their first piece.
    std::vector<StrokeGeometry> assemble() const {
        std::vector<StrokeGeometry> out;
        std::vector<uint8_t> used(pieces_.size(), 0);
        for (int pass = 0; pass < 2; ++pass) {
            for (size_t p = 0; p < pieces_.size(); ++p) {
                if (used[p]) continue;
                const bool free0 = links_[p][0].piece == kNone, free1 = links_[p][1].piece == kNone;
                if (pass == 0 && !free0 && !free1) continue;  // cycles wait for the second pass
                out.push_back(walk(p, pass == 0 && free0 ? 0 : (pass == 0 ? 1 : 0), used));
            }
        }
        return out;
    }

  private:
    StrokeGeometry walk(size_t first, int enter, std::vector<uint8_t>& used) const {
        StrokeGeometry out = pieces_[first].geometry;
        if (enter == 1) out.reverse();
        used[first] = 1;
        size_t p = first;
        int e = enter;
        while (true) {
            const Link next = links_[p][size_t(1 - e)];
            if (next.piece == kNone) {
                out.ends[1] = pieces_[p].geometry.ends[size_t(1 - e)];
                break;
            }
            if (next.piece == first && next.end == enter) {
                out.closed = true;
                out.ends = {StrokeEnd::kLoop, StrokeEnd::kLoop};
                break;
            }
            p = next.piece;
            e = next.end;
            used[p] = 1;
            internal::splice(out, pieces_[p].geometry, e == 1);
        }
        if (!out.closed) out.ends[0] = pieces_[first].geometry.ends[size_t(enter)];
        return out;
    }

    std::vector<Piece>& pieces_;
    double turn_;
    std::vector<std::array<Link, 2>> links_;
};

}  // namespace

std::vector<double> turn_angles_deg(const std::vector<glm::dvec2>& points_px, bool closed, double window_px) {
    std::vector<double> out(points_px.size(), 0.0);
    if (points_px.size() < 3) return out;
    const Turns t = measure_turns(points_px, closed, window_px, window_px);
    for (size_t j = 0; j < t.kept.size(); ++j) out[t.kept[j]] = t.wide[j];
    if (closed) out.back() = out.front();
    return out;
}

PureStrokes build_pure_strokes(const std::vector<Polyline>& polylines, const PureStrokeOptions& options) {
    PureStrokes result;
    std::vector<Piece> pieces;
    for (const Polyline& line : polylines) {
        if (line.points_px.size() < 2) continue;
        split_polyline(line, options.turn_angle_deg, pieces, result.corners);
    }
    result.pure_strokes = pieces.size();

    // Polyline ends: grouped where they touch; a lone end may still end on another stroke.
    std::vector<EndRef> ends;
    for (size_t p = 0; p < pieces.size(); ++p) {
        for (int e = 0; e < 2; ++e) {
            if (!pieces[p].polyline_end[size_t(e)]) continue;
            const auto& pts = pieces[p].geometry.points_px;
            ends.push_back({p, e, e == 0 ? pts.front() : pts.back()});
        }
    }
    const SegmentGrid grid(pieces);
    Linker linker(pieces, options.turn_angle_deg);
    for (const std::vector<size_t>& group : touching_groups(ends)) {
        std::vector<EndRef> members;
        for (size_t i : group) members.push_back(ends[i]);
        const bool t_junction = members.size() == 1 && grid.passes_near(members[0].p, kTJunctionPx, members[0].piece);
        linker.resolve(members, t_junction, result.links);
    }
    result.strokes = linker.assemble();
    return result;
}

}  // namespace inkline::core
