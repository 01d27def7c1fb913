// SPDX-License-Identifier: MIT
// An open-addressing hash from 64-bit keys to small values (the tone's grids, the glTF weld's cells):
// a slot holds its key and value together (one cache line per probe), linear probing, never more
// than half full (it doubles as it fills).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace inkline::core::internal {

// A 64-bit mixer (the finaliser of MurmurHash3): every bit of a key reaches the low bits that
// pick a slot.
inline uint64_t mix_key(uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    return x ^ (x >> 33);
}

template <typename Value>
class KeyTable {
  public:
    // The key no entry may have.
    static constexpr uint64_t kEmpty = ~uint64_t(0);

    explicit KeyTable(size_t expected = 0) { reserve(expected); }

    // The value of a key, default-constructed when it was absent (then inserted).
    Value& operator[](uint64_t key) {
        if (2 * (size_ + 1) > slots_.size()) reserve(2 * (size_ + 1));
        Slot& slot = slots_[slot_of(key)];
        if (slot.key == kEmpty) {
            slot.key = key;
            ++size_;
        }
        return slot.value;
    }
    // The value of a key; nullptr when absent.
    const Value* find(uint64_t key) const {
        if (slots_.empty()) return nullptr;
        const Slot& slot = slots_[slot_of(key)];
        return slot.key == kEmpty ? nullptr : &slot.value;
    }
    size_t size() const { return size_; }

  private:
    struct Slot {
        uint64_t key = kEmpty;
        Value value{};
    };

    // Room for `count` entries at most half full.
    void reserve(size_t count) {
        size_t capacity = 16;
        while (capacity < 2 * count) capacity *= 2;
        if (capacity <= slots_.size()) return;
        std::vector<Slot> old(capacity);
        old.swap(slots_);
        for (const Slot& slot : old) {
            if (slot.key != kEmpty) slots_[slot_of(slot.key)] = slot;
        }
    }
    size_t slot_of(uint64_t key) const {
        const size_t mask = slots_.size() - 1;
        size_t slot = size_t(mix_key(key)) & mask;
        while (slots_[slot].key != kEmpty && slots_[slot].key != key) slot = (slot + 1) & mask;
        return slot;
    }

    std::vector<Slot> slots_;
    size_t size_ = 0;
};

}  // namespace inkline::core::internal
