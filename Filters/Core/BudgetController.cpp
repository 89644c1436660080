#include "BudgetController.h"

#include <algorithm>
#include <cmath>

namespace gmm
{

namespace
{
// The median of v (reordered); v not empty.
double median(std::vector<double>& v)
{
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double upper = v[mid];
  if (v.size() % 2)
  {
    return upper;
  }
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

// Counts this far apart (relative to the larger) make a pair that tells the fixed part
// from the per-triangle part.
constexpr double kPairSpread = 0.4;
} // namespace

const char* BudgetController::setSettings(const Settings& s)
{
  if (s.minBudget < 1 || s.maxBudget < s.minBudget || s.initialBudget < s.minBudget ||
    s.initialBudget > s.maxBudget)
  {
    return "budgets must satisfy 1 <= minBudget <= initialBudget <= maxBudget";
  }
  if (!(s.hysteresis >= 0.0 && s.hysteresis < 1.0))
  {
    return "hysteresis must be in [0, 1)";
  }
  if (!(s.maxGrowth > 1.0 && std::isfinite(s.maxGrowth)))
  {
    return "maxGrowth must be finite and > 1";
  }
  if (s.window < 3 || s.window > 64 || s.slopeWindow < 1 || s.slopeWindow > s.window)
  {
    return "window must be in [3, 64] and slopeWindow in [1, window]";
  }
  settings_ = s;
  reset();
  return "";
}

void BudgetController::reset()
{
  budget_ = settings_.initialBudget;
  ring_.clear();
  fixed_ = perTriangle_ = 0.0;
  frames_ = 0;
  lastTriangles_ = 0;
  lastReached_ = false;
}

const BudgetController::Frame& BudgetController::recent(int k) const
{
  const int w = settings_.window;
  return ring_[static_cast<std::size_t>(((frames_ - 1 - k) % w + w) % w)];
}

void BudgetController::observe(double seconds, std::size_t triangles, bool budgetReached)
{
  if (!(std::isfinite(seconds) && seconds >= 0.0) || triangles == 0)
  {
    return;
  }
  const Frame f{ seconds, static_cast<double>(triangles) };
  if (static_cast<int>(ring_.size()) < settings_.window)
  {
    ring_.push_back(f);
  }
  else
  {
    ring_[static_cast<std::size_t>(frames_ % settings_.window)] = f;
  }
  ++frames_;
  lastTriangles_ = triangles;
  lastReached_ = budgetReached;
  fit();
}

void BudgetController::fit()
{
  const int held = std::min(frames_, settings_.window);
  // Fixed part: Theil-Sen over the pairs whose counts differ enough.
  scratch_.clear();
  for (int i = 0; i < held; ++i)
  {
    for (int j = i + 1; j < held; ++j)
    {
      const Frame& a = recent(i);
      const Frame& b = recent(j);
      if (std::fabs(a.triangles - b.triangles) >= kPairSpread * std::max(a.triangles, b.triangles))
      {
        scratch_.push_back((a.seconds - b.seconds) / (a.triangles - b.triangles));
      }
    }
  }
  if (static_cast<int>(scratch_.size()) >= kMinPairs)
  {
    const double slope = median(scratch_);
    if (slope > 0.0)
    {
      scratch_.clear();
      for (int i = 0; i < held; ++i)
      {
        scratch_.push_back(recent(i).seconds - slope * recent(i).triangles);
      }
      fixed_ = std::max(median(scratch_), 0.0);
    }
  }
  double fastest = recent(0).seconds;
  for (int i = 1; i < held; ++i)
  {
    fastest = std::min(fastest, recent(i).seconds);
  }
  fixed_ = std::min(fixed_, 0.9 * fastest);
  // Cost per triangle: the median of the recent frames' own, over the fixed part.
  scratch_.clear();
  for (int i = 0; i < std::min(held, settings_.slopeWindow); ++i)
  {
    scratch_.push_back((recent(i).seconds - fixed_) / recent(i).triangles);
  }
  perTriangle_ = median(scratch_);
}

double BudgetController::predict(std::size_t triangles) const
{
  return frames_ ? fixed_ + perTriangle_ * static_cast<double>(triangles) : 0.0;
}

std::size_t BudgetController::budgetFor(double seconds)
{
  if (!(std::isfinite(seconds) && seconds > 0.0) || frames_ == 0 || !(perTriangle_ > 0.0))
  {
    return budget_;
  }
  const double predicted = predict(budget_);
  if (std::fabs(predicted - seconds) <= settings_.hysteresis * seconds)
  {
    return budget_;
  }
  double want = (seconds - fixed_) / perTriangle_;
  // Growth: at most maxGrowth of what the last frame could use (see the header).
  const double usable = lastReached_ ? std::max(static_cast<double>(lastTriangles_), static_cast<double>(budget_))
                                     : static_cast<double>(lastTriangles_);
  want = std::min(want, usable * settings_.maxGrowth);
  want = std::max(want, static_cast<double>(settings_.minBudget));
  want = std::min(want, static_cast<double>(settings_.maxBudget));
  budget_ = static_cast<std::size_t>(want);
  return budget_;
}

} // namespace gmm
