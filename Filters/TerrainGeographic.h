// TerrainGeographic: lon/lat rasters onto a regular grid in the reader's local transverse
// Mercator frame (private; vtkGeoMipMapTerrainReader.h says why and how accurate).
#pragma once

#include "TerrainIO.h"

#include <string>
#include <vector>

namespace gmm
{

// `r` holds the source lattice as gdalHeader/gdalRead leave it (nx x ny samples from (lon0,
// lat0) by lonStep/latStep, heights south to north when withHeights). Replaces it with the
// regular grid: spacing dx, dy (the source's resolution at its centre, from gdalHeader), the
// smallest node-aligned rectangle around the source's footprint in the local frame (nodes
// at multiples of the spacing from (0, 0), the source's south-west sample), and heights
// interpolated bilinearly from the 4 source samples around each node's lon/lat (the nearest
// sample when one of them is nodata; NaN outside the footprint). Returns "" or a sentence
// saying why the raster cannot be resampled (the caller adds the file name). inside
// (optional, with heights): set to nx x ny, 1 for the nodes within the source's footprint.
std::string geoGrid(
  TerrainRaster& r, bool withHeights, std::vector<unsigned char>* inside = nullptr);

// The local frame of geographic rasters: WGS84 transverse Mercator (scale 1 on the central
// meridian), shifted so that (lon0, lat0) is (0, 0). Degrees and metres.
void geographicToLocal(double centralMeridian, double lon0, double lat0, double lon, double lat,
  double& x, double& y);
void localToGeographic(double centralMeridian, double lon0, double lat0, double x, double y,
  double& lon, double& lat);

} // namespace gmm
