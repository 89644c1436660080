#include "vtkGeoMipMapMapper.h"

#include "vtkGeoMipMapConversion.h"
#include "vtkGeoMipMapShaders.h"
#include "vtkGeoMipMapTerrain.h"
#include "vtkGeoMipMapGPUTerrain.h"
#include "vtkGeoMipMapMorphTexture.h"
#include "vtkGeoMipMapSoftwareRenderer.h"

#include "vtkActor.h"
#include "vtkCommand.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkMatrix3x3.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLActor.h"
#include "vtkOpenGLBufferObject.h"
#include "vtkOpenGLCamera.h"
#include "vtkOpenGLHelper.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLRenderTimer.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkOpenGLState.h"
#include "vtkOpenGLTexture.h"
#include "vtkOpenGLVertexBufferObjectGroup.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkRenderer.h"
#include "vtkScalarsToColors.h"
#include "vtkShaderProgram.h"
#include "vtkSmartPointer.h"
#include "vtkTexture.h"
#include "vtkTextureObject.h"
#include "vtkWeakPointer.h"
#include "vtk_glew.h"

#include "BudgetController.h"
#include "DrawOrder.h"
#include "Engine.h"
#include "Frame.h"
#include "RayCast.h"
#include "VertexPitch.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <vector>

namespace
{
using Clock = std::chrono::steady_clock;
double SecondsSince(Clock::time_point start)
{
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// SetGlobalRetainHeapOnSoftwareRenderer: process-wide, as the heap policy it governs.
std::atomic<bool> GlobalRetainHeapOnSoftwareRenderer{ true };
}

struct vtkGeoMipMapMapper::Internals
{
  // The LOD settings shared with vtkGeoMipMapFilter, and the frame recipe that runs them.
  gmm::FrameSettings Settings;
  gmm::FrameDriver Driver;
  const gmm::Engine& Engine() const { return this->Driver.engine(); }
  const gmm::FrameStats& Stats() const { return this->Driver.frame().stats; }
  vtkSmartPointer<vtkGeoMipMapTerrain> Terrain;

  // What VTK's vertex-buffer machinery sees: one vertex with a normal (and texture
  // coordinates while textured), so that it declares the shader inputs our code replaces.
  vtkNew<vtkPolyData> Proxy;

  // GPU data, all in the context of Window.
  vtkWeakPointer<vtkOpenGLRenderWindow> Window;
  bool SoftwareRenderer = false; // Window's OpenGL runs on the CPU (vtkGeoMipMapSoftwareRenderer)
  vtkGeoMipMapGPUTerrain GPU;
  // The texture of this frame's edge levels and geomorph factors; Morphing while drawn so.
  vtkGeoMipMapMorphTexture MorphTexture;
  bool Morphing = false;
  std::string ReportedMorphError;
  std::map<const vtkOpenGLHelper*, std::string> ShaderKeys; // per helper: key built for
  bool ReportedCellScalars = false;

  // Model coordinates are relative to the anchor sample (near the camera) and a reference
  // height; AnchorShift is their translation, transposed as VTK's key matrices are.
  int AnchorI = 0, AnchorJ = 0;
  float HeightRef = 0.0f;
  vtkNew<vtkMatrix4x4> AnchorShift;
  vtkNew<vtkMatrix4x4> Temp;

  // FollowAllocatedRenderTime: this machine's cost per frame, learnt from timed frames.
  gmm::BudgetController Controller;
  // FrontToBack: the drawn blocks nearest first, and their slots for glMultiDrawElements.
  std::vector<int> Order;
  std::vector<GLsizei> Counts;
  std::vector<const void*> Offsets;

  std::vector<unsigned int> Lines; // scratch for wireframe edges
  // The indices as uploaded: the engine's sample indices as drawing ids (gmm::toDrawIds),
  // whole or one dirty range at a time.
  std::vector<unsigned int> DrawIds;
  size_t IndexBytes = 0;
  // The index buffer holds the engine's arena as of this version (0: it does not).
  uint64_t MirroredArena = 0;
  int PrimitiveRestart = -1; // GL_PRIMITIVE_RESTART_FIXED_INDEX available (-1: not asked)

  vtkSmartPointer<vtkImageData> Drape;
  std::string ReportedDrapeError; // said once, not every frame

  // x, y bounds of the valid samples of Terrain (found once per terrain).
  const gmm::Terrain* BoundsOf = nullptr;
  double ValidXY[4] = { 0, 0, 0, 0 };
  bool AnyValid = false;

  // The anchor of this frame: the sample under the camera (in data coordinates), clamped to
  // the grid, and the reference height.
  void PlaceAnchor(const gmm::View& view, vtkActor* act)
  {
    const gmm::Heightfield& hf = this->Engine().heightfield();
    double eye[4] = { view.eye.x, view.eye.y, view.eye.z, 1.0 };
    if (!act->GetIsIdentity())
    {
      vtkNew<vtkMatrix4x4> inv;
      vtkMatrix4x4::Invert(act->GetMatrix(), inv);
      inv->MultiplyPoint(eye, eye);
    }
    this->AnchorI = static_cast<int>(vtkMath::ClampValue(std::round((eye[0] - hf.x0) / hf.dx), 0.0, hf.nx - 1.0));
    this->AnchorJ = static_cast<int>(vtkMath::ClampValue(std::round((eye[1] - hf.y0) / hf.dy), 0.0, hf.ny - 1.0));
    const gmm::Box& root = this->Engine().quadtree().nodes[0].box;
    this->HeightRef = static_cast<float>(0.5 * (root.lo.z + root.hi.z));
    this->AnchorShift->Identity();
    this->AnchorShift->SetElement(3, 0, hf.worldX(this->AnchorI));
    this->AnchorShift->SetElement(3, 1, hf.worldY(this->AnchorJ));
    this->AnchorShift->SetElement(3, 2, hf.z0 + this->Settings.heightScale * static_cast<double>(this->HeightRef));
  }

  // Texture coordinates only while textured: the proxy then declares them to VTK.
  void DeclareTextureCoordinates(vtkActor* act)
  {
    const bool textured = act->GetTexture() != nullptr || act->GetProperty()->GetNumberOfTextures() > 0;
    vtkPointData* pd = this->Proxy->GetPointData();
    if (textured && !pd->GetTCoords())
    {
      vtkNew<vtkFloatArray> tc;
      tc->SetName("TCoords");
      tc->SetNumberOfComponents(2);
      tc->InsertNextTuple2(0.0, 0.0);
      pd->SetTCoords(tc);
    }
    else if (!textured && pd->GetTCoords())
    {
      pd->RemoveArray("TCoords");
    }
    this->GPU.SetTextureCoordinates(textured);
  }

  // The texture of the frame's edge levels and geomorph factors (FrameDriver::morph()), the
  // only per-frame data the vertex shader places vertices by (glided edges' samples, and
  // morphing); returns the bytes uploaded. A texture that cannot be made leaves every vertex
  // at its sample's height (no geomorphing; the frame's bound is then the selection's, and
  // glided edges are drawn through their samples), and is said once.
  vtkTypeInt64 UploadMorph(vtkObject* self, vtkOpenGLRenderWindow* win, const gmm::Frame& frame)
  {
    this->Morphing = false;
    vtkTypeInt64 bytes = 0;
    if (frame.ok())
    {
      const std::string err = this->MorphTexture.Update(win, this->Engine().quadtree(), this->Driver.morph());
      this->Morphing = err.empty();
      bytes = static_cast<vtkTypeInt64>(this->MorphTexture.GetLastUploadBytes());
      if (!err.empty() && err != this->ReportedMorphError)
      {
        vtkWarningWithObjectMacro(self, << err << " (glided edges are drawn through their samples, which the "
                                              "reported error does not bound)");
      }
      this->ReportedMorphError = err;
    }
    this->GPU.SetMorph(this->Morphing);
    return bytes;
  }
};

vtkStandardNewMacro(vtkGeoMipMapMapper);

//------------------------------------------------------------------------------
vtkGeoMipMapMapper::vtkGeoMipMapMapper()
  : BlockSize(gmm::kDefaultBlockQuads)
  , Internal(new Internals)
{
  // A renderer flying a camera starts each budgeted frame's search at the last one's tau.
  this->Internal->Settings.budgetWarmStart = true;
  vtkNew<vtkPoints> p;
  p->InsertNextPoint(0.0, 0.0, 0.0);
  vtkNew<vtkFloatArray> n;
  n->SetName("Normals");
  n->SetNumberOfComponents(3);
  n->InsertNextTuple3(0.0, 0.0, 1.0);
  this->Internal->Proxy->SetPoints(p);
  this->Internal->Proxy->GetPointData()->SetNormals(n);
  // Colours come from the shaders; VTK must not map (absent) proxy scalars.
  this->InterpolateScalarsBeforeMapping = 0;
}

//------------------------------------------------------------------------------
vtkGeoMipMapMapper::~vtkGeoMipMapMapper()
{
  this->ReleaseWindowResources();
  this->SetTableCacheDirectory(nullptr);
}

//------------------------------------------------------------------------------
int vtkGeoMipMapMapper::FillInputPortInformation(int vtkNotUsed(port), vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetInputData(vtkImageData* image)
{
  this->SetInputDataInternal(0, image);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::ModifiedIndicesOnly()
{
  // Remember this MTime as "indices only" when the buffers were current before it, so
  // GetNeedToRebuildBufferObjects does not rebuild them for a new tau.
  const vtkMTimeType m = this->GetMTime();
  const bool buffersCurrent = this->VBOBuildTime >= m || m == this->IndicesOnlyMTime;
  this->Modified();
  if (buffersCurrent)
  {
    this->IndicesOnlyMTime = this->GetMTime();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetDrapeImage(vtkImageData* image)
{
  if (this->Internal->Drape != image)
  {
    this->Internal->Drape = image;
    this->Internal->ReportedDrapeError.clear();
    this->Modified();
  }
}

vtkImageData* vtkGeoMipMapMapper::GetDrapeImage()
{
  return this->Internal->Drape;
}

//------------------------------------------------------------------------------
// The LOD settings: stored in the FrameSettings shared with vtkGeoMipMapFilter, by its rules;
// a change needs new indices, not new buffers.
vtkGeoMipMapFrameSettingsMacro(vtkGeoMipMapMapper, ModifiedIndicesOnly);

void vtkGeoMipMapMapper::SetFollowAllocatedRenderTime(bool follow)
{
  if (follow != this->FollowAllocatedRenderTime)
  {
    this->FollowAllocatedRenderTime = follow;
    this->Internal->Controller.reset();
    this->ModifiedIndicesOnly();
  }
}

std::size_t vtkGeoMipMapMapper::FrameTriangleBudget(vtkRenderer* ren, vtkActor* act, bool& interactive)
{
  interactive = false;
  const std::size_t fixed = this->Internal->Settings.triangleBudget;
  vtkRenderWindow* win = ren->GetRenderWindow();
  if (!this->FollowAllocatedRenderTime || !win)
  {
    return fixed;
  }
  // The interactor switches the window between its DesiredUpdateRate and StillUpdateRate
  // (vtkInteractorStyle's StartInteraction / EndInteraction); 0.0001 is VTK's still rate.
  vtkRenderWindowInteractor* iren = win->GetInteractor();
  const double still = iren ? iren->GetStillUpdateRate() : 0.0001;
  if (!(win->GetDesiredUpdateRate() > still))
  {
    return fixed;
  }
  interactive = true;
  this->LastAllocatedRenderTime = act->GetAllocatedRenderTime();
  const std::size_t learnt = this->Internal->Controller.budgetFor(this->LastAllocatedRenderTime);
  return fixed ? std::min(fixed, learnt) : learnt;
}

void vtkGeoMipMapMapper::SetFreezeLevelOfDetail(bool freeze)
{
  if (freeze != this->FreezeLevelOfDetail)
  {
    this->FreezeLevelOfDetail = freeze;
    this->ModifiedIndicesOnly();
  }
}

void vtkGeoMipMapMapper::SetGlobalRetainHeapOnSoftwareRenderer(bool retain)
{
  GlobalRetainHeapOnSoftwareRenderer = retain;
}

bool vtkGeoMipMapMapper::GetGlobalRetainHeapOnSoftwareRenderer()
{
  return GlobalRetainHeapOnSoftwareRenderer;
}

int vtkGeoMipMapMapper::GetMinimumBlockSize()
{
  return gmm::kMinBlockQuads;
}

int vtkGeoMipMapMapper::GetDefaultBlockSize()
{
  return gmm::kDefaultBlockQuads;
}

void vtkGeoMipMapMapper::SetBlockSize(int quads)
{
  if (vtkGeoMipMapConversion::AcceptBlockSize(this, quads, this->BlockSize))
  {
    this->ModifiedIndicesOnly();
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkGeoMipMapMapper::GetNumberOfRenderedTriangles() const
{
  return this->LastFrameDrawn ? static_cast<vtkIdType>(this->Internal->Stats().triangles) : 0;
}
int vtkGeoMipMapMapper::GetNumberOfVisibleBlocks() const
{
  return this->LastFrameDrawn ? this->Internal->Stats().visibleBlocks : 0;
}
int vtkGeoMipMapMapper::GetNumberOfCulledBlocks() const
{
  return this->LastFrameDrawn ? this->Internal->Stats().culledBlocks : 0;
}
double vtkGeoMipMapMapper::GetMaximumScreenSpaceError() const
{
  // The frame's bound includes the morphed surface's (still <= PixelError, or a budgeted
  // frame's own certified error); the selection's own when the factors could not be drawn.
  const Internals& in = *this->Internal;
  if (!this->LastFrameDrawn)
  {
    return 0.0;
  }
  const gmm::Frame& f = in.Driver.frame();
  return f.morphed && !in.Morphing ? f.selectionScreenError : f.stats.maxScreenError;
}
double vtkGeoMipMapMapper::GetAutomaticVertexNormalsPixels()
{
  // Measured on real DEMs (decision record 004): at a certified pixel, normals per vertex
  // and per fragment differ from the full-resolution render on the same share of pixels;
  // at 2 px per vertex already differs on up to 1.4x as many.
  return 1.0;
}
const char* vtkGeoMipMapMapper::GetNormalModeAsString()
{
  switch (this->NormalMode)
  {
    case NORMALS_PER_VERTEX:
      return "PerVertex";
    case NORMALS_PER_FRAGMENT:
      return "PerFragment";
    default:
      return "Automatic";
  }
}
void vtkGeoMipMapMapper::SetVertexNormals(bool on)
{
  this->SetNormalMode(on ? NORMALS_PER_VERTEX : NORMALS_PER_FRAGMENT);
}
bool vtkGeoMipMapMapper::GetVertexNormals()
{
  return this->NormalMode == NORMALS_PER_VERTEX;
}
double vtkGeoMipMapMapper::GetMaximumGeometricError() const
{
  return this->LastFrameDrawn ? this->Internal->Stats().maxGeometricError : 0.0;
}
vtkIdType vtkGeoMipMapMapper::GetTriangleBudgetInForce() const
{
  return this->LastFrameDrawn ? static_cast<vtkIdType>(this->Internal->Stats().triangleBudget) : 0;
}
bool vtkGeoMipMapMapper::GetTriangleBudgetReached() const
{
  return this->LastFrameDrawn && this->Internal->Stats().budgetReached;
}
double vtkGeoMipMapMapper::GetLastBudgetStartTau() const
{
  return this->LastFrameDrawn ? this->Internal->Stats().budgetStartTau : 0.0;
}
bool vtkGeoMipMapMapper::GetOverTriangleBudget() const
{
  return this->LastFrameDrawn && this->Internal->Stats().overBudget;
}
bool vtkGeoMipMapMapper::GetIndicesReused() const
{
  return this->LastFrameDrawn && (this->LastFrameFrozen || this->Internal->Stats().reused);
}

bool vtkGeoMipMapMapper::GetHeightsShared() const
{
  return this->Internal->GPU.SharesHeights();
}

vtkTypeInt64 vtkGeoMipMapMapper::GetGPUMemoryBytes() const
{
  const Internals& in = *this->Internal;
  return static_cast<vtkTypeInt64>(in.GPU.GetBytes() + in.IndexBytes);
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapMapper::UpdateTerrain(vtkImageData* image)
{
  Internals& in = *this->Internal;
  // Refuse before anything large is allocated: the tables are small next to the samples,
  // so the estimate is the textures plus a float copy when the heights cannot be shared.
  vtkDataArray* heights = image->GetPointData()->GetScalars();
  if (heights && (!in.Terrain || in.Terrain->GetHeights() != heights || !in.GPU.HasHeights()))
  {
    const double samples = static_cast<double>(image->GetNumberOfPoints());
    const auto format = vtkGeoMipMapSampleTexture::FormatFor(heights, false);
    // Heights on the GPU, and the slope texture (for lighting) where asked for. (Heights
    // read in place take none, but whether they can is known only in a render.)
    double need = samples * vtkGeoMipMapSampleTexture::BytesPerTexel(format);
    if (this->SlopeTextureWanted())
    {
      need += samples * vtkGeoMipMapSampleTexture::BytesPerTexel(vtkGeoMipMapSampleTexture::Slopes16F);
    }
    if (!(heights->GetDataType() == VTK_FLOAT && heights->GetNumberOfComponents() == 1))
    {
      need += samples * sizeof(float);
    }
    const double have = this->MemoryLimit > 0 ? static_cast<double>(this->MemoryLimit)
                                              : vtkGeoMipMapConversion::AvailableMemoryBytes();
    if (have > 0 && need > have)
    {
      int dims[3];
      image->GetDimensions(dims);
      vtkErrorMacro(<< "The DEM of " << dims[0] << " x " << dims[1] << " samples needs about "
                    << need / 1048576.0 << " MiB (heights on the GPU, engine tables), more than the "
                    << have / 1048576.0 << " MiB "
                    << (this->MemoryLimit > 0 ? "of MemoryLimit" : "available") << "; not drawn");
      return false;
    }
  }
  bool changed = false;
  vtkGeoMipMapTerrain* terrain = vtkGeoMipMapTerrain::Bind(image, this->BlockSize, this,
    vtkGeoMipMapTerrain::TableCacheOptions(this->TableCache, this->TableCacheDirectory), in.Terrain,
    in.Driver, changed);
  if (!terrain)
  {
    return false;
  }
  if (changed)
  {
    // A frozen selection and the budget's warm start belonged to the old terrain: the
    // driver started afresh.
    this->LastTerrainBuildTime = terrain->GetBuildTime();
    this->LastTablesFromCache = terrain->GetTableCacheReport().hit;
    this->IndicesDirty = true;
  }
  return true;
}

//------------------------------------------------------------------------------
double* vtkGeoMipMapMapper::GetBounds()
{
  if (!this->GetNumberOfInputConnections(0))
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return this->Bounds;
  }
  if (!this->Static)
  {
    this->Update();
  }
  this->ComputeBounds();
  return this->Bounds;
}

void vtkGeoMipMapMapper::ComputeBounds()
{
  vtkMath::UninitializeBounds(this->Bounds);
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!image || !this->UpdateTerrain(image))
  {
    return;
  }
  Internals& in = *this->Internal;
  const gmm::Terrain& t = *in.Terrain->GetTerrain();
  if (in.BoundsOf != &t)
  {
    in.BoundsOf = &t;
    in.AnyValid = gmm::validSampleBounds(t, in.ValidXY);
  }
  if (!in.AnyValid)
  {
    return;
  }
  std::copy(in.ValidXY, in.ValidXY + 4, this->Bounds);
  const gmm::Box& root = t.qt.nodes[0].box;
  this->Bounds[4] = t.hf.z0 + this->Internal->Settings.heightScale * root.lo.z;
  this->Bounds[5] = t.hf.z0 + this->Internal->Settings.heightScale * root.hi.z;
}

//------------------------------------------------------------------------------
double vtkGeoMipMapMapper::GetHeightAt(double x, double y)
{
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!this->Static && this->GetNumberOfInputConnections(0))
  {
    this->Update();
    image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  }
  if (!image || !this->UpdateTerrain(image))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return gmm::heightAt(this->Internal->Terrain->GetTerrain()->hf, x, y, this->Internal->Settings.heightScale);
}

bool vtkGeoMipMapMapper::IntersectWithLine(const double p1[3], const double p2[3], double& t,
  double x[3], double normal[3], vtkIdType& pointId, vtkIdType& cellId)
{
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!image || !this->UpdateTerrain(image))
  {
    return false;
  }
  const gmm::Terrain& terrain = *this->Internal->Terrain->GetTerrain();
  const gmm::SurfaceHit hit = gmm::intersectSegment(terrain, glm::dvec3(p1[0], p1[1], p1[2]),
    glm::dvec3(p2[0], p2[1], p2[2]), this->Internal->Settings.heightScale);
  if (!hit.hit)
  {
    return false;
  }
  t = hit.t;
  for (int k = 0; k < 3; ++k)
  {
    x[k] = hit.point[k];
    normal[k] = hit.normal[k];
  }
  // The hit triangle's vertex nearest to the hit, in x, y (all three are valid samples).
  const gmm::Heightfield& hf = terrain.hf;
  double best = VTK_DOUBLE_MAX;
  for (uint32_t v : hit.vertex)
  {
    const double dx = hf.worldX(v % hf.nx) - x[0], dy = hf.worldY(v / hf.nx) - x[1];
    if (dx * dx + dy * dy < best)
    {
      best = dx * dx + dy * dy;
      pointId = static_cast<vtkIdType>(v);
    }
  }
  cellId = static_cast<vtkIdType>(hit.cellJ) * (hf.nx - 1) + hit.cellI;
  return true;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::RenderPiece(vtkRenderer* ren, vtkActor* act)
{
  vtkOpenGLRenderWindow* win = vtkOpenGLRenderWindow::SafeDownCast(ren->GetRenderWindow());
  if (!win || win->CheckAbortStatus())
  {
    return;
  }
  Internals& in = *this->Internal;
  // GPU data belong to one context: drawing in another window frees them there first
  // (VTK's stock mappers do the same through a callback whose header Debian does not ship).
  if (in.Window != win)
  {
    this->ReleaseWindowResources(); // frees in the old window, or forgets a vanished one's
    win->MakeCurrent();
    in.SoftwareRenderer = vtkGeoMipMapSoftwareRenderer::IsCurrent();
    if (GlobalRetainHeapOnSoftwareRenderer && in.SoftwareRenderer)
    {
      vtkGeoMipMapSoftwareRenderer::RetainHeap();
    }
  }
  in.Window = win;

  // Until the engine has run for this frame, the statistics say "nothing drawn" (an
  // input or camera error below must not leave the previous frame's figures behind).
  this->LastFrameDrawn = this->LastFrameFrozen = false;
  this->LastUpdateTime = this->LastIndexUploadTime = 0.0;
  this->LastIndexUploadBytes = 0;
  this->LastMorphUploadBytes = 0;
  this->LastRenderTime = this->LastAllocatedRenderTime = 0.0;
  this->LastFragmentsPassed = 0;
  this->LastVertexInvocations = this->CountFragments && !GLEW_ARB_pipeline_statistics_query ? -1 : 0;
  // The budget (and whether this frame is timed) first: a timed frame starts with the GPU
  // idle, so that it is charged for its own work only.
  bool interactive = false;
  const std::size_t budget = this->FrameTriangleBudget(ren, act, interactive);
  this->LastFrameInteractive = interactive;
  if (interactive)
  {
    glFinish();
  }
  const auto frameStart = Clock::now();
  const int heightUploadsBefore = this->NumberOfHeightUploads;
  const double buildTimeBefore = this->LastTerrainBuildTime;
  this->InvokeEvent(vtkCommand::StartEvent, nullptr);
  if (!this->Static)
  {
    this->GetInputAlgorithm()->Update();
  }
  this->InvokeEvent(vtkCommand::EndEvent, nullptr);
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!image)
  {
    vtkErrorMacro("No input image.");
    return;
  }
  if (!this->UpdateTerrain(image) || in.Engine().empty())
  {
    return;
  }

  // LOD for the camera being rendered; the actor's matrix goes to the engine whole.
  int width = 0, height = 0, x0 = 0, y0 = 0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  gmm::View view;
  std::string err = vtkGeoMipMapConversion::CameraToView(ren->GetActiveCamera(),
    act->GetIsIdentity() ? nullptr : act->GetMatrix(), width, height, view);
  if (!err.empty())
  {
    vtkErrorMacro("Cannot use the camera: " << err);
    return;
  }
  // The frame (gmm::FrameDriver): selection, triangles, geomorph factors and bound. A frozen
  // LOD keeps the last selection (indices and statistics) as it is. LastUpdateTime counts
  // it all: a frame whose blocks all change configuration spends more on geomorphing's
  // part errors than on the selection.
  gmm::FrameSettings settings = in.Settings;
  settings.triangleBudget = budget;
  this->LastFrameFrozen = this->FreezeLevelOfDetail && in.Driver.hasSelection();
  const auto lodStart = Clock::now();
  const gmm::Frame& frame = this->LastFrameFrozen ? in.Driver.keep(settings) : in.Driver.update(view, settings);
  this->LastUpdateTime = this->LastFrameFrozen ? 0.0 : SecondsSince(lodStart);
  if (!frame.ok())
  {
    vtkErrorMacro("LOD update failed: " << frame.error);
    return;
  }
  const gmm::FrameStats& stats = frame.stats;
  this->LastFrameDrawn = true;
  this->IndicesDirty = this->IndicesDirty || !this->GetIndicesReused();
  if (stats.triangles == 0)
  {
    return;
  }
  // Automatic normals: per vertex where the per-fragment normal is most of a fill-bound
  // frame's cost (OpenGL on the CPU) and the frame is certified within a pixel.
  this->LastFrameVertexNormals = this->NormalMode == NORMALS_PER_VERTEX ||
    (this->NormalMode == NORMALS_AUTOMATIC && in.SoftwareRenderer &&
      stats.maxScreenError <= GetAutomaticVertexNormalsPixels());
  if (!this->UpdateTextures(win, image, act))
  {
    this->LastFrameDrawn = false;
    return;
  }

  in.PlaceAnchor(view, act);
  in.DeclareTextureCoordinates(act);
  this->LastMorphUploadBytes = in.UploadMorph(this, win, frame);

  this->CurrentInput = in.Proxy;
  this->RenderPieceStart(ren, act); // may rebuild buffers, and then the IBO through BuildIBO
  if (this->IndicesDirty)
  {
    this->UploadIndices(act, false);
  }
  if (this->FrontToBack)
  {
    gmm::frontToBack(in.Engine().quadtree(),
      gmm::heightfieldToWorld(view, in.Engine().heightfield().z0, in.Settings.heightScale), view.eye,
      in.Engine().drawnBlocks(), in.Engine().mergedNodeList(), in.Order);
  }
  else
  {
    in.Order.clear();
  }
  this->RenderPieceDraw(ren, act);
  this->RenderPieceFinish(ren, act);
  if (interactive)
  {
    glFinish();
    this->LastRenderTime = SecondsSince(frameStart);
    // A frame that built tables or uploaded heights says nothing about the cost of drawing.
    if (this->NumberOfHeightUploads == heightUploadsBefore && this->LastTerrainBuildTime == buildTimeBefore)
    {
      in.Controller.observe(this->LastRenderTime, stats.triangles, stats.budgetReached);
    }
  }
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapMapper::UpdateTextures(vtkOpenGLRenderWindow* win, vtkImageData* image, vtkActor* act)
{
  Internals& in = *this->Internal;
  vtkGeoMipMapGPUTerrain::Inputs gpu;
  gpu.Heights = in.Terrain->GetHeights();
  gpu.HF = &in.Engine().heightfield();
  gpu.Lit = act->GetProperty()->GetLighting() && act->GetProperty()->GetInterpolation() != VTK_FLAT;
  gpu.MaximumTileSize = this->MaximumTileSize;
  gpu.ShareHeights = this->ShareHeights;
  gpu.SlopeTexture = this->SlopeTextureWanted();
  gpu.VertexNormals = this->LastFrameVertexNormals;
  // Colouring: the array VTK's own mappers would colour by, on the GPU as well.
  int cellFlag = 0;
  gpu.Color = this->ScalarVisibility
    ? vtkAbstractMapper::GetScalars(image, this->ScalarMode, this->ArrayAccessMode, this->ArrayId,
        this->ArrayName, cellFlag)
    : nullptr;
  if (gpu.Color && cellFlag)
  {
    if (!in.ReportedCellScalars)
    {
      vtkErrorMacro("Colouring by cell scalars is not supported; the actor's colour is used.");
      in.ReportedCellScalars = true;
    }
    gpu.Color = nullptr;
  }
  if (gpu.Color)
  {
    gpu.DirectColors = gpu.Color->GetDataType() == VTK_UNSIGNED_CHAR &&
      this->ColorMode != VTK_COLOR_MODE_MAP_SCALARS;
    if (!gpu.DirectColors)
    {
      gpu.Lookup = this->GetLookupTable();
      if (!this->UseLookupTableScalarRange)
      {
        gpu.Lookup->SetRange(this->ScalarRange);
      }
      gpu.Lookup->Build();
    }
  }
  gpu.Drape = in.Drape;
  const vtkGeoMipMapGPUTerrain::Result r = in.GPU.Update(win, gpu);
  this->NumberOfHeightUploads += r.Uploads;
  if (r.Uploads)
  {
    this->LastHeightUploadTime = r.UploadSeconds;
  }
  if (!r.ShareError.empty())
  {
    vtkWarningMacro("Cannot read the heights in place (ShareHeights): " << r.ShareError
                                                                       << "; they are copied into a texture instead.");
  }
  if (!r.HeightsError.empty())
  {
    vtkErrorMacro("Cannot store the heights on the GPU: " << r.HeightsError);
    return false;
  }
  if (!r.ColorError.empty())
  {
    vtkErrorMacro("Cannot store the colouring array on the GPU (the actor's colour is used): "
      << r.ColorError);
  }
  if (r.DrapeError.empty())
  {
    in.ReportedDrapeError.clear();
  }
  else if (r.DrapeError != in.ReportedDrapeError)
  {
    vtkErrorMacro("Cannot drape the image (the terrain is drawn without it): " << r.DrapeError);
    in.ReportedDrapeError = r.DrapeError;
  }
  return true;
}

//------------------------------------------------------------------------------
vtkUnsignedCharArray* vtkGeoMipMapMapper::MapScalars(double alpha)
{
  int cellFlag = 0;
  return this->MapScalars(alpha, cellFlag);
}

vtkUnsignedCharArray* vtkGeoMipMapMapper::MapScalars(double alpha, int& cellFlag)
{
  return this->Superclass::MapScalars(this->Internal->Proxy, alpha, cellFlag);
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapMapper::GetNeedToRebuildBufferObjects(vtkRenderer*, vtkActor* act)
{
  // Same watch list as vtkOpenGLPolyDataMapper, except mapper changes that only alter
  // the indices (PixelError, BlockSize, HeightScale).
  this->TempState.Clear();
  this->TempState.Append(act->GetProperty()->GetMTime(), "prop mtime");
  this->TempState.Append(this->CurrentInput ? this->CurrentInput->GetMTime() : 0, "input mtime");
  this->TempState.Append(act->GetTexture() ? act->GetTexture()->GetMTime() : 0, "texture mtime");
  const vtkMTimeType m = this->GetMTime();
  const bool mapperChanged = this->VBOBuildTime < m && m != this->IndicesOnlyMTime;
  if (this->VBOBuildState != this->TempState || mapperChanged)
  {
    this->VBOBuildState = this->TempState;
    return true;
  }
  return false;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::BuildIBO(vtkRenderer*, vtkActor* act, vtkPolyData*)
{
  // The proxy has no cells: the only primitive is the engine's triangles.
  for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
  {
    this->Primitives[i].IBO->IndexCount = 0;
  }
  this->UploadIndices(act, true); // a new buffer: everything
}

void vtkGeoMipMapMapper::UploadIndices(vtkActor* act, bool whole)
{
  Internals& in = *this->Internal;
  const auto start = Clock::now();
  vtkOpenGLIndexBufferObject* ibo = this->Primitives[PrimitiveTris].IBO;
  ++this->NumberOfIndexUploads;
  this->IndicesDirty = false;
  if (in.PrimitiveRestart < 0)
  {
    in.PrimitiveRestart = (GLEW_VERSION_4_3 || GLEW_ARB_ES3_compatibility) ? 1 : 0;
  }
  const gmm::IndexArena& arena = in.Engine().indexArena();
  // The arena (slots, unused space = restart index) needs primitive restart; without it,
  // the plain concatenated triangles are uploaded whole.
  const std::vector<uint32_t>& tris = in.PrimitiveRestart ? arena.indices() : in.Engine().indices();
  const gmm::Heightfield& hf = in.Engine().heightfield();
  const uint32_t pitch = gmm::drawPitch(hf.nx, hf.ny); // the vertex shader decodes ids with it
  vtkTypeInt64 bytes = 0;
  if (in.Engine().stats().triangles == 0)
  {
    ibo->IndexCount = 0;
    in.MirroredArena = 0;
  }
  else if (act->GetProperty()->GetRepresentation() == VTK_WIREFRAME)
  {
    // The stock mapper draws wireframe triangles as GL_LINES: three edges per triangle.
    // From the plain list in block order: an edge shared by two triangles is drawn twice,
    // and which one shows depends on the order, which must not depend on the history.
    const std::vector<uint32_t>& plain = in.Engine().indices();
    std::vector<unsigned int>& up = in.Lines;
    up.resize(plain.size() * 2);
    for (std::size_t t = 0; t < plain.size(); t += 3)
    {
      unsigned int* e = up.data() + 2 * t;
      e[0] = plain[t];
      e[1] = plain[t + 1];
      e[2] = plain[t + 1];
      e[3] = plain[t + 2];
      e[4] = plain[t + 2];
      e[5] = plain[t];
    }
    gmm::toDrawIds(up.data(), up.size(), hf.nx, pitch, up.data());
    ibo->Upload(up, vtkOpenGLBufferObject::ElementArrayBuffer);
    ibo->IndexCount = up.size();
    bytes = static_cast<vtkTypeInt64>(up.size() * sizeof(unsigned int));
    in.MirroredArena = 0;
  }
  else if (!in.PrimitiveRestart || whole || arena.rewritten() ||
    in.MirroredArena + 1 != arena.version() || ibo->IndexCount != tris.size())
  {
    // Triangles (GL_TRIANGLES) or points (GL_POINTS draws every referenced vertex).
    in.DrawIds.resize(tris.size());
    gmm::toDrawIds(tris.data(), tris.size(), hf.nx, pitch, in.DrawIds.data());
    ibo->Upload(in.DrawIds, vtkOpenGLBufferObject::ElementArrayBuffer);
    ibo->IndexCount = tris.size();
    bytes = static_cast<vtkTypeInt64>(tris.size() * sizeof(unsigned int));
    in.MirroredArena = in.PrimitiveRestart ? arena.version() : 0;
  }
  else
  {
    // Only the slots this frame changed.
    ibo->Bind();
    for (const gmm::IndexArena::Range& r : arena.dirtyRanges())
    {
      const GLsizeiptr n = static_cast<GLsizeiptr>((r.end - r.begin) * sizeof(unsigned int));
      in.DrawIds.resize(r.end - r.begin);
      gmm::toDrawIds(tris.data() + r.begin, r.end - r.begin, hf.nx, pitch, in.DrawIds.data());
      glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLintptr>(r.begin * sizeof(unsigned int)),
        n, in.DrawIds.data());
      bytes += n;
    }
    ibo->Release();
    in.MirroredArena = arena.version();
  }
  in.IndexBytes = ibo->IndexCount * sizeof(unsigned int);
  this->LastIndexUploadBytes += bytes;
  this->LastIndexUploadTime += SecondsSince(start);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::DrawTriangles(unsigned int mode, std::size_t indexCount)
{
  Internals& in = *this->Internal;
  const gmm::IndexArena& arena = in.Engine().indexArena();
  GLuint query = 0, vertexQuery = 0;
  if (this->CountFragments)
  {
    glGenQueries(1, &query);
    glBeginQuery(GL_SAMPLES_PASSED, query);
    if (GLEW_ARB_pipeline_statistics_query)
    {
      glGenQueries(1, &vertexQuery);
      glBeginQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB, vertexQuery);
    }
  }
  // Sorted only when the buffer mirrors the arena's slots (not for wireframe lines or the
  // plain list drawn without primitive restart).
  const bool sorted = !in.Order.empty() && in.PrimitiveRestart > 0 && mode != GL_LINES &&
    in.MirroredArena != 0 && in.MirroredArena == arena.version();
  if (sorted)
  {
    in.Counts.clear();
    in.Offsets.clear();
    for (int b : in.Order)
    {
      const gmm::IndexArena::Range r = arena.slot(b);
      if (r.end > r.begin)
      {
        in.Counts.push_back(static_cast<GLsizei>(r.end - r.begin));
        in.Offsets.push_back(reinterpret_cast<const void*>(r.begin * sizeof(GLuint)));
      }
    }
    glMultiDrawElements(mode, in.Counts.data(), GL_UNSIGNED_INT, in.Offsets.data(),
      static_cast<GLsizei>(in.Counts.size()));
  }
  else
  {
    glDrawElements(mode, static_cast<GLsizei>(indexCount), GL_UNSIGNED_INT, nullptr);
  }
  if (vertexQuery)
  {
    glEndQuery(GL_VERTEX_SHADER_INVOCATIONS_ARB);
    GLuint64 runs = 0;
    glGetQueryObjectui64v(vertexQuery, GL_QUERY_RESULT, &runs);
    glDeleteQueries(1, &vertexQuery);
    this->LastVertexInvocations += static_cast<vtkTypeInt64>(runs);
  }
  if (query)
  {
    glEndQuery(GL_SAMPLES_PASSED);
    GLuint64 passed = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &passed);
    glDeleteQueries(1, &query);
    this->LastFragmentsPassed += static_cast<vtkTypeInt64>(passed);
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::RenderPieceDraw(vtkRenderer* ren, vtkActor* act)
{
  Internals& in = *this->Internal;
  vtkOpenGLHelper& tris = this->Primitives[PrimitiveTris];
  if (!tris.IBO->IndexCount)
  {
    return;
  }
  in.GPU.Bind();
  if (in.Morphing)
  {
    in.MorphTexture.Activate();
  }

  const int representation = act->GetProperty()->GetRepresentation();
  this->DrawingVertices = false;
  this->DrawingSelection = false;
  const GLenum mode = this->GetOpenGLMode(representation, PrimitiveTris);
  this->UpdateShaders(tris, ren, act);
  if (mode == GL_LINES && !this->HaveWideLines(ren, act))
  {
    static_cast<vtkOpenGLRenderWindow*>(ren->GetRenderWindow())
      ->GetState()
      ->vtkglLineWidth(act->GetProperty()->GetLineWidth());
  }
  tris.IBO->Bind();
  // glDrawElements, not VTK's glDrawRangeElements: the range would be the proxy's one
  // vertex, while the indices address every sample. The arena's unused space is the
  // fixed restart index, which draws nothing.
  if (in.PrimitiveRestart > 0)
  {
    glEnable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  }
  this->DrawTriangles(mode, tris.IBO->IndexCount);
  if (in.PrimitiveRestart > 0)
  {
    glDisable(GL_PRIMITIVE_RESTART_FIXED_INDEX);
  }
  tris.IBO->Release();
  if (in.Morphing)
  {
    in.MorphTexture.Deactivate();
  }
  in.GPU.Unbind();
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::ReplaceShaderValues(
  std::map<vtkShader::Type, vtkShader*> shaders, vtkRenderer* ren, vtkActor* act)
{
  vtkGeoMipMapShaders::PrepareTemplates(shaders);
  this->Superclass::ReplaceShaderValues(shaders, ren, act);
  vtkGeoMipMapShaders::InsertTerrainCode(shaders, this->Internal->GPU.GetShading());
  this->Internal->ShaderKeys[this->LastBoundBO] = this->Internal->GPU.GetShading().Key();
}

bool vtkGeoMipMapMapper::GetNeedToRebuildShaders(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  if (this->Superclass::GetNeedToRebuildShaders(cellBO, ren, act))
  {
    return true;
  }
  auto it = this->Internal->ShaderKeys.find(&cellBO);
  return it == this->Internal->ShaderKeys.end() || it->second != this->Internal->GPU.GetShading().Key();
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetMapperShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::SetMapperShaderParameters(cellBO, ren, act);
  Internals& in = *this->Internal;
  vtkShaderProgram* p = cellBO.Program;
  in.GPU.SetUniforms(
    p, in.Engine().heightfield(), this->Internal->Settings.heightScale, in.AnchorI, in.AnchorJ, in.HeightRef);
  if (in.Morphing)
  {
    in.MorphTexture.SetUniforms(p);
  }

  // Clipping planes in model coordinates, which are relative to the anchor.
  if (this->GetNumberOfClippingPlanes() && p->IsUniformUsed("clipPlanes"))
  {
    const int count = std::min(6, this->GetNumberOfClippingPlanes());
    float planes[6][4] = {};
    for (int i = 0; i < count; ++i)
    {
      double e[4];
      this->GetClippingPlaneInDataCoords(act->GetMatrix(), i, e);
      planes[i][0] = static_cast<float>(e[0]);
      planes[i][1] = static_cast<float>(e[1]);
      planes[i][2] = static_cast<float>(e[2]);
      planes[i][3] = static_cast<float>(e[3] + e[0] * in.AnchorShift->GetElement(3, 0) +
        e[1] * in.AnchorShift->GetElement(3, 1) + e[2] * in.AnchorShift->GetElement(3, 2));
    }
    p->SetUniform4fv("clipPlanes", 6, planes);
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetCameraShaderParameters(
  vtkOpenGLHelper& cellBO, vtkRenderer* ren, vtkActor* act)
{
  this->Superclass::SetCameraShaderParameters(cellBO, ren, act);
  // VTK's key matrices are transposed for OpenGL, so products read left to right from
  // model coordinates: anchor shift, actor, then camera. All in double; only the results
  // (small translations near the camera) are cast to float.
  Internals& in = *this->Internal;
  vtkShaderProgram* p = cellBO.Program;
  vtkMatrix4x4 *wcdc, *wcvc, *vcdc;
  vtkMatrix3x3* norms;
  static_cast<vtkOpenGLCamera*>(ren->GetActiveCamera())->GetKeyMatrices(ren, wcvc, norms, vcdc, wcdc);
  vtkNew<vtkMatrix4x4> mcwc;
  mcwc->DeepCopy(in.AnchorShift);
  if (!act->GetIsIdentity())
  {
    vtkMatrix4x4* actor;
    vtkMatrix3x3* anorms;
    static_cast<vtkOpenGLActor*>(act)->GetKeyMatrices(actor, anorms);
    vtkMatrix4x4::Multiply4x4(in.AnchorShift, actor, mcwc);
  }
  if (p->IsUniformUsed("MCWCMatrix"))
  {
    p->SetUniformMatrix("MCWCMatrix", mcwc);
  }
  vtkMatrix4x4::Multiply4x4(mcwc, wcdc, in.Temp);
  p->SetUniformMatrix("MCDCMatrix", in.Temp);
  if (p->IsUniformUsed("MCVCMatrix"))
  {
    vtkMatrix4x4::Multiply4x4(mcwc, wcvc, in.Temp);
    p->SetUniformMatrix("MCVCMatrix", in.Temp);
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::ReleaseWindowResources()
{
  Internals& in = *this->Internal;
  vtkOpenGLRenderWindow* win = in.Window;
  in.ShaderKeys.clear();
  in.IndexBytes = 0;
  in.MirroredArena = 0;
  in.PrimitiveRestart = -1;
  this->IndicesDirty = true;
  if (!win)
  {
    // Never drawn, or the window (its context, with everything in it) is gone without
    // telling us: forget the handles rather than use them in another context.
    in.GPU.Forget();
    in.MorphTexture.Forget();
    this->VBOBuildState.Clear();
    this->IBOBuildState.Clear();
    return;
  }
  win->PushContext();
  in.GPU.Release(win);
  in.MorphTexture.Release(win);
  // What vtkOpenGLPolyDataMapper::ReleaseGraphicsResources frees, which it only does
  // through its unregistered callback (see RenderPiece).
  this->VBOs->ReleaseGraphicsResources(win);
  for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
  {
    this->Primitives[i].ReleaseGraphicsResources(win);
    this->SelectionPrimitives[i].ReleaseGraphicsResources(win);
  }
  for (vtkTextureObject* t : { this->CellScalarTexture, this->CellNormalTexture, this->EdgeTexture })
  {
    if (t)
    {
      t->ReleaseGraphicsResources(win);
    }
  }
  for (vtkOpenGLBufferObject* b : { this->CellScalarBuffer, this->CellNormalBuffer, this->EdgeBuffer })
  {
    if (b)
    {
      b->ReleaseGraphicsResources();
    }
  }
  if (this->InternalColorTexture)
  {
    this->InternalColorTexture->ReleaseGraphicsResources(win);
  }
  this->TimerQuery->ReleaseGraphicsResources();
  this->VBOBuildState.Clear();
  this->IBOBuildState.Clear();
  this->CellTextureBuildState.Clear();
  win->PopContext();
  in.Window = nullptr;
}

void vtkGeoMipMapMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  // Only the window our GPU data live in can free them; another window releasing its
  // resources holds none of ours.
  if (win == this->Internal->Window.GetPointer())
  {
    this->ReleaseWindowResources();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  vtkGeoMipMapConversion::PrintFrameSettings(os, indent, this->Internal->Settings);
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "TableCache: " << this->TableCache << "\n";
  os << indent << "TableCacheDirectory: "
     << (this->TableCacheDirectory ? this->TableCacheDirectory : "(default)") << "\n";
  os << indent << "MemoryLimit: " << this->MemoryLimit << "\n";
  os << indent << "MaximumTileSize: " << this->MaximumTileSize << "\n";
  os << indent << "ShareHeights: " << this->ShareHeights << "\n";
  os << indent << "SlopeTexture: " << this->SlopeTexture << "\n";
  os << indent << "NormalMode: " << this->GetNormalModeAsString() << "\n";
  os << indent << "LastFrameVertexNormals: " << this->LastFrameVertexNormals << "\n";
  os << indent << "FreezeLevelOfDetail: " << this->FreezeLevelOfDetail << "\n";
  os << indent << "FollowAllocatedRenderTime: " << this->FollowAllocatedRenderTime << "\n";
  os << indent << "FrontToBack: " << this->FrontToBack << "\n";
  os << indent << "TriangleBudgetInForce: " << this->GetTriangleBudgetInForce() << "\n";
  os << indent << "DrapeImage: " << this->Internal->Drape.GetPointer() << "\n";
  os << indent << "NumberOfRenderedTriangles: " << this->GetNumberOfRenderedTriangles() << "\n";
  os << indent << "NumberOfVisibleBlocks: " << this->GetNumberOfVisibleBlocks() << "\n";
  os << indent << "NumberOfCulledBlocks: " << this->GetNumberOfCulledBlocks() << "\n";
  os << indent << "MaximumScreenSpaceError: " << this->GetMaximumScreenSpaceError() << "\n";
  os << indent << "LastUpdateTime: " << this->LastUpdateTime << "\n";
  os << indent << "NumberOfHeightUploads: " << this->NumberOfHeightUploads << "\n";
  os << indent << "NumberOfIndexUploads: " << this->NumberOfIndexUploads << "\n";
  os << indent << "LastIndexUploadTime: " << this->LastIndexUploadTime << "\n";
  os << indent << "GPUMemoryBytes: " << this->GetGPUMemoryBytes() << "\n";
}
