// HeightBuffer: a raster's heights in one block of memory that a vtkFloatArray can adopt
// (private header of geomipmap::Filters).
//
// The reader used to hold its heights in a std::vector<float> and copy them into the
// output's vtkFloatArray: two copies of the DEM at the read's peak (2 GiB at 16385²),
// usually the peak of the whole application. A vector cannot give its memory away; this
// buffer can: release() hands the block to vtkFloatArray::SetArray(p, n, 0,
// VTK_DATA_ARRAY_FREE), which frees it with std::free, so the block is allocated with
// std::malloc, or std::aligned_alloc on whole huge pages for DEM-sized buffers
// (HugePages.h: advised before the first write).
//
// Holds floats only, value-initialised by assign(); copies are deep. Allocation failure
// throws std::bad_alloc, as a vector's would.
#pragma once

#include <cstddef>

namespace gmm
{

class HeightBuffer
{
public:
  HeightBuffer() = default;
  HeightBuffer(std::size_t n, float value) { this->assign(n, value); }
  HeightBuffer(const HeightBuffer& other);
  HeightBuffer(HeightBuffer&& other) noexcept;
  HeightBuffer& operator=(const HeightBuffer& other);
  HeightBuffer& operator=(HeightBuffer&& other) noexcept;
  ~HeightBuffer();

  // A fresh block of n samples, all `value` (the old block is freed first).
  void assign(std::size_t n, float value = 0.0f);
  // Frees the block: size 0.
  void clear();
  // Hands the block over (free it with std::free); the buffer is then empty.
  float* release();
  void swap(HeightBuffer& other) noexcept;

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  float* data() { return data_; }
  const float* data() const { return data_; }
  float& operator[](std::size_t k) { return data_[k]; }
  const float& operator[](std::size_t k) const { return data_[k]; }
  float* begin() { return data_; }
  float* end() { return data_ + size_; }
  const float* begin() const { return data_; }
  const float* end() const { return data_ + size_; }

private:
  float* data_ = nullptr;
  std::size_t size_ = 0;
};

} // namespace gmm
