#include "BudgetController.h"

#include <algorithm>
#include <cmath>

namespace gmm
{

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
  if (!(s.forgetting >= 0.0 && s.forgetting < 1.0))
  {
    return "forgetting must be in [0, 1)";
  }
  settings_ = s;
  reset();
  return "";
}

void BudgetController::reset()
{
  budget_ = settings_.initialBudget;
  w_ = sn_ = st_ = snn_ = snt_ = 0.0;
  fixed_ = perTriangle_ = 0.0;
  frames_ = 0;
  lastTriangles_ = 0;
}

void BudgetController::observe(double seconds, std::size_t triangles)
{
  if (!(std::isfinite(seconds) && seconds >= 0.0) || triangles == 0)
  {
    return;
  }
  const double n = static_cast<double>(triangles), f = settings_.forgetting;
  w_ = f * w_ + 1.0;
  sn_ = f * sn_ + n;
  st_ = f * st_ + seconds;
  snn_ = f * snn_ + n * n;
  snt_ = f * snt_ + n * seconds;
  ++frames_;
  lastTriangles_ = triangles;
  fit();
}

void BudgetController::fit()
{
  const double meanN = sn_ / w_, meanT = st_ / w_;
  const double varN = snn_ / w_ - meanN * meanN;
  const double covNT = snt_ / w_ - meanN * meanT;
  // Regress only when the triangle counts spread (relative deviation above ~5 %): else
  // the slope is noise over noise.
  if (varN > 0.0025 * meanN * meanN && covNT > 0.0)
  {
    const double slope = covNT / varN;
    const double intercept = meanT - slope * meanN;
    if (intercept >= 0.0)
    {
      perTriangle_ = slope;
      fixed_ = intercept;
      return;
    }
  }
  // Keep the fixed part (clamped to what the frames allow) and fit the slope through it.
  fixed_ = std::min(fixed_, 0.9 * meanT);
  perTriangle_ = (meanT - fixed_) / meanN;
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
  want = std::min(want, static_cast<double>(lastTriangles_) * settings_.maxGrowth);
  want = std::max(want, static_cast<double>(settings_.minBudget));
  want = std::min(want, static_cast<double>(settings_.maxBudget));
  budget_ = static_cast<std::size_t>(want);
  return budget_;
}

} // namespace gmm
