"""`import vimlop` in a plain Python with VTK's package, and a bad input.

Checks that the wrapped classes are there, are VTK algorithms that connect
to VTK's own classes, and that a registration without its inputs fails with
the filter's one-line message (caught from VTK's ErrorEvent). Exits non-zero
on any failure.
"""

import sys

from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
from vtkmodules.vtkCommonExecutionModel import vtkAlgorithm
from vtkmodules.vtkCommonTransforms import vtkLinearTransform
from vtkmodules.util.misc import calldata_type

import vimlop

failures = []


def check(ok, what):
    print(("ok: " if ok else "FAILED: ") + what)
    if not ok:
        failures.append(what)


registration = vimlop.vtkVIMLOPRegistration()
reader = vimlop.vtkVIMLOPCTReader()
check(isinstance(registration, vtkAlgorithm), "vtkVIMLOPRegistration is a vtkAlgorithm")
check(isinstance(reader, vtkAlgorithm), "vtkVIMLOPCTReader is a vtkAlgorithm")
check(isinstance(registration.GetTransform(), vtkLinearTransform),
      "GetTransform() is a vtkLinearTransform")
check(registration.GetNumberOfInputPorts() == 4 and registration.GetNumberOfOutputPorts() == 3,
      "four input ports, three output ports")
registration.SetMinScale(0.8)
registration.SetMaxScale(1.25)
check((registration.GetMinScale(), registration.GetMaxScale()) == (0.8, 1.25), "scale bounds set and read")
backends = vimlop.vtkVIMLOPRegistration.VisibilityBackend
registration.SetVisibilityBackend(backends.ZBuffer)
check(registration.GetVisibilityBackend() == backends.ZBuffer, "the visibility backend enum is wrapped")
registration.SetVisibilityBackend(backends.Embree)
registration.SetMethodToIMLP()
check("Method: imlp" in str(registration), "SetMethodToIMLP() selects IMLP")
registration.SetMethodToVIMLOP()

errors = []


@calldata_type(VTK_STRING)
def on_error(caller, event, message):
    errors.append(message)


registration.AddObserver(vtkCommand.ErrorEvent, on_error)
# The executive adds its own report of the failed request: not checked here.
registration.GetExecutive().AddObserver(vtkCommand.ErrorEvent, lambda caller, event: None)
registration.Update()
print("error reported: %r" % (errors[0].strip() if errors else None))
check(len(errors) == 1 and "no model surface on input port 0" in errors[0],
      "a registration without inputs reports the missing model surface")

sys.exit(1 if failures else 0)
