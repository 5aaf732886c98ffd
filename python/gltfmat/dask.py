"""Checking many assets on a Dask cluster.

Checking is stateless per file, so a run is a map over asset URLs: each partition of URLs
is checked on a worker, and the findings come back as one table. An asset that cannot be
read is a row saying why, never a failed job.

    from dask.distributed import Client
    import gltfmat.dask

    client = Client()                        # a LocalCluster, or a real cluster's address
    table = gltfmat.dask.check_table(["s3://bucket/a.glb", "s3://bucket/b.gltf"],
                                     storage_options={"anon": True})
    table.compute()                          # pandas; or table.to_parquet("findings/")

Local paths are read as ``gltfmat.check`` reads them (external files from the asset's own
folder, never outside it); other URLs through fsspec, their external files fetched beside
them, never above their folder.
"""

from __future__ import annotations

import posixpath
from typing import Any, Dict, Iterable, List, Optional

import dask
import dask.dataframe as dd
import pandas as pd

import gltfmat

COLUMNS = {
    "file": "object",
    "kind": "object",
    "code": "object",
    "severity": "object",
    "message": "object",
    "pointer": "object",
    "offset": "Int64",
    "line": "Int64",
    "column": "Int64",
    "errors": "Int64",
    "warnings": "Int64",
    "infos": "Int64",
    "hints": "Int64",
    "truncated": "boolean",
    "failure": "object",
}
"""The table's columns. ``kind`` is ``"file"`` for a file's row (its counts, or ``failure``:
why it could not be checked) and ``"finding"`` for each finding's row."""


def rows_of(report: gltfmat.Report) -> List[Dict[str, Any]]:
    """A report as table rows: the file's row, then one per finding."""
    rows = [
        {
            "file": report.uri,
            "kind": "file",
            "errors": report.errors,
            "warnings": report.warnings,
            "infos": report.infos,
            "hints": report.hints,
            "truncated": report.truncated,
        }
    ]
    for f in report.findings:
        rows.append(
            {
                "file": report.uri,
                "kind": "finding",
                "code": f.code,
                "severity": f.severity,
                "message": f.message,
                "pointer": f.pointer,
                "offset": f.offset,
                "line": f.line,
                "column": f.column,
            }
        )
    return rows


def check_table(
    urls: Iterable[str],
    *,
    profile: str = "default",
    deep: bool = False,
    ignore: Iterable[str] = (),
    max_issues: int = 0,
    storage_options: Optional[Dict[str, Any]] = None,
    files_per_partition: int = 64,
) -> dd.DataFrame:
    """A Dask DataFrame of the findings of every asset in ``urls`` (paths or fsspec URLs; a
    glob such as ``"s3://bucket/**/*.glb"`` is expanded here, on the client).

    Nothing runs until the table is computed or written; each partition of
    ``files_per_partition`` URLs is one task.
    """
    urls = list(_expand(urls, storage_options))
    options = dict(profile=profile, deep=deep, ignore=list(ignore), max_issues=max_issues)
    parts = [
        dask.delayed(_check_partition)(urls[i : i + files_per_partition], options, storage_options)
        for i in range(0, len(urls), files_per_partition)
    ]
    meta = _frame([])
    if not parts:
        return dd.from_pandas(meta, npartitions=1)
    return dd.from_delayed(parts, meta=meta, verify_meta=False)


def _check_partition(
    urls: List[str], options: Dict[str, Any], storage_options: Optional[Dict[str, Any]]
) -> pd.DataFrame:
    rows: List[Dict[str, Any]] = []
    for url in urls:
        try:
            rows.extend(rows_of(_check_one(url, options, storage_options)))
        except Exception as failure:  # one asset's failure is a row, never a failed job
            rows.append({"file": url, "kind": "file", "failure": f"{type(failure).__name__}: {failure}"})
    return _frame(rows)


def _check_one(url: str, options: Dict[str, Any], storage_options: Optional[Dict[str, Any]]) -> gltfmat.Report:
    if _is_local(url) and not storage_options:
        return gltfmat.check(url.removeprefix("file://"), **options)
    import fsspec

    fs, path = fsspec.core.url_to_fs(url, **(storage_options or {}))
    folder = posixpath.dirname(path)

    def beside(relative: str) -> Optional[bytes]:
        # A URI that climbs out of the asset's folder is not fetched (as for a local path).
        target = posixpath.normpath(posixpath.join(folder, relative))
        if folder and not target.startswith(folder + "/"):
            return None
        try:
            return fs.cat_file(target)
        except FileNotFoundError:
            return None

    return gltfmat.check(fs.cat_file(path), name=url, resources=beside, **options)


def _is_local(url: str) -> bool:
    return "://" not in url or url.startswith("file://")


def _expand(urls: Iterable[str], storage_options: Optional[Dict[str, Any]]) -> Iterable[str]:
    for url in [urls] if isinstance(urls, str) else urls:
        if any(c in url for c in "*?["):
            import fsspec

            fs, _ = fsspec.core.url_to_fs(url, **(storage_options or {}))
            found = sorted(fs.glob(url))
            yield from (found if _is_local(url) else map(fs.unstrip_protocol, found))
        else:
            yield url


def _frame(rows: List[Dict[str, Any]]) -> pd.DataFrame:
    frame = pd.DataFrame(rows, columns=list(COLUMNS))
    return frame.astype(COLUMNS)
