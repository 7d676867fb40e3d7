"""vericad: verification-first CAD geometry.

Every function calls the vericad library job the command line calls, with the same options
(keyword arguments named like the command-line flags) and the same output files when asked
for. Results are :class:`Result` objects: dicts with the keys of the command's JSON output,
readable as attributes too, with numpy arrays for points, parameters, knots, weights and
control nets. Bad input raises :class:`BadInputError`; a failed computation
:class:`ComputationError`; an output that cannot be written :class:`OutputError`; all three
derive from :class:`VericadError`. The work runs with the GIL released.
"""

from __future__ import annotations

import json
import os
from typing import Any, Dict, Iterable, List, Optional, Union

from . import _vericad
from ._vericad import (
    BadInputError,
    ComputationError,
    OutputError,
    VericadError,
    __version__,
)

PathLike = Union[str, "os.PathLike[str]"]

__all__ = [
    "BadInputError",
    "ComputationError",
    "OutputError",
    "VericadError",
    "Result",
    "Model",
    "SsiResult",
    "CertifyReport",
    "CurveOnSurfaceResult",
    "FacesCurvesResult",
    "RepairResult",
    "ReparamResult",
    "CoonsResult",
    "ApproximateResult",
    "read_model",
    "info",
    "ssi",
    "certify_ssi",
    "curve_on_surface",
    "curve_on_faces",
    "repair",
    "reparam",
    "coons",
    "approximate",
    "batch",
    "batch_record",
    "batch_record_line",
    "discover",
    "read_records",
    "set_skip_invalid",
    "__version__",
]


def _wrap(v: Any) -> Any:
    if isinstance(v, dict) and not isinstance(v, Result):
        return Result(v)
    if isinstance(v, list):
        return [_wrap(x) for x in v]
    return v


class Result(dict):  # type: ignore[type-arg]
    """A result: a dict (the keys of the command's JSON output) whose keys are attributes too.

    Nested objects are ``Result`` objects; point lists, knots, weights and control nets are
    numpy arrays. ``to_json()`` gives plain JSON (arrays as lists).
    """

    def __init__(self, data: Optional[Dict[str, Any]] = None) -> None:
        super().__init__({k: _wrap(v) for k, v in (data or {}).items()})

    def __getattr__(self, name: str) -> Any:
        try:
            return self[name]
        except KeyError:
            raise AttributeError(name) from None

    def __reduce__(self) -> Any:
        return (type(self), (dict(self),))

    def to_json(self, **kwargs: Any) -> str:
        """The result as JSON text (numpy arrays as lists)."""
        return json.dumps(self, default=_json_default, **kwargs)


def _json_default(o: Any) -> Any:
    tolist = getattr(o, "tolist", None)
    if tolist is not None:
        return tolist()
    raise TypeError(f"{type(o).__name__} is not JSON serializable")


class Model(Result):
    """A model file's contents.

    ``surfaces``: per face ``name``, ``source``, ``kind``, ``degree_u``, ``degree_v``,
    ``knots_u``, ``knots_v``, ``control_points`` (nu × nv × 3), ``weights`` (nu × nv),
    ``reversed``, ``trim_loops`` (count); ``curves``: ``name``, ``dimension`` (2: a domain
    curve, 3: a space curve), ``degree``, ``knots``, ``control_points`` (n × dimension),
    ``weights``; ``triangulations``: ``vertices`` (n × 3), ``triangles`` (m × 3 indices);
    ``unit``, ``brep_faces``, ``brep_edges`` (None without topology), ``warnings``.
    """


class SsiResult(Result):
    """The result of :func:`ssi`: ``summary`` (with ``certified``) and ``pairs``, each with
    its ``branches`` (``points`` n × 3, ``uv_a``/``uv_b`` n × 2, ``closed``, distances)."""

    @property
    def certified(self) -> bool:
        """Everything reported is proven (the command's exit code 0)."""
        return bool(self["summary"]["certified"])

    @property
    def branches(self) -> List[Result]:
        """The branches of every face pair, in pair order."""
        return [b for p in self["pairs"] for b in p["branches"]]


class CertifyReport(Result):
    """The verdict of :func:`certify_ssi`; ``certified`` is the command's exit code 0."""


class CurveOnSurfaceResult(Result):
    """The result of :func:`curve_on_surface`: ``segments`` (each with ``control_points``),
    ``bspline`` (``degree``, ``knots``, ``control_points``), ``certificate``, ``evidence``."""


class FacesCurvesResult(Result):
    """The result of :func:`curve_on_faces`: ``faces`` (each with ``loops``, each with
    ``edges``: ``pcurve``, ``pcurve_bound``, ``bound_to_edge`` and ``curves``, results as in
    :class:`CurveOnSurfaceResult`), ``certified`` and ``edges`` (edge uses)."""

    @property
    def all_certified(self) -> bool:
        """Every edge use carries a certified curve (the command's exit code 0)."""
        return self["certified"] == self["edges"]


class RepairResult(Result):
    """The result of :func:`repair`: ``report`` (as ``vericad repair --json``) and ``patches``
    (the repaired surfaces, with control nets as in :class:`Model`)."""


class ReparamResult(Result):
    """The report of :func:`reparam` (as ``vericad reparam --json``)."""


class CoonsResult(Result):
    """The result of :func:`coons`: ``report`` (as ``vericad coons --json``) and
    ``surface`` (the approximant)."""


class ApproximateResult(Result):
    """The result of :func:`approximate`: ``report`` and ``surfaces`` (layout order)."""


def _p(p: Optional[PathLike]) -> Optional[str]:
    return None if p is None else os.fspath(p)


def read_model(path: PathLike) -> Model:
    """Read a model file: native JSON, STEP, IGES, STL or Plot3D."""
    return Model(_vericad.read_model(os.fspath(path)))


def set_skip_invalid(on: bool) -> None:
    """From now on (in this process), read STEP and IGES files whose faces are partly invalid
    by skipping those faces, as the command line's ``--skip-invalid``: each is accounted
    ``invalid`` with its id and reason and named in the model's warnings. Off by default: such
    a file raises :class:`BadInputError` naming the entity."""
    _vericad.set_skip_invalid(bool(on))


def info(path: PathLike) -> Result:
    """The model's summary, as ``vericad info --json`` prints it."""
    return Result(_vericad.info(os.fspath(path)))


def ssi(
    file: PathLike,
    file2: Optional[PathLike] = None,
    *,
    tol: float = 1e-6,
    flatness: Optional[float] = None,
    time_limit: Optional[float] = None,
    untrimmed: bool = False,
    threads: Optional[int] = None,
    out: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
    iges: Optional[PathLike] = None,
    fits: bool = False,
    certify: bool = True,
    svg: Optional[PathLike] = None,
    view: str = "-60,25",
    pieces: str = "chords",
) -> SsiResult:
    """Intersect surfaces (``vericad ssi``): all face pairs of ``file``, or the faces of
    ``file`` against those of ``file2``. ``certify=False`` skips the curve radii and the
    coverage (``--no-certify``: faster, reported as not certified). ``svg`` writes a picture
    seen from ``view`` (``"AZIMUTH,ELEVATION"`` in degrees). ``pieces="cubic"``
    (``--pieces cubic``): branches as cubic Hermite pieces between far fewer certified points,
    each point's tangent jet in ``tangents``."""
    return SsiResult(
        _vericad.ssi(
            os.fspath(file),
            _p(file2),
            tol=tol,
            flatness=flatness,
            time_limit=time_limit,
            untrimmed=untrimmed,
            threads=threads,
            out=_p(out),
            vtk=_p(vtk),
            iges=_p(iges),
            fits=fits,
            certify=certify,
            svg=_p(svg),
            view=view,
            pieces=pieces,
        )
    )


def certify_ssi(
    a: PathLike,
    b: Optional[PathLike] = None,
    *,
    curves: PathLike,
    tol: float = 1e-6,
    match_distance: Optional[float] = None,
    out: Optional[PathLike] = None,
) -> CertifyReport:
    """Check another system's intersection curves (``vericad certify-ssi``)."""
    return CertifyReport(
        _vericad.certify_ssi(
            os.fspath(a),
            _p(b),
            curves=os.fspath(curves),
            tol=tol,
            match_distance=match_distance,
            out=_p(out),
        )
    )


def curve_on_surface(
    surface: PathLike,
    curve: PathLike,
    *,
    tol: float = 1e-3,
    angle: float = 10.0,
    bound: str = "local",
    exact: bool = False,
    evidence: int = 0,
    out: Optional[PathLike] = None,
    svg: Optional[PathLike] = None,
    iges: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
    svg_3d: Optional[PathLike] = None,
    view: str = "-60,25",
) -> CurveOnSurfaceResult:
    """A domain curve's image on a surface as Bézier curves lying on it, with a proven
    Hausdorff bound (``vericad curve-on-surface``). ``surface`` and ``curve`` are model files,
    optionally followed by ``:INDEX``. ``evidence=N`` also measures the distance between the
    segments and the true image at ``N`` samples per segment (evidence, not proof; 0, the
    default: not measured). ``svg_3d`` writes a 3D picture seen from ``view``
    (``"AZIMUTH,ELEVATION"`` in degrees)."""
    return CurveOnSurfaceResult(
        _vericad.curve_on_surface(
            os.fspath(surface),
            os.fspath(curve),
            tol=tol,
            angle=angle,
            bound=bound,
            exact=exact,
            evidence=evidence,
            out=_p(out),
            svg=_p(svg),
            iges=_p(iges),
            vtk=_p(vtk),
            svg_3d=_p(svg_3d),
            view=view,
        )
    )


def curve_on_faces(
    file: PathLike,
    faces: str = "all",
    *,
    tol: float = 1e-3,
    angle: float = 10.0,
    bound: str = "local",
    exact: bool = False,
    out: Optional[PathLike] = None,
    iges: Optional[PathLike] = None,
) -> FacesCurvesResult:
    """Certified curves on surfaces along every edge of every loop of B-rep faces of a STEP
    or IGES file (``vericad curve-on-surface --surface FILE --face FACES``): ``faces`` is
    ``"all"`` or a comma-separated list of indices and source ids (``"#12"``). Each edge's
    curve lies exactly on its face's surface, within ``tol`` of the image of the edge's
    pcurve; ``bound_to_edge`` adds the pcurve's proven distance to the edge."""
    return FacesCurvesResult(
        _vericad.curve_on_faces(
            os.fspath(file),
            faces,
            tol=tol,
            angle=angle,
            bound=bound,
            exact=exact,
            out=_p(out),
            iges=_p(iges),
        )
    )


def repair(
    input: PathLike,
    *,
    mode: str = "auto",
    u1: float = 1e-3,
    u2: float = 1e-3,
    feature_angle: float = 30.0,
    features: Optional[PathLike] = None,
    out: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
    svg: Optional[PathLike] = None,
    view: str = "-60,25",
) -> RepairResult:
    """Repair a patch set, or a B-rep's faces (``vericad repair``); ``svg`` writes a picture
    seen from ``view`` (``"AZIMUTH,ELEVATION"`` in degrees). ``mode``: ``"auto"`` (the faces
    repair when the model's B-rep has trimmed faces, as the command line), ``"patches"``
    (``--patches``) or ``"faces"`` (``--faces``); the faces repair returns no ``patches`` (its
    B-rep is written to ``out``)."""
    return RepairResult(
        _vericad.repair(
            os.fspath(input),
            mode=mode,
            u1=u1,
            u2=u2,
            feature_angle=feature_angle,
            features=_p(features),
            out=_p(out),
            report=_p(report),
            vtk=_p(vtk),
            svg=_p(svg),
            view=view,
        )
    )


def reparam(
    model: PathLike,
    *,
    tol: float = 1e-4,
    max_lines: int = 500,
    bound: bool = True,
    out: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    svg: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
) -> ReparamResult:
    """Reparametrize faces to chord length within ``tol`` (``vericad reparam``); ``model``
    optionally followed by ``:FACE``. ``bound=False`` skips the proven deviation bound
    (``--no-bound``): the measured E_max decides."""
    return ReparamResult(
        _vericad.reparam(
            os.fspath(model),
            tol=tol,
            max_lines=max_lines,
            bound=bound,
            out=_p(out),
            report=_p(report),
            svg=_p(svg),
            vtk=_p(vtk),
        )
    )


def coons(
    model: PathLike,
    *,
    boundary: PathLike,
    tol: float = 1e-3,
    m: int = 8,
    n: int = 8,
    max_resolution: int = 128,
    closure: Optional[float] = None,
    k: int = 8,
    out: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
) -> CoonsResult:
    """One bicubic C1 approximant over four boundary curves (``vericad coons``)."""
    return CoonsResult(
        _vericad.coons(
            os.fspath(model),
            boundary=os.fspath(boundary),
            tol=tol,
            m=m,
            n=n,
            max_resolution=max_resolution,
            closure=closure,
            k=k,
            out=_p(out),
            report=_p(report),
            vtk=_p(vtk),
        )
    )


def approximate(
    model: PathLike,
    *,
    layout: PathLike,
    tol: float = 1e-3,
    m: int = 8,
    n: int = 8,
    max_resolution: int = 128,
    closure: Optional[float] = None,
    k: int = 8,
    out: Optional[PathLike] = None,
    report: Optional[PathLike] = None,
    vtk: Optional[PathLike] = None,
) -> ApproximateResult:
    """Many Coons approximants over a layout of curves (``vericad approximate``)."""
    return ApproximateResult(
        _vericad.approximate(
            os.fspath(model),
            layout=os.fspath(layout),
            tol=tol,
            m=m,
            n=n,
            max_resolution=max_resolution,
            closure=closure,
            k=k,
            out=_p(out),
            report=_p(report),
            vtk=_p(vtk),
        )
    )


def batch_record_line(
    path: PathLike,
    job: str = "info",
    *,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads: Optional[int] = None,
) -> str:
    """One model's record as the JSON line ``vericad batch --job JOB`` writes for it (without
    the newline). A fault of the model is in the record (``bad_input``, ``failed``,
    ``panic``), never raised; bad options raise :class:`BadInputError`. ``threads``: the
    job's thread pool (default: one thread per core)."""
    return _vericad.batch_record_line(
        os.fspath(path), job, tol=tol, time_limit=time_limit, threads=threads
    )


def batch_record(
    path: PathLike,
    job: str = "info",
    *,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads: Optional[int] = None,
) -> Dict[str, Any]:
    """One model's batch record as a dict (see :func:`batch_record_line`)."""
    line = batch_record_line(path, job, tol=tol, time_limit=time_limit, threads=threads)
    rec: Dict[str, Any] = json.loads(line)
    return rec


def discover(inputs: Iterable[PathLike]) -> List[str]:
    """The models ``vericad batch`` runs on for these inputs (directories searched
    recursively, files, ``@LIST`` files), sorted, without repeats."""
    return list(_vericad.discover([os.fspath(i) for i in inputs]))


def read_records(out: PathLike) -> List[Dict[str, Any]]:
    """The records in a batch output (empty when it does not exist); a last line cut short is
    removed from the file, as ``vericad batch`` does when it resumes."""
    return list(_vericad.read_records(os.fspath(out)))


def batch(
    inputs: Iterable[PathLike],
    job: str = "info",
    *,
    out: PathLike,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads: Optional[int] = None,
    shard: Optional[str] = None,
) -> Dict[str, Any]:
    """``vericad batch`` in this process: one record per model appended to ``out``, models
    already there skipped. Returns ``models``, ``resumed``, ``counts`` (by status),
    ``seconds``. For a cluster see :mod:`vericad.dask`."""
    s: Dict[str, Any] = _vericad.batch(
        [os.fspath(i) for i in inputs],
        job,
        out=os.fspath(out),
        tol=tol,
        time_limit=time_limit,
        threads=threads,
        shard=shard,
    )
    return s
