"""Type stubs of the native module; the documented API is in ``vericad/__init__.py``."""

from typing import Any, Dict, List, Optional

__version__: str

class VericadError(Exception): ...
class BadInputError(VericadError): ...
class ComputationError(VericadError): ...
class OutputError(VericadError): ...

def read_model(path: str) -> Dict[str, Any]: ...
def info(path: str) -> Dict[str, Any]: ...
def set_skip_invalid(on: bool) -> None: ...
def ssi(
    file: str,
    file2: Optional[str] = None,
    *,
    tol: float = 1e-6,
    flatness: Optional[float] = None,
    time_limit: Optional[float] = None,
    untrimmed: bool = False,
    threads: Optional[int] = None,
    out: Optional[str] = None,
    vtk: Optional[str] = None,
    iges: Optional[str] = None,
    fits: bool = False,
    certify: bool = True,
    svg: Optional[str] = None,
    view: str = "-60,25",
    pieces: str = "chords",
) -> Dict[str, Any]: ...
def certify_ssi(
    a: str,
    b: Optional[str] = None,
    *,
    curves: str,
    tol: float = 1e-6,
    match_distance: Optional[float] = None,
    out: Optional[str] = None,
) -> Dict[str, Any]: ...
def curve_on_surface(
    surface: str,
    curve: str,
    *,
    tol: float = 1e-3,
    angle: float = 10.0,
    bound: str = "local",
    exact: bool = False,
    out: Optional[str] = None,
    svg: Optional[str] = None,
    iges: Optional[str] = None,
    vtk: Optional[str] = None,
    svg_3d: Optional[str] = None,
    view: str = "-60,25",
) -> Dict[str, Any]: ...
def curve_on_faces(
    file: str,
    faces: str = "all",
    *,
    tol: float = 1e-3,
    angle: float = 10.0,
    bound: str = "local",
    exact: bool = False,
    out: Optional[str] = None,
    iges: Optional[str] = None,
) -> Dict[str, Any]: ...
def repair(
    input: str,
    *,
    mode: str = "auto",
    u1: float = 1e-3,
    u2: float = 1e-3,
    feature_angle: float = 30.0,
    features: Optional[str] = None,
    out: Optional[str] = None,
    report: Optional[str] = None,
    vtk: Optional[str] = None,
    svg: Optional[str] = None,
    view: str = "-60,25",
) -> Dict[str, Any]: ...
def reparam(
    model: str,
    *,
    tol: float = 1e-4,
    max_lines: int = 500,
    bound: bool = True,
    out: Optional[str] = None,
    report: Optional[str] = None,
    svg: Optional[str] = None,
    vtk: Optional[str] = None,
) -> Dict[str, Any]: ...
def coons(
    model: str,
    *,
    boundary: str,
    tol: float = 1e-3,
    m: int = 8,
    n: int = 8,
    max_resolution: int = 128,
    closure: Optional[float] = None,
    k: int = 8,
    out: Optional[str] = None,
    report: Optional[str] = None,
    vtk: Optional[str] = None,
) -> Dict[str, Any]: ...
def approximate(
    model: str,
    *,
    layout: str,
    tol: float = 1e-3,
    m: int = 8,
    n: int = 8,
    max_resolution: int = 128,
    closure: Optional[float] = None,
    k: int = 8,
    out: Optional[str] = None,
    report: Optional[str] = None,
    vtk: Optional[str] = None,
) -> Dict[str, Any]: ...
def batch_check(job: str = "info", *, tol: float = 1e-6, time_limit: Optional[float] = None) -> None: ...
def batch_record_line(
    path: str,
    job: str = "info",
    *,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads: Optional[int] = None,
) -> str: ...
def discover(inputs: List[str]) -> List[str]: ...
def batch(
    inputs: List[str],
    job: str = "info",
    *,
    out: str,
    tol: float = 1e-6,
    time_limit: Optional[float] = None,
    threads: Optional[int] = None,
    shard: Optional[str] = None,
) -> Dict[str, Any]: ...
def read_records(out: str) -> List[Dict[str, Any]]: ...
