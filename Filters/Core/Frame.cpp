#include "Frame.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace gmm
{

double morphErrorBudget(const FrameStats& stats, double tau)
{
  return stats.triangleBudget > 0 && std::isfinite(stats.maxScreenError) ? std::max(tau, stats.maxScreenError)
                                                                          : tau;
}

void FrameDriver::setTerrain(std::shared_ptr<const Terrain> terrain)
{
  engine_.setTerrain(std::move(terrain));
  morphCache_ = MorphCache();
  morph_ = MorphFrame();
  frame_ = Frame();
  hasSelection_ = cameraSelection_ = false;
  morphHeld_ = MorphHeld::Nothing;
  warmStartTau_ = 0.0;
}

const Frame& FrameDriver::update(const View& view, const FrameSettings& settings)
{
  engine_.setHeightScale(settings.heightScale);
  // Geomorphing's level path (MorphRamp.h; none for a range that is not finite and > 1).
  engine_.setMorphRange(settings.geomorphing ? settings.geomorphRange : 0.0);
  engine_.setMergeOnPath(settings.geomorphMerges);
  const double start = settings.budgetWarmStart ? warmStartTau_ : settings.budgetStartTau;
  const FrameStats& stats = engine_.update(view, settings.pixelError, settings.triangleBudget, start);
  hasSelection_ = engine_.lastError().empty();
  cameraSelection_ = hasSelection_;
  morphHeld_ = MorphHeld::Nothing;
  if (hasSelection_ && settings.triangleBudget > 0)
  {
    warmStartTau_ = stats.budgetTau;
  }
  morphSelection(settings);
  return frame_;
}

const Frame& FrameDriver::updateForError(double maxError, const FrameSettings& settings)
{
  engine_.setHeightScale(settings.heightScale);
  engine_.updateForError(maxError);
  hasSelection_ = engine_.lastError().empty();
  cameraSelection_ = false;
  morphHeld_ = MorphHeld::Nothing;
  return finish(false);
}

const Frame& FrameDriver::keep(const FrameSettings& settings)
{
  if (!hasSelection_)
  {
    return finish(false);
  }
  morphSelection(settings);
  return frame_;
}

void FrameDriver::morphSelection(const FrameSettings& settings)
{
  // Geomorphing needs a camera's projection factors; a frame that draws nothing needs no
  // factors.
  const bool morphed = settings.geomorphing && hasSelection_ && cameraSelection_ && engine_.stats().triangles > 0;
  if (morphed && morphHeld_ != MorphHeld::Factors)
  {
    morphCache_.measureLimit = settings.geomorphMeasureSamples;
    computeMorph(engine_.heightfield(), engine_.quadtree(), engine_.levels(), engine_.pixelFactors(),
      morphErrorBudget(engine_.stats(), settings.pixelError), morphCache_, morph_, engine_.morphRamp(),
      &engine_.drawnBlocks(), &engine_.drawnConfigs(), &engine_.errorTable());
    morphHeld_ = MorphHeld::Factors;
  }
  finish(morphed);
}

const Frame& FrameDriver::finish(bool morphed)
{
  frame_.error = engine_.lastError();
  frame_.stats = engine_.stats();
  frame_.selectionScreenError = frame_.stats.maxScreenError;
  frame_.morphed = morphed && frame_.error.empty();
  if (frame_.morphed)
  {
    frame_.stats.maxScreenError = std::max(frame_.stats.maxScreenError, morph_.maxBoundPixels);
  }
  else if (hasSelection_ && frame_.error.empty() && morphHeld_ != MorphHeld::EdgeLevels)
  {
    // Unmorphed, the frame's glided edges still draw their samples on their polylines.
    drawnEdgeFrame(engine_.quadtree(), engine_.levels(), morph_, &engine_.drawnBlocks(), &engine_.drawnConfigs());
    morphHeld_ = MorphHeld::EdgeLevels;
  }
  return frame_;
}

} // namespace gmm
