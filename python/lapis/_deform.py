"""lapis.Deformer: the C++ deformers (every method of the registry) with keyword options."""

import numpy as np

from . import _lapis


def _is_settings(obj):
    return hasattr(type(obj), "_fields")


def _assign(target, key, value, where):
    """Sets target.key = value, converting strings to the field's enum and dicts to nested structs."""
    current = getattr(target, key)
    if isinstance(value, dict) and _is_settings(current):
        for k, v in value.items():
            if k not in type(current)._fields:
                raise TypeError(f"{where}.{key} has no option '{k}'; options: {', '.join(type(current)._fields)}")
            _assign(current, k, v, f"{where}.{key}")
        value = current
    elif isinstance(value, str) and hasattr(type(current), "__members__"):
        members = type(current).__members__
        if value not in members:
            raise ValueError(f"{where}.{key} must be one of {', '.join(members)}, not '{value}'")
        value = members[value]
    setattr(target, key, value)


def method_settings(method="implicit", **options):
    """A lapis.MethodSettings for `method` (one of lapis.methods()) with `options` applied.

    An option is looked up first in the method's own options (settings.edge, .salient,
    .isolines: EdgeLaplacianOptions, SalientOptions, IsolinesOptions), then among the common
    settings (weights, scale_features, arap_iterations). Enum values may be given by name
    (weights="uniform"), nested options as dicts (fields={"point_handle_radius": 0.05}).
    """
    settings = _lapis.MethodSettings()
    members = _lapis.Method.__members__
    if method not in members:
        raise ValueError(f"method must be one of {', '.join(_lapis.methods())}, not '{method}'")
    settings.method = members[method]
    own = getattr(settings, method, None) if method in type(settings)._fields else None
    for key, value in options.items():
        if own is not None and key in type(own)._fields:
            _assign(own, key, value, method)
        elif key in type(settings)._fields and key not in ("method", "edge", "salient", "isolines"):
            _assign(settings, key, value, "settings")
        else:
            known = (list(type(own)._fields) if own is not None else []) + [
                f for f in type(settings)._fields if f not in ("method", "edge", "salient", "isolines")
            ]
            raise TypeError(f"unknown option '{key}' for method '{method}'; options: {', '.join(known)}")
    return settings


def _float_array(x, empty_shape):
    if x is None:
        return np.empty(empty_shape)
    if isinstance(x, np.ndarray):
        return x
    x = np.asarray(x, dtype=np.float64)
    return x.reshape(empty_shape) if x.size == 0 else x


def _index_array(x):
    if x is None:
        return np.empty(0, dtype=np.int32)
    return x if isinstance(x, np.ndarray) else np.asarray(x, dtype=np.int64).reshape(-1)


def _roi(roi, num_vertices, name):
    """Vertex indices, or "all" of them."""
    if isinstance(roi, str):
        if roi != "all":
            raise ValueError(f"{name} must be vertex indices or 'all', not '{roi}'")
        return np.arange(num_vertices, dtype=np.int32)
    return _index_array(roi)


class Deformer:
    """Handle-based deformation of a mesh with one of the C++ methods (lapis.methods()).

    Precompute once per selection, then deform per frame, as in C++:

        d = lapis.Deformer(V, F, method="implicit")      # or naive, arap, edge, salient, isolines
        d.set_selection(roi, regions=[handle_vertices], points=[v])
        d.precompute()                                   # assembly + factorization (GIL released)
        W = d.deform([T], [[0.0, 0.1, 0.0]])             # (#V, 3) float64, per frame

    V (#V, 3) float64 and F (#F, 3) int32/int64 are copied once. Options are keywords, looked
    up in the method's own options first (lapis.EdgeLaplacianOptions, lapis.IsolinesOptions,
    lapis.SalientOptions) and then in lapis.MethodSettings, e.g.
    Deformer(V, F, "edge", iterations=6, domain="vertices"); see method_settings().
    The settings in use are in .settings. Errors raise lapis.InvalidArgument (a ValueError)
    with the C++ message, e.g. for a handle vertex outside the ROI.
    """

    def __init__(self, V, F, method="implicit", **options):
        self.settings = method_settings(method, **options)
        self._num_vertices = int(np.shape(V)[0]) if np.ndim(V) > 0 else 0
        self._impl = _lapis._Deformer(V, F, self.settings)

    def set_selection(self, roi, regions=(), points=()):
        """roi: vertex indices that may move, or "all"; regions: a list of index arrays, each a
        handle moved by a 4x4 transform; points: vertex indices moved by a translation each.
        Marks the deformer dirty: the next deform() precomputes again."""
        self._impl.set_selection(_roi(roi, self._num_vertices, "roi"), [_index_array(r) for r in regions],
                                 _index_array(points))

    def precompute(self):
        """Validates the selection and runs the method's setup; raises InvalidArgument for a bad
        selection. The GIL is released meanwhile."""
        self._impl.precompute()

    def deform(self, regions=None, points=None):
        """Deformed positions (#V, 3) float64 for one frame. regions: (#region handles, 4, 4)
        transforms applied to the rest positions; points: (#point handles, 3) translations."""
        return self._impl.deform(_float_array(regions, (0, 4, 4)), _float_array(points, (0, 3)))

    @property
    def name(self):
        """The method's name."""
        return self._impl.name

    @property
    def dirty(self):
        """Whether the next deform() runs precompute() first."""
        return self._impl.dirty

    def report(self):
        """The method's report of its setup and last frame (sizes, iterations, timings) as a dict."""
        return self._impl.report()

    # The salient method (Zhao et al.): features and the solid subspace.

    def set_features(self, features):
        """salient: user features (§3.1), a list of vertex index arrays, combined with the detected
        ones as the option user_features says ("union" by default, or "replace"). Checked by the
        next precompute()."""
        self._impl.set_features([_index_array(f) for f in features])

    def set_subspace(self, V, T):
        """salient: a given solid subspace, tetrahedra T (#T, 4) over V (#TV, 3) enclosing the
        mesh (e.g. from a tetrahedral mesher), instead of the lattice. Checked by the next
        precompute()."""
        self._impl.set_subspace(V, T)

    @property
    def features(self):
        """salient, after precompute(): the features in use, a list of int32 vertex index arrays."""
        return self._impl.features

    @property
    def saliency(self):
        """salient, after precompute(): the per-vertex saliency (#V,) (empty without detection)."""
        return self._impl.saliency

    @property
    def subspace(self):
        """salient, after precompute(): the solid subspace as (V (#TV, 3), T (#T, 4))."""
        return self._impl.subspace

    # The isolines method (Au et al.): the harmonic handle fields.

    @property
    def fields(self):
        """isolines, after precompute(): the harmonic fields (#V, H), one column per handle, the
        fixed region first (§4.1)."""
        return self._impl.fields

    @property
    def rigidity(self):
        """isolines, after precompute(): psi = sqrt(sum |grad phi_i|^2) per vertex (#V,) (§4.1)."""
        return self._impl.rigidity

    def __repr__(self):
        return f"lapis.Deformer(method='{self.name}', vertices={self._num_vertices})"


def _handles(h, num_vertices, name):
    """(roi, regions, points) from a dict with keys roi ("all" or indices), regions, points."""
    if not isinstance(h, dict):
        raise TypeError(f"{name} must be a dict with keys roi, regions, points")
    unknown = set(h) - {"roi", "regions", "points"}
    if unknown:
        raise TypeError(f"{name} has unknown keys {sorted(unknown)}; keys: roi, regions, points")
    roi = _roi(h.get("roi", "all"), num_vertices, f"{name}['roi']")
    return (roi, [_index_array(r) for r in h.get("regions", ())], _index_array(h.get("points")))


class DeformationTransfer:
    """Deformation transfer by handle correspondence (Au et al. 2007, §6).

        x = lapis.DeformationTransfer(source_V, source_F, target_V, target_F,
                                      source_handles={"roi": roi_s, "regions": [h0_s, h1_s]},
                                      target_handles={"roi": roi_t, "regions": [h0_t, h1_t]})
        W_target = x.transfer(W_source)     # per pose of the source (GIL released)

    Handles pair by index: the ROI's complement is the fixed region (handle 0) on both meshes,
    then the region handles and the point handles in order. The source's deformation is fitted
    as one 3x3 transform per isoline (Eq. 11) and the target rebuilt from its own edges turned
    by them (Eq. 12), one vertex per component held. Mismatched handle counts raise
    lapis.InvalidArgument. isolines: n_iso on both meshes (TransferOptions: 20);
    point_handle_radius: the disc of a point handle's field, relative to each mesh's
    bounding-box diagonal (HandleFieldOptions: 0.02).
    """

    def __init__(self, source_V, source_F, target_V, target_F, source_handles, target_handles, isolines=None,
                 point_handle_radius=None):
        s = _handles(source_handles, int(np.shape(source_V)[0]), "source_handles")
        t = _handles(target_handles, int(np.shape(target_V)[0]), "target_handles")
        given = {"isolines": isolines, "point_handle_radius": point_handle_radius}  # None: the C++ default
        options = {k: v for k, v in given.items() if v is not None}
        self._impl = _lapis._DeformationTransfer(source_V, source_F, s, target_V, target_F, t, **options)

    def transfer(self, source_deformed):
        """The target deformed (#V_target, 3) as source_deformed (#V_source, 3) deforms the source."""
        return self._impl.transfer(source_deformed)

    def report(self):
        """Sizes, the Eq. 11 / Eq. 12 residuals of the last transfer, the held vertices, setup time."""
        return self._impl.report()
