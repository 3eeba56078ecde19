// StaticVector<T, N>: a vector of at most N trivially copyable elements stored inline, so copying a struct that
// holds one (a draw's pipeline state, copied per state change) never allocates. Past N elements push_back and
// resize stop at N (callers stay below the limits the driver reports; N leaves room above them).
#pragma once

#include <algorithm>
#include <cstddef>
#include <initializer_list>
#include <type_traits>

namespace tilevk::rast {

template <class T, size_t N>
class StaticVector {
    static_assert(std::is_trivially_copyable_v<T>);

  public:
    StaticVector() = default;
    StaticVector(std::initializer_list<T> init) { assign(init.begin(), init.end()); }
    StaticVector& operator=(std::initializer_list<T> init) {
        assign(init.begin(), init.end());
        return *this;
    }
    template <class It>
    void assign(It first, It last) {
        size_ = 0;
        for (; first != last && size_ < N; ++first) items_[size_++] = *first;
    }

    void push_back(const T& v) {
        if (size_ < N) items_[size_++] = v;
    }
    void resize(size_t n) {
        n = std::min(n, N);
        for (size_t i = size_; i < n; ++i) items_[i] = T{};
        size_ = n;
    }
    void clear() { size_ = 0; }

    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    static constexpr size_t capacity() { return N; }
    T& operator[](size_t i) { return items_[i]; }
    const T& operator[](size_t i) const { return items_[i]; }
    T* data() { return items_; }
    const T* data() const { return items_; }
    T* begin() { return items_; }
    T* end() { return items_ + size_; }
    const T* begin() const { return items_; }
    const T* end() const { return items_ + size_; }

  private:
    T items_[N] = {};
    size_t size_ = 0;
};

}  // namespace tilevk::rast
