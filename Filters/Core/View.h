// View: what level selection and culling need to know about a camera and viewport.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <string>

namespace gmm
{

struct View
{
  glm::dvec3 eye{ 0.0 };
  glm::dvec3 forward{ 0.0, 1.0, 0.0 }; // view direction (need not be unit length)
  glm::dvec3 up{ 0.0, 0.0, 1.0 };      // view-up (projected orthogonal to forward)
  double fovYDegrees = 30.0;            // vertical field of view, perspective only
  bool parallel = false;                // orthographic projection
  double parallelScale = 1.0;           // half the view height in world units (orthographic)
  double nearDistance = 0.1;            // clipping range along forward, world units
  double farDistance = 1e6;
  int viewportWidth = 1280;             // pixels
  int viewportHeight = 720;
  // Data -> world: the matrix of the actor that draws the heightfield (glm, column-major).
  // eye, forward, up and the clipping range are in world coordinates. Any invertible
  // affine matrix (rotation, translation, non-uniform scale, shear): culling and the error
  // bound are exact under it. Default identity.
  glm::dmat4 model{ 1.0 };
  // Optional exact world -> clip matrix of the camera (OpenGL convention, clip w > 0 in
  // front). When hasClipMatrix is set the frustum planes come from it, so a window centre
  // or view shear culls exactly; the fields above still give the error bound.
  bool hasClipMatrix = false;
  glm::dmat4 clipFromWorld{ 1.0 };
};

// Frustum as 6 planes (a, b, c, d) with a*x + b*y + c*z + d >= 0 inside; order: left, right,
// bottom, top, near, far. Normals are unit length.
using Frustum = std::array<glm::dvec4, 6>;

// |v| also when |v|^2 would overflow or underflow a double (a direction (0, 1e200, 0), an
// eye 1e200 m away); 0 for the zero vector, NaN for NaN.
double robustLength(const glm::dvec3& v);

// v / |v| by robustLength; the zero vector for zero.
glm::dvec3 robustUnit(const glm::dvec3& v);

// Checks a view. Empty string when usable, else what is wrong (non-finite values, zero
// forward, up zero or parallel to forward, field of view outside (0, 180), parallel scale
// <= 0, near <= 0 or far <= near, viewport below 1 x 1, a model matrix that is not affine
// or not invertible, a non-finite clip matrix). The field of view and the parallel
// scale are checked in both modes. There is no fallback for a degenerate view-up: the
// caller knows which "up" it meant. forward and up may have any finite, non-zero length
// (1e-200 and 1e200 included).
std::string validateView(const View& view);

// The view's frustum in world coordinates: from clipFromWorld when the view has one, else
// from eye, forward, up, field of view (or parallel scale) and clipping range.
Frustum frustumOf(const View& view);

// Frustum planes in another frame: `planes` hold in the frame that `toPlanesFrame` maps
// into; the result holds in its source frame (p' = M^T p, renormalised). Exact for any
// invertible affine M.
Frustum transformPlanes(const Frustum& planes, const glm::dmat4& toPlanesFrame);

// Heightfield coordinates (x, y, stored height h) -> world: model * (x, y, z0 + scale * h).
// z0 is the heightfield's datum, scale its vertical exaggeration (both exact in double).
glm::dmat4 heightfieldToWorld(const View& view, double z0, double heightScale);

// Orthonormal camera frame derived from the view (right, true up, unit forward).
struct CameraFrame
{
  glm::dvec3 right, up, forward;
};
CameraFrame cameraFrameOf(const View& view);

// Pixels per world unit at depth 1 (perspective) or everywhere (orthographic).
double pixelsPerUnit(const View& view);

// Projects a world point to pixel coordinates (x right, y up, origin at the viewport's
// lower-left corner). Returns false when the point is not in front of the near plane.
// Used by tests and benchmarks to measure error independently of level selection.
bool projectToPixels(const View& view, const glm::dvec3& p, double& px, double& py);

} // namespace gmm
