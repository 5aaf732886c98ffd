"""gltfmat: check glTF 2.0 / GLB assets and their materials, upgrade glTF 1.0, compare and
render materials with a reference shading evaluator.

The work runs in Rust with the GIL released, so a thread pool checks files in parallel::

    >>> import gltfmat
    >>> report = gltfmat.check(b'{"asset": {"version": "2.0"}, "materials": [{"alphaCutoff": 0.5}]}')
    >>> report.errors, report.warnings
    (0, 1)
    >>> report.findings[0].code
    'MATERIAL_ALPHA_CUTOFF_INVALID_MODE'

Assets given as bytes read their external files through ``resources``: a mapping from the
URI to bytes, or a callable ``uri -> bytes | None`` (fsspec, boto3, …). A path reads them
from its own folder and never outside it.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, List, Mapping, Optional, Sequence, Tuple, Union

from . import _gltfmat
from ._gltfmat import GltfmatError, UpgradeRefused, __version__

__all__ = [
    "check",
    "upgrade",
    "compare",
    "render",
    "Report",
    "Finding",
    "Upgraded",
    "Note",
    "Comparison",
    "Picture",
    "GltfmatError",
    "UpgradeRefused",
    "__version__",
]

Source = Union[str, "os.PathLike[str]", bytes, bytearray]
Resources = Union[Mapping[str, bytes], Callable[[str], Optional[bytes]]]

SEVERITIES = ("error", "warning", "info", "hint")


@dataclass(frozen=True)
class Finding:
    """One finding: its code, severity, place and message, as ``gltfmat check`` reports it."""

    code: str
    severity: str
    message: str
    pointer: Optional[str] = None
    """A JSON pointer into the asset, when the finding is about its JSON."""
    offset: Optional[int] = None
    """A byte offset, when the finding is about binary data."""
    line: Optional[int] = None
    column: Optional[int] = None

    def __str__(self) -> str:
        where = f"{self.line}:{self.column}: " if self.line is not None else ""
        place = self.pointer if self.pointer is not None else f"byte {self.offset}"
        return f"{where}{self.severity}[{self.code}]: {self.message} ({place})"


@dataclass(frozen=True)
class Report:
    """The check of one asset.

    ``to_dict()`` is the Khronos glTF-Validator's report shape, as ``gltfmat check --format
    json`` writes it.
    """

    uri: str
    errors: int
    warnings: int
    infos: int
    hints: int
    truncated: bool
    findings: List[Finding]
    _khronos: Mapping[str, Any] = field(repr=False)

    @property
    def has_errors(self) -> bool:
        return self.errors > 0

    def to_dict(self) -> dict:
        """The report in the Khronos validator's shape (a fresh copy)."""
        return json.loads(json.dumps(self._khronos))

    def __str__(self) -> str:
        return (
            f"{self.uri}: {self.errors} error(s), {self.warnings} warning(s), "
            f"{self.infos} info(s), {self.hints} hint(s)"
        )

    @classmethod
    def _of(cls, khronos: Mapping[str, Any], places: Sequence[Optional[Tuple[int, int]]]) -> "Report":
        issues = khronos["issues"]
        findings = [
            Finding(
                code=m["code"],
                severity=SEVERITIES[m["severity"]],
                message=m["message"],
                pointer=m.get("pointer"),
                offset=m.get("offset"),
                line=place[0] if place else None,
                column=place[1] if place else None,
            )
            for m, place in zip(issues["messages"], places)
        ]
        return cls(
            uri=khronos["uri"],
            errors=issues["numErrors"],
            warnings=issues["numWarnings"],
            infos=issues["numInfos"],
            hints=issues["numHints"],
            truncated=issues["truncated"],
            findings=findings,
            _khronos=khronos,
        )


def check(
    source: Source,
    *,
    name: Optional[str] = None,
    profile: str = "default",
    deep: bool = False,
    ignore: Iterable[str] = (),
    only: Iterable[str] = (),
    max_issues: int = 0,
    resources: Optional[Resources] = None,
) -> Report:
    """Checks a glTF 2.0 / GLB asset, as ``gltfmat check`` does.

    ``source`` is a path or the asset's bytes. ``profile="khronos"`` reports exactly what the
    Khronos glTF-Validator reports; ``deep`` decodes textures for the pixel rules;
    ``max_issues`` (0: all) cuts the list of findings but not the counts.

    >>> import gltfmat
    >>> gltfmat.check(b'{"asset": {"version": "2.0"}}').errors
    0

    Raises ``GltfmatError`` when the file cannot be read; problems in the asset are findings.
    """
    khronos, places = _gltfmat.check(
        _source(source),
        name=name,
        profile=profile,
        deep=deep,
        ignore=list(ignore),
        only=list(only),
        max_issues=max_issues,
        resources=resources,
    )
    return Report._of(json.loads(khronos), places)


@dataclass(frozen=True)
class Note:
    """A line of the conversion report: a decision taken, or a part of the input dropped."""

    kind: str
    pointer: str
    text: str


@dataclass(frozen=True)
class Comparison:
    """How far one material pair renders apart (ΔE2000, 1 ≈ a just-noticeable difference)."""

    a: Tuple[int, str]
    b: Tuple[int, str]
    max: float
    p99: float
    mean: float
    same: bool
    """Everything evaluated, and ``max`` within the threshold."""
    dominant: Optional[str]
    """The input that dominates the worst difference ("emission", "coverage", …)."""
    not_evaluated: List[str]
    """What the evaluator could not show of either material: the pair is then never same."""
    evaluated: bool
    """False for a glTF 1.0 material nothing can be read of (a technique id naming nothing, an
    unreadable texture): nothing was evaluated, the figures are 0, and an upgrade's proof is
    not failed by it. A 1.0 material drawn by a technique's shaders or KHR_materials_common is
    evaluated by its emission and coverage, its lighting named in ``not_evaluated``."""
    worst: Mapping[str, Any]
    details: Mapping[str, Any] = field(repr=False)

    @classmethod
    def _of(cls, o: Mapping[str, Any]) -> "Comparison":
        return cls(
            a=(o["a"], o["aName"]),
            b=(o["b"], o["bName"]),
            max=o["max"],
            p99=o["p99"],
            mean=o["mean"],
            same=o["pass"],
            dominant=o["dominant"],
            not_evaluated=list(o["notEvaluated"]),
            evaluated=o["evaluated"],
            worst=o["worst"],
            details=o,
        )


@dataclass(frozen=True)
class Upgraded:
    """An upgraded asset: its GLB bytes (when no output path was given) or the files written,
    the conversion's notes, the proof (one ``Comparison`` per converted material) and the
    check of the output."""

    data: Optional[bytes]
    written: List[str]
    notes: List[Note]
    proof: List[Comparison]
    check: Report


def upgrade(
    source: Source,
    output: Union[str, "os.PathLike[str]", None] = None,
    *,
    name: Optional[str] = None,
    force: bool = False,
    verify: bool = False,
    prove: bool = True,
    threshold: Optional[float] = None,
    specular_glossiness: str = "metal-rough",
    double_sided: bool = False,
    draft_reading: str = "appendix",
    strict: bool = False,
    resources: Optional[Resources] = None,
) -> Upgraded:
    """Upgrades a glTF 1.0 asset to glTF 2.0, or converts a glTF 2.0 asset's
    KHR_materials_pbrSpecularGlossiness materials, as ``gltfmat upgrade`` does.

    Without ``output`` the result's ``data`` is the GLB; with it the files are written
    atomically (``*.glb``, or ``*.gltf`` with its ``.bin`` and images), never over the input or
    an existing file unless ``force``. Every converted material is proved against its source
    unless ``prove=False``; ``verify=True`` refuses a conversion whose proof fails.

    Raises ``UpgradeRefused`` (nothing written) or ``GltfmatError``.
    """
    text, data = _gltfmat.upgrade(
        _source(source),
        None if output is None else os.fspath(output),
        name=name,
        force=force,
        verify=verify,
        prove=prove,
        specular_glossiness=specular_glossiness,
        double_sided=double_sided,
        draft_reading=draft_reading,
        strict=strict,
        resources=resources,
        **_given(threshold=threshold),
    )
    result = json.loads(text)
    check = result["check"]
    return Upgraded(
        data=data,
        written=result["written"],
        notes=[Note(**n) for n in result["notes"]],
        proof=[Comparison._of(o) for o in result["proof"]],
        check=Report._of(check, [None] * len(check["issues"]["messages"])),
    )


def compare(
    a: Union[str, "os.PathLike[str]"],
    b: Union[str, "os.PathLike[str]"],
    *,
    threshold: Optional[float] = None,
    pairs: Iterable[Tuple[int, int]] = (),
    draft_reading: str = "appendix",
) -> List[Comparison]:
    """Compares the materials of two assets on disk, paired by index (or by ``pairs``), as
    ``gltfmat compare`` does."""
    text = _gltfmat.compare(
        os.fspath(a), os.fspath(b), pairs=list(pairs), draft_reading=draft_reading, **_given(threshold=threshold)
    )
    return [Comparison._of(o) for o in json.loads(text)]


@dataclass(frozen=True)
class Picture:
    """A rendered material ball or contact sheet: PNG bytes, and per material drawn its
    index, name and what the picture does not show of it."""

    png: bytes
    drawn: List[Tuple[int, str, List[str]]]


def render(
    asset: Union[str, "os.PathLike[str]"],
    *,
    material: Union[int, str, None] = None,
    all: bool = False,
    size: int = 512,
) -> Picture:
    """Renders a material ball (or with ``all`` every material on one sheet) as a PNG."""
    png, drawn = _gltfmat.render(
        os.fspath(asset), material=None if material is None else str(material), all=all, size=size
    )
    return Picture(png=png, drawn=[(i, n, list(m)) for i, n, m in drawn])


def _given(**options: Any) -> dict:
    """The options the caller set: the others keep the library's defaults (one place)."""
    return {k: v for k, v in options.items() if v is not None}


def _source(source: Source) -> Union[str, bytes, bytearray]:
    if isinstance(source, (bytes, bytearray)):
        return source
    return os.fspath(source)
