// BudgetController: the triangle budget that makes a frame take a given time.
//
// VTK hands each prop an AllocatedRenderTime (seconds) for interactive frames. The
// controller learns this machine's cost model from the renderer's own recent frames,
//   seconds = fixed + perTriangle * triangles,
// by least squares with exponential forgetting, and answers the budget whose predicted
// time is the target. When recent frames all drew about the same number of triangles the
// two terms cannot be told apart: the fixed part is then kept from earlier and the slope
// alone follows the frames.
//
// Hysteresis: the budget in force is kept while its predicted time is within
// `hysteresis` (a fraction) of the target, so measurement noise does not make it
// oscillate; when it moves, it moves to the predicted budget, but it grows at most to
// `maxGrowth` times the triangles last drawn (a model learnt on small frames may
// extrapolate badly, and a budget far above what tau lets the scene draw would allow one
// very slow frame when the view changes) and drops as far as needed at once (a slow frame
// is worse than a coarse one).
//
//   BudgetController c;
//   std::size_t n = c.budgetFor(allocatedSeconds);  // before the frame
//   ... draw within n ...
//   c.observe(measuredSeconds, trianglesDrawn);      // after it
#pragma once

#include <cstddef>

namespace gmm
{

class BudgetController
{
public:
  struct Settings
  {
    std::size_t initialBudget = 65536; // before any frame was observed
    std::size_t minBudget = 512;
    std::size_t maxBudget = std::size_t(1) << 30;
    double hysteresis = 0.1; // keep the budget while predicted time is within 10 % of target
    double maxGrowth = 2.0;  // at most x2 the triangles last drawn
    double forgetting = 0.7; // weight of the past per observed frame (0..1)
  };

  BudgetController() = default;
  explicit BudgetController(const Settings& s)
    : settings_(s)
  {
  }

  // "" when the settings are usable, else the reason (they are then not changed).
  const char* setSettings(const Settings& s);
  const Settings& settings() const { return settings_; }

  // Records a frame that took `seconds` (finite, >= 0) to draw `triangles`; others ignored.
  void observe(double seconds, std::size_t triangles);

  // The budget for a frame that should take `seconds`; updates the budget in force. A
  // target that is not finite and > 0 leaves the budget as it is.
  std::size_t budgetFor(double seconds);

  std::size_t budget() const { return budget_; }
  // The model (0 until a frame was observed).
  double fixedSeconds() const { return fixed_; }
  double secondsPerTriangle() const { return perTriangle_; }
  int framesObserved() const { return frames_; }
  // Predicted seconds for `triangles` (0 before any frame).
  double predict(std::size_t triangles) const;

  // Forgets the model and returns to the initial budget.
  void reset();

private:
  void fit();

  Settings settings_;
  std::size_t budget_ = Settings().initialBudget;
  // Weighted sums over frames: weight, n, t, n^2, n t.
  double w_ = 0.0, sn_ = 0.0, st_ = 0.0, snn_ = 0.0, snt_ = 0.0;
  double fixed_ = 0.0, perTriangle_ = 0.0;
  int frames_ = 0;
  std::size_t lastTriangles_ = 0;
};

} // namespace gmm
