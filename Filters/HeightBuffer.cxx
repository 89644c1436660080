#include "HeightBuffer.h"

#include "HugePages.h" // gmm::adviseHugePages, kHugePageBytes

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

namespace gmm
{

namespace
{
// n floats from malloc, or on whole huge pages when they fill one; freed by std::free.
float* allocateHeights(std::size_t n)
{
  if (n == 0)
  {
    return nullptr;
  }
  if (n > static_cast<std::size_t>(-1) / sizeof(float) - kHugePageBytes)
  {
    throw std::bad_alloc();
  }
  const std::size_t bytes = n * sizeof(float);
  void* p = nullptr;
  if (bytes >= kHugePageBytes)
  {
    // aligned_alloc wants a multiple of the alignment.
    const std::size_t whole = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
    p = std::aligned_alloc(kHugePageBytes, whole);
    if (p)
    {
      adviseHugePages(p, whole);
    }
  }
  else
  {
    p = std::malloc(bytes);
  }
  if (!p)
  {
    throw std::bad_alloc();
  }
  return static_cast<float*>(p);
}
} // namespace

HeightBuffer::HeightBuffer(const HeightBuffer& other)
{
  data_ = allocateHeights(other.size_);
  size_ = other.size_;
  if (size_)
  {
    std::memcpy(data_, other.data_, size_ * sizeof(float));
  }
}

HeightBuffer::HeightBuffer(HeightBuffer&& other) noexcept
{
  this->swap(other);
}

HeightBuffer& HeightBuffer::operator=(const HeightBuffer& other)
{
  if (this != &other)
  {
    HeightBuffer copy(other);
    this->swap(copy);
  }
  return *this;
}

HeightBuffer& HeightBuffer::operator=(HeightBuffer&& other) noexcept
{
  if (this != &other)
  {
    this->clear();
    this->swap(other);
  }
  return *this;
}

HeightBuffer::~HeightBuffer()
{
  this->clear();
}

void HeightBuffer::assign(std::size_t n, float value)
{
  this->clear();
  data_ = allocateHeights(n);
  size_ = n;
  std::fill(data_, data_ + n, value);
}

void HeightBuffer::clear()
{
  std::free(data_);
  data_ = nullptr;
  size_ = 0;
}

float* HeightBuffer::release()
{
  float* p = data_;
  data_ = nullptr;
  size_ = 0;
  return p;
}

void HeightBuffer::swap(HeightBuffer& other) noexcept
{
  std::swap(data_, other.data_);
  std::swap(size_, other.size_);
}

} // namespace gmm
