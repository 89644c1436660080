// BudgetController against fake cost models: it must converge to the budget that fits the
// target, move in the right direction when the target changes, hold still under noise
// (hysteresis), and refuse bad settings. No clock is read.
#include "BudgetController.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace
{
// This "machine": 3 ms per frame plus 40 ns per triangle.
double cost(std::size_t n)
{
  return 0.003 + 40e-9 * static_cast<double>(n);
}
} // namespace

TEST(BudgetController, ConvergesToTheBudgetThatFits)
{
  gmm::BudgetController c;
  const double target = 0.040; // 25 frames/s
  const double ideal = (target - 0.003) / 40e-9;
  std::size_t n = c.budget();
  for (int frame = 0; frame < 30; ++frame)
  {
    c.observe(cost(n), n);
    n = c.budgetFor(target);
  }
  EXPECT_NEAR(static_cast<double>(n), ideal, 0.1 * ideal);
  EXPECT_NEAR(cost(n), target, 0.1 * target);
  EXPECT_NEAR(c.secondsPerTriangle(), 40e-9, 4e-9);
  EXPECT_NEAR(c.fixedSeconds(), 0.003, 0.001);
}

TEST(BudgetController, FollowsTheTargetBothWays)
{
  gmm::BudgetController c;
  std::size_t n = c.budget();
  for (int frame = 0; frame < 30; ++frame)
  {
    c.observe(cost(n), n);
    n = c.budgetFor(0.040);
  }
  const std::size_t at40 = n;
  c.observe(cost(n), n);
  n = c.budgetFor(0.020); // faster frames wanted: at once, all the way
  EXPECT_LT(n, at40);
  EXPECT_NEAR(cost(n), 0.020, 0.002);
  c.observe(cost(n), n);
  const std::size_t before = n;
  n = c.budgetFor(0.200); // much slower allowed: grows, at most x2 what was drawn
  EXPECT_GT(n, before);
  EXPECT_LE(n, 2 * before);
  for (int frame = 0; frame < 10; ++frame)
  {
    c.observe(cost(n), n);
    n = c.budgetFor(0.200);
  }
  EXPECT_NEAR(cost(n), 0.200, 0.02);
}

TEST(BudgetController, HysteresisHoldsTheBudgetUnderNoise)
{
  gmm::BudgetController c;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(-0.05, 0.05); // +-5 % timing jitter
  std::size_t n = c.budget();
  for (int frame = 0; frame < 30; ++frame)
  {
    c.observe(cost(n) * (1 + noise(rng)), n);
    n = c.budgetFor(0.040);
  }
  int changes = 0;
  for (int frame = 0; frame < 200; ++frame)
  {
    c.observe(cost(n) * (1 + noise(rng)), n);
    const std::size_t next = c.budgetFor(0.040);
    changes += next != n;
    n = next;
    EXPECT_NEAR(cost(n), 0.040, 0.2 * 0.040);
  }
  EXPECT_LE(changes, 4) << "the budget oscillates under 5 % noise";
}

TEST(BudgetController, ASceneNeedingFewerTrianglesDoesNotDisturbIt)
{
  // Tau stops every frame at 20 000 triangles, below the budget: the counts do not spread,
  // so the fixed part cannot be learnt. The model must still reproduce what it saw, the
  // budget must settle (no oscillation, no runaway) and never fall below what is drawn.
  gmm::BudgetController c;
  std::size_t n = c.budget();
  int changesLate = 0;
  for (int frame = 0; frame < 60; ++frame)
  {
    const std::size_t drawn = std::min<std::size_t>(n, 20000);
    c.observe(cost(drawn), drawn);
    const std::size_t next = c.budgetFor(0.040);
    if (frame >= 30)
      changesLate += next != n;
    n = next;
  }
  EXPECT_NEAR(c.predict(20000), cost(20000), 0.02 * cost(20000));
  EXPECT_EQ(changesLate, 0);
  EXPECT_GE(n, 20000u);
  EXPECT_LE(n, 40000u); // at most maxGrowth x what is drawn
}

TEST(BudgetController, BadInputIsIgnoredOrRefused)
{
  gmm::BudgetController c;
  c.observe(std::nan(""), 1000);
  c.observe(-1.0, 1000);
  c.observe(0.01, 0);
  EXPECT_EQ(c.framesObserved(), 0);
  EXPECT_EQ(c.budgetFor(0.04), c.settings().initialBudget); // nothing learnt yet
  c.observe(cost(1000), 1000);
  const std::size_t b = c.budget();
  EXPECT_EQ(c.budgetFor(std::nan("")), b);
  EXPECT_EQ(c.budgetFor(0.0), b);
  gmm::BudgetController::Settings s;
  s.hysteresis = 1.5;
  EXPECT_STRNE(c.setSettings(s), "");
  s = gmm::BudgetController::Settings();
  s.maxGrowth = 1.0;
  EXPECT_STRNE(c.setSettings(s), "");
  s = gmm::BudgetController::Settings();
  s.minBudget = 0;
  EXPECT_STRNE(c.setSettings(s), "");
  s = gmm::BudgetController::Settings();
  s.initialBudget = 1000;
  EXPECT_STREQ(c.setSettings(s), "");
  EXPECT_EQ(c.budget(), 1000u);
}
