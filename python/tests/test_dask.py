"""The Dask run over other people's assets gives the CLI's findings, row for row."""

import json

import pytest

import pandas as pd

from conftest import REPO, cli, shared

dask_distributed = pytest.importorskip("dask.distributed", reason="pip install ./python[dask]")
import gltfmat.dask  # noqa: E402


@pytest.fixture(scope="module")
def client():
    cluster = dask_distributed.LocalCluster(n_workers=2, threads_per_worker=1, dashboard_address=None)
    with dask_distributed.Client(cluster) as client:
        yield client
    cluster.close()


def test_a_local_cluster_gives_the_clis_findings_for_every_file(client):
    folder = shared("real-world", "gltf2")
    reports = [json.loads(line) for line in cli("check", str(folder), "--format", "jsonl").splitlines()]
    files = [r["uri"] for r in reports]
    assert len(files) > 100
    table = gltfmat.dask.check_table(files, files_per_partition=16).compute()
    assert table.attrs == {} and len(table) > len(files)

    per_file = table[table.kind == "file"].set_index("file")
    assert sorted(per_file.index) == sorted(files) and per_file.failure.isna().all()
    findings = table[table.kind == "finding"]
    for report in reports:
        issues = report["issues"]
        row = per_file.loc[report["uri"]]
        counts = [int(row[k]) for k in ("errors", "warnings", "infos", "hints")]
        assert counts == [issues[k] for k in ("numErrors", "numWarnings", "numInfos", "numHints")], report["uri"]
        expected = [
            (m["code"], gltfmat.SEVERITIES[m["severity"]], m["message"], m.get("pointer"), m.get("offset"))
            for m in issues["messages"]
        ]
        mine = findings[findings.file == report["uri"]]
        got = [
            (r.code, r.severity, r.message, r.pointer, None if r.offset is None or r.offset != r.offset else int(r.offset))
            for r in mine.astype(object).where(mine.notna(), None).itertuples()
        ]
        assert got == expected, report["uri"]


def test_an_asset_that_cannot_be_read_is_a_row_not_a_failed_job(client, tmp_path):
    good = tmp_path / "good.gltf"
    good.write_text('{"asset": {"version": "2.0"}}')
    folder = tmp_path / "a-folder.gltf"
    folder.mkdir()
    urls = [str(good), str(tmp_path / "missing.glb"), str(folder), "memory://nowhere/x.glb"]
    table = gltfmat.dask.check_table(urls, files_per_partition=1).compute()
    files = table[table.kind == "file"].set_index("file")
    assert pd.isna(files.loc[str(good)].failure)
    for bad in urls[1:]:
        assert isinstance(files.loc[bad].failure, str) and files.loc[bad].failure, bad


def test_object_storage_assets_read_their_files_beside_them_and_never_above(client):
    import fsspec

    memory = fsspec.filesystem("memory")
    source = REPO / "fixtures" / "spec-gloss"
    for name in ("textured.gltf", "quad.bin", "diffuse16.png", "specgloss16.png", "normal.png"):
        memory.pipe_file(f"/bucket/assets/{name}", (source / name).read_bytes())
    memory.pipe_file("/bucket/escape.gltf", b'{"asset": {"version": "2.0"}, "buffers": [{"uri": "../secret.bin", "byteLength": 4}]}')
    memory.pipe_file("/secret.bin", b"abcd")
    # Memory filesystems live in one process: computed here, on the client's threads.
    table = gltfmat.dask.check_table(["memory://bucket/**/*.gltf"]).compute(scheduler="threads")
    files = table[table.kind == "file"].set_index("file")
    textured, escape = sorted(files.index)
    assert textured.startswith("memory://") and textured.endswith("/bucket/assets/textured.gltf")
    assert escape.endswith("/bucket/escape.gltf")
    on_disk = gltfmat.check(source / "textured.gltf")
    row = files.loc[textured]
    assert [int(row.errors), int(row.warnings), int(row.infos)] == [on_disk.errors, on_disk.warnings, on_disk.infos]
    climbing = table[(table.file == escape) & (table.kind == "finding")]
    assert (climbing.pointer == "/buffers/0/uri").any(), "the climbing URI is reported, not read"
    assert climbing.message.str.contains("not found").any()
