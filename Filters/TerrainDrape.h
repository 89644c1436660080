// TerrainDrape: a georeferenced colour image (an orthophoto) brought into a terrain's frame
// with GDAL, behind vtkGeoMipMapImageDrape (private header; that class's header describes
// the feature for users).
//
// Kept free of VTK like TerrainIO.h: the VTK class copies the result into a vtkImageData.
#pragma once

#include <string>
#include <vector>

namespace gmm
{

// The frame of a terrain image, as vtkGeoMipMapTerrainReader records it in its field data:
// x, y are the CRS's coordinates in metres (projected CRS), or the reader's local
// transverse Mercator frame (geographic CRS: GeographicOrigin, CentralMeridian).
struct TerrainFrame
{
  std::string crs = "none"; // "EPSG:xxxx", WKT, "EPSG:4326 (assumed)" or "none"
  bool geographic = false;
  double lon0 = 0.0, lat0 = 0.0, centralMeridian = 0.0;
};

struct DrapeOptions
{
  int maximumSize = 0; // pixels a side at most (resampled to fit); 0: the image's own size
};

struct DrapeRaster
{
  int nx = 0, ny = 0;
  double x0 = 0.0, y0 = 0.0; // centre of pixel (0, 0), the south-west one, in the frame
  double dx = 0.0, dy = 0.0; // pixel size in the frame, positive
  std::vector<unsigned char> rgba; // nx * ny * 4, row 0 south; alpha 0 where no image
  std::string crs;     // the image's own CRS ("EPSG:xxxx" or WKT), as found or assumed
  bool warped = false; // resampled by GDAL's warper (false: the file's pixels, untouched)
  std::string warning; // something the user should know (e.g. a CRS was assumed)
};

// Plans the image's grid in the frame (size, origin, spacing, crs, warped, warning)
// without reading pixels. Returns "" or a sentence saying what is wrong ("the file ...",
// "the terrain ...": the caller adds the file name).
std::string planDrape(const std::string& path, const TerrainFrame& frame,
  const DrapeOptions& options, DrapeRaster& out);

// planDrape, then the pixels: read as they are when the image is in the terrain's CRS,
// axis-aligned and within maximumSize; else warped (bilinear) by GDAL into the planned grid.
std::string readDrape(const std::string& path, const TerrainFrame& frame,
  const DrapeOptions& options, DrapeRaster& out);

} // namespace gmm
