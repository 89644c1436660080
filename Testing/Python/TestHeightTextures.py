"""GPU-resident heights (issue #10): tiling, 16-bit heights, colouring arrays, memory limits.

Each case is checked against a stock full-resolution vtkPolyDataMapper of the same samples
(refscene.reference_mesh: every valid quad, split as the engine splits it, normals from
vtkPolyDataNormals), rendered with the same camera at tau = 0.5:
- tiling: a DEM split into many texture layers (MaximumTileSize 64, 5 x 3 layers) draws
  the same surface as one layer, bit for bit (depth buffers), and the same picture as the
  stock render (seam lines seen from above too); and a DEM wider than
  GL_MAX_TEXTURE_SIZE (16385 x 33 samples here) renders, seam column checked against the
  stock render;
- int16 and uint16 heights draw the same picture as the same heights in float, from 2
  bytes a sample less;
- colouring by a second point array (a numpy "slope" field through a lookup table) and by
  unsigned char RGB colours matches the stock mapper colouring by the same array
  (InterpolateScalarsBeforeMapping on);
- a MemoryLimit below the DEM's needs refuses it with an error naming both sizes and draws
  nothing; lifting the limit draws it;
- heights read in place (ShareHeights, where the renderer runs on the CPU: llvmpipe here)
  draw the texture path's surface bit for bit (depth buffers and pixels) for float, int16
  and uint16 heights, in one band of one sample a texel, and in bands of four samples a
  texel (MaximumTileSize 64: 3 bands of 4096 texels; 128: one band; the last sample in
  no texel), from 4 (float) or 2 (16-bit) bytes a sample less; elsewhere the texture is
  used.
- lit with the slopes computed per fragment from the heights (SlopeTexture off, the
  default): the slope texture's picture within its rounding, with a nodata hole too, 4
  bytes a sample less.
- automatic normals (the default): the picture of normals per vertex at tau 0.5 where OpenGL
  runs on the CPU, of normals per fragment at tau 8 (and everywhere on a GPU);
- lit with normals per vertex (VertexNormals): at tau = 0 (every triangle a level-0 half
  quad) the stock mapper's picture of the full-resolution mesh carrying the same
  central-difference point normals (computed in numpy), with a nodata hole too, heights
  read in place or from the texture; no slope texture even where SlopeTexture asks for one.
The texture-path cases run with ShareHeights off, as on a GPU with its own memory.
"""

import numpy as np
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import numpy_to_vtk
from vtkmodules.util.vtkConstants import VTK_STRING
from vtkmodules.vtkCommonCore import vtkCommand, vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkCamera, vtkPolyDataMapper, vtkRenderer

import geomipmap
import gmmtestutil
import refscene
from geomipmap_apps.bench.meshes import _grid_normals

W, H = 480, 320
BG = (0.1, 0.1, 0.2)
check = refscene.Checks()


base = refscene.fractal_image(301, 157, seed=21)
zf = refscene.heights(base)

ren = vtkRenderer()
ren.SetBackground(*BG)
win = refscene.window(W, H, ren)


def frame(actor, elevation=-50.0, parallel=False, focus=None, scale=None):
    ren.RemoveAllViewProps()
    ren.AddActor(actor)
    ren.SetActiveCamera(vtkCamera())
    ren.ResetCamera()
    cam = ren.GetActiveCamera()
    if focus is not None:
        cam.SetFocalPoint(*focus)
        cam.SetPosition(focus[0], focus[1], focus[2] + 1.0e5)
        cam.SetViewUp(0, 1, 0)
        cam.SetParallelProjection(True)
        cam.SetParallelScale(scale)
    else:
        cam.Elevation(elevation)
    ren.ResetCameraClippingRange()
    win.Render()
    return refscene.grab(win)


def ours(img, **kw):
    m = geomipmap.vtkGeoMipMapMapper()
    m.SetInputData(img)
    m.SetPixelError(0.5)
    m.ScalarVisibilityOff()
    m.SetShareHeights(kw.pop("ShareHeights", False))
    # The checks below are of the per-fragment normals unless told otherwise (the default,
    # automatic normals, would shade this tau 0.5 per vertex).
    m.SetNormalModeToPerFragment()
    for k, v in kw.items():
        getattr(m, "Set" + k)(v)
    a = vtkActor()
    a.SetMapper(m)
    return m, a


def differing(a, b, tol=24):
    return float((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > tol).mean())


ref = refscene.reference_actor(base)
stock = frame(ref)

# Tiling: 5 x 3 layers of 64 x 64 texels against one layer, the slopes tiled too.
m1, a1 = ours(base, SlopeTexture=True)
one = frame(a1)
one_depth = refscene.depth(win)
m2, a2 = ours(base, MaximumTileSize=64, SlopeTexture=True)
tiled = frame(a2)
check(np.array_equal(one_depth, refscene.depth(win)),
      "5 x 3 texture layers draw the one-layer surface bit for bit (depth buffers)")
d = differing(one, tiled, 8)
check(d < 0.002, f"5 x 3 texture layers vs one: {100 * d:.3f} % of pixels differ by > 8 (one "
      "layer filters the slopes bilinearly, several interpolate them on the triangle)")
d = differing(stock, tiled)
check(d < 0.01, f"tiled vs stock full-resolution render: {100 * d:.3f} % of pixels differ by > 24")
# Seam lines (every 64th sample) from straight above: pixels near them as in the stock render.
top_stock = frame(ref, focus=(150 * 30.0, 78 * 30.0, 0.0), scale=40 * 30.0)
top_tiled = frame(a2, focus=(150 * 30.0, 78 * 30.0, 0.0), scale=40 * 30.0)
d = differing(top_stock, top_tiled)
check(refscene.covered(top_stock, BG).mean() > 0.9 and d < 0.01,
      f"top view across the seams at samples 128 and 192: {100 * d:.3f} % of pixels "
      "differ from the stock render")

# Wider than GL_MAX_TEXTURE_SIZE (16384 on llvmpipe; queried, not assumed, by the mapper).
wimg = refscene.fractal_image(16385, 33, seed=4)
mw, aw = ours(wimg)
seam = 8193 * 30.0  # 16385 = 2 layers of 8193 columns: the seam is after column 8192
wref = refscene.reference_actor(wimg)
focus = (seam, 16 * 30.0, 0.0)
wt = frame(aw, focus=focus, scale=12 * 30.0)
wgpu, wtris = mw.GetGPUMemoryBytes(), mw.GetNumberOfRenderedTriangles()
ws = frame(wref, focus=focus, scale=12 * 30.0)
d = differing(ws, wt)
check(wtris > 0 and wgpu >= 16385 * 33 * 4 and refscene.covered(ws, BG).mean() > 0.9 and d < 0.01,
      f"16385 x 33 DEM, 2 texture layers: {wtris} triangles, {wgpu} GPU bytes, "
      f"{100 * d:.3f} % of pixels around the seam differ from the stock render")

# 16-bit heights: the same picture from half the texture.
zi = np.round(zf).astype(np.int16)
zu = np.round(zf).astype(np.uint16)
pictures, gpu = {}, {}
for name, z in (("float32", np.round(zf).astype(np.float32)), ("int16", zi), ("uint16", zu)):
    m, a = ours(refscene.image_from_heights(z))
    pictures[name] = frame(a)
    gpu[name] = m.GetGPUMemoryBytes() - 4 * m.GetNumberOfRenderedTriangles() * 3
for name in ("int16", "uint16"):
    check(np.array_equal(pictures[name], pictures["float32"]),
          f"{name} heights draw the float32 picture bit for bit")
    check(gpu["float32"] - gpu[name] == 2 * zf.size,
          f"{name} heights: {gpu[name]} texture bytes, float32 {gpu['float32']}: 2 bytes a "
          "sample less")

def layer_texels(tile):
    """Texels of a texture holding zf in layers of equal tiles (vtkGeoMipMapTileLayout::Plan)."""
    ny, nx = zf.shape
    tx, ty = (-(-nx // tile), -(-ny // tile)) if tile else (1, 1)
    return tx * ty * -(-nx // tx) * -(-ny // ty)


# Heights read in place: the texture path's surface, from fewer bytes, where the renderer
# runs on the CPU.
on_cpu = "llvmpipe" in win.ReportCapabilities() or "softpipe" in win.ReportCapabilities()
for name, z in (("float32", np.round(zf).astype(np.float32)), ("int16", zi), ("uint16", zu)):
    img = refscene.image_from_heights(z)
    for tile in (0, 64, 128):
        mt, at = ours(img, MaximumTileSize=tile)
        texture = frame(at)
        texture_depth, texture_bytes = refscene.depth(win), mt.GetGPUMemoryBytes()
        ms, as_ = ours(img, MaximumTileSize=tile, ShareHeights=True)
        shared = frame(as_)
        same = np.array_equal(texture, shared) and np.array_equal(texture_depth, refscene.depth(win))
        saved = texture_bytes - ms.GetGPUMemoryBytes()  # the same triangles: the same index bytes
        per_sample = 4 if name == "float32" else 2
        # A band holds MaximumTileSize^2 texels here: one sample a texel while one band
        # holds the DEM, else four (the last sample, 47257 % 4, fills no texel).
        bands = ("one band, one sample a texel" if tile == 0 else
                 f"{-(-zf.size // (4 * tile * tile))} band(s) of four samples a texel")
        texels = layer_texels(tile)
        if on_cpu:
            check(ms.GetHeightsShared() and same and saved == per_sample * texels,
                  f"{name} heights read in place, {bands}: the texture path's picture and depth "
                  f"bit for bit: {same}; {saved} bytes less (the texture's {texels} texels of "
                  f"{per_sample} bytes)")
        else:
            check(not ms.GetHeightsShared() and same,
                  f"{name} heights on a GPU with its own memory: a texture, as without ShareHeights")

# Heights that cannot be read in place (more bands than the shader takes: a band holds
# MaximumTileSize^2 texels, here 16^2, so the DEM needs 47 bands of 16 at most) are copied
# into a texture instead, with one warning that says why, not one a frame.
if on_cpu:
    img = refscene.image_from_heights(np.round(zf).astype(np.float32))
    mt, at = ours(img, MaximumTileSize=16)
    texture = frame(at)
    texture_depth = refscene.depth(win)
    ms, as_ = ours(img, MaximumTileSize=16, ShareHeights=True)
    warnings = []
    as_.GetMapper().AddObserver(vtkCommand.WarningEvent,
                                calldata_type(VTK_STRING)(lambda o, e, t=None: warnings.append(t)))
    shared = frame(as_)
    same = np.array_equal(texture, shared) and np.array_equal(texture_depth, refscene.depth(win))
    ren.GetActiveCamera().Azimuth(10.0)  # a second frame of the same actor (frame() would
    win.Render()                         # remove it, which releases its GPU resources)
    text = " ".join(t for t in warnings if t)
    check(not ms.GetHeightsShared() and same and len(warnings) == 1 and "ShareHeights" in text and
          "buffer textures" in text,
          f"heights in 47 bands: in a texture instead, the same picture ({same}), one warning over "
          f"two frames ({len(warnings)}: {text[:140]!r})")

# Slopes computed per fragment from the heights (SlopeTexture off, the default): the slope
# texture's picture but for its half-float rounding (and, on one layer, its bilinear
# filtering), with a nodata hole too (one-sided differences beside it), the heights read in
# place or from the texture.
hole = np.round(zf).astype(np.float32)
hole[60:80, 100:140] = np.nan
for name, z in (("no nodata", np.round(zf).astype(np.float32)), ("a nodata hole", hole)):
    img = refscene.image_from_heights(z)
    for tile, share in ((0, False), (64, False), (64, True)):
        mt, at = ours(img, MaximumTileSize=tile, ShareHeights=share, SlopeTexture=True)
        texture = frame(at)
        texture_bytes = mt.GetGPUMemoryBytes()
        mf, af = ours(img, MaximumTileSize=tile, ShareHeights=share)  # SlopeTexture off by default
        per_fragment = frame(af)
        drawn = refscene.covered(per_fragment, BG)
        d = differing(texture, per_fragment, 8) / drawn.mean()  # of the terrain's pixels
        saved = texture_bytes - mf.GetGPUMemoryBytes()
        layers = "one layer" if tile == 0 else "5 x 3 layers"
        where = "read in place" if mf.GetHeightsShared() else "from the texture"
        # Layers: both interpolate the same three slopes on the triangle (only the half-float
        # rounding differs); one layer: the texture's slopes are filtered bilinearly.
        check(drawn.mean() > 0.1 and d < (0.01 if tile == 0 else 0.001) and saved == 4 * layer_texels(tile),
              f"slopes per fragment, {name}, {layers}, heights {where}: {100 * d:.3f} % of the "
              f"terrain's pixels differ by > 8 from the slope texture's; {saved} bytes less")

# Normals per vertex (VertexNormals): each drawn vertex takes its sample's full-resolution
# normal and the triangle interpolates it. At tau 0 every drawn triangle is a level-0 half
# quad, so the picture is the stock mapper's of the full-resolution mesh (the union jack:
# refscene.reference_mesh) whose point normals follow the same rule, computed here with numpy
# (geomipmap-bench's reference normals). SlopeTexture is overridden.
# With HeightScale 3 the reference is the mesh of the heights times 3.
for name, z, scale in (("no nodata", np.round(zf).astype(np.float32), 1.0), ("a nodata hole", hole, 1.0),
                       ("HeightScale 3", np.round(zf).astype(np.float32), 3.0)):
    img = refscene.image_from_heights(z)
    scaled = refscene.image_from_heights(z * np.float32(scale))
    mesh = refscene.reference_mesh(scaled, normals=False)
    normals = numpy_to_vtk(_grid_normals(refscene.heights(scaled), *refscene.sample_xy(scaled)).reshape(-1, 3),
                           deep=True)
    normals.SetName("Normals")
    mesh.GetPointData().SetNormals(normals)
    stock_vertex = frame(refscene.stock_actor(mesh))
    drawn = refscene.covered(stock_vertex, BG)
    # One texture layer or band, and 5 x 3 layers or 3 bands of four samples a texel.
    for tile, share in ((0, False), (0, True), (64, False), (64, True)):
        mv, av = ours(img, ShareHeights=share, VertexNormals=True, SlopeTexture=True, PixelError=0.0,
                      HeightScale=scale, MaximumTileSize=tile)
        vertex = frame(av)
        vertex_bytes, where = mv.GetGPUMemoryBytes(), "read in place" if mv.GetHeightsShared() else "from the texture"
        mp, ap = ours(img, ShareHeights=share, PixelError=0.0, MaximumTileSize=tile)  # per fragment
        frame(ap)
        d = differing(stock_vertex, vertex, 2) / drawn.mean()
        where += f", MaximumTileSize {tile}"
        check(drawn.mean() > 0.1 and d < 0.005 and vertex_bytes == mp.GetGPUMemoryBytes(),
              f"normals per vertex, {name}, heights {where}, tau 0: {100 * d:.3f} % of the terrain's "
              f"pixels differ by > 2 from the stock mapper's with the same point normals; "
              f"{vertex_bytes} GPU bytes (per fragment: {mp.GetGPUMemoryBytes()})")

# Automatic normals (NormalMode's default): where OpenGL runs on the CPU, per vertex while the
# frame is certified within 1 px (the documented threshold, written here, not read from the
# mapper) and per fragment above; on a GPU per fragment. Each automatic frame must be the
# very picture of the mode it stands for, and the two modes must differ. Which side of 1 px
# the frame's certificate is on comes from outside the engine: at tau 0.5 it is at most tau;
# at tau 8 it is at least the error vtkGeoMipMapScreenError measures on the drawn triangles
# (vtkGeoMipMapFilter's, the mapper's), which must then exceed 1 px.
software = refscene.renders_on_cpu(win)
img = refscene.image_from_heights(np.round(zf).astype(np.float32))
for tau in (0.5, 8.0):
    pictures = {}
    for mode in ("Automatic", "PerVertex", "PerFragment"):
        m, a = ours(img, PixelError=tau)
        getattr(m, "SetNormalModeTo" + mode)()
        pictures[mode] = frame(a)
        chose_vertex = m.GetLastFrameVertexNormals() if mode == "Automatic" else chose_vertex
    measured = gmmtestutil.measure_drawn(img, ren, a, tau, m.GetBlockSize()).error_px
    if tau > 1.0:
        check(measured > 1.0, f"tau {tau:g}: measured {measured:.3f} px, above 1 px: the certificate is too")
    expect = "PerVertex" if software and tau <= 1.0 else "PerFragment"
    other = "PerFragment" if expect == "PerVertex" else "PerVertex"
    apart = differing(pictures[expect], pictures[other], 0)
    check(chose_vertex == (expect == "PerVertex") and np.array_equal(pictures["Automatic"], pictures[expect])
          and apart > 0.01,
          f"automatic normals at tau {tau:g} (measured {measured:.3f} px, renderer on the CPU: {software}): "
          f"the picture of {expect}, {100 * apart:.1f} % of pixels apart from {other}'s")

# Colouring by a second point array through a lookup table, and by RGB colours.
slope = np.hypot(*np.gradient(zf, 30.0)).astype(np.float32)
img = refscene.image_from_heights(zf.astype(np.float32))
s = numpy_to_vtk(slope.ravel(), deep=True)
s.SetName("Slope")
img.GetPointData().AddArray(s)
rgb = np.zeros(zf.shape + (3,), np.uint8)
rgb[..., 0] = (np.arange(zf.shape[1]) * 255 // zf.shape[1])[None, :]
rgb[..., 1] = (np.arange(zf.shape[0]) * 255 // zf.shape[0])[:, None]
rgb[..., 2] = 128
c = numpy_to_vtk(rgb.reshape(-1, 3), deep=True)
c.SetName("Cover")
img.GetPointData().AddArray(c)
lut = vtkLookupTable()
lut.SetHueRange(0.6, 0.0)
lut.Build()
refmesh = refscene.reference_mesh(img)
refmesh.GetPointData().AddArray(s)
refmesh.GetPointData().AddArray(c)
for array, mapped in (("Slope", True), ("Cover", False)):
    m, a = ours(img)
    rm = vtkPolyDataMapper()
    rm.SetInputData(refmesh)
    ra = vtkActor()
    ra.SetMapper(rm)
    for mapper in (m, rm):
        mapper.ScalarVisibilityOn()
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray(array)
        mapper.InterpolateScalarsBeforeMappingOn()
        if mapped:
            mapper.SetLookupTable(lut)
            mapper.SetScalarRange(0.0, float(np.percentile(slope, 95)))
            mapper.SetColorModeToMapScalars()
    d = differing(frame(ra), frame(a))
    check(d < 0.01, f"coloured by {array} ({'lookup table' if mapped else 'RGB'}): "
          f"{100 * d:.3f} % of pixels differ by > 24 from the stock mapper")

# Too big for the memory limit: refused before any allocation, with both sizes named.
m, a = ours(base)
m.SetMemoryLimit(100000)
errors = []


def on_error(obj, event, text=None):
    errors.append(text)



on_error = calldata_type(VTK_STRING)(on_error)
m.AddObserver(vtkCommand.ErrorEvent, on_error)
frame(a)
text = " ".join(t for t in errors if t)
check(m.GetNumberOfRenderedTriangles() == 0 and m.GetGPUMemoryBytes() == 0 and
      "301 x 157" in text and "MemoryLimit" in text,
      f"MemoryLimit 100000 B: refused, nothing drawn or held ({text[:160]!r})")
m.SetMemoryLimit(0)
errors.clear()
frame(a)
check(m.GetNumberOfRenderedTriangles() > 0 and not errors, "limit lifted: drawn")

check.exit()
