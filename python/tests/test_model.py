"""Models from Python: the same creature `pelage info` and `pelage skin` describe."""

import json
import os

import numpy as np
import pytest

import pelage
from conftest import bits

SHARED = os.environ.get("PELAGE_SHARED_MODELS_DIR", "")


def test_model_equals_info(monkey, cli):
    info = json.loads(cli("info", "--json", quiet=False).stdout)
    assert monkey.name == info["name"]
    assert monkey.segments == [s["name"] for s in info["segments"]]
    assert list(monkey.clips) == [c["name"] for c in info["clips"]]
    for c in info["clips"]:
        assert monkey.clips[c["name"]] == pytest.approx(c["durationSeconds"], rel=1e-7)
    assert monkey.regions == [r["name"] if isinstance(r, dict) else r for r in info["regions"]]


def test_skin_equals_the_command_line(monkey, cli, tmp_path):
    positions, normals, triangles = monkey.skin(clip="walk", time=0.3)
    out = tmp_path / "skin.ply"
    cli("skin", "--clip", "walk", "--time", 0.3, "--out", out)
    data = out.read_bytes()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    vertices = np.frombuffer(data, dtype="<f4", count=positions.shape[0] * 6, offset=end)
    vertices = vertices.reshape(-1, 6)
    np.testing.assert_array_equal(bits(positions), bits(vertices[:, :3]))
    np.testing.assert_array_equal(bits(normals), bits(vertices[:, 3:]))
    faces = np.frombuffer(data, dtype=np.dtype([("n", "u1"), ("v", "<i4", 3)]),
                          offset=end + vertices.nbytes)
    assert np.all(faces["n"] == 3)
    np.testing.assert_array_equal(faces["v"], triangles)


def test_rest_skin_differs_from_a_posed_one(monkey):
    rest, _, _ = monkey.skin()
    posed, normals, _ = monkey.skin(clip="tumble", time=1.5)
    assert rest.shape == posed.shape and not np.allclose(rest, posed)
    np.testing.assert_allclose(np.linalg.norm(normals, axis=1), 1.0, atol=1e-4)


def test_fur_params_round_trip(monkey):
    fur = monkey.fur("fig9", hairs=1234, overcoat={"stiffness": 0.55})
    params = fur.params
    assert params["name"] == "fig9" and params["hairs"] == 1234
    assert params["overcoat"]["stiffness"] == 0.55  # the float32 value, as its shortest decimal
    again = monkey.fur("fig9", **{k: v for k, v in params.items() if k != "name"})
    np.testing.assert_array_equal(fur.hairs().points, again.hairs().points)


def test_a_partial_preset_is_the_default_with_its_changes(monkey, tmp_path):
    default = monkey.fur("default").params
    same = tmp_path / "same.json"
    same.write_text('{"lengthScale": 1.0}')
    params = monkey.fur(str(same)).params
    assert params.pop("name") == "same"
    assert params == {k: v for k, v in default.items() if k != "name"}
    based = tmp_path / "based.json"
    based.write_text('{"base": "fig9", "seed": 3}')
    assert monkey.fur(str(based)).params["overcoat"] == monkey.fur("fig9").params["overcoat"]


def test_coverage_sets_the_count_and_hairs_replace_it(monkey):
    assert monkey.fur().params["coverage"] == 0.95
    half = monkey.fur(coverage=0.5)
    dense = monkey.fur(coverage=0.9)
    assert 0 < len(half.hairs()) < len(dense.hairs())
    counted = monkey.fur(hairs=2000).params
    assert counted["hairs"] == 2000 and "coverage" not in counted


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_gltf_creature(cli):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    assert set(fox.clips) >= {"Survey", "Walk", "Run"}
    hairs = fox.fur(hairs=5000).hairs(clip="Run", time=0.2)
    assert len(hairs) > 4000
    lo, hi = hairs.points.reshape(-1, 3).min(0), hairs.points.reshape(-1, 3).max(0)
    assert 0.5 < (hi - lo).max() < 2.5  # a fox of about a metre and a half, in metres


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_regions_and_groom_files(tmp_path):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    n = len(fox.skin()[0])
    regions = [{"match": "b_Tail*", "lengthScale": 2.0}, {"match": "b_Head*", "lengthScale": 0.4}]
    groomed = fox.fur(hairs=3000, regions=regions)
    assert groomed.params["regions"][0]["match"] == "b_Tail*"
    length = groomed.groom["length"]
    assert length.shape == (n,) and set(groomed.groom) == {"length"}
    plain = fox.fur(hairs=3000)
    assert plain.groom == {}
    base = 0.0351  # the Fox's own fur length: 2 % of its bounding-box diagonal
    assert np.isclose(length.max(), 2 * length.min() / 0.4, rtol=1e-5)
    assert length.min() < base < length.max()
    # The regions' values written from numpy and read back grow the same hairs, bit for bit.
    path = str(tmp_path / "fox.groom.json")
    tint = np.ones((n, 3), np.float32)
    tint[:, 0] = 0.5
    fox.write_groom(path, length=length, tint=tint)
    from_file = fox.fur(hairs=3000, groom=path)
    assert np.array_equal(bits(from_file.groom["length"]), bits(length))
    assert np.array_equal(bits(from_file.groom["tint"]), bits(tint))
    assert np.array_equal(bits(from_file.hairs().points), bits(groomed.hairs().points))
    with pytest.raises(ValueError, match=r"length.*shape \(%d,\)" % n):
        fox.write_groom(path, length=length[:-1])
    with pytest.raises(ValueError, match=r"density\[0\].*\[0, 100\]"):
        fox.write_groom(str(tmp_path / "bad.json"), density=np.full(n, -1.0))
    assert not os.path.exists(tmp_path / "bad.json")
    with pytest.raises(ValueError, match="another mesh"):
        pelage.load("monkey", triangles=2000).fur(groom=path)
    with pytest.raises(ValueError, match=r"regions\[0\].match 'b_Tial\*' matches no region"):
        fox.fur(hairs=100, regions=[{"match": "b_Tial*"}])


# A per-coat value by region and from numpy: (the preset's and groom file's field, write_groom's
# keyword and Fur.groom's key, the default coats' (overcoat, undercoat), the tail's).
PER_COAT_VALUES = [
    ("stiffness", "stiffness", (0.3, 0.7), (0.9, 0.95)),
    ("segmentDirectionWeight", "segment_direction_weight", (0.3, 0.3), (1.0, 0.5)),
]


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
@pytest.mark.parametrize("field,key,coats,tail", PER_COAT_VALUES)
def test_per_coat_values_by_region_and_from_numpy(tmp_path, field, key, coats, tail):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    n = len(fox.skin()[0])
    groomed = fox.fur(hairs=3000, regions=[{"match": "b_Tail*", field: list(tail)}])
    assert groomed.params["regions"][0][field] == pytest.approx(list(tail))
    values = groomed.groom[key]
    assert values.shape == (n, 2) and set(groomed.groom) == {key}
    # From the coats' own to the tail's.
    for c in range(2):
        lo, hi = sorted((np.float32(coats[c]), np.float32(tail[c])))
        assert values[:, c].min() == lo and values[:, c].max() == hi
    plain = fox.fur(hairs=3000)
    assert not np.array_equal(groomed.hairs().points, plain.hairs().points)
    # The same values from numpy, through a groom file: the same hairs, bit for bit.
    path = str(tmp_path / "groomed.groom.json")
    fox.write_groom(path, **{key: values})
    from_file = fox.fur(hairs=3000, groom=path)
    assert np.array_equal(bits(from_file.groom[key]), bits(values))
    assert np.array_equal(bits(from_file.hairs().points), bits(groomed.hairs().points))
    with pytest.raises(ValueError, match=r"%s.*shape \(%d, 2\)" % (key, n)):
        fox.write_groom(path, **{key: values[:, 0]})
    with pytest.raises(ValueError, match=r"%s\[0\].*\[0, 1\]" % field):
        fox.write_groom(str(tmp_path / "bad.json"), **{key: np.full((n, 2), 1.5)})
    assert not os.path.exists(tmp_path / "bad.json")


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_curl_by_region_and_from_numpy(tmp_path):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    n = len(fox.skin()[0])
    curve = {"style": "curve", "curl": {"turns": 3}}
    curly = fox.fur(hairs=3000, overcoat=curve, undercoat=curve,
                    regions=[{"match": "b_Tail*", "curl": {"radius": [0.2, 0.1]}}])
    assert curly.params["regions"][0]["curl"] == {"radius": pytest.approx([0.2, 0.1])}
    assert set(curly.groom) == {"curl_radius"}
    radius = curly.groom["curl_radius"]
    assert radius.shape == (n, 2)
    assert radius[:, 0].min() == 0 and radius[:, 0].max() == np.float32(0.2)
    straight = fox.fur(hairs=3000, overcoat=curve, undercoat=curve)
    assert not np.array_equal(curly.hairs().points, straight.hairs().points)
    # From numpy through a groom file, radius and turns: the same hairs, bit for bit.
    turns = np.full((n, 2), 3.0, dtype=np.float32)
    path = str(tmp_path / "curl.groom.json")
    fox.write_groom(path, curl_radius=radius, curl_turns=turns)
    from_file = fox.fur(hairs=3000, overcoat=curve, undercoat=curve, groom=path)
    assert np.array_equal(bits(from_file.groom["curl_turns"]), bits(turns))
    assert np.array_equal(bits(from_file.hairs().points), bits(curly.hairs().points))
    with pytest.raises(ValueError, match=r"curlRadius\[0\].*\[0, 0.5\]"):
        fox.write_groom(str(tmp_path / "bad.json"), curl_radius=np.full((n, 2), 0.6))
    with pytest.raises(ValueError, match=r"curl_turns.*shape \(%d, 2\)" % n):
        fox.write_groom(path, curl_turns=turns[:, 0])
    assert not os.path.exists(tmp_path / "bad.json")


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_width_by_region_and_from_numpy(tmp_path):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    n = len(fox.skin()[0])
    tube = {"style": "tube"}
    thick = fox.fur(hairs=3000, overcoat=tube, undercoat=tube,
                    regions=[{"match": "b_Tail*", "widthScale": [2, 0.5]}])
    assert thick.params["regions"][0]["widthScale"] == pytest.approx([2, 0.5])
    assert set(thick.groom) == {"width_scale"}
    scale = thick.groom["width_scale"]
    assert scale.shape == (n, 2)
    assert scale[:, 0].min() == 1 and scale[:, 0].max() == 2
    assert scale[:, 1].min() == 0.5 and scale[:, 1].max() == 1
    # Tubes grow that thick; strands keep their points (they are drawn and exported that wide).
    plain = fox.fur(hairs=3000, overcoat=tube, undercoat=tube)
    assert not np.array_equal(thick.hairs().points, plain.hairs().points)
    strands = fox.fur(hairs=3000, regions=[{"match": "b_Tail*", "widthScale": 2}])
    assert np.array_equal(strands.hairs().points, fox.fur(hairs=3000).hairs().points)
    # From numpy through a groom file: the same hairs, bit for bit.
    path = str(tmp_path / "width.groom.json")
    fox.write_groom(path, width_scale=scale)
    from_file = fox.fur(hairs=3000, overcoat=tube, undercoat=tube, groom=path)
    assert np.array_equal(bits(from_file.groom["width_scale"]), bits(scale))
    assert np.array_equal(bits(from_file.hairs().points), bits(thick.hairs().points))
    with pytest.raises(ValueError, match=r"widthScale\[0\].*\[0, 10\]"):
        fox.write_groom(str(tmp_path / "bad.json"), width_scale=np.full((n, 2), 11.0))
    with pytest.raises(ValueError, match=r"width_scale.*shape \(%d, 2\)" % n):
        fox.write_groom(path, width_scale=scale[:, 0])
    assert not os.path.exists(tmp_path / "bad.json")


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_colour_source_by_region_and_from_numpy(tmp_path):
    fox = pelage.load(os.path.join(SHARED, "Fox", "Fox.glb"))
    n = len(fox.skin()[0])
    white = {"color": {"source": "creature"}, "diffuse": [1, 1, 1]}
    tailed = fox.fur(hairs=3000, overcoat=white,
                     regions=[{"match": "b_Tail*", "colorSource": "material"}])
    assert tailed.params["regions"][0]["colorSource"] == ["material", "material"]
    weights = tailed.groom["color_source_weight"]
    assert sorted(weights) == ["creature", "map", "material", "texture", "vertex"]
    assert weights["material"].shape == (n, 2)
    assert weights["material"][:, 0].max() == 1 and weights["creature"][:, 0].min() == 0
    total = sum(weights[k] for k in weights)
    assert np.allclose(total, 1, atol=1e-6)
    plain = fox.fur(hairs=3000, overcoat=white)
    assert not np.array_equal(tailed.hairs().colors, plain.hairs().colors)
    assert np.array_equal(tailed.hairs().points, plain.hairs().points)
    # From numpy through a groom file: the same colours, bit for bit.
    path = str(tmp_path / "sources.groom.json")
    fox.write_groom(path, color_source_weight=weights)
    from_file = fox.fur(hairs=3000, overcoat=white, groom=path)
    assert np.array_equal(from_file.hairs().colors, tailed.hairs().colors)
    with pytest.raises(ValueError, match="lacks 'map'"):
        fox.write_groom(path, color_source_weight={k: v for k, v in weights.items() if k != "map"})
    with pytest.raises(ValueError, match=r"colorSourceWeight.material\[0\].*\[0, 1\]"):
        fox.write_groom(str(tmp_path / "bad.json"),
                        color_source_weight=dict(weights, material=np.full((n, 2), 2.0)))
    assert not os.path.exists(tmp_path / "bad.json")
    with pytest.raises(ValueError, match=r"regions\[0\].colorSource.*unknown colour source"):
        fox.fur(hairs=100, regions=[{"match": "b_Tail*", "colorSource": "paint"}])


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_subdivision_levels():
    path = os.path.join(SHARED, "Fox", "Fox.glb")
    tris = {s: len(pelage.load(path, subdivide=s).skin()[2]) for s in (0, 1, "auto")}
    assert tris == {0: 576, 1: 2304, "auto": 9216}
    for bad in (4, -1, "twice"):
        with pytest.raises((ValueError, TypeError)):
            pelage.load(path, subdivide=bad)


@pytest.mark.skipif(not os.path.exists(os.path.join(SHARED, "Fox", "Fox.glb")),
                    reason="the shared glTF models are not here")
def test_grooming_strokes_equal_the_command_line(tmp_path, cli):
    path = os.path.join(SHARED, "Fox", "Fox.glb")
    fox = pelage.load(path)
    rest = fox.skin()[0]
    back = [[0.2, 0, 0.669], [0.0, 0, 0.643], [-0.2, 0, 0.651], [-0.4, 0, 0.613]]
    # A dab on the head's left side (the skin vertex nearest a point there), mirrored to the right.
    dab = rest[np.argmin(np.linalg.norm(rest - np.array([0.45, 0.05, 0.73]), axis=1))]
    strokes = {"strokes": [
        {"tool": "length", "points": back, "radius": 0.06, "strength": 1.5},
        {"tool": "color", "points": [dab.tolist()], "radius": 0.05, "strength": 1.0,
         "color": [0.2, 0.2, 0.2], "mirror": "y"},
        {"tool": "comb", "points": back, "radius": 0.06, "strength": 1.0},
        {"tool": "cut", "points": [dab.tolist()], "radius": 0.05, "length": 0.01, "mirror": "y"},
        {"tool": "clump", "points": [dab.tolist()], "radius": 0.05, "strength": 0.2}]}
    from_python = tmp_path / "python.groom.json"
    fox.write_groom(str(from_python), strokes=strokes)
    # The command line on the same strokes (a file) writes the same bytes.
    strokes_file = tmp_path / "back.json"
    strokes_file.write_text(json.dumps(strokes))
    from_cli = tmp_path / "cli.groom.json"
    cli("groom", path, "--strokes", strokes_file, "--out", from_cli)
    assert from_python.read_bytes() == from_cli.read_bytes()
    groom = fox.fur(hairs=100, groom=str(from_python)).groom
    # Far from the strokes the model's own length (one length everywhere on a glTF creature) and
    # tint 1, bit for bit; within half the radius of the back's line, 1.5 times that length.
    far = (rest[:, 0] > 0.3) | (rest[:, 0] < -0.5)  # the line runs from x = 0.2 to -0.4
    comb_far = far.copy()
    for centre in (dab, dab * np.array([1, -1, 1])):  # the cut's dabs
        far &= np.linalg.norm(rest - centre, axis=1) > 0.05
    model_length = groom["length"][far][0]
    assert np.isclose(model_length, 0.0351, rtol=0.01)
    assert np.all(groom["length"][far] == model_length)
    on_line = (np.abs(rest[:, 1]) < 0.005) & (rest[:, 0] > -0.2) & (rest[:, 0] < 0.0)
    on_line &= rest[:, 2] > 0.6
    assert on_line.sum() > 3
    assert np.all(groom["length"][on_line] == np.float32(1.5) * model_length)
    for centre in (dab, dab * np.array([1, -1, 1])):
        inside = np.linalg.norm(rest - centre, axis=1) <= 0.025  # half the radius: full
        assert inside.sum() >= 3
        assert np.allclose(groom["tint"][inside], 0.2)
        # The cut to 1 cm, exactly under the dab's core (strength 1); it only shortens.
        assert np.all(groom["length"][inside] == np.float32(0.01))
    assert np.all(groom["length"] <= np.float32(1.5) * model_length)
    # The clump scale painted toward 0.2 under the (unmirrored) dab's core; 1 far from it.
    core = np.linalg.norm(rest - dab, axis=1) <= 0.025
    assert np.all(groom["clump"][core] == np.float32(0.2))
    assert np.all(groom["clump"][far] == 1.0)
    clumped = tmp_path / "clump.groom.json"
    fox.write_groom(str(clumped), clump=groom["clump"])
    assert np.array_equal(bits(fox.fur(hairs=100, groom=str(clumped)).groom["clump"]),
                          bits(groom["clump"]))
    with pytest.raises(ValueError, match=r"clump\[0\].*\[0, 1\]"):
        fox.write_groom(str(tmp_path / "bad.json"), clump=np.full(len(rest), 2.0))
    assert np.all(groom["tint"][rest[:, 0] < 0.35] == 1.0)
    # The comb: unit, toward the tail (-x), on the line; nothing far from it.
    comb = groom["comb"]
    assert np.allclose(np.linalg.norm(comb[on_line], axis=1), 1.0, atol=1e-5)
    assert np.all(comb[on_line][:, 0] < -0.9)
    assert np.all(comb[comb_far] == 0.0)
    # Combs from numpy: written and read back bit for bit; longer than 1 is refused by index.
    combed = tmp_path / "comb.groom.json"
    fox.write_groom(str(combed), comb=comb)
    assert np.array_equal(bits(fox.fur(hairs=100, groom=str(combed)).groom["comb"]), bits(comb))
    with pytest.raises(ValueError, match=r"comb\[0\] has length 1.55.*at most 1"):
        fox.write_groom(str(tmp_path / "bad.json"), comb=np.full((len(rest), 3), 0.9))
    with pytest.raises(ValueError, match=r"strokes\[0\].radius"):
        fox.write_groom(str(tmp_path / "bad.json"),
                        strokes={"strokes": [{"tool": "length", "points": [[0, 0, 0]],
                                              "radius": 0, "strength": 2}]})
    assert not os.path.exists(tmp_path / "bad.json")
