#pragma once
// A dense row-major 2-D array; the raster type every algorithm works on.
#include <cstddef>
#include <utility>
#include <vector>

namespace skyview {

template <class T>
class Grid {
 public:
  Grid() = default;
  Grid(int width, int height, T fill = T{})
      : width_(width), height_(height), data_(static_cast<std::size_t>(width) * height, fill) {}
  // Takes over `values`, row-major, which must hold width * height of them.
  Grid(int width, int height, std::vector<T>&& values) : width_(width), height_(height), data_(std::move(values)) {
    data_.resize(static_cast<std::size_t>(width) * height);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return data_.size(); }
  bool in_grid(int col, int row) const { return col >= 0 && row >= 0 && col < width_ && row < height_; }

  T& operator()(int col, int row) { return data_[index(col, row)]; }
  const T& operator()(int col, int row) const { return data_[index(col, row)]; }
  std::size_t index(int col, int row) const { return static_cast<std::size_t>(row) * width_ + col; }

  T* data() { return data_.data(); }
  const T* data() const { return data_.data(); }
  std::vector<T>& values() { return data_; }
  const std::vector<T>& values() const { return data_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<T> data_;
};

}  // namespace skyview
