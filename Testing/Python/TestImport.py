"""The package imports and exposes every class at package level and per module."""
import geomipmap
from geomipmap.geomipmapFilters import (vtkGeoMipMapTerrainReader, vtkGeoMipMapFractalSource,
                                        vtkGeoMipMapFilter)
from geomipmap.geomipmapRendering import vtkGeoMipMapMapper

for cls in (vtkGeoMipMapTerrainReader, vtkGeoMipMapFractalSource, vtkGeoMipMapFilter,
            vtkGeoMipMapMapper):
    assert getattr(geomipmap, cls.__name__) is cls, cls.__name__
    obj = cls()
    assert obj.GetClassName() == cls.__name__
    assert obj.__str__()  # PrintSelf runs
print("ok: geomipmap exposes", [c for c in dir(geomipmap) if c.startswith("vtk")])
