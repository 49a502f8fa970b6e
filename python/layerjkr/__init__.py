"""layerjkr: adhesive (JKR) contact of thin elastic layers, from Python.

The same library as the ``layerjkr`` command line, with numpy in and out::

    import numpy as np, layerjkr
    s = layerjkr.scene("data/scenes/hydrogel_film_two_term.json")  # or a dict, same schema
    c = layerjkr.curve(s, np.linspace(1e-7, 2e-6, 200))           # Curve: c.P, c.delta, ...
    layerjkr.summary(s).pull_off_force                             # or ["pull_off_force"]
    r = layerjkr.fit(delta, P, s, free=["E", "w", "delta0"], branch="retract")
    r.values["E"], r.errors["E"], r.correlation["E", "w"]
    print(r.report())

Every option is a keyword with its default in the signature; a misspelt keyword is a
``TypeError``, a misspelt choice an :class:`InputError` naming the parameter. Long calls
release the GIL, so threads run fits in parallel. Errors raise :class:`Error` and its
subclasses with the C++ library's messages; an answer the library warns about also emits a
:class:`ModelWarning` through :mod:`warnings`.
"""
from __future__ import annotations

from . import _core
from ._core import DomainError, Error, InputError, NumericalError, Scene
from ._common import ModelWarning
from ._scene import AdhesionCheck, AutoChoice, FixedGrips, ModelError, scene
from ._curve import Curve, curve
from ._summary import Summary, summary
from ._fit_result import FitResult, NamedArray
from ._simulate import Simulation, simulate
from ._fit import JointFitResult, fit, fit_joint
from ._batch import BatchResult, fit_batch, fit_files
from ._batch_tables import BatchResults
from ._instrument import Instrument, open_instrument, read_instrument

__version__: str = _core.__version__

__all__ = ["__version__", "Error", "DomainError", "InputError", "NumericalError", "ModelWarning", "Scene",
           "simulate", "Simulation", "fit_joint", "JointFitResult",
           "AutoChoice", "AdhesionCheck", "FixedGrips", "ModelError", "Curve", "Summary", "NamedArray", "FitResult", "BatchResult", "BatchResults",
           "Instrument", "scene", "curve", "summary", "fit", "fit_batch", "fit_files", "read_instrument",
           "open_instrument"]

# The public names live in private modules; they present themselves as layerjkr's, as numpy's do,
# so reprs, help() and pickles name layerjkr.FitResult whichever module defines it.
for _name in __all__:
    _value = globals()[_name]
    if getattr(_value, "__module__", "").startswith("layerjkr._") and _value.__module__ != "layerjkr._core":
        _value.__module__ = __name__
del _name, _value
