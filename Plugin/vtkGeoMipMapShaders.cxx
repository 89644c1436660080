// VTK-HeaderTest-Exclude: vtkGeoMipMapShaders.cxx
#include "vtkGeoMipMapShaders.h"

#include "vtkShaderProgram.h"

namespace
{

// The sampler type of the heights: "isampler", "usampler" or "sampler", + `kind`.
std::string SamplerFor(vtkGeoMipMapShaders::Options::Heights h, const char* kind)
{
  switch (h)
  {
    case vtkGeoMipMapShaders::Options::Int16Heights:
      return std::string("isampler") + kind;
    case vtkGeoMipMapShaders::Options::UInt16Heights:
      return std::string("usampler") + kind;
    default:
      return std::string("sampler") + kind;
  }
}

// Heights read in place (vtkGeoMipMapSharedHeights.h): sample k = j * nx + i of bands of
// 2^gmmBandShift samples, one buffer texture each, n = HeightsPerTexel samples a texel
// (component k % n of texel k / n; the last samples that fill no texel are uniforms). With
// several bands the band is picked by a chain of branches: indexing an array of samplers by
// a value that differs between vertices is undefined in GLSL 4.5.
std::string SharedHeightFetch(const vtkGeoMipMapShaders::Options& o)
{
  const int n = o.HeightsPerTexel; // a power of two
  const bool packed = n > 1;
  int log2n = 0;
  while ((1 << log2n) < n)
  {
    ++log2n;
  }
  const std::string tail = std::to_string(n - 1), shift = std::to_string(log2n);
  std::string s = "uniform int gmmBandShift;\n";
  s += packed ? "uniform int gmmTailStart;\nuniform float gmmTail[" + tail + "];\n" : "";
  for (int k = 0; k < o.HeightBands; ++k)
  {
    s += "uniform highp " + SamplerFor(o.HeightFormat, "Buffer") + " gmmHeightBand" + std::to_string(k) + ";\n";
  }
  s += "float gmmHeight(ivec2 ij)\n"
       "{\n"
       "  int k = ij.y * gmmGridSize.x + ij.x;\n";
  s += packed ? "  int t = min(k, gmmTailStart - 1);\n" : "  int t = k;\n";
  s += "  float h;\n";
  const std::string texel = packed ? "t >> " + shift + ")[t & " + tail + "]" : "t).r";
  if (o.HeightBands == 1)
  {
    s += "  h = float(texelFetch(gmmHeightBand0, " + texel + ");\n";
  }
  else
  {
    s += "  int band = t >> gmmBandShift;\n"
         "  t -= band << gmmBandShift;\n";
    for (int k = 0; k < o.HeightBands; ++k)
    {
      const std::string fetch = "h = float(texelFetch(gmmHeightBand" + std::to_string(k) + ", " + texel + ");";
      s += k + 1 < o.HeightBands ? "  " + std::string(k ? "else " : "") + "if (band == " + std::to_string(k) + ") { " + fetch + " }\n"
                                 : "  else { " + fetch + " }\n";
    }
  }
  return s + (packed ? "  return k < gmmTailStart ? h : gmmTail[clamp(k - gmmTailStart, 0, " + tail + " - 1)];\n}\n"
                      : "  return h;\n}\n");
}

// Sample (i, j) of a tiled array texture (vtkGeoMipMapTextures.h): layer, then texel. One
// layer needs no arithmetic; several divide by the tile size through a float reciprocal
// (exact here: (i + 0.5) / w never rounds across an integer for i < 2^24), because integer
// division is scalarised, hence slow, on software rasterisers.
std::string FetchFunctions(const vtkGeoMipMapShaders::Options& o)
{
  std::string s = (o.HeightBands > 0 ? std::string() : "uniform highp " + SamplerFor(o.HeightFormat, "2DArray") + " gmmHeights;\n") +
    "uniform ivec2 gmmGridSize;   // samples nx, ny\n"
    "uniform ivec2 gmmTileSize;   // texels per layer\n"
    "uniform vec2 gmmTileScale;   // 1 / texels per layer\n"
    "uniform int gmmTilesX;       // layers per row of tiles\n"
    "uniform vec2 gmmSpacing;     // dx, dy\n"
    "uniform float gmmHeightScale; // vertical exaggeration\n";
  if (o.SingleLayer)
  {
    s += "ivec3 gmmTexel(ivec2 ij) { return ivec3(ij, 0); }\n";
  }
  else
  {
    s += "ivec3 gmmTexel(ivec2 ij)\n"
         "{\n"
         "  ivec2 tile = ivec2((vec2(ij) + 0.5) * gmmTileScale);\n"
         "  return ivec3(ij - tile * gmmTileSize, tile.y * gmmTilesX + tile.x);\n"
         "}\n";
  }
  s += o.HeightBands > 0
    ? SharedHeightFetch(o)
    : "float gmmHeight(ivec2 ij) { return float(texelFetch(gmmHeights, gmmTexel(ij), 0).r); }\n";
  return s;
}

// Whether a stored height is a height (vertex and fragment shaders).
const char* const kValid =
  "bool gmmValid(float h) { return abs(h) <= 1.0e38; } // false for NaN, +-Inf, sentinels\n";
// The unit normal (model coordinates) of slopes g = (dh/dx, dh/dy) of the stored heights,
// the height scale applied: every normal source below ends in it.
const char* const kNormalOfSlope =
  "vec3 gmmNormalOfSlope(vec2 g) { return normalize(vec3(-gmmHeightScale * g, 1.0)); }\n";

// The fragment's level-0 triangle: quad c split as the full-resolution surface is
// (gmm::fullResolutionAntiDiagonal, the union jack: along its (0,0)-(1,1) diagonal where
// c.x + c.y is even, along (1,0)-(0,1) where it is odd), its vertices c + o0, c + o1,
// c + o2 (offsets in the quad) and their barycentric weights.
const char* const kQuad =
  "in vec2 gmmGridVSOutput;\n"
  "struct GmmTri { ivec2 c; ivec2 o0; ivec2 o1; ivec2 o2; vec3 w; };\n"
  "GmmTri gmmTriangle(vec2 g)\n"
  "{\n"
  "  GmmTri t;\n"
  "  vec2 gc = clamp(g, vec2(0.0), vec2(gmmGridSize - 1));\n"
  "  t.c = min(ivec2(floor(gc)), gmmGridSize - 2);\n"
  "  vec2 f = gc - vec2(t.c);\n"
  "  bool anti = ((t.c.x + t.c.y) & 1) == 1;\n"
  "  bool lower = anti ? f.x + f.y <= 1.0 : f.x >= f.y;\n"
  "  t.o0 = anti && !lower ? ivec2(1, 0) : ivec2(0);\n"
  "  t.o1 = lower ? ivec2(1, 0) : (anti ? ivec2(1, 1) : ivec2(0, 1));\n"
  "  t.o2 = anti ? ivec2(0, 1) : ivec2(1, 1);\n"
  "  t.w = anti ? (lower ? vec3(1.0 - f.x - f.y, f.x, f.y) : vec3(1.0 - f.y, f.x + f.y - 1.0, 1.0 - f.x))\n"
  "             : (lower ? vec3(1.0 - f.x, f.x - f.y, f.y) : vec3(1.0 - f.y, f.y - f.x, f.x));\n"
  "  return t;\n"
  "}\n";

// Normals on the level-0 triangle under the fragment: the slopes of its three samples
// (gmmTriangleSlopes, from one of the two sources below) are interpolated with its weights,
// then scaled and normalised once. (The full-resolution mesh interpolates unit normals
// instead; the two differ by a fraction of a degree where the slopes vary fast within one
// quad.)
const char* const kNormalOnTriangle =
  "vec3 gmmNormalMC(GmmTri t)\n"
  "{\n"
  "  vec2 s0, s1, s2;\n"
  "  gmmTriangleSlopes(t, s0, s1, s2);\n"
  "  vec2 g = t.w.x * s0 + t.w.y * s1 + t.w.z * s2;\n"
  "  return gmmNormalOfSlope(g);\n"
  "}\n";
// Slopes from the slope texture (gmm::sampleSlope, made once at upload).
const char* const kSlopeFromTexture =
  "uniform highp sampler2DArray gmmSlopes;\n"
  "vec2 gmmSlope(ivec2 ij) { return texelFetch(gmmSlopes, gmmTexel(ij), 0).rg; }\n"
  "void gmmTriangleSlopes(GmmTri t, out vec2 s0, out vec2 s1, out vec2 s2)\n"
  "{\n"
  "  s0 = gmmSlope(t.c + t.o0);\n"
  "  s1 = gmmSlope(t.c + t.o1);\n"
  "  s2 = gmmSlope(t.c + t.o2);\n"
  "}\n";
// gmm::sampleSlope's rule (Heightfield.h) on heights already fetched: central
// differences, one-sided next to the border or nodata, 0 where neither neighbour is valid.
// Neighbours are fetched at positions clamped into the grid; a clamped one is never used
// (hasA / hasB).
const char* const kSlopeRule =
  "float gmmSlope1(float ha, float hc, float hb, bool hasA, bool hasB, float spacing)\n"
  "{\n"
  "  bool okA = hasA && gmmValid(ha), okB = hasB && gmmValid(hb), okC = gmmValid(hc);\n"
  "  if (okA && okB) { return (hb - ha) / (2.0 * spacing); }\n"
  "  if (okB && okC) { return (hb - hc) / spacing; }\n"
  "  if (okA && okC) { return (hc - ha) / spacing; }\n"
  "  return 0.0;\n"
  "}\n"
  "// The slopes at p from its height and its west, east, south and north neighbours'.\n"
  "vec2 gmmSlope(ivec2 p, float hc, float hw, float he, float hs, float hn)\n"
  "{\n"
  "  return vec2(gmmSlope1(hw, hc, he, p.x > 0, p.x + 1 < gmmGridSize.x, gmmSpacing.x),\n"
  "    gmmSlope1(hs, hc, hn, p.y > 0, p.y + 1 < gmmGridSize.y, gmmSpacing.y));\n"
  "}\n"
  "float gmmHeightIn(ivec2 ij) { return gmmHeight(clamp(ij, ivec2(0), gmmGridSize - 1)); }\n";
// Slopes computed per fragment from the heights (SlopeTexture off: no slope texture), by
// that rule. The three vertices' 12 neighbours are 10 distinct samples: the quad's corners,
// and for each vertex the two beyond it along the quad's sides. Fetched without branches
// (llvmpipe runs both sides of a branch).
const char* const kSlopeFromHeights =
  "// The slopes at corner c + o of quad c, its corners' heights q00 .. q11 fetched.\n"
  "vec2 gmmCornerSlope(ivec2 c, ivec2 o, float q00, float q10, float q01, float q11)\n"
  "{\n"
  "  bool west = o.x == 0, south = o.y == 0;\n"
  "  float hc = south ? (west ? q00 : q10) : (west ? q01 : q11);\n"
  "  float inX = south ? (west ? q10 : q00) : (west ? q11 : q01); // across the quad\n"
  "  float inY = west ? (south ? q01 : q00) : (south ? q11 : q10);\n"
  "  float outX = gmmHeightIn(c + ivec2(west ? -1 : 2, o.y)); // beyond it\n"
  "  float outY = gmmHeightIn(c + ivec2(o.x, south ? -1 : 2));\n"
  "  return gmmSlope(c + o, hc, west ? outX : inX, west ? inX : outX, south ? outY : inY,\n"
  "    south ? inY : outY);\n"
  "}\n"
  "void gmmTriangleSlopes(GmmTri t, out vec2 s0, out vec2 s1, out vec2 s2)\n"
  "{\n"
  "  ivec2 c = t.c;\n"
  "  float q00 = gmmHeightIn(c), q10 = gmmHeightIn(c + ivec2(1, 0));\n"
  "  float q01 = gmmHeightIn(c + ivec2(0, 1)), q11 = gmmHeightIn(c + ivec2(1, 1));\n"
  "  s0 = gmmCornerSlope(c, t.o0, q00, q10, q01, q11);\n"
  "  s1 = gmmCornerSlope(c, t.o1, q00, q10, q01, q11);\n"
  "  s2 = gmmCornerSlope(c, t.o2, q00, q10, q01, q11);\n"
  "}\n";
// VertexNormals: the full-resolution normal at the vertex's own sample, by the same rule
// (four neighbours fetched a vertex), interpolated across the triangle by VTK's own
// normalVCVSOutput, as vtkPolyDataMapper shades a mesh with point normals.
const char* const kVertexNormal =
  "vec3 gmmVertexNormal(ivec2 p, float hc)\n"
  "{\n"
  "  vec2 g = gmmSlope(p, hc, gmmHeightIn(p - ivec2(1, 0)), gmmHeightIn(p + ivec2(1, 0)),\n"
  "    gmmHeightIn(p - ivec2(0, 1)), gmmHeightIn(p + ivec2(0, 1)));\n"
  "  return gmmNormalOfSlope(g);\n"
  "}\n";
// One layer: the slopes bilinearly filtered at the fragment (one fetch; the exact
// triangle interpolation above takes three, and differs from it by a fraction of a degree).
const char* const kNormalBilinear =
  "uniform highp sampler2DArray gmmSlopes;\n"
  "vec3 gmmNormalMC(GmmTri t)\n"
  "{\n"
  "  vec2 g = texture(gmmSlopes, vec3((gmmGridVSOutput + 0.5) * gmmTileScale, 0.0)).rg;\n"
  "  return gmmNormalOfSlope(g);\n"
  "}\n";

// A draped image at the fragment: texture coordinates are affine in the grid position,
// which is affine in model x, y (vtkGeoMipMapDrapeTexture::GetMap); outside the image the
// transparent border leaves the colour below.
const char* const kDrape =
  "uniform sampler2D gmmDrape;\n"
  "uniform vec4 gmmDrapeMap; // st = grid position * xy + zw\n"
  "vec4 gmmDrapeColor() { return texture(gmmDrape, gmmGridVSOutput * gmmDrapeMap.xy + gmmDrapeMap.zw); }\n";

// Vertex placement and geomorphing in the vertex shader, mirroring gmm::morphedHeight
// (MorphTargets.cpp) line by line: the block of sample (i, j) from its column's and row's entries
// in gmmSampleBands (the band search of Quadtree.h's bandOfSample, tabulated:
// vtkGeoMipMapMorphTexture.h), then the edge or the block it lies on, its target level and
// factor. An edge vertex starts on the edge's polyline at its level (a glided edge's
// samples, EdgeHeights.h; the edge's own samples are on it) and moves toward the polyline
// at the target level; a block corner moves only onto a merging node's fan (its texel holds
// the fan's height there: gmm::MorphFrame::cornerT); an interior vertex moves toward the
// block's cell at the target level, split as Tessellate splits it (gmm::ringCellAntiDiagonal, Levels.h), whose corners
// on the block's border are where their edges draw them (gmm::blockVertexTarget).
const char* const kMorph =
  "uniform highp sampler2D gmmMorph;\n"
  "uniform ivec2 gmmMorphLayout; // block columns, rows\n"
  "uniform highp sampler2D gmmSampleBands;\n"
  "uniform ivec2 gmmSampleBandsLayout; // log2 texels a row, rows of the column entries\n"
  "vec3 gmmMorphAt(int x, int y) { return texelFetch(gmmMorph, ivec2(x, y), 0).rgb; }\n"
  "// (band, first sample, last sample, upper-half flag) of sample s along columns\n"
  "// (rows0 = 0) or rows.\n"
  "ivec4 gmmBandOf(int s, int rows0)\n"
  "{\n"
  "  int w = gmmSampleBandsLayout.x;\n"
  "  return ivec4(texelFetch(gmmSampleBands, ivec2(s & ((1 << w) - 1), rows0 + (s >> w)), 0));\n"
  "}\n"
  "float gmmLerp(float a, float b, float w) { return a + w * (b - a); }\n"
  "float gmmPolyline(int first, int last, int level, int s, ivec2 fixedAxis, bool alongI)\n"
  "{\n"
  "  int step = 1 << level;\n"
  "  int lo = first + ((s - first) >> level) * step;\n"
  "  ivec2 a = alongI ? ivec2(lo, fixedAxis.y) : ivec2(fixedAxis.x, lo);\n"
  "  if (lo == s) { return gmmHeight(a); }\n"
  "  int hi = min(lo + step, last);\n"
  "  ivec2 b = alongI ? ivec2(hi, fixedAxis.y) : ivec2(fixedAxis.x, hi);\n"
  "  return gmmLerp(gmmHeight(a), gmmHeight(b), float(s - lo) / float(hi - lo));\n"
  "}\n"
  "// A sample on an edge as the edge draws it, d its texel (target, factor, level): on the\n"
  "// polyline at its level, moved by the factor toward the polyline at its target.\n"
  "float gmmEdgeHeight(int first, int last, int s, ivec2 p, bool alongI, vec3 d, float h)\n"
  "{\n"
  "  float base = d.z > 0.0 ? gmmPolyline(first, last, int(d.z), s, p, alongI) : h;\n"
  "  if (!(d.y > 0.0)) { return base; }\n"
  "  float target = gmmPolyline(first, last, int(d.x), s, p, alongI);\n"
  "  return abs(target) <= 1.0e38 ? base + d.y * (target - base) : base;\n"
  "}\n"
  "// Sample p of block [i0, i1] x [j0, j1] as the block draws it, its edges' texels\n"
  "// (south, east, north, west) in `edge`: on a side, as that edge draws it.\n"
  "float gmmBorderHeight(ivec2 p, int i0, int i1, int j0, int j1, vec3 edge[4])\n"
  "{\n"
  "  bool onV = p.x == i0 || p.x == i1, onH = p.y == j0 || p.y == j1;\n"
  "  float h = gmmHeight(p);\n"
  "  if (onV == onH) { return h; }\n"
  "  if (onH) { return gmmEdgeHeight(i0, i1, p.x, p, true, edge[p.y == j0 ? 0 : 2], h); }\n"
  "  return gmmEdgeHeight(j0, j1, p.y, p, false, edge[p.x == i0 ? 3 : 1], h);\n"
  "}\n"
  "float gmmBlockSurface(ivec2 ij, int i0, int i1, int j0, int j1, int level, bool oneQuadAnti, vec3 edge[4])\n"
  "{\n"
  "  int step = 1 << level;\n"
  "  int u = (ij.x - i0) >> level, v = (ij.y - j0) >> level;\n"
  "  int ia = i0 + u * step, ja = j0 + v * step;\n"
  "  int ib = min(ia + step, i1), jb = min(ja + step, j1);\n"
  "  int k = (i1 - i0 + step - 1) >> level, L = (j1 - j0 + step - 1) >> level;\n"
  "  bool ring = step < i1 - i0 && step < j1 - j0;\n"
  "  bool corner = (u == 0 || u == k - 1) && (v == 0 || v == L - 1);\n"
  "  bool anti = ring ? (corner ? (u == k - 1 && v == 0) || (u == 0 && v == L - 1) : ((u + v) & 1) == 1)\n"
  "                   : oneQuadAnti;\n"
  "  float fx = float(ij.x - ia) / float(ib - ia), fy = float(ij.y - ja) / float(jb - ja);\n"
  "  float h00 = gmmBorderHeight(ivec2(ia, ja), i0, i1, j0, j1, edge);\n"
  "  float h10 = gmmBorderHeight(ivec2(ib, ja), i0, i1, j0, j1, edge);\n"
  "  float h01 = gmmBorderHeight(ivec2(ia, jb), i0, i1, j0, j1, edge);\n"
  "  float h11 = gmmBorderHeight(ivec2(ib, jb), i0, i1, j0, j1, edge);\n"
  "  if (!anti)\n"
  "    return fx >= fy ? h00 + fx * (h10 - h00) + fy * (h11 - h10) : h00 + fy * (h01 - h00) + fx * (h11 - h01);\n"
  "  return fx + fy <= 1.0 ? h00 + fx * (h10 - h00) + fy * (h01 - h00)\n"
  "                        : h11 + (1.0 - fx) * (h01 - h11) + (1.0 - fy) * (h10 - h11);\n"
  "}\n"
  "float gmmMorphHeight(ivec2 ij, float h)\n"
  "{\n"
  "  int br = gmmMorphLayout.y;\n"
  "  ivec4 cb = gmmBandOf(ij.x, 0), rb = gmmBandOf(ij.y, gmmSampleBandsLayout.y);\n"
  "  int c = cb.x, i0 = cb.y, i1 = cb.z, r = rb.x, j0 = rb.y, j1 = rb.z;\n"
  "  bool onV = ij.x == i0 || ij.x == i1, onH = ij.y == j0 || ij.y == j1;\n"
  "  if (onV && onH)\n"
  "  {\n"
  "    int corners = max(gmmMorphLayout.x, br) + 1; // the corners' first column\n"
  "    vec3 k = gmmMorphAt(corners + (ij.x == i0 ? c : c + 1), ij.y == j0 ? r : r + 1);\n"
  "    return k.y > 0.0 ? h + k.y * (k.x - h) : h;\n"
  "  }\n"
  "  if (onV) { return gmmEdgeHeight(j0, j1, ij.y, ij, false, gmmMorphAt(ij.x == i0 ? c : c + 1, br + r), h); }\n"
  "  if (onH) { return gmmEdgeHeight(i0, i1, ij.x, ij, true, gmmMorphAt(c, 2 * br + (ij.y == j0 ? r : r + 1)), h); }\n"
  "  vec3 d = gmmMorphAt(c, r);\n"
  "  if (!(d.y > 0.0)) { return h; }\n"
  "  vec3 edge[4] = vec3[4](gmmMorphAt(c, 2 * br + r), gmmMorphAt(c + 1, br + r), gmmMorphAt(c, 2 * br + r + 1),\n"
  "                         gmmMorphAt(c, br + r));\n"
  "  float target = gmmBlockSurface(ij, i0, i1, j0, j1, int(d.x), cb.w != rb.w, edge);\n"
  "  return abs(target) <= 1.0e38 ? h + d.y * (target - h) : h;\n"
  "}\n";

// Lookup-table colours: texel 0 below range, 1..n the bins, n + 1 above, n + 2 NaN.
std::string ColorTable(const vtkGeoMipMapShaders::Options& o)
{
  std::string s = "uniform sampler2D gmmColorTable;\n"
                  "uniform vec4 gmmColorMap; // range low, 1 / range width, unused, bins\n"
                  "vec4 gmmMapScalar(float s)\n"
                  "{\n"
                  "  int n = int(gmmColorMap.w);\n"
                  "  int k = n + 2;\n"
                  "  if (gmmValid(s))\n"
                  "  {\n";
  s += o.LogScale ? "    float v = s > 0.0 ? log(s) * 0.43429448190325176 : -1.0e38; // log10\n"
                  : "    float v = s;\n";
  s += "    float t = (v - gmmColorMap.x) * gmmColorMap.y;\n"
       "    k = t < 0.0 ? 0 : (t > 1.0 ? n + 1 : 1 + min(int(t * float(n)), n - 1));\n"
       "  }\n"
       "  return texelFetch(gmmColorTable, ivec2(k, 0), 0);\n"
       "}\n";
  return s;
}

std::string ColorFunctions(const vtkGeoMipMapShaders::Options& o)
{
  using O = vtkGeoMipMapShaders::Options;
  switch (o.Color)
  {
    case O::MapHeights:
      // The drawn surface's own height, interpolated from the vertices: one lookup per
      // fragment instead of three fetches. It differs from the full-resolution height by at
      // most the frame's geometric error, a fraction of a colour step in practice.
      return ColorTable(o) +
        "in float gmmHeightVSOutput;\n"
        "vec4 gmmColor(GmmTri t) { return gmmMapScalar(gmmHeightVSOutput); }\n";
    case O::MapScalars:
      return ColorTable(o) +
        "uniform highp sampler2DArray gmmScalars;\n"
        "float gmmScalar(ivec2 ij) { return texelFetch(gmmScalars, gmmTexel(ij), 0).r; }\n"
        "vec4 gmmColor(GmmTri t)\n"
        "{\n"
        "  return gmmMapScalar(t.w.x * gmmScalar(t.c + t.o0) + t.w.y * gmmScalar(t.c + t.o1) +\n"
        "    t.w.z * gmmScalar(t.c + t.o2));\n"
        "}\n";
    case O::DirectColors:
      return "uniform highp sampler2DArray gmmColors;\n"
             "vec4 gmmRGBA(ivec2 ij) { return texelFetch(gmmColors, gmmTexel(ij), 0); }\n"
             "vec4 gmmColor(GmmTri t)\n"
             "{\n"
             "  return t.w.x * gmmRGBA(t.c + t.o0) + t.w.y * gmmRGBA(t.c + t.o1) + t.w.z * gmmRGBA(t.c + t.o2);\n"
             "}\n";
    default:
      return std::string();
  }
}

} // namespace

namespace vtkGeoMipMapShaders
{

std::string Options::Key() const
{
  return std::to_string(this->HeightFormat) + "/" + std::to_string(this->Color) + "/" +
    (this->TextureCoordinates ? "t" : "-") + (this->SingleLayer ? "1" : "n") +
    (this->LogScale ? "l" : "-") + (this->Drape ? "d" : "-") + (this->Morph ? "m" : "-") + "b" +
    std::to_string(this->HeightBands) + "x" + std::to_string(this->HeightsPerTexel) +
    (this->SlopesFromHeights ? "s" : "-") + (this->VertexNormals ? "v" : "-");
}

void PrepareTemplates(std::map<vtkShader::Type, vtkShader*>& shaders)
{
  // VTK replaces these tags with its own code and drops them; a marker next to each keeps a
  // place for ours (declarations before main, colour after VTK's colour code).
  for (auto type : { vtkShader::Vertex, vtkShader::Fragment })
  {
    std::string src = shaders[type]->GetSource();
    if (src.empty())
    {
      continue;
    }
    vtkShaderProgram::Substitute(
      src, "//VTK::CustomUniforms::Dec", "//GMM::Dec\n//VTK::CustomUniforms::Dec");
    if (type == vtkShader::Fragment)
    {
      vtkShaderProgram::Substitute(src, "//VTK::Color::Impl", "//VTK::Color::Impl\n//GMM::Color::Impl");
    }
    shaders[type]->SetSource(src);
  }
}

void InsertTerrainCode(std::map<vtkShader::Type, vtkShader*>& shaders, const Options& o)
{
  std::string vs = shaders[vtkShader::Vertex]->GetSource();
  std::string fs = shaders[vtkShader::Fragment]->GetSource();
  std::string gs = shaders[vtkShader::Geometry]->GetSource();

  // Vertex shader: the attributes VTK declared become values computed from gl_VertexID.
  vtkShaderProgram::Substitute(vs, "in vec4 vertexMC;", "vec4 vertexMC;");
  // VTK declares normalMC only where it lights the surface.
  const bool vertexNormals = o.VertexNormals &&
    vtkShaderProgram::Substitute(vs, "in vec3 normalMC;", "vec3 normalMC;");
  vtkShaderProgram::Substitute(vs, "in vec3 normalMC;", "vec3 normalMC = vec3(0.0, 0.0, 1.0);");
  vtkShaderProgram::Substitute(vs, "in vec2 tcoord;", "vec2 tcoord;");
  vtkShaderProgram::Substitute(vs, "//GMM::Dec",
    FetchFunctions(o) +
      "uniform ivec2 gmmAnchor;      // sample at the model-coordinate origin\n"
      "uniform int gmmVertexPitch;   // vertex id = j * pitch + i (gmm::drawPitch)\n"
      "uniform float gmmInvPitch;    // 1 / pitch\n"
      "uniform float gmmHeightRef;   // stored height at the model-coordinate origin\n"
      "out vec2 gmmGridVSOutput;\n" +
      (o.Color == Options::MapHeights ? "out float gmmHeightVSOutput;\n" : "") +
      (vertexNormals ? std::string(kValid) + kSlopeRule + kNormalOfSlope + kVertexNormal : std::string()) +
      (o.Morph ? kMorph : ""));
  // Sample (i, j) of vertex id j * pitch + i (gmm::drawPitch: a little over nx, so that
  // a software renderer shades shared vertices once) without an integer division
  // (scalarised, hence slow, on software rasterisers): a float estimate of j (relative error
  // 2^-24), refined once from its remainder (now small enough to be exact in float), then
  // corrected by one; exact for every id < 2^32 whatever the pitch (checked against integer
  // division in numpy for shapes from 2 x 2^31 to 2^31 x 3).
  std::string begin = "  uint gmmId = uint(gl_VertexID);\n"
                      "  int gmmJ = int(float(gmmId) * gmmInvPitch);\n"
                      "  int gmmI = int(gmmId - uint(gmmJ) * uint(gmmVertexPitch));\n"
                      "  gmmJ += int(floor(float(gmmI) * gmmInvPitch));\n"
                      "  gmmI = int(gmmId - uint(gmmJ) * uint(gmmVertexPitch));\n"
                      "  if (gmmI < 0) { gmmJ -= 1; gmmI += gmmVertexPitch; }\n"
                      "  else if (gmmI >= gmmVertexPitch) { gmmJ += 1; gmmI -= gmmVertexPitch; }\n"
                      "  ivec2 gmmIJ = ivec2(gmmI, gmmJ);\n"
                      "  float gmmH = gmmHeight(gmmIJ);\n" +
    std::string(vertexNormals ? "  normalMC = gmmVertexNormal(gmmIJ, gmmH);\n" : "") +
    std::string(o.Morph ? "  gmmH = gmmMorphHeight(gmmIJ, gmmH);\n" : "") +
    "  vertexMC = vec4(vec2(gmmIJ - gmmAnchor) * gmmSpacing,\n"
                      "    (gmmH - gmmHeightRef) * gmmHeightScale, 1.0);\n"
                      "  gmmGridVSOutput = vec2(gmmIJ);\n";
  if (o.Color == Options::MapHeights)
  {
    begin += "  gmmHeightVSOutput = gmmH;\n";
  }
  if (o.TextureCoordinates)
  {
    begin += "  tcoord = vec2(gmmIJ) / vec2(max(gmmGridSize - 1, ivec2(1)));\n";
  }
  vtkShaderProgram::Substitute(vs, "//VTK::CustomBegin::Impl", begin + "//VTK::CustomBegin::Impl");

  // Geometry shader (wide lines, edges): pass the grid position through with each vertex
  // (VTK's geometry templates emit input vertex i).
  if (!gs.empty())
  {
    std::string dec = "in vec2 gmmGridVSOutput[];\nout vec2 gmmGridGSOutput;\n";
    std::string pass = "gmmGridGSOutput = gmmGridVSOutput[i];\n";
    if (o.Color == Options::MapHeights)
    {
      dec += "in float gmmHeightVSOutput[];\nout float gmmHeightGSOutput;\n";
      pass += "gmmHeightGSOutput = gmmHeightVSOutput[i];\n";
    }
    vtkShaderProgram::Substitute(gs, "void main()", dec + "void main()", false);
    vtkShaderProgram::Substitute(gs, "EmitVertex();", pass + "    EmitVertex();");
  }

  // Fragment shader: full-resolution normal and colour at the fragment's grid position,
  // from one fetch of its quad's corners.
  // With vertex normals VTK's interpolated normal is kept: the fragment computes none.
  const bool lit = !vertexNormals &&
    fs.find("vec3 normalVCVSOutput = normalize(normalVCVSOutput);") != std::string::npos;
  const bool colored = o.Color != Options::PropertyColor;
  vtkShaderProgram::Substitute(fs, "//GMM::Dec",
    FetchFunctions(o) + kValid + kQuad +
      (!lit ? std::string()
            : kNormalOfSlope +
              (o.SlopesFromHeights ? std::string(kSlopeRule) + kSlopeFromHeights + kNormalOnTriangle
                : o.SingleLayer    ? std::string(kNormalBilinear)
                                   : std::string(kSlopeFromTexture) + kNormalOnTriangle)) +
      ColorFunctions(o) + (o.Drape ? kDrape : ""));
  // The level-0 triangle under the fragment, where full-resolution values are interpolated
  // per fragment (colouring arrays; normals of DEMs in several layers or without a slope
  // texture).
  const bool triangle =
    (colored && o.Color != Options::MapHeights) || (lit && (!o.SingleLayer || o.SlopesFromHeights));
  std::string color = triangle ? "  GmmTri gmmT = gmmTriangle(gmmGridVSOutput);\n"
                               : "  GmmTri gmmT;\n";
  if (colored)
  {
    color += "  vec4 gmmC = gmmColor(gmmT);\n"
             "  ambientColor = ambientIntensity * gmmC.rgb;\n"
             "  diffuseColor = diffuseIntensity * gmmC.rgb;\n"
             "  opacity = opacityUniform * gmmC.a;\n";
  }
  if (o.Drape)
  {
    // Premultiplied by alpha (vtkGeoMipMapDrapeTexture): over the colour below, then lit.
    color += "  vec4 gmmP = gmmDrapeColor();\n"
             "  ambientColor = ambientColor * (1.0 - gmmP.a) + ambientIntensity * gmmP.rgb;\n"
             "  diffuseColor = diffuseColor * (1.0 - gmmP.a) + diffuseIntensity * gmmP.rgb;\n";
  }
  vtkShaderProgram::Substitute(fs, "//GMM::Color::Impl", color);
  // Lit: VTK declared and normalised an interpolated normalVCVSOutput; replace its value.
  if (lit)
  {
    vtkShaderProgram::Substitute(fs, "//VTK::Normal::Impl",
      "  normalVCVSOutput = normalize(normalMatrix * gmmNormalMC(gmmT));\n"
      "  if (gl_FrontFacing == false) { normalVCVSOutput = -normalVCVSOutput; }\n"
      "//VTK::Normal::Impl");
  }
  shaders[vtkShader::Vertex]->SetSource(vs);
  shaders[vtkShader::Fragment]->SetSource(fs);
  shaders[vtkShader::Geometry]->SetSource(gs);
}

} // namespace vtkGeoMipMapShaders
