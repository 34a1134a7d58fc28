// A vector with inline storage for the common case (box faces, small hull faces) that spills to
// the heap only for very large faces, so the collide hot path does not allocate.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace gdc::detail {

template <class T, std::size_t InlineCapacity>
class SmallVector {
public:
    void push_back(const T& value) {
        if (size_ < InlineCapacity) {
            inline_[size_++] = value;
            return;
        }
        if (size_ == InlineCapacity) spill_.assign(inline_.begin(), inline_.end());
        spill_.push_back(value);
        ++size_;
    }
    void clear() { size_ = 0, spill_.clear(); }
    void swap(SmallVector& other) {
        if (size_ <= InlineCapacity && other.size_ <= InlineCapacity) {
            std::swap_ranges(inline_.begin(), inline_.begin() + std::max(size_, other.size_), other.inline_.begin());
        } else {
            std::swap(inline_, other.inline_);
        }
        spill_.swap(other.spill_);
        std::swap(size_, other.size_);
    }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T* data() { return size_ > InlineCapacity ? spill_.data() : inline_.data(); }
    const T* data() const { return size_ > InlineCapacity ? spill_.data() : inline_.data(); }
    T& operator[](std::size_t i) { return data()[i]; }
    const T& operator[](std::size_t i) const { return data()[i]; }
    T& back() { return data()[size_ - 1]; }
    void pop_back() {
        if (size_ == InlineCapacity + 1) spill_.clear();
        else if (size_ > InlineCapacity + 1) spill_.pop_back();
        --size_;
    }
    T* begin() { return data(); }
    T* end() { return data() + size_; }
    const T* begin() const { return data(); }
    const T* end() const { return data() + size_; }

private:
    std::array<T, InlineCapacity> inline_;  // not value-initialised: only [0, size) is ever read
    std::vector<T> spill_;
    std::size_t size_ = 0;
};

}  // namespace gdc::detail
