// SPDX-License-Identifier: MIT
// Items at image points (or over boxes: a segment by its bounding box) on a uniform grid of square
// cells, sorted by cell and then by item, so that lookups visit them in an order that depends on
// the input alone.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/vec2.hpp>
#include <tuple>
#include <vector>

namespace inkline::core::internal {

template <typename Item>  // ordered by operator<
class PointGrid {
  public:
    explicit PointGrid(double cell_px) : cell_px_(cell_px) {}

    void add(const glm::dvec2& p, const Item& item) { entries_.push_back({key(cell(p)), item}); }
    // Adds the item to every cell that the box [lo, hi] touches.
    void add_box(const glm::dvec2& lo, const glm::dvec2& hi, const Item& item) {
        const glm::ivec2 a = cell(lo), b = cell(hi);
        for (int y = a.y; y <= b.y; ++y) {
            for (int x = a.x; x <= b.x; ++x) entries_.push_back({key({x, y}), item});
        }
    }
    // After the last add, before the first lookup.
    void sort() {
        std::sort(entries_.begin(), entries_.end(),
                  [](const Entry& a, const Entry& b) { return std::tie(a.key, a.item) < std::tie(b.key, b.item); });
    }

    // Calls visit(item) for every item in p's cell and the eight around it: all items within one
    // cell size of p, and some farther.
    template <typename Visit>
    void around(const glm::dvec2& p, Visit visit) const {
        const glm::ivec2 c = cell(p);
        for (int y = c.y - 1; y <= c.y + 1; ++y) {
            for (int x = c.x - 1; x <= c.x + 1; ++x) visit_cell({x, y}, visit);
        }
    }

    // Whether found(item) holds for an item in a cell that the box [lo, hi] touches (all items
    // within the box, and some beyond it); stops at the first.
    template <typename Found>
    bool any_in_box(const glm::dvec2& lo, const glm::dvec2& hi, Found found) const {
        const glm::ivec2 a = cell(lo), b = cell(hi);
        for (int y = a.y; y <= b.y; ++y) {
            for (int x = a.x; x <= b.x; ++x) {
                const int64_t k = key({x, y});
                for (auto it = first_of(k); it != entries_.end() && it->key == k; ++it) {
                    if (found(it->item)) return true;
                }
            }
        }
        return false;
    }

  private:
    struct Entry {
        int64_t key;
        Item item;
    };

    // The first entry of the cell with key k, or where it would be.
    typename std::vector<Entry>::const_iterator first_of(int64_t k) const {
        return std::lower_bound(entries_.begin(), entries_.end(), k,
                                [](const Entry& e, int64_t v) { return e.key < v; });
    }
    template <typename Visit>
    void visit_cell(const glm::ivec2& c, Visit& visit) const {
        const int64_t k = key(c);
        for (auto it = first_of(k); it != entries_.end() && it->key == k; ++it) visit(it->item);
    }

    glm::ivec2 cell(const glm::dvec2& p) const {
        return {int(std::floor(std::clamp(p.x, -1e8, 1e8) / cell_px_)),
                int(std::floor(std::clamp(p.y, -1e8, 1e8) / cell_px_))};
    }
    static int64_t key(const glm::ivec2& c) { return (int64_t(c.x) << 32) ^ int64_t(uint32_t(c.y)); }

    double cell_px_;
    std::vector<Entry> entries_;
};

}  // namespace inkline::core::internal
