"""The native module: the library's façade. Results are the CLI's JSON texts; the package's
Python half (gltfmat/__init__.py) wraps them in classes."""

import os
from typing import Callable, List, Mapping, Optional, Tuple, Union

__version__: str

class GltfmatError(Exception):
    """An asset could not be read or used (the CLI's exit status 2)."""

class UpgradeRefused(GltfmatError):
    """An upgrade was refused; nothing was written."""

_Resources = Union[Mapping[str, bytes], Callable[[str], Optional[bytes]]]

def check(
    source: Union[str, bytes, bytearray, "os.PathLike[str]"],
    *,
    name: Optional[str] = ...,
    profile: str = ...,
    deep: bool = ...,
    ignore: List[str] = ...,
    only: List[str] = ...,
    max_issues: int = ...,
    resources: Optional[_Resources] = ...,
) -> Tuple[str, List[Optional[Tuple[int, int]]]]: ...
def upgrade(
    source: Union[str, bytes, bytearray, "os.PathLike[str]"],
    output: Optional[str] = ...,
    *,
    name: Optional[str] = ...,
    force: bool = ...,
    verify: bool = ...,
    prove: bool = ...,
    threshold: float = ...,
    specular_glossiness: str = ...,
    double_sided: bool = ...,
    draft_reading: str = ...,
    strict: bool = ...,
    resources: Optional[_Resources] = ...,
) -> Tuple[str, Optional[bytes]]: ...
def compare(
    a: str, b: str, *, threshold: float = ..., pairs: List[Tuple[int, int]] = ..., draft_reading: str = ...
) -> str: ...
def render(
    asset: str, *, material: Optional[str] = ..., all: bool = ..., size: int = ...
) -> Tuple[bytes, List[Tuple[int, str, List[str]]]]: ...
