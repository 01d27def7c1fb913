// SPDX-License-Identifier: MIT
#include "core/strokes/drawing_order.h"

#include "core/internal/point_grid.h"
#include "core/internal/union_find.h"
#include "core/strokes/stroke_path.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <limits>
#include <numeric>
#include <tuple>
#include <utility>

namespace inkline::core {

std::vector<std::vector<uint32_t>> touching_strokes(std::span<const Stroke> strokes, double junction_px) {
    // Points by their boxes, grown by junction_px: an end within junction_px of a point lies in
    // a cell the point's box touches. Cells of 1 px hold few points, so an end seldom reaches
    // kCrowded before it reaches the points it shares.
    struct Point {
        uint32_t stroke, index;
        bool operator<(const Point& o) const { return std::tie(stroke, index) < std::tie(o.stroke, o.index); }
    };
    internal::PointGrid<Point> grid(std::max(1.0, 4.0 * junction_px));
    for (uint32_t s = 0; s < strokes.size(); ++s) {
        const std::vector<glm::dvec2>& p = strokes[s].geometry.points_px;
        for (uint32_t i = 0; i < p.size(); ++i) grid.add_box(p[i] - junction_px, p[i] + junction_px, {s, i});
    }
    grid.sort();
    std::vector<std::vector<uint32_t>> touches(strokes.size());
    // An end looks at no more than kCrowded points around it: where more crowd (thousands of
    // strokes meeting at one point), the ends that share the point join through the hub below.
    constexpr size_t kCrowded = 64;
    std::vector<std::tuple<double, double, uint32_t>> ends;  // (x, y, stroke) of every end
    for (uint32_t s = 0; s < strokes.size(); ++s) {
        const std::vector<glm::dvec2>& p = strokes[s].geometry.points_px;
        if (p.empty()) continue;
        for (const glm::dvec2& end : {p.front(), p.back()}) {
            ends.emplace_back(end.x, end.y, s);
            size_t seen = 0;
            grid.any_in_box(end, end, [&](const Point& q) {
                if (++seen > kCrowded) return true;
                if (q.stroke == s) return false;
                if (glm::distance(end, strokes[q.stroke].geometry.points_px[q.index]) <= junction_px) {
                    touches[s].push_back(q.stroke);
                    touches[q.stroke].push_back(s);
                }
                return false;
            });
        }
    }
    // Strokes whose ends share a point touch: each joins the point's first stroke (all of them
    // one another when few), so a junction of k strokes costs k, not k squared.
    std::sort(ends.begin(), ends.end());
    for (size_t a = 0; a < ends.size();) {
        size_t b = a;
        std::vector<uint32_t> hub;
        for (; b < ends.size() && std::get<0>(ends[b]) == std::get<0>(ends[a]) && std::get<1>(ends[b]) == std::get<1>(ends[a]); ++b) {
            hub.push_back(std::get<2>(ends[b]));
        }
        hub.erase(std::unique(hub.begin(), hub.end()), hub.end());
        const size_t partners = hub.size() <= kCrowded ? hub.size() : 1;
        for (size_t i = 0; i < partners; ++i) {
            for (size_t j = i + 1; j < hub.size(); ++j) {
                touches[hub[i]].push_back(hub[j]);
                touches[hub[j]].push_back(hub[i]);
            }
        }
        a = b;
    }
    for (std::vector<uint32_t>& t : touches) {
        std::sort(t.begin(), t.end());
        t.erase(std::unique(t.begin(), t.end()), t.end());
    }
    return touches;
}

namespace {

// Whether an end of a lies within max_px of b's polyline, or an end of b of a's.
bool ends_near(const std::vector<glm::dvec2>& a, const std::vector<glm::dvec2>& b, double max_px) {
    auto end_near = [max_px](const glm::dvec2& end, const std::vector<glm::dvec2>& line) {
        if (line.size() == 1) return glm::distance(end, line[0]) <= max_px;
        for (size_t k = 0; k + 1 < line.size(); ++k) {
            if (distance_to_segment(end, line[k], line[k + 1]) <= max_px) return true;
        }
        return false;
    };
    return !a.empty() && !b.empty() &&
           (end_near(a.front(), b) || end_near(a.back(), b) || end_near(b.front(), a) || end_near(b.back(), a));
}

// Adds to `r_touches` each stroke and last frame's parent (`last_parent`: id -> parent id) that
// no longer touch but whose ends lie within max_px; the lists stay ascending.
void keep_parents_touching(std::span<const Stroke> strokes, const std::unordered_map<uint32_t, uint32_t>& last_parent,
                           double max_px, std::vector<std::vector<uint32_t>>& r_touches) {
    if (last_parent.empty()) return;
    std::unordered_map<uint32_t, uint32_t> index_of;
    for (uint32_t i = 0; i < strokes.size(); ++i) index_of.emplace(strokes[i].id, i);
    auto insert = [](std::vector<uint32_t>& list, uint32_t v) { list.insert(std::upper_bound(list.begin(), list.end(), v), v); };
    for (uint32_t i = 0; i < strokes.size(); ++i) {
        const auto lp = last_parent.find(strokes[i].id);
        const auto p = lp == last_parent.end() ? index_of.end() : index_of.find(lp->second);
        if (p == index_of.end() || std::binary_search(r_touches[i].begin(), r_touches[i].end(), p->second)) continue;
        if (!ends_near(strokes[i].geometry.points_px, strokes[p->second].geometry.points_px, max_px)) continue;
        insert(r_touches[i], p->second);
        insert(r_touches[p->second], i);
    }
}

}  // namespace

void DrawingOrder::hold_back_joins(std::span<const Stroke> strokes, std::vector<std::vector<uint32_t>>& r_touches) {
    std::unordered_map<uint64_t, uint32_t> held;
    std::vector<std::pair<uint32_t, uint32_t>> dropped;
    for (uint32_t i = 0; i < strokes.size() && options_.join_after_frames > 1; ++i) {
        const auto group_i = last_group_.find(strokes[i].id);
        if (group_i == last_group_.end()) continue;
        for (const uint32_t j : r_touches[i]) {
            const auto group_j = j > i ? last_group_.find(strokes[j].id) : last_group_.end();
            if (group_j == last_group_.end() || group_j->second == group_i->second) continue;
            const uint64_t pair = (uint64_t(std::min(strokes[i].id, strokes[j].id)) << 32) | std::max(strokes[i].id, strokes[j].id);
            const auto before = held_.find(pair);
            const uint32_t frames = held[pair] = (before == held_.end() ? 0 : before->second) + 1;
            if (frames < options_.join_after_frames) dropped.emplace_back(i, j);
        }
    }
    for (const auto& [i, j] : dropped) {
        std::erase(r_touches[i], j);
        std::erase(r_touches[j], i);
    }
    held_ = std::move(held);
}

void DrawingOrder::assign(std::vector<Stroke>& r_strokes) {
    const size_t n = r_strokes.size();
    std::vector<std::vector<uint32_t>> touches = touching_strokes(r_strokes, options_.junction_px);
    // A stroke and last frame's parent still touch while their ends stay near.
    keep_parents_touching(r_strokes, last_parent_, options_.keep_parent_px, touches);
    // Last frame's groups join only through a touch that has held join_after_frames frames.
    hold_back_joins(r_strokes, touches);
    std::vector<double> length(n);
    for (size_t i = 0; i < n; ++i) length[i] = r_strokes[i].geometry.length_px();
    constexpr uint32_t kNew = std::numeric_limits<uint32_t>::max();
    auto last_order = [&](size_t i) {
        const auto it = last_order_.find(r_strokes[i].id);
        return it == last_order_.end() ? kNew : it->second;
    };
    // Persisting strokes in last frame's order, then the others longest first.
    auto earlier = [&](size_t a, size_t b) {
        return std::make_tuple(last_order(a), -length[a], r_strokes[a].id) <
               std::make_tuple(last_order(b), -length[b], r_strokes[b].id);
    };

    // Groups: connected sets of touching strokes (the joins held back aside), members ascending.
    internal::UnionFind<uint32_t> sets(n);
    for (uint32_t i = 0; i < n; ++i) {
        for (const uint32_t j : touches[i]) sets.unite(i, j);
    }
    std::vector<std::vector<uint32_t>> groups;
    std::vector<uint32_t> group_of_root(n, kNew);
    for (uint32_t i = 0; i < n; ++i) {
        const uint32_t root = sets.find(i);
        if (group_of_root[root] == kNew) {
            group_of_root[root] = uint32_t(groups.size());
            groups.emplace_back();
        }
        groups[group_of_root[root]].push_back(i);
    }

    constexpr uint32_t kUnset = std::numeric_limits<uint32_t>::max();
    auto last_level = [&](uint32_t i) {
        const auto it = last_level_.find(r_strokes[i].id);
        return it == last_level_.end() ? kUnset : it->second;
    };
    // The levels of a group's strokes under a main stroke: each stroke keeps last frame's level
    // where a stroke it touches is one level up (last frame's parent first), taken level by
    // level from the main stroke down; the others hang from the nearest stroke already placed,
    // breadth first. Returns how many strokes keep last frame's level.
    std::vector<uint32_t> level(n, kUnset), parent(n, kUnset);
    std::vector<uint32_t> keeping, heap;
    auto place = [&](const std::vector<uint32_t>& group, uint32_t main) {
        for (const uint32_t i : group) level[i] = parent[i] = kUnset;
        level[main] = 0;
        keeping.clear();
        for (const uint32_t i : group) {
            if (i != main && last_level(i) != kUnset && last_level(i) > 0) keeping.push_back(i);
        }
        std::sort(keeping.begin(), keeping.end(), [&](uint32_t a, uint32_t b) {
            return std::make_tuple(last_level(a), last_order(a), r_strokes[a].id) < std::make_tuple(last_level(b), last_order(b), r_strokes[b].id);
        });
        for (const uint32_t t : keeping) {
            const uint32_t want = last_level(t);
            const auto lp = last_parent_.find(r_strokes[t].id);
            uint32_t best = kUnset;
            for (const uint32_t x : touches[t]) {
                if (level[x] != want - 1) continue;
                if (lp != last_parent_.end() && r_strokes[x].id == lp->second) {
                    best = x;
                    break;
                }
                if (best == kUnset || earlier(x, best)) best = x;
            }
            if (best != kUnset) {
                level[t] = want;
                parent[t] = best;
            }
        }
        // The rest, nearest first from what is placed (a queue by level, then drawing order).
        auto later = [&](uint32_t a, uint32_t b) { return level[a] != level[b] ? level[a] > level[b] : earlier(b, a); };
        heap.clear();
        for (const uint32_t i : group) {
            if (level[i] != kUnset) heap.push_back(i);
        }
        std::make_heap(heap.begin(), heap.end(), later);
        while (!heap.empty()) {
            std::pop_heap(heap.begin(), heap.end(), later);
            const uint32_t s_index = heap.back();
            heap.pop_back();
            for (const uint32_t t : touches[s_index]) {
                if (level[t] != kUnset) continue;
                level[t] = level[s_index] + 1;
                parent[t] = s_index;
                heap.push_back(t);
                std::push_heap(heap.begin(), heap.end(), later);
            }
        }
        size_t kept = 0;
        for (const uint32_t i : group) kept += level[i] == last_level(i) ? 1 : 0;
        return kept;
    };

    // The main stroke of each group: of its strokes at least keep_main_share as long as its
    // longest (the longest main_candidates of them, last frame's main strokes first), the one
    // under which the most strokes keep last frame's level; a tie goes to last frame's main
    // stroke, then to the longer. In a first frame that is the longest.
    auto longer = [&](uint32_t a, uint32_t b) {
        return length[a] > length[b] || (length[a] == length[b] && r_strokes[a].id < r_strokes[b].id);
    };
    std::vector<uint32_t> mains, candidates;
    for (const std::vector<uint32_t>& group : groups) {
        const uint32_t longest = *std::min_element(group.begin(), group.end(), longer);
        candidates.clear();
        for (const uint32_t i : group) {
            if (length[i] >= options_.keep_main_share * length[longest]) candidates.push_back(i);
        }
        std::sort(candidates.begin(), candidates.end(), [&](uint32_t a, uint32_t b) {
            const bool main_a = last_level(a) == 0, main_b = last_level(b) == 0;
            return main_a != main_b ? main_a : longer(a, b);
        });
        const bool seen = std::any_of(group.begin(), group.end(), [&](uint32_t i) { return last_level(i) != kUnset; });
        candidates.resize(seen ? std::min(candidates.size(), options_.main_candidates) : 1);
        uint32_t main = candidates.front();
        size_t most = place(group, main);
        for (size_t c = 1; c < candidates.size(); ++c) {
            if (const size_t kept = place(group, candidates[c]); kept > most) {
                most = kept;
                main = candidates[c];
            }
        }
        if (main != candidates.back()) place(group, main);
        mains.push_back(main);
    }
    std::vector<uint32_t> group_order(groups.size());
    for (uint32_t g = 0; g < groups.size(); ++g) group_order[g] = g;
    std::sort(group_order.begin(), group_order.end(), [&](uint32_t a, uint32_t b) { return earlier(mains[a], mains[b]); });

    // The order a fresh frame would have: group after group, level after level, each level by
    // its parents' order, then as `earlier` says.
    std::vector<uint32_t> fresh(n, kUnset);
    {
        std::vector<std::vector<uint32_t>> by_level;
        uint32_t next = 0;
        for (const uint32_t g : group_order) {
            by_level.clear();
            for (const uint32_t i : groups[g]) {
                if (by_level.size() <= level[i]) by_level.resize(level[i] + 1);
                by_level[level[i]].push_back(i);
            }
            for (std::vector<uint32_t>& members : by_level) {
                std::sort(members.begin(), members.end(), [&](uint32_t a, uint32_t b) {
                    const uint32_t pa = parent[a] == kUnset ? 0 : fresh[parent[a]];
                    const uint32_t pb = parent[b] == kUnset ? 0 : fresh[parent[b]];
                    return pa != pb ? pa < pb : earlier(a, b);
                });
                for (const uint32_t i : members) fresh[i] = next++;
            }
        }
    }
    // The order: parents before their strokes; among the strokes whose parents are drawn, those
    // of last frame in last frame's order, the new ones just before the first stroke of last
    // frame that hangs from them, else at their place in the fresh order.
    std::vector<std::vector<uint32_t>> children(n);
    for (uint32_t i = 0; i < n; ++i) {
        if (parent[i] != kUnset) children[parent[i]].push_back(i);
    }
    // A new stroke from which strokes of last frame hang is drawn just before the first of them
    // (as their parent it comes before them anyway), so they keep their order.
    std::vector<uint32_t> first_kept(n, kNew);  // the least order last frame in each stroke's subtree
    {
        std::vector<uint32_t> deepest_first(n);
        std::iota(deepest_first.begin(), deepest_first.end(), 0u);
        std::sort(deepest_first.begin(), deepest_first.end(), [&](uint32_t a, uint32_t b) { return level[a] > level[b]; });
        for (const uint32_t i : deepest_first) {
            first_kept[i] = std::min(first_kept[i], last_order(i));
            if (parent[i] != kUnset) first_kept[parent[i]] = std::min(first_kept[parent[i]], first_kept[i]);
        }
    }
    auto key = [&](uint32_t i) {
        const uint32_t last = last_order(i);
        const double at = last != kNew ? double(last) : double(first_kept[i] != kNew ? first_kept[i] : fresh[i]) - 0.5;
        return std::make_tuple(at, r_strokes[i].id);
    };
    auto after = [&](uint32_t a, uint32_t b) { return key(a) > key(b); };
    std::vector<uint32_t> ready(mains.begin(), mains.end());
    std::make_heap(ready.begin(), ready.end(), after);
    uint32_t next = 0;
    while (!ready.empty()) {
        std::pop_heap(ready.begin(), ready.end(), after);
        const uint32_t i = ready.back();
        ready.pop_back();
        r_strokes[i].order = next++;
        for (const uint32_t c : children[i]) {
            ready.push_back(c);
            std::push_heap(ready.begin(), ready.end(), after);
        }
    }
    for (uint32_t g = 0; g < groups.size(); ++g) {
        for (const uint32_t i : groups[g]) {
            Stroke& st = r_strokes[i];
            st.group = r_strokes[mains[g]].id;
            st.level = level[i];
            st.parent = parent[i] == kUnset ? -1 : int64_t(r_strokes[parent[i]].id);
        }
    }

    last_order_.clear();
    last_level_.clear();
    last_parent_.clear();
    last_group_.clear();
    for (const Stroke& st : r_strokes) {
        last_order_[st.id] = st.order;
        last_level_[st.id] = st.level;
        last_group_[st.id] = st.group;
        if (st.parent >= 0) last_parent_[st.id] = uint32_t(st.parent);
    }
}

}  // namespace inkline::core
