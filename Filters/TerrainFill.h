// TerrainFill: void (nodata) filling of the reader's heights with GDAL's GDALFillNodata
// (private header; vtkGeoMipMapTerrainReader.h describes the feature for users).
//
// Kept free of VTK like TerrainIO.h: the heights are filled in the reader's own buffer,
// through an in-memory (MEM driver) GDAL dataset that points at it.
#pragma once

#include "HeightBuffer.h"

#include <functional>
#include <string>
#include <vector>

namespace gmm
{

// Smoothing passes allowed: GDAL keeps iterations + 2 rows in a rolling buffer and makes a
// pass over the raster per iteration, so an absurd count would hang or exhaust memory.
constexpr int kMaxFillSmoothingIterations = 1000;

// "" when the fill options are usable, else a sentence naming the bad one.
std::string checkFillOptions(double searchDistance, int smoothingIterations);

// Bytes the fill needs beyond the heights themselves (masks, GDAL's work rasters and its
// smoothing buffer), for the reader's memory check.
double fillMemoryBytes(double nx, double ny, int smoothingIterations);

// Fills the NaN samples of z (nx x ny, row-major) that have a valid sample within
// searchDistance samples (Euclidean, in sample steps): GDALFillNodata's inverse distance
// weighting of the nearest valid sample in each of four quadrants, then
// smoothingIterations passes of a 3x3 mean over the filled samples only. Valid samples
// are never written. inside (optional, nx x ny): samples that may be filled at all (0:
// outside the data's footprint, left NaN). filled: set to nx x ny, 1 where a NaN sample
// was filled, else 0. progress(fraction) is called now and then. Returns "" or a sentence
// saying what went wrong.
std::string fillNodata(HeightBuffer& z, int nx, int ny, double searchDistance,
  int smoothingIterations, const std::vector<unsigned char>* inside,
  std::vector<unsigned char>& filled, const std::function<void(double)>& progress);

} // namespace gmm
