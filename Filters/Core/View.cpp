#include "View.h"

#include <glm/geometric.hpp>

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

Frustum frustumOf(const View& v)
{
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
