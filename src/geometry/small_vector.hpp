// A vector with inline storage for the common case (box faces, small hull faces) that spills to
// the heap only for very large faces, so the collide hot path does not allocate.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace gdc::detail {

template <class T, std::size_t InlineCapacity>
class SmallVector {
public:
    SmallVector() = default;
    SmallVector(const SmallVector& other) { *this = other; }
    SmallVector(SmallVector&& other) noexcept { *this = std::move(other); }
    ~SmallVector() {
        if (data_ != inline_.data()) delete[] data_;
    }
    SmallVector& operator=(const SmallVector& other) {
        if (this == &other) return *this;
        clear();
        reserve(other.size_);
        std::copy(other.data_, other.data_ + other.size_, data_);
        size_ = other.size_;
        return *this;
    }
    SmallVector& operator=(SmallVector&& other) noexcept {
        if (this == &other) return *this;
        if (other.data_ == other.inline_.data()) {
            release();
            std::copy(other.data_, other.data_ + other.size_, inline_.data());
        } else {
            release();
            data_ = other.data_, capacity_ = other.capacity_;
            other.data_ = other.inline_.data(), other.capacity_ = InlineCapacity;
        }
        size_ = other.size_;
        other.size_ = 0;
        return *this;
    }

    // Every access goes through `data_` (the inline array or the spill), with no branch on which.
    void push_back(const T& value) {
        if (size_ == capacity_) grow(size_ + 1);
        data_[size_++] = value;
    }
    void clear() { size_ = 0; }
    /// Room for `count` elements in all, the ones held kept; returns data(). For a loop that writes
    /// through the pointer and then calls setSize: it keeps its count in a register, where
    /// push_back reloads the vector's fields after each element (Eigen's stores may alias them).
    T* reserve(std::size_t count) {
        if (count > capacity_) grow(count);
        return data_;
    }
    /// The size after writing through reserve()'s pointer (`count` ≤ the count reserved).
    void setSize(std::size_t count) { size_ = count; }
    void swap(SmallVector& other) {
        SmallVector temporary(std::move(other));
        other = std::move(*this);
        *this = std::move(temporary);
    }
    std::size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    T* data() { return data_; }
    const T* data() const { return data_; }
    T& operator[](std::size_t i) { return data_[i]; }
    const T& operator[](std::size_t i) const { return data_[i]; }
    T& back() { return data_[size_ - 1]; }
    void pop_back() { --size_; }
    T* begin() { return data_; }
    T* end() { return data_ + size_; }
    const T* begin() const { return data_; }
    const T* end() const { return data_ + size_; }

private:
    // Moves the elements to a spill of at least `count` (and twice the old capacity).
    void grow(std::size_t count) {
        const std::size_t capacity = std::max(count, 2 * capacity_);
        T* larger = new T[capacity];
        std::copy(data_, data_ + size_, larger);
        release();
        data_ = larger, capacity_ = capacity;
    }
    // Back to the inline storage (the elements are not kept).
    void release() {
        if (data_ != inline_.data()) delete[] data_;
        data_ = inline_.data(), capacity_ = InlineCapacity;
    }

    std::array<T, InlineCapacity> inline_;  // not value-initialised: only [0, size) is ever read
    T* data_ = inline_.data();  // inline_, or the heap once more than InlineCapacity were held
    std::size_t size_ = 0;
    std::size_t capacity_ = InlineCapacity;
};

}  // namespace gdc::detail
