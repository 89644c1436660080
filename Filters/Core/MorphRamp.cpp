#include "MorphRamp.h"

#include "Levels.h"
#include "Morph.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace gmm
{

double rampSlope(double range)
{
  return 1.0 / std::log(range);
}

namespace
{
// Block b's chain (nextValidLevel unrolled): 0, the ring levels 1 .. rings (2^m below the
// narrow side: m < ceilLog2(narrow)), then the top level when it is above them.
struct ChainShape
{
  int rings; // links 0 .. rings are the levels 0 .. rings
  int top;
  int links;
};

ChainShape chainShape(const Quadtree& qt, int b)
{
  const int top = qt.blockTopLevel(b);
  const int capacity = static_cast<int>(MorphChain().size());
  const int rings = std::max(std::min({ top - 1, qt.blockRingLevelCount(b) - 1, capacity - 2 }), 0);
  return { rings, top, rings + 1 + (top > rings ? 1 : 0) };
}
} // namespace

int morphChain(const Quadtree& qt, int b, MorphChain& chain)
{
  // Links 0 .. rings are the levels themselves: copied whole from 0, 1, 2, ... (a loop of
  // byte stores was 2.4 % of a 4097^2 mapper-default frame's instructions).
  static constexpr MorphChain kLevels = [] {
    MorphChain c{};
    for (std::size_t m = 0; m < c.size(); ++m)
    {
      c[m] = static_cast<int8_t>(m);
    }
    return c;
  }();
  const ChainShape shape = chainShape(qt, b);
  chain = kLevels;
  if (shape.links > shape.rings + 1)
  {
    chain[shape.rings + 1] = static_cast<int8_t>(shape.top);
  }
  return shape.links;
}

namespace
{
// A lower bound of ln r for r >= 1, within 0.06 of it, from the bits of r alone (no call,
// no division: a bound costing about what it saves lost to the logarithm it skipped):
// r = z 2^e with z in [1, 2), and ln z >= (z - 1) ln 2 there (the chord of a concave
// function), so ln r >= (e + z - 1) ln 2. 0 where r is not finite (the caller takes the log).
double lnAtLeast(double r)
{
  if (!(r >= 1.0 && r <= std::numeric_limits<double>::max()))
  {
    return 0.0;
  }
  uint64_t bits = 0;
  std::memcpy(&bits, &r, sizeof bits);
  const int e = static_cast<int>(bits >> 52) - 1023; // r >= 1: sign 0, exponent >= 1023
  bits = (bits & 0x000FFFFFFFFFFFFFULL) | 0x3FF0000000000000ULL;
  double z = 0.0;
  std::memcpy(&z, &bits, sizeof z);
  return (e + (z - 1.0)) * 0.69314718055994529;
}

// lambda_max at the budget itself (y = x): the coarsest link within the budget (kMax), and
// how far toward the next one the certificate allows. count >= 1.
double lambdaMaxAt(const double* error, int count, double budget, int& kMax)
{
  kMax = 0;
  while (kMax + 1 < count && error[kMax + 1] <= budget)
  {
    ++kMax;
  }
  double lambda = kMax;
  if (kMax + 1 < count)
  {
    lambda += std::max(0.0, budget - error[kMax]) / (error[kMax + 1] - error[kMax]);
  }
  return lambda;
}

// Segment k's best y before it is clamped to the segment's top (or the budget): s dE, and
// at least E_k (and the least normal double, so that ln y is finite). dE = E_k+1 - E_k > 0.
double bestYFromBelow(const double* error, int k, double dE, double s)
{
  return std::max(s * dE, std::max(error[k], std::numeric_limits<double>::min()));
}
} // namespace

double rampPath(const double* error, int count, double budget, double range)
{
  return rampPathWithSlope(error, count, budget, rampSlope(range));
}

double rampPathWithSlope(const double* error, int count, double budget, double s, double ceiling)
{
  if (count <= 0)
  {
    return std::min(ceiling, 0.0);
  }
  int kMax = 0;
  double lambda = lambdaMaxAt(error, count, budget, kMax);
  // With a ceiling the running minimum starts there: every candidate ruled out below is
  // above it too, so the minimum is min(ceiling, path) as a last min would give it.
  lambda = std::min(lambda, ceiling);
  // Smaller budgets y on each rising segment: h(y) = k + (y - E_k) / dE + s ln(x / y) is
  // convex in y, lowest at y = s dE (clamped to the segment). Flat segments (equal errors)
  // are jumps of lambda_max: their ends are the neighbouring segments' ends.
  // The segments are those below the first error >= x. Most candidates are ruled out by a
  // lower bound of their logarithm (lnAtLeast) and cost no log (logs were 7 % of a 4097^2
  // frame's time; the least candidate is usually on a low segment, which is taken first).
  // The minimum is the same double as taking every candidate in turn.
  // Candidates on link k are at least k (linear >= k, and s ln(x / y) >= 0 for s >= 0):
  // none from links at or above the running minimum can lower it.
  for (int k = 0; k + 1 < count && error[k] < budget && (s < 0.0 || k < lambda); ++k)
  {
    const double dE = error[k + 1] - error[k];
    if (!(dE > 0.0))
    {
      continue;
    }
    const double y = std::min(bestYFromBelow(error, k, dE, s), std::min(error[k + 1], budget));
    const double linear = k + (y - error[k]) / dE, ratio = budget / y; // ratio >= 1: log >= 0
    if (s >= 0.0 && (linear >= lambda || linear + s * lnAtLeast(ratio) > lambda + 1e-9))
    {
      continue; // the candidate cannot be below lambda (1e-9: far above the rounding)
    }
    lambda = std::min(lambda, linear + s * std::log(ratio));
  }
  return std::min(ceiling, std::min(std::max(lambda, 0.0), static_cast<double>(count - 1)));
}

void rampPathConstants(const double* error, int count, double s, double* constant)
{
  constant[0] = std::numeric_limits<double>::infinity();
  for (int k = 0; k + 1 < count; ++k)
  {
    const double dE = error[k + 1] - error[k];
    if (!(dE > 0.0))
    {
      constant[k] = std::numeric_limits<double>::infinity(); // a jump of lambda_max
      continue;
    }
    // The segment's best y, as rampPathWithSlope takes it on a segment wholly below x.
    const double y = std::min(bestYFromBelow(error, k, dE, s), error[k + 1]);
    constant[k] = k + (y - error[k]) / dE - s * std::log(y);
  }
}

double rampPathFromConstants(const double* error, const double* constant, int count, double budget, double s)
{
  if (count <= 0)
  {
    return 0.0;
  }
  int kMax = 0;
  double lambda = lambdaMaxAt(error, count, budget, kMax);
  // Segments wholly below x (k < kMax) take their best y; segment kMax, when x cuts it,
  // takes it only when it is at most x (else y = x, whose candidate is lambda_max itself).
  double least = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kMax; ++k)
  {
    least = std::min(least, constant[k]);
  }
  if (kMax + 1 < count && error[kMax] < budget)
  {
    const double dE = error[kMax + 1] - error[kMax];
    if (dE > 0.0 && bestYFromBelow(error, kMax, dE, s) <= budget)
    {
      least = std::min(least, constant[kMax]);
    }
  }
  // No logarithm where its lower bound already rules the candidates out (x >= 1; below 1
  // the logarithm is negative and any finite constant may win).
  if (least <= std::numeric_limits<double>::max() && !(budget >= 1.0 && least + s * lnAtLeast(budget) >= lambda))
  {
    lambda = std::min(lambda, least + s * std::log(budget));
  }
  return std::min(std::max(lambda, 0.0), static_cast<double>(count - 1));
}

double rampPathFloor(int j, double errorJ, double budget, double s)
{
  // For y < errorJ the certificate's level is j - 1 + y / errorJ, and ln(x / y) >= 1 - y / x,
  // so each candidate is at least j - 1 + y / errorJ + s (1 - y / x), linear in y: its least
  // value on (0, min(errorJ, x)] is s or min(errorJ, x) / errorJ + s (1 - min / x) >= the
  // smaller of 1 and x / errorJ. Candidates with y >= errorJ are at least j.
  return j - 1 + std::min({ 1.0, s, budget / errorJ });
}

double rampTopBudget(const double* error, int count, double s)
{
  if (count <= 1)
  {
    return 0.0;
  }
  const int top = count - 1;
  double x = error[top];
  for (int k = 0; k < top; ++k)
  {
    const double dE = error[k + 1] - error[k];
    if (!(dE > 0.0))
    {
      continue; // a jump of lambda_max: no candidate inside
    }
    // The candidate reaches `top` where x >= y exp((top - k - (y - E_k) / dE) / s); the
    // logarithm of the right side is concave in y, largest at y = s dE.
    const double y = std::min(std::max(s * dE, error[k]), error[k + 1]);
    if (y > 0.0)
    {
      x = std::max(x, y * std::exp((top - k - (y - error[k]) / dE) / s));
    }
  }
  return x;
}

namespace
{
// The chain's errors errorOf(level) into `error`, up to the first level that is not allowed
// (+inf: nodata ends the chain). Returns how many.
template <typename ErrorOf>
int chainErrors(const MorphChain& chain, int links, ErrorOf errorOf, std::array<double, 32>& error)
{
  int count = 0;
  while (count < links)
  {
    const double e = errorOf(chain[count]);
    if (!(e <= std::numeric_limits<double>::max()))
    {
      break;
    }
    error[count++] = e;
  }
  return count;
}

// rampPath over the chain's errors errorOf(level) (chainErrors).
template <typename ErrorOf>
double pathOverChain(const MorphChain& chain, int links, ErrorOf errorOf, double budget, double slope,
  double ceiling = std::numeric_limits<double>::infinity())
{
  std::array<double, 32> error; // not zero-filled: only the first `count` are read (a fill
                                // was 1 % of a mapper-default frame's instructions)
  const int count = chainErrors(chain, links, errorOf, error);
  return rampPathWithSlope(error.data(), count, budget, slope, ceiling);
}
} // namespace

double rampNodeTopBudget(const Quadtree& qt, const ErrorTable& t, MorphRamp& ramp, int node)
{
  if (!(ramp.nodeTopRange == ramp.range) || ramp.nodeTop.size() != qt.nodes.size())
  {
    ramp.nodeTop.assign(qt.nodes.size(), std::numeric_limits<double>::quiet_NaN());
    ramp.nodeTopRange = ramp.range;
  }
  double& memo = ramp.nodeTop[node];
  if (!std::isnan(memo))
  {
    return memo;
  }
  const QuadtreeNode& n = qt.nodes[node];
  double x = 0.0;
  if (n.childCount == 0)
  {
    MorphChain chain;
    const int links = morphChain(qt, n.block, chain);
    std::array<double, 32> error{};
    const int count = chainErrors(chain, links, [&](int m) { return double(t.own(n.block, m)); }, error);
    // A chain cut short by nodata never reaches the block's top level.
    x = count == links ? rampTopBudget(error.data(), count, ramp.slope())
                       : std::numeric_limits<double>::infinity();
  }
  for (int k = 0; k < n.childCount; ++k)
  {
    x = std::max(x, rampNodeTopBudget(qt, t, ramp, n.firstChild + k));
  }
  memo = x;
  return x;
}

int levelOnChain(const MorphChain& chain, int count, double lambda, float& factor)
{
  const int k = std::min(std::max(static_cast<int>(lambda), 0), std::max(count - 1, 0));
  factor = k + 1 < count ? static_cast<float>(std::min(std::max(lambda - k, 0.0), 1.0)) : 0.0f;
  return count > 0 ? chain[k] : 0;
}

int chainIndex(const Quadtree& qt, int block, int level)
{
  // The first link at or above `level` (the last link when none is): links 0 .. rings are
  // the levels themselves, and the one after them (if any) is the top.
  const ChainShape shape = chainShape(qt, block);
  return level <= 0 ? 0 : level <= shape.rings ? level : shape.links - 1;
}

double rampedLambda(const ErrorTable& t, int b, const MorphChain& chain, int links, double budget,
  MorphRamp& ramp)
{
  const double s = ramp.slope();
  // One constant for each of a block's ErrorTable::levels entries (a chain has at most that
  // many links): the memo is as long as the own errors.
  const std::size_t stride = static_cast<std::size_t>(t.levels);
  if (!(ramp.ownPathSlope == s) || ramp.ownPathErrors != t.ownError.data() ||
    ramp.ownPath.size() != t.ownError.size())
  {
    ramp.ownPath.assign(t.ownError.size(), std::numeric_limits<double>::quiet_NaN());
    ramp.ownPathErrors = t.ownError.data();
    ramp.ownPathSlope = s;
  }
  std::array<double, 32> error; // only the first `count` are read
  const int count = chainErrors(chain, links, [&](int m) { return double(t.own(b, m)); }, error);
  double* constant = ramp.ownPath.data() + static_cast<std::size_t>(b) * stride;
  if (std::isnan(constant[0]))
  {
    rampPathConstants(error.data(), count, s, constant);
  }
  return rampPathFromConstants(error.data(), constant, count, budget, s);
}

double rampedLambdaBeside(const ErrorTable& t, const MorphChain& chain, int links, int nb,
  int nbSide, int nbLevel, double nbBudget, double slope, double ceiling)
{
  return pathOverChain(chain, links,
    [&](int v) { return v <= nbLevel ? 0.0 : double(t.strip(nb, nbSide, nbLevel, v)); }, nbBudget,
    slope, ceiling);
}

} // namespace gmm
