"""Lapis from Python: differential shape modeling on NumPy arrays.

Meshes are libigl-style arrays: V (#V, 3) float64 positions and F (#F, 3) int32 or int64 vertex
indices. Sparse matrices are scipy.sparse. Errors are lapis.Error subclasses that also derive
from the matching built-in (InvalidArgument is a ValueError, IoError an OSError).

    import lapis
    V, F = lapis.read_mesh("bunny.off")
    d = lapis.Deformer(V, F, method="implicit")
    d.set_selection(roi, regions=[handle])
    d.precompute()
    W = d.deform([T])            # T: a 4x4 transform of the handle
    lapis.write_mesh("out.obj", W, F)

See docs/python.md for the whole API.
"""

from ._lapis import *  # noqa: F401,F403  (the compiled core: every public name)
from ._lapis import Error, InvalidArgument, IoError, NotPositiveDefinite, ResourceLimit, SolverFailure, UsageError
from ._deform import DeformationTransfer, Deformer, method_settings

__all__ = [name for name in dir() if not name.startswith("_")]
