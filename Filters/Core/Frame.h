// Frame: one LOD frame from settings and a view, the recipe every consumer runs.
//
//   FrameDriver d;
//   d.setTerrain(sharedTerrain);             // a Terrain built once (Terrain.h)
//   FrameSettings s;                          // tau, budget, geomorphing, height scale ...
//   const Frame& f = d.update(view, s);       // select, tessellate, morph factors, bound
//   if (f.ok()) draw(d.engine().indexArena(), d.morph());   // dirty ranges, factors
//
// The driver runs, in this order: the engine's update (tau-driven, on geomorphing's level
// path, or within a triangle budget; or the view-independent mode), the geomorph factors of
// that selection (computeMorph), and the frame's bound, the larger of the selection's and
// the morphed surface's. The mapper and the filter are its consumers: the mapper uploads
// what it returns, the filter turns it into a vtkPolyData, so both draw the same triangles
// at the same heights with the same reported bound.
#pragma once

#include "Engine.h"
#include "Morph.h"
#include "MorphRamp.h"
#include "Terrain.h"
#include "View.h"

#include <cstddef>
#include <memory>
#include <string>

namespace gmm
{

// What a frame is asked for: the settings the mapper and the filter share, with their
// defaults (vtkGeoMipMapMapper and vtkGeoMipMapFilter document them for VTK users).
struct FrameSettings
{
  // tau: the certified screen-space error, pixels (finite, >= 0).
  double pixelError = 1.0;
  // At most this many triangles a frame (0: no budget); the frame then reports the smallest
  // certified error the budget allows (BudgetSelection.h).
  std::size_t triangleBudget = 0;
  // Where a budgeted frame's search starts (0: cold). With budgetWarmStart, the last
  // budgeted frame's tau of this driver instead (what a renderer flying a camera wants).
  double budgetStartTau = 0.0;
  bool budgetWarmStart = false;
  // Vertical exaggeration: the drawn surface is z0 + heightScale * height (finite, > 0).
  double heightScale = 1.0;
  // Geomorphing (Morph.h): blocks on the level path of factor geomorphRange (MorphRamp.h),
  // their vertices moving toward the next coarser level within the bound; merges wait for
  // the path when geomorphMerges is on (the default: merged nodes' fans do not nest, and a
  // merge that skips the path's levels was the largest cause of pops left; vtkGeoMipMapMapper
  // documents what it costs).
  bool geomorphing = true;
  double geomorphRange = kDefaultMorphRange;
  bool geomorphMerges = true;
  // The most full-resolution samples a frame rasterises to measure geomorphing's part
  // errors (MorphCache::measureLimit; 0: no limit). A jump of the camera changes nearly
  // every drawn block's configuration; past the limit the farthest blocks morph by the
  // error table's looser bounds for a few frames instead of the frame waiting for all.
  std::size_t geomorphMeasureSamples = kDefaultMorphMeasureSamples;
};

// The result of a frame. The triangles, their slots and the ranges this frame changed are
// the engine's (FrameDriver::engine(): indexArena(), indices()); the morph factors the
// driver's (FrameDriver::morph()).
struct Frame
{
  // The engine's statistics, with maxScreenError the bound of what is drawn: the larger of
  // the selection's certified bound and the morphed surface's (both <= tau, or a budgeted
  // frame's own error; morphErrorBudget).
  FrameStats stats;
  // The selection's own bound (pixels): the unmorphed surface's, for a consumer that ends
  // up drawing without the morph factors.
  double selectionScreenError = 0.0;
  // The morph factors apply to this frame's selection (geomorphing on, a camera frame).
  bool morphed = false;
  // Empty, or why the frame was refused (bad view, bad tau, no terrain); nothing is drawn.
  std::string error;

  bool ok() const { return error.empty(); }
};

// The screen error (pixels) geomorphing may use in a frame drawn at `tau` with `stats`:
// tau, or in a budgeted frame whose certified error is larger, that error. Each block's
// morph stays within it (computeMorph), so the frame's bound is the same, and blocks at
// the budget's margin morph instead of popping: a budgeted frame's error is well above tau
// (tau 0 asks for the smallest error the budget allows), so with tau alone nearly nothing
// morphed.
double morphErrorBudget(const FrameStats& stats, double tau);

class FrameDriver
{
public:
  // The terrain the frames are of (nullptr: none). Per-frame state starts afresh: the
  // selection, the morph history and the budget's warm start belong to the old terrain.
  void setTerrain(std::shared_ptr<const Terrain> terrain);

  // One frame for a camera.
  const Frame& update(const View& view, const FrameSettings& settings);

  // The view-independent frame (Engine::updateForError): every block at the coarsest level
  // within `maxError` data units of the scaled surface. Never morphed.
  const Frame& updateForError(double maxError, const FrameSettings& settings);

  // The last selection kept as it is (a frozen LOD): its triangles are not touched. Its
  // morph factors are computed when geomorphing asks for them and the selection, made
  // for a camera, has none yet; without geomorphing the frame is drawn unmorphed.
  const Frame& keep(const FrameSettings& settings);

  // There is a selection of the current terrain to keep (the last frame succeeded).
  bool hasSelection() const { return hasSelection_; }
  // The last budgeted frame's tau (0: none yet): where a warm start begins.
  double warmStartTau() const { return warmStartTau_; }

  const Frame& frame() const { return frame_; }
  const Engine& engine() const { return engine_; }
  // The heights the frame draws its vertices at (morphedHeight, the mapper's vertex
  // shader): the morph factors while frame().morphed, all 0 otherwise, and every drawn
  // block's edge levels, which place the samples of glided edges (EdgeHeights.h).
  const MorphFrame& morph() const { return morph_; }

private:
  // Computes the morph factors of the engine's selection at `settings`' tau and combines
  // the bounds into frame_.
  void morphSelection(const FrameSettings& settings);
  // frame_ from the engine's result and morph_, for a frame drawn morphed or not.
  const Frame& finish(bool morphed);

  Engine engine_;
  MorphCache morphCache_;
  MorphFrame morph_;
  Frame frame_;
  bool hasSelection_ = false;
  bool cameraSelection_ = false; // the selection was made for a camera (factors exist)
  // What morph_ holds for the current selection: nothing yet, its morph factors, or its
  // unmorphed edge levels (drawnEdgeFrame), so that a kept frame computes neither again.
  enum class MorphHeld
  {
    Nothing,
    Factors,
    EdgeLevels
  };
  MorphHeld morphHeld_ = MorphHeld::Nothing;
  double warmStartTau_ = 0.0;
};

} // namespace gmm
