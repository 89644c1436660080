#include "View.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace gmm
{

namespace
{
bool finite3(const glm::dvec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::dvec4 plane(const glm::dvec3& normal, const glm::dvec3& through)
{
  const glm::dvec3 n = glm::normalize(normal);
  return glm::dvec4(n, -glm::dot(n, through));
}
} // namespace

double robustLength(const glm::dvec3& v)
{
  const double d2 = glm::dot(v, v);
  if (std::isfinite(d2) && d2 >= std::numeric_limits<double>::min())
  {
    return std::sqrt(d2); // the common case: |v|^2 neither overflowed nor underflowed
  }
  const double s = std::max({ std::abs(v.x), std::abs(v.y), std::abs(v.z) });
  if (s == 0.0)
  {
    return 0.0;
  }
  return s * glm::length(v / s); // largest component +-1: no overflow, no underflow
}

glm::dvec3 robustUnit(const glm::dvec3& v)
{
  const double l = robustLength(v);
  return l > 0.0 ? v / l : glm::dvec3(0.0);
}

std::string validateView(const View& v)
{
  std::ostringstream why;
  if (!finite3(v.eye) || !finite3(v.forward) || !finite3(v.up))
  {
    return "camera position, direction and view-up must be finite";
  }
  const glm::dvec3 f = robustUnit(v.forward);
  if (f == glm::dvec3(0.0))
  {
    return "camera direction has zero length";
  }
  const glm::dvec3 u = robustUnit(v.up);
  if (u == glm::dvec3(0.0) || glm::length(glm::cross(f, u)) < 1e-9)
  {
    return "camera view-up is zero or parallel to the view direction";
  }
  // Both projection parameters must be sane whatever the mode: a NaN in the unused one is
  // still a caller bug worth reporting, and switching modes must not expose it later.
  if (!(v.fovYDegrees > 0.0 && v.fovYDegrees < 180.0))
  {
    why << "field of view " << v.fovYDegrees << " degrees is outside (0, 180)";
    return why.str();
  }
  if (!(v.parallelScale > 0.0 && std::isfinite(v.parallelScale)))
  {
    why << "parallel scale " << v.parallelScale << " must be positive and finite";
    return why.str();
  }
  if (!(v.nearDistance > 0.0) || !(v.farDistance > v.nearDistance) || !std::isfinite(v.farDistance))
  {
    why << "clipping range (" << v.nearDistance << ", " << v.farDistance
        << ") must satisfy 0 < near < far < inf";
    return why.str();
  }
  if (v.viewportWidth < 1 || v.viewportHeight < 1)
  {
    why << "viewport " << v.viewportWidth << " x " << v.viewportHeight << " is empty";
    return why.str();
  }
  const glm::dmat4& m = v.model;
  for (int c = 0; c < 4; ++c)
  {
    if (!finite3(glm::dvec3(m[c])) || !std::isfinite(m[c][3]))
    {
      return "model matrix must be finite";
    }
  }
  // Row 3 of an affine matrix is (0, 0, 0, 1); glm indexes [column][row].
  if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
  {
    return "model matrix is projective (its last row is not 0 0 0 1); only affine actor "
           "matrices are supported";
  }
  const double det = glm::determinant(glm::dmat3(m));
  if (!(std::abs(det) > 0.0) || !std::isfinite(det))
  {
    return "model matrix is singular";
  }
  if (v.hasClipMatrix)
  {
    for (int c = 0; c < 4; ++c)
    {
      if (!finite3(glm::dvec3(v.clipFromWorld[c])) || !std::isfinite(v.clipFromWorld[c][3]))
      {
        return "clip matrix must be finite";
      }
    }
  }
  return std::string();
}

CameraFrame cameraFrameOf(const View& v)
{
  CameraFrame c;
  c.forward = robustUnit(v.forward);
  c.right = robustUnit(glm::cross(c.forward, robustUnit(v.up)));
  c.up = glm::cross(c.right, c.forward);
  return c;
}

namespace
{
// The plane scaled so that (a, b, c) is a unit normal (d is then a distance); a degenerate
// plane is left as it is.
glm::dvec4 normalisedPlane(const glm::dvec4& p)
{
  const double n = robustLength(glm::dvec3(p));
  return n > 0.0 ? p / n : p;
}

// Gribb & Hartmann: plane k of the clip volume -w <= x, y, z <= w, as a row combination
// of the matrix (glm::row would copy; index [column][row] directly).
glm::dvec4 clipPlane(const glm::dmat4& m, int axis, double sign)
{
  glm::dvec4 p;
  for (int c = 0; c < 4; ++c)
  {
    p[c] = m[c][3] + sign * m[c][axis];
  }
  return normalisedPlane(p);
}
} // namespace

Frustum transformPlanes(const Frustum& planes, const glm::dmat4& toPlanesFrame)
{
  Frustum out;
  const glm::dmat4 t = glm::transpose(toPlanesFrame);
  for (std::size_t k = 0; k < planes.size(); ++k)
  {
    out[k] = normalisedPlane(t * planes[k]);
  }
  return out;
}

glm::dmat4 heightfieldToWorld(const View& v, double z0, double heightScale)
{
  glm::dmat4 vertical(1.0);
  vertical[2][2] = heightScale;
  vertical[3][2] = z0;
  return v.model * vertical;
}

Frustum frustumOf(const View& v)
{
  if (v.hasClipMatrix)
  {
    const glm::dmat4& m = v.clipFromWorld;
    return Frustum{ clipPlane(m, 0, 1.0), clipPlane(m, 0, -1.0), clipPlane(m, 1, 1.0),
      clipPlane(m, 1, -1.0), clipPlane(m, 2, 1.0), clipPlane(m, 2, -1.0) };
  }
  const CameraFrame c = cameraFrameOf(v);
  const double aspect = static_cast<double>(v.viewportWidth) / v.viewportHeight;
  Frustum fr;
  if (v.parallel)
  {
    const double sy = v.parallelScale, sx = sy * aspect;
    fr[0] = plane(c.right, v.eye - c.right * sx);
    fr[1] = plane(-c.right, v.eye + c.right * sx);
    fr[2] = plane(c.up, v.eye - c.up * sy);
    fr[3] = plane(-c.up, v.eye + c.up * sy);
  }
  else
  {
    const double ty = std::tan(v.fovYDegrees * M_PI / 360.0), tx = ty * aspect;
    fr[0] = plane(c.right + c.forward * tx, v.eye);
    fr[1] = plane(-c.right + c.forward * tx, v.eye);
    fr[2] = plane(c.up + c.forward * ty, v.eye);
    fr[3] = plane(-c.up + c.forward * ty, v.eye);
  }
  fr[4] = plane(c.forward, v.eye + c.forward * v.nearDistance);
  fr[5] = plane(-c.forward, v.eye + c.forward * v.farDistance);
  return fr;
}

double pixelsPerUnit(const View& v)
{
  const double half = 0.5 * v.viewportHeight;
  if (v.parallel)
  {
    return half / v.parallelScale;
  }
  return half / std::tan(v.fovYDegrees * M_PI / 360.0);
}

bool projectToPixels(const View& v, const glm::dvec3& p, double& px, double& py)
{
  const CameraFrame c = cameraFrameOf(v);
  const glm::dvec3 q = p - v.eye;
  const double depth = glm::dot(q, c.forward);
  if (depth < v.nearDistance)
  {
    return false;
  }
  const double f = pixelsPerUnit(v);
  const double scale = v.parallel ? f : f / depth;
  px = 0.5 * v.viewportWidth + glm::dot(q, c.right) * scale;
  py = 0.5 * v.viewportHeight + glm::dot(q, c.up) * scale;
  return true;
}

} // namespace gmm
