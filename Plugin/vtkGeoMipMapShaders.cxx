// VTK-HeaderTest-Exclude: vtkGeoMipMapShaders.cxx
#include "vtkGeoMipMapShaders.h"

#include "vtkShaderProgram.h"

namespace
{

const char* SamplerFor(vtkGeoMipMapShaders::Options::Heights h)
{
  switch (h)
  {
    case vtkGeoMipMapShaders::Options::Int16Heights:
      return "isampler2DArray";
    case vtkGeoMipMapShaders::Options::UInt16Heights:
      return "usampler2DArray";
    default:
      return "sampler2DArray";
  }
}

// Sample (i, j) of a tiled array texture (vtkGeoMipMapTextures.h): layer, then texel. One
// layer needs no arithmetic; several divide by the tile size through a float reciprocal
// (exact here: (i + 0.5) / w never rounds across an integer for i < 2^24), because integer
// division is scalarised, hence slow, on software rasterisers.
std::string FetchFunctions(const vtkGeoMipMapShaders::Options& o)
{
  std::string s = std::string("uniform highp ") + SamplerFor(o.HeightFormat) +
    " gmmHeights;\n"
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
  s += "float gmmHeight(ivec2 ij) { return float(texelFetch(gmmHeights, gmmTexel(ij), 0).r); }\n";
  return s;
}

// The fragment's level-0 triangle (Tessellate.h's quad split along its (0,0)-(1,1)
// diagonal): its vertices c, c + d, c + (1, 1) and their barycentric weights.
const char* const kQuad =
  "in vec2 gmmGridVSOutput;\n"
  "bool gmmValid(float h) { return abs(h) <= 1.0e38; } // false for NaN, +-Inf, sentinels\n"
  "struct GmmTri { ivec2 c; ivec2 d; vec3 w; };\n"
  "GmmTri gmmTriangle(vec2 g)\n"
  "{\n"
  "  GmmTri t;\n"
  "  vec2 gc = clamp(g, vec2(0.0), vec2(gmmGridSize - 1));\n"
  "  t.c = min(ivec2(floor(gc)), gmmGridSize - 2);\n"
  "  vec2 f = gc - vec2(t.c);\n"
  "  bool lower = f.x >= f.y;\n"
  "  t.d = lower ? ivec2(1, 0) : ivec2(0, 1);\n"
  "  t.w = lower ? vec3(1.0 - f.x, f.x - f.y, f.y) : vec3(1.0 - f.y, f.y - f.x, f.x);\n"
  "  return t;\n"
  "}\n";

// Normals from the slope texture (central differences as vtkGeoMipMapConversion::
// SampleNormal computes them, made once at upload): the slopes of the triangle's three
// samples are interpolated with its weights, then scaled and normalised once. (The
// full-resolution mesh interpolates unit normals instead; the two differ by a fraction of
// a degree where the slopes vary fast within one quad.)
const char* const kNormal =
  "uniform highp sampler2DArray gmmSlopes;\n"
  "vec2 gmmSlope(ivec2 ij) { return texelFetch(gmmSlopes, gmmTexel(ij), 0).rg; }\n"
  "vec3 gmmNormalMC(GmmTri t)\n"
  "{\n"
  "  vec2 g = t.w.x * gmmSlope(t.c) + t.w.y * gmmSlope(t.c + t.d) + t.w.z * gmmSlope(t.c + ivec2(1));\n"
  "  return normalize(vec3(-gmmHeightScale * g, 1.0));\n"
  "}\n";
// One layer: the slopes bilinearly filtered at the fragment (one fetch; the exact
// triangle interpolation above takes three, and differs from it by a fraction of a degree).
const char* const kNormalBilinear =
  "uniform highp sampler2DArray gmmSlopes;\n"
  "vec3 gmmNormalMC(GmmTri t)\n"
  "{\n"
  "  vec2 g = texture(gmmSlopes, vec3((gmmGridVSOutput + 0.5) * gmmTileScale, 0.0)).rg;\n"
  "  return normalize(vec3(-gmmHeightScale * g, 1.0));\n"
  "}\n";

// A draped image at the fragment: texture coordinates are affine in the grid position,
// which is affine in model x, y (vtkGeoMipMapDrapeTexture::GetMap); outside the image the
// transparent border leaves the colour below.
const char* const kDrape =
  "uniform sampler2D gmmDrape;\n"
  "uniform vec4 gmmDrapeMap; // st = grid position * xy + zw\n"
  "vec4 gmmDrapeColor() { return texture(gmmDrape, gmmGridVSOutput * gmmDrapeMap.xy + gmmDrapeMap.zw); }\n";

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
        "  return gmmMapScalar(t.w.x * gmmScalar(t.c) + t.w.y * gmmScalar(t.c + t.d) +\n"
        "    t.w.z * gmmScalar(t.c + ivec2(1)));\n"
        "}\n";
    case O::DirectColors:
      return "uniform highp sampler2DArray gmmColors;\n"
             "vec4 gmmRGBA(ivec2 ij) { return texelFetch(gmmColors, gmmTexel(ij), 0); }\n"
             "vec4 gmmColor(GmmTri t)\n"
             "{\n"
             "  return t.w.x * gmmRGBA(t.c) + t.w.y * gmmRGBA(t.c + t.d) + t.w.z * gmmRGBA(t.c + ivec2(1));\n"
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
    (this->LogScale ? "l" : "-") + (this->Drape ? "d" : "-");
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
  vtkShaderProgram::Substitute(vs, "in vec3 normalMC;", "vec3 normalMC = vec3(0.0, 0.0, 1.0);");
  vtkShaderProgram::Substitute(vs, "in vec2 tcoord;", "vec2 tcoord;");
  vtkShaderProgram::Substitute(vs, "//GMM::Dec",
    FetchFunctions(o) +
      "uniform ivec2 gmmAnchor;      // sample at the model-coordinate origin\n"
      "uniform float gmmInvGridX;    // 1 / nx\n"
      "uniform float gmmHeightRef;   // stored height at the model-coordinate origin\n"
      "out vec2 gmmGridVSOutput;\n" +
      (o.Color == Options::MapHeights ? "out float gmmHeightVSOutput;\n" : ""));
  // Sample (i, j) of vertex id j * nx + i without an integer division (scalarised, hence
  // slow, on software rasterisers): a float estimate of j (relative error 2^-24), refined
  // once from its remainder (now small enough to be exact in float), then corrected by one;
  // exact for every id < 2^32 whatever nx (checked against integer division in numpy for
  // shapes from 2 x 2^31 to 2^31 x 3).
  std::string begin = "  uint gmmId = uint(gl_VertexID);\n"
                      "  int gmmJ = int(float(gmmId) * gmmInvGridX);\n"
                      "  int gmmI = int(gmmId - uint(gmmJ) * uint(gmmGridSize.x));\n"
                      "  gmmJ += int(floor(float(gmmI) * gmmInvGridX));\n"
                      "  gmmI = int(gmmId - uint(gmmJ) * uint(gmmGridSize.x));\n"
                      "  if (gmmI < 0) { gmmJ -= 1; gmmI += gmmGridSize.x; }\n"
                      "  else if (gmmI >= gmmGridSize.x) { gmmJ += 1; gmmI -= gmmGridSize.x; }\n"
                      "  ivec2 gmmIJ = ivec2(gmmI, gmmJ);\n"
                      "  float gmmH = gmmHeight(gmmIJ);\n"
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
  const bool lit = fs.find("vec3 normalVCVSOutput = normalize(normalVCVSOutput);") != std::string::npos;
  const bool colored = o.Color != Options::PropertyColor;
  vtkShaderProgram::Substitute(fs, "//GMM::Dec",
    FetchFunctions(o) + kQuad + (lit ? (o.SingleLayer ? kNormalBilinear : kNormal) : "") +
      ColorFunctions(o) + (o.Drape ? kDrape : ""));
  // The level-0 triangle under the fragment, where full-resolution values are interpolated
  // per fragment (colouring arrays; normals of DEMs in several layers).
  const bool triangle = (colored && o.Color != Options::MapHeights) || (lit && !o.SingleLayer);
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
