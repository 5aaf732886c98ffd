"""The Python package's API, end to end, on the repository's fixtures."""

import doctest
import json
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

import gltfmat

from conftest import REPO, cli

FIXTURES = REPO / "fixtures"
BAD = FIXTURES / "broken" / "bad-material.gltf"
SHEEN = FIXTURES / "valid" / "sheen-triangle.gltf"
TEXTURED = FIXTURES / "spec-gloss" / "textured.gltf"


def test_a_path_is_checked_as_the_cli_checks_it():
    report = gltfmat.check(BAD)
    expected = json.loads(cli("check", "--format", "json", str(BAD)))
    got = report.to_dict()
    for k in ("validatorVersion", "uri"):
        got.pop(k), expected.pop(k)
    assert got == expected
    assert report.errors == expected["issues"]["numErrors"] > 0
    assert report.has_errors
    first = report.findings[0]
    assert first.severity == "error" and first.pointer.startswith("/materials/0")
    # Located in the text as the CLI's human output locates it.
    human = cli("check", str(BAD), "--color", "never")
    assert f"{BAD}:{first.line}:{first.column}: error[{first.code}]" in human


def test_bytes_read_their_files_through_a_mapping_or_a_callable():
    text = TEXTURED.read_bytes()
    files = {p.name: p.read_bytes() for p in TEXTURED.parent.iterdir() if p.suffix in (".bin", ".png")}
    without = gltfmat.check(text, name="textured.gltf")
    with_mapping = gltfmat.check(text, name="textured.gltf", resources=files)
    asked = []

    def fetch(uri):
        asked.append(uri)
        return files.get(uri)

    with_callable = gltfmat.check(text, name="textured.gltf", resources=fetch)
    not_read = lambda r: [f.pointer for f in r.findings if f.code == "EXTERNAL_RESOURCE_NOT_READ"]
    assert len(not_read(without)) == 4, "no resources: the buffer and images are not read"
    assert not_read(with_mapping) == not_read(with_callable) == []
    assert with_mapping.to_dict()["issues"] == with_callable.to_dict()["issues"] == gltfmat.check(TEXTURED).to_dict()["issues"]
    assert with_mapping.errors == 0
    assert asked and len(asked) == len(set(asked)), "each file asked for once"


def test_a_resource_loader_that_fails_is_a_finding_not_a_crash():
    def broken(uri):
        raise RuntimeError("storage is down")

    report = gltfmat.check(TEXTURED.read_bytes(), resources=broken)
    assert report.errors > 0
    assert any("storage is down" in f.message for f in report.findings)

    def wrong(uri):
        return 42

    report = gltfmat.check(TEXTURED.read_bytes(), resources=wrong)
    assert any("not bytes" in f.message for f in report.findings)


def test_options_filter_as_on_the_command_line():
    codes = {f.code for f in gltfmat.check(BAD).findings}
    kept = next(iter(codes))
    assert {f.code for f in gltfmat.check(BAD, only=[kept]).findings} == {kept}
    assert kept not in {f.code for f in gltfmat.check(BAD, ignore=[kept]).findings}
    cut = gltfmat.check(BAD, max_issues=1)
    assert len(cut.findings) == 1 and cut.truncated and cut.errors == gltfmat.check(BAD).errors
    with pytest.raises(ValueError, match="profile"):
        gltfmat.check(BAD, profile="strict")


def test_errors_are_exceptions_with_the_cli_message(tmp_path):
    with pytest.raises(gltfmat.GltfmatError, match="no-such.gltf"):
        gltfmat.check(tmp_path / "no-such.gltf")
    with pytest.raises(TypeError):
        gltfmat.check(12)
    with pytest.raises(gltfmat.UpgradeRefused, match="invalid JSON: .* line 1 column 2"):
        gltfmat.upgrade(b"not json at all")
    assert issubclass(gltfmat.UpgradeRefused, gltfmat.GltfmatError)


def test_upgrade_to_bytes_is_proved_and_checked():
    source = FIXTURES / "gltf1" / "pbr-mr-web3d.gltf"
    upgraded = gltfmat.upgrade(source)
    assert upgraded.data[:4] == b"glTF" and upgraded.written == []
    assert upgraded.proof and all(c.same and c.max < 1.0 for c in upgraded.proof)
    assert upgraded.check.errors == 0
    assert any(n.kind == "decision" for n in upgraded.notes)
    again = gltfmat.check(upgraded.data, name="out.glb")
    assert again.errors == 0 and again.to_dict()["info"]["version"] == "2.0"


def test_upgrade_writes_atomically_and_never_replaces_without_force(tmp_path):
    source = FIXTURES / "gltf1" / "pbr-mr-web3d.gltf"
    target = tmp_path / "out.gltf"
    upgraded = gltfmat.upgrade(source, target)
    assert upgraded.data is None and str(target) in upgraded.written
    assert all(Path(p).exists() for p in upgraded.written)
    before = target.read_bytes()
    with pytest.raises(gltfmat.GltfmatError, match="exists"):
        gltfmat.upgrade(source, target)
    gltfmat.upgrade(source, target, force=True)
    assert target.read_bytes() == before
    with pytest.raises(gltfmat.GltfmatError):
        gltfmat.upgrade(source, source, force=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(Path(p).name for p in upgraded.written)


def test_verify_refuses_a_conversion_whose_proof_fails():
    source = FIXTURES / "gltf1" / "pbr-sg-khr.gltf"
    assert gltfmat.upgrade(source, verify=True).proof
    with pytest.raises(gltfmat.UpgradeRefused, match="renders like its source"):
        gltfmat.upgrade(source, verify=True, draft_reading="example-shader", threshold=0.01)


def test_a_lit_material_is_proved_by_its_emission_and_coverage_and_verify_holds():
    asset = {
        "asset": {"version": "1.0"},
        "extensionsUsed": ["KHR_materials_common"],
        "materials": {"lit": {"extensions": {"KHR_materials_common": {
            "technique": "BLINN", "transparent": True,
            "values": {"diffuse": [0.8, 0.2, 0.1, 1.0], "emission": [0.3, 0.3, 0.3, 1.0],
                       "transparency": 0.5}}}}},
    }
    upgraded = gltfmat.upgrade(json.dumps(asset).encode(), name="common.gltf", verify=True)
    [proof] = upgraded.proof
    assert proof.a == (0, "lit") and proof.evaluated and not proof.same
    assert proof.max == 0
    assert "KHR_materials_common" in proof.not_evaluated[0]
    assert "emission and coverage" in proof.not_evaluated[0]


def test_a_material_nothing_is_read_of_is_named_not_evaluated_and_does_not_fail_verify():
    asset = {
        "asset": {"version": "1.0"},
        "materials": {"lit": {"technique": "missing", "values": {"diffuse": [0.8, 0.2, 0.1, 1.0]}}},
    }
    upgraded = gltfmat.upgrade(json.dumps(asset).encode(), name="technique.gltf", verify=True)
    [proof] = upgraded.proof
    assert proof.a == (0, "lit") and not proof.evaluated and not proof.same
    assert proof.not_evaluated[0].startswith("first: ")


def test_compare_and_render():
    textured = TEXTURED
    factors = FIXTURES / "spec-gloss" / "factors.gltf"
    same = gltfmat.compare(textured, textured)
    assert same and all(c.same and c.max == 0 for c in same)
    different = gltfmat.compare(textured, factors)
    assert any(not c.same and c.max > 1 for c in different)
    picture = gltfmat.render(SHEEN, size=32)
    assert picture.png.startswith(b"\x89PNG") and picture.drawn[0][:2] == (0, "velvet")
    with pytest.raises(gltfmat.GltfmatError, match="no such material"):
        gltfmat.render(SHEEN, material="nothing")


def test_a_thread_pool_checks_in_parallel_with_the_same_answers():
    files = sorted(p for p in FIXTURES.rglob("*") if p.suffix in (".gltf", ".glb"))
    alone = [gltfmat.check(p).to_dict()["issues"] for p in files]
    with ThreadPoolExecutor(max_workers=4) as pool:
        pooled = list(pool.map(lambda p: gltfmat.check(p).to_dict()["issues"], files * 3))
    assert pooled == alone * 3


def test_the_docstring_examples_run():
    failed, tried = doctest.testmod(gltfmat)
    assert tried >= 3 and failed == 0
