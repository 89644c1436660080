// BudgetController: the triangle budget that makes a frame take a given time.
//
// VTK hands each prop an AllocatedRenderTime (seconds) for interactive frames. The
// controller learns this machine's cost model from the renderer's own recent frames,
//   seconds = fixed + perTriangle * triangles,
// and answers the budget whose predicted time is the target.
//
// Robust to single slow frames. Frame times on a shared machine have a heavy upper tail
// (another process, a page-fault burst, the application's own work between frames): one
// frame may take 1.5x its neighbours at the same triangle count. A least-squares fit lets
// such a frame move the model arbitrarily (on a recorded flight the fixed part jumped from
// 41 to 111 ms on one slow frame, above the 100 ms target, and the budget fell to its
// minimum for ten frames: TestBudgetController replays it). So both terms are medians:
// - fixed: Theil-Sen, the median of the slopes between pairs of frames whose counts differ
//   by at least a quarter (closer pairs give noise over noise), and the median intercept
//   under that slope. Kept from earlier while fewer than kMinPairs pairs qualify (a steady
//   budget does not spread the counts), and never above 0.9x the fastest recent frame.
// - perTriangle: the median over the last `slopeWindow` frames of (seconds - fixed) /
//   triangles, so a spike moves it only if it persists for half of them.
//
// Hysteresis: the budget in force is kept while its predicted time is within
// `hysteresis` (a fraction) of the target, so measurement noise does not make it
// oscillate; when it moves, it moves to the predicted budget, and drops as far as needed
// at once (a slow frame is worse than a coarse one), but grows at most by maxGrowth (2x)
// of what the last frame could use:
// - the factor: a model learnt on small frames may extrapolate badly. A two-speed cap
//   (sqrt(target / last frame's time), clamped to [1.25, 2]) was tried in session 6 and
//   dropped in session 7: it had been measured while llvmpipe's page faults moved the cost
//   per triangle by 2x from frame to frame (vtkGeoMipMapSoftwareRenderer.h); without them,
//   in five alternated runs of bench_budget.py's rate mode, the plain 2x cap held more
//   frames within +-20 % of the target (4097²: 95 against 90 %, Puget Sound: 90 against
//   86 %; benchmarks-core.md, session 7);
// - what the last frame could use: the triangles it drew, or the budget in force when the
//   budget, not tau, stopped it (a refinement step that did not fit leaves the count below
//   the budget, and growing from the count alone could stall there). Never more: a budget
//   far above what tau lets the scene draw would allow one very slow frame when the view
//   changes.
//
//   BudgetController c;
//   std::size_t n = c.budgetFor(allocatedSeconds);  // before the frame
//   ... draw within n ...
//   c.observe(measuredSeconds, trianglesDrawn);      // after it
#pragma once

#include <cstddef>
#include <vector>

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
    double maxGrowth = 2.0;  // growth per frame, of what the last frame could use (> 1)
    int window = 16;         // frames the fixed part is fitted on (3..64)
    int slopeWindow = 5;     // frames the cost per triangle is the median of (1..window)
  };

  // Pairs of frames with counts apart enough that the fixed part is refitted.
  static constexpr int kMinPairs = 6;

  BudgetController() = default;
  explicit BudgetController(const Settings& s)
    : settings_(s)
  {
  }

  // "" when the settings are usable, else the reason (they are then not changed).
  const char* setSettings(const Settings& s);
  const Settings& settings() const { return settings_; }

  // Records a frame that took `seconds` (finite, >= 0) to draw `triangles`; others ignored.
  // budgetReached: the budget in force, not tau, stopped that frame's refinement.
  void observe(double seconds, std::size_t triangles, bool budgetReached = false);

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
  struct Frame
  {
    double seconds;
    double triangles;
  };
  // The k-th most recent observed frame (0: the last), k < min(frames_, window).
  const Frame& recent(int k) const;
  void fit();

  Settings settings_;
  std::size_t budget_ = Settings().initialBudget;
  std::vector<Frame> ring_; // the last `window` frames, oldest overwritten
  std::vector<double> scratch_;
  double fixed_ = 0.0, perTriangle_ = 0.0;
  int frames_ = 0;
  std::size_t lastTriangles_ = 0;
  bool lastReached_ = false;
};

} // namespace gmm
