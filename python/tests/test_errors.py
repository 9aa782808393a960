"""Errors: FileNotFoundError for a missing file, pelage.InputError (a ValueError) for a malformed
file, ValueError naming the keyword (and its range) for a bad value or an unknown keyword."""

import pytest

import pelage


def test_input_error_is_a_value_error():
    assert issubclass(pelage.InputError, ValueError)


@pytest.mark.parametrize("name", ["missing.glb", "missing.json", "missing.obj", "missing"])
def test_missing_files(tmp_path, name):
    with pytest.raises(FileNotFoundError, match="missing"):
        pelage.load(str(tmp_path / name))


def test_missing_fur_preset_file(monkey, tmp_path):
    with pytest.raises(FileNotFoundError, match="nope.json"):
        monkey.fur(str(tmp_path / "nope.json"))


@pytest.mark.parametrize("name,content,words", [
    ("bad.json", "{ not json", "bad.json"),
    ("bad.glb", "glTF but not really", "bad.glb"),
    ("bad.obj", "v 0 0 0\nf 1 2 3\n", "bad.obj"),
    ("bad.gltf", '{"asset": {"version": "2.0"}, "meshes": 3}', "bad.gltf"),
])
def test_malformed_files(tmp_path, name, content, words):
    path = tmp_path / name
    path.write_text(content)
    with pytest.raises(pelage.InputError, match=words):
        pelage.load(str(path))


@pytest.mark.parametrize("call,words", [
    (lambda m: m.fur(hairs=-5), r"hairs.*-5.*\[0, 2e\+07\]"),
    (lambda m: m.fur(overcoat={"stiffness": 3}), r"overcoat\.stiffness.*\[0, 1\]"),
    (lambda m: m.fur(hairz=10), r"unknown field 'hairz'"),
    (lambda m: m.fur(overcoat={"stif": 1}), r"unknown field 'overcoat\.stif'"),
    (lambda m: m.fur(overcoat={"style": "fluffy"}), r"overcoat\.style.*fluffy"),
    (lambda m: m.fur().hairs(clip="nope"), r"clip.*'nope'.*walk"),
    (lambda m: m.fur().hairs(clip="walk", time=-1), r"time -1.*\[0, 1000000\]"),
    (lambda m: m.fur().hairs(time=0.5), r"time needs a clip"),
    (lambda m: m.fur().hairs(clip="walk", fps=0), r"fps 0.*\[1, 1000\]"),
    (lambda m: m.fur().hairs(clip="walk", dynamics={"frequency": 0}), r"frequency.*0"),
    (lambda m: m.fur().hairs(clip="walk", dynamics={"spring": 1}), r"unknown keyword 'spring'"),
    (lambda m: m.fur().hairs(dynamics=True), r"dynamics.*needs a clip"),
    (lambda m: pelage.load(triangles=5), r"triangles 5.*\[2000, 2000000\]"),
    (lambda m: pelage.load(unit_scale=0), r"unit_scale 0.*\(0, 1000000\]"),
    (lambda m: pelage.load(colour=1), r"unknown keyword 'colour'.*triangles"),
    (lambda m: pelage.analyze(m, "walk", frames=(5, 2)), r"frames 5:2"),
    (lambda m: pelage.analyze(m, "walk", groups="limb"), r"groups 'limb'"),
    (lambda m: pelage.analyze(m, "walk", hold=-1), r"hold -1"),
    (lambda m: pelage.analyze(m, "walk", sweep="colour=1:2:3"), r"sweep.*colour"),
    (lambda m: pelage.export(m, "walk", format="fbx", out="x"), r"format.*fbx.*usda"),
    (lambda m: pelage.set_threads(-1), r"threads -1.*\[0, 1024\]"),
])
def test_bad_values_name_the_keyword(monkey, call, words):
    with pytest.raises(ValueError, match=words):
        call(monkey)


def test_fur_of_another_model(monkey):
    other = pelage.load("monkey", triangles=4000)
    with pytest.raises(ValueError, match="another model"):
        pelage.analyze(monkey, "walk", fur=other.fur(hairs=100))
