#include "vtkGeoMipMapMapper.h"

#include "vtkGeoMipMapConversion.h"

#include "vtkActor.h"
#include "vtkCommand.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLIndexBufferObject.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTexture.h"

#include "Engine.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

struct vtkGeoMipMapMapper::Internals
{
  gmm::Engine Engine;
  bool HaveEngine = false;
  std::vector<unsigned int> Upload; // scratch for wireframe edges
};

vtkStandardNewMacro(vtkGeoMipMapMapper);

//------------------------------------------------------------------------------
vtkGeoMipMapMapper::vtkGeoMipMapMapper()
  : Internal(new Internals)
{
  vtkMath::UninitializeBounds(this->ValidBounds);
}

//------------------------------------------------------------------------------
vtkGeoMipMapMapper::~vtkGeoMipMapMapper() = default;

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
  // Remember this MTime as "indices only" when the VBOs were current before it, so
  // GetNeedToRebuildBufferObjects does not re-upload every vertex for a new tau.
  const vtkMTimeType m = this->GetMTime();
  const bool vbosCurrent = this->VBOBuildTime >= m || m == this->IndicesOnlyMTime;
  this->Modified();
  if (vbosCurrent)
  {
    this->IndicesOnlyMTime = this->GetMTime();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetPixelError(double tau)
{
  if (vtkGeoMipMapConversion::AcceptPixelError(this, tau, this->PixelError))
  {
    this->ModifiedIndicesOnly();
  }
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::SetBlockSize(int quads)
{
  if (quads < 2)
  {
    vtkErrorMacro("BlockSize must be >= 2, got " << quads << "; keeping " << this->BlockSize);
    return;
  }
  if (quads != this->BlockSize)
  {
    this->BlockSize = quads;
    this->ModifiedIndicesOnly();
  }
}

//------------------------------------------------------------------------------
vtkIdType vtkGeoMipMapMapper::GetNumberOfRenderedTriangles() const
{
  const auto& stats = this->Internal->Engine.stats();
  return this->LastFrameDrawn ? static_cast<vtkIdType>(stats.triangles) : 0;
}
int vtkGeoMipMapMapper::GetNumberOfVisibleBlocks() const
{
  return this->LastFrameDrawn ? this->Internal->Engine.stats().visibleBlocks : 0;
}
int vtkGeoMipMapMapper::GetNumberOfCulledBlocks() const
{
  return this->LastFrameDrawn ? this->Internal->Engine.stats().culledBlocks : 0;
}
double vtkGeoMipMapMapper::GetMaximumScreenSpaceError() const
{
  return this->LastFrameDrawn ? this->Internal->Engine.stats().maxScreenError : 0.0;
}
bool vtkGeoMipMapMapper::GetIndicesReused() const
{
  return this->LastFrameDrawn ? this->Internal->Engine.stats().reused : false;
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapMapper::UpdateMesh(vtkImageData* image)
{
  if (this->Internal->HaveEngine && image->GetMTime() == this->MeshInputTime &&
    this->BlockSize == this->MeshBlockSize)
  {
    return true;
  }
  gmm::Heightfield hf;
  std::string err = vtkGeoMipMapConversion::ImageToHeightfield(image, hf);
  if (err.empty())
  {
    err = this->Internal->Engine.setHeightfield(hf, this->BlockSize);
  }
  this->Internal->HaveEngine = err.empty();
  this->MeshInputTime = image->GetMTime();
  this->MeshBlockSize = this->BlockSize;
  this->IndicesDirty = true;
  if (!err.empty())
  {
    vtkErrorMacro("Cannot use the input image: " << err);
    this->Mesh->Initialize();
    return false;
  }
  // The mesh (and its VBOs) depends on the samples only: a new block size keeps it.
  if (this->MeshVerticesTime == this->MeshInputTime && this->Mesh->GetNumberOfPoints() > 0)
  {
    return true;
  }
  const gmm::Heightfield& h = this->Internal->Engine.heightfield();
  const vtkIdType n = static_cast<vtkIdType>(h.z.size());
  vtkNew<vtkDoubleArray> xyz; // double: the VBO shift/scale then works from exact values
  xyz->SetNumberOfComponents(3);
  xyz->SetNumberOfTuples(n);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  double* p = xyz->GetPointer(0);
  float* nn = normals->GetPointer(0);
  double zmin = std::numeric_limits<double>::max(), zmax = -zmin;
  for (float z : h.z)
  {
    if (std::isfinite(z))
    {
      zmin = std::min(zmin, static_cast<double>(z));
      zmax = std::max(zmax, static_cast<double>(z));
    }
  }
  const double zfill = zmin <= zmax ? zmin : 0.0;
  for (int j = 0; j < h.ny; ++j)
  {
    for (int i = 0; i < h.nx; ++i)
    {
      const std::size_t k = h.index(i, j);
      const float z = h.z[k];
      // Nodata vertices are never referenced; a finite height keeps bounds and the VBO
      // shift/scale sane.
      p[3 * k] = h.worldX(i);
      p[3 * k + 1] = h.worldY(j);
      p[3 * k + 2] = std::isfinite(z) ? z : zfill;
      vtkGeoMipMapConversion::SampleNormal(h, i, j, nn + 3 * k);
    }
  }
  vtkNew<vtkPoints> points;
  points->SetData(xyz);
  this->Mesh->Initialize();
  this->Mesh->SetPoints(points);
  this->Mesh->GetPointData()->SetNormals(normals);
  if (vtkDataArray* s = image->GetPointData()->GetScalars())
  {
    this->Mesh->GetPointData()->SetScalars(s); // shared, not copied: colours via the LUT
  }
  this->Mesh->Modified();
  this->MeshVerticesTime = this->MeshInputTime;
  double* b = this->ValidBounds;
  b[0] = std::min(h.worldX(0), h.worldX(h.nx - 1));
  b[1] = std::max(h.worldX(0), h.worldX(h.nx - 1));
  b[2] = std::min(h.worldY(0), h.worldY(h.ny - 1));
  b[3] = std::max(h.worldY(0), h.worldY(h.ny - 1));
  b[4] = zmin <= zmax ? zmin : 0.0;
  b[5] = zmin <= zmax ? zmax : 0.0;
  return true;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::ComputeBounds()
{
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!image || !this->UpdateMesh(image))
  {
    vtkMath::UninitializeBounds(this->Bounds);
    return;
  }
  std::copy(this->ValidBounds, this->ValidBounds + 6, this->Bounds);
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

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::RenderPiece(vtkRenderer* ren, vtkActor* act)
{
  if (ren->GetRenderWindow()->CheckAbortStatus())
  {
    return;
  }
  // vtkOpenGLPolyDataMapper::RenderPiece registers a resource-free callback here, but its
  // class header is not installed by Debian's VTK 9.1. Our buffers are still released by
  // ReleaseGraphicsResources when the window or the actor lets go of them.

  // Until the engine has run for this frame, the statistics say "nothing drawn" (an
  // input or camera error below must not leave the previous frame's figures behind).
  this->LastFrameDrawn = false;
  this->LastUpdateTime = this->LastIndexUploadTime = 0.0;
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
  if (!this->UpdateMesh(image) || this->Mesh->GetNumberOfPoints() == 0)
  {
    return;
  }

  // LOD for the camera being rendered, in the data's coordinates.
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
  const auto start = std::chrono::steady_clock::now();
  const gmm::FrameStats& stats = this->Internal->Engine.update(view, this->PixelError);
  this->LastUpdateTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!this->Internal->Engine.lastError().empty())
  {
    vtkErrorMacro("LOD update failed: " << this->Internal->Engine.lastError());
  }
  this->LastFrameDrawn = true;
  this->IndicesDirty = this->IndicesDirty || !stats.reused;
  // LastIndexUploadTime (0 above) is accumulated by UploadIndices during this frame.

  this->CurrentInput = this->Mesh;
  this->UpdateCameraShiftScale(ren, act);
  this->RenderPieceStart(ren, act); // may rebuild VBOs, and then the IBO through BuildIBO
  if (this->IndicesDirty)
  {
    this->UploadIndices(act);
  }
  this->RenderPieceDraw(ren, act);
  this->RenderPieceFinish(ren, act);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::UpdateTextureCoordinates(bool wanted)
{
  vtkPointData* pd = this->Mesh->GetPointData();
  const vtkIdType n = this->Mesh->GetNumberOfPoints();
  if (!wanted || n == 0)
  {
    if (pd->GetTCoords())
    {
      pd->RemoveArray("TCoords");
    }
    return;
  }
  if (pd->GetTCoords())
  {
    return;
  }
  // 0..1 over the extent, (i, j) order: a texture image maps onto the DEM as on the input.
  const gmm::Heightfield& h = this->Internal->Engine.heightfield();
  vtkNew<vtkFloatArray> tcoords;
  tcoords->SetName("TCoords");
  tcoords->SetNumberOfComponents(2);
  tcoords->SetNumberOfTuples(n);
  float* tc = tcoords->GetPointer(0);
  const double su = h.nx > 1 ? 1.0 / (h.nx - 1) : 0.0, sv = h.ny > 1 ? 1.0 / (h.ny - 1) : 0.0;
  for (int j = 0; j < h.ny; ++j)
  {
    for (int i = 0; i < h.nx; ++i)
    {
      const std::size_t k = h.index(i, j);
      tc[2 * k] = static_cast<float>(i * su);
      tc[2 * k + 1] = static_cast<float>(j * sv);
    }
  }
  pd->SetTCoords(tcoords);
}

//------------------------------------------------------------------------------
bool vtkGeoMipMapMapper::GetNeedToRebuildBufferObjects(vtkRenderer*, vtkActor* act)
{
  // Texture coordinates only while the actor is textured: 8 bytes a sample in the mesh
  // and again in the vertex buffer that an untextured scene never reads. Adding or
  // removing them changes the mesh's MTime, hence the rebuild decided below.
  this->UpdateTextureCoordinates(
    act->GetTexture() != nullptr || act->GetProperty()->GetNumberOfTextures() > 0);
  // Same watch list as vtkOpenGLPolyDataMapper, except mapper changes that only alter
  // the indices (PixelError, BlockSize).
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
void vtkGeoMipMapMapper::BuildBufferObjects(vtkRenderer* ren, vtkActor* act)
{
  ++this->NumberOfVertexUploads;
  this->Superclass::BuildBufferObjects(ren, act);
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::BuildIBO(vtkRenderer*, vtkActor* act, vtkPolyData*)
{
  // The mesh has no cells: the only primitive is the engine's triangles.
  for (int i = PrimitiveStart; i < PrimitiveEnd; ++i)
  {
    this->Primitives[i].IBO->IndexCount = 0;
  }
  this->UploadIndices(act);
}

//------------------------------------------------------------------------------
namespace
{
// Adds the time from its start to its destruction to a counter (every return path of
// UploadIndices is timed).
struct UploadTimer
{
  std::chrono::steady_clock::time_point Start;
  double& Seconds;
  ~UploadTimer()
  {
    this->Seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - this->Start).count();
  }
};
}

void vtkGeoMipMapMapper::UploadIndices(vtkActor* act)
{
  const std::vector<uint32_t>& tris = this->Internal->Engine.indices();
  vtkOpenGLIndexBufferObject* ibo = this->Primitives[PrimitiveTris].IBO;
  ++this->NumberOfIndexUploads;
  const auto start = std::chrono::steady_clock::now();
  UploadTimer timer{ start, this->LastIndexUploadTime };
  this->IndicesDirty = false;
  if (tris.empty())
  {
    ibo->IndexCount = 0;
    return;
  }
  std::vector<unsigned int>& up = this->Internal->Upload;
  if (act->GetProperty()->GetRepresentation() == VTK_WIREFRAME)
  {
    // The stock mapper draws wireframe triangles as GL_LINES: three edges per triangle.
    up.resize(tris.size() * 2);
    for (std::size_t t = 0; t < tris.size(); t += 3)
    {
      unsigned int* e = up.data() + 2 * t;
      e[0] = tris[t];
      e[1] = tris[t + 1];
      e[2] = tris[t + 1];
      e[3] = tris[t + 2];
      e[4] = tris[t + 2];
      e[5] = tris[t];
    }
    ibo->Upload(up, vtkOpenGLBufferObject::ElementArrayBuffer);
    ibo->IndexCount = up.size();
    return;
  }
  // Triangles (GL_TRIANGLES) or points (GL_POINTS draws every referenced vertex).
  ibo->Upload(tris, vtkOpenGLBufferObject::ElementArrayBuffer);
  ibo->IndexCount = tris.size();
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::ReleaseGraphicsResources(vtkWindow* win)
{
  this->Superclass::ReleaseGraphicsResources(win);
  this->IndicesDirty = true;
}

//------------------------------------------------------------------------------
void vtkGeoMipMapMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PixelError: " << this->PixelError << "\n";
  os << indent << "BlockSize: " << this->BlockSize << "\n";
  os << indent << "NumberOfRenderedTriangles: " << this->GetNumberOfRenderedTriangles() << "\n";
  os << indent << "NumberOfVisibleBlocks: " << this->GetNumberOfVisibleBlocks() << "\n";
  os << indent << "NumberOfCulledBlocks: " << this->GetNumberOfCulledBlocks() << "\n";
  os << indent << "MaximumScreenSpaceError: " << this->GetMaximumScreenSpaceError() << "\n";
  os << indent << "LastUpdateTime: " << this->LastUpdateTime << "\n";
  os << indent << "NumberOfVertexUploads: " << this->NumberOfVertexUploads << "\n";
  os << indent << "NumberOfIndexUploads: " << this->NumberOfIndexUploads << "\n";
  os << indent << "LastIndexUploadTime: " << this->LastIndexUploadTime << "\n";
}
