// RecycledList<T>: a list whose elements live on after clear(): emplace_back() hands out an element of an earlier
// round, reset by T::reset() (which keeps the capacity of its vectors), so the second and later rounds of the
// same size allocate nothing (per-draw records of a steady frame). References stay valid until clear().
#pragma once

#include <cstddef>
#include <memory>
#include <utility>
#include <vector>

namespace tilevk::rast {

template <class T>
class RecycledList {
  public:
    T& emplace_back() {
        if (size_ == items_.size()) items_.push_back(std::make_unique<T>());
        T& t = *items_[size_++];
        t.reset();
        return t;
    }
    void clear() { size_ = 0; }
    // Keeps only the last element, which becomes element 0 (at the same address: references to it stay valid).
    void keep_only_last() {
        if (size_ == 0) return;
        std::swap(items_[0], items_[size_ - 1]);
        size_ = 1;
    }
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T& operator[](size_t i) { return *items_[i]; }
    const T& operator[](size_t i) const { return *items_[i]; }
    T& back() { return *items_[size_ - 1]; }
    const T& back() const { return *items_[size_ - 1]; }

  private:
    std::vector<std::unique_ptr<T>> items_;
    size_t size_ = 0;
};

}  // namespace tilevk::rast
