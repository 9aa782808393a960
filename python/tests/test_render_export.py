"""pelage.render equals `pelage render`'s PNG; pelage.export writes the files `pelage export`
writes."""

import os

import numpy as np
import pytest

import pelage

render = getattr(pelage, "render", None)


@pytest.mark.skipif(render is None, reason="built without the renderer (PELAGE_BUILD_VIEWER)")
@pytest.mark.parametrize("source", ["gpu", "cpu"])
def test_render_equals_the_png(monkey, cli, tmp_path, source):
    from PIL import Image

    fur = monkey.fur(hairs=8000)
    image = render(monkey, "walk", fur=fur, frame=3, size=(192, 108), hair_source=source,
                   skin_color=(0.5, 0.4, 0.3))
    assert image.shape == (108, 192, 3) and image.dtype == np.uint8
    cli("render", "--clip", "walk", "--hairs", 8000, "--frames", 3, "--size", "192x108",
        "--hair-source", source, "--skin-color", 0.5, 0.4, 0.3, "--out", tmp_path)
    png = np.asarray(Image.open(tmp_path / "frame_00003.png").convert("RGB"))
    np.testing.assert_array_equal(image, png)
    # A creature is in the picture: the centre differs from the background corner.
    assert np.abs(image[54, 96].astype(int) - image[2, 2].astype(int)).sum() > 30


@pytest.mark.skipif(render is None, reason="built without the renderer (PELAGE_BUILD_VIEWER)")
def test_render_look_options_match_the_command_line(monkey, cli, tmp_path):
    from PIL import Image

    fur = monkey.fur(hairs=8000)
    look = dict(shading="marschner", self_shadowing=False, light=(-120, 30))
    image = render(monkey, "walk", fur=fur, frame=3, size=(192, 108), **look)
    cli("render", "--clip", "walk", "--hairs", 8000, "--frames", 3, "--size", "192x108",
        "--shading", "marschner", "--self-shadowing", "off", "--light", -120, 30, "--out",
        tmp_path)
    png = np.asarray(Image.open(tmp_path / "frame_00003.png").convert("RGB"))
    np.testing.assert_array_equal(image, png)
    # The fur's own shadow takes light away: the default (self-shadowed) frame is darker.
    shadowed = render(monkey, "walk", fur=fur, frame=3, size=(192, 108), shading="marschner",
                      light=(-120, 30))
    assert shadowed.astype(int).sum() < image.astype(int).sum()
    with pytest.raises(ValueError, match=r"light.*elevation 95 is out of range \[-90, 90\]"):
        render(monkey, "walk", fur=fur, frame=3, size=(192, 108), light=(0, 95))


@pytest.mark.skipif(render is None, reason="built without the renderer (PELAGE_BUILD_VIEWER)")
def test_render_light_parts_match_the_command_line(monkey, cli, tmp_path):
    from PIL import Image

    fur = monkey.fur(hairs=6000)
    common = dict(fur=fur, frame=3, size=(160, 90), background="transparent")
    key = render(monkey, "walk", light_color=(1.2, 1.0, 0.8), ambient=0, **common)
    cli("render", "--clip", "walk", "--hairs", 6000, "--frames", 3, "--size", "160x90",
        "--background", "transparent", "--light-color", 1.2, 1.0, 0.8, "--ambient", 0, "--out",
        tmp_path)
    png = np.asarray(Image.open(tmp_path / "frame_00003.png"))
    np.testing.assert_array_equal(key, png)
    # The frame lit by both is, in linear light, the key light's part plus the ambient's.
    ambient = render(monkey, "walk", light_color=0, ambient=0.35, **common)
    both = render(monkey, "walk", light_color=(1.2, 1.0, 0.8), ambient=0.35, **common)

    def linear(rgba):
        c = rgba[..., :3] / 255.0
        lin = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
        return lin * (rgba[..., 3:] / 255.0)

    parts = linear(key) + linear(ambient)
    assert linear(key).sum() > 0.2 * linear(both).sum()
    assert np.abs(linear(both) - parts).mean() < 0.002
    with pytest.raises(ValueError, match=r"ambient.*out of range \[0, 16\]"):
        render(monkey, "walk", ambient=(0.3, 0.3, 17), **common)
    with pytest.raises(ValueError, match=r"light_color: one intensity or three values"):
        render(monkey, "walk", light_color=(1, 1), **common)


def _files(directory):
    return sorted(os.listdir(directory))


@pytest.mark.parametrize("fmt", ["ply", "glb"])
def test_export_equals_the_command_line(monkey, cli, tmp_path, fmt):
    fur = monkey.fur(hairs=3000)
    py_dir, cli_dir = tmp_path / "py", tmp_path / "cli"
    files = pelage.export(monkey, "walk", fur=fur, frames=(2, 4), format=fmt, out=str(py_dir))
    assert [os.path.basename(f) for f in files] == [f"frame_0000{i}.{fmt}" for i in (2, 3, 4)]
    cli("export", "--clip", "walk", "--hairs", 3000, "--frames", "2:4", "--format", fmt, "--out",
        cli_dir)
    assert _files(py_dir) == _files(cli_dir)
    for name in _files(py_dir):
        assert (py_dir / name).read_bytes() == (cli_dir / name).read_bytes(), name
    # Resume keeps the complete frames and writes none again.
    assert pelage.export(monkey, "walk", fur=fur, frames=(2, 4), format=fmt, out=str(py_dir),
                         resume=True) == []


@pytest.mark.skipif(render is None, reason="built without the renderer (PELAGE_BUILD_VIEWER)")
def test_render_background_colour_and_transparent(monkey, cli, tmp_path):
    from PIL import Image

    fur = monkey.fur(hairs=4000)
    rgba = render(monkey, "walk", fur=fur, frame=2, size=(160, 90), background="transparent")
    assert rgba.shape == (90, 160, 4)
    assert rgba[0, 0, 3] == 0 and rgba[45, 80, 3] == 255
    cli("render", "--clip", "walk", "--hairs", 4000, "--frames", 2, "--size", "160x90",
        "--background", "transparent", "--out", tmp_path)
    png = np.asarray(Image.open(tmp_path / "frame_00002.png"))
    np.testing.assert_array_equal(rgba, png)
    green = render(monkey, "walk", fur=fur, frame=2, size=(160, 90), background=(0.0, 1.0, 0.0))
    np.testing.assert_array_equal(green[0, 0], [0, 255, 0])
    with pytest.raises(ValueError, match="background"):
        render(monkey, "walk", fur=fur, size=(32, 32), background="clear")
