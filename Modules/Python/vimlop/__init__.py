"""VIMLOP's VTK classes in Python: V-IMLOP video-CT registration for VTK pipelines.

    import vimlop
    registration = vimlop.vtkVIMLOPRegistration()

vtkVIMLOPRegistration (the registration filter with a live GetTransform())
and vtkVIMLOPCTReader (CT volumes through ITK and InVesalius projects) work
with the classes of VTK's own Python package, `vtkmodules`. The layouts of
the filter's inputs and outputs are in Documentation/Embedding.md.
"""

# VTK's modules that hold the base classes and argument types come first, so
# that the wrapped classes find them.
from vtkmodules import vtkCommonCore, vtkCommonDataModel  # noqa: F401
from vtkmodules import vtkCommonExecutionModel, vtkCommonTransforms  # noqa: F401

from .VIMLOPImaging import vtkVIMLOPCTReader  # noqa: F401
from .VIMLOPRegistration import vtkVIMLOPRegistration  # noqa: F401

__all__ = ["vtkVIMLOPCTReader", "vtkVIMLOPRegistration"]
