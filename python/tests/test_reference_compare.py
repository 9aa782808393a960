"""scripts/reference/compare.py, pelage's frame against a path-traced reference, on images of
known content: exact figures on a tiny pair, and the reference's Monte Carlo noise measured and
taken out of its detail from two independent renders (a statistical test on a known texture)."""

import importlib.util
import json
import os
import shutil
import subprocess

import numpy as np
import pytest

SOURCE = os.environ.get("PELAGE_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
SCRIPT = os.path.join(SOURCE, "scripts", "reference", "compare.py")
BACKGROUND = (0.80, 0.82, 0.86)
pytestmark = pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="needs ffmpeg")


def _module():
    spec = importlib.util.spec_from_file_location("compare", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _opaque(grey):
    """An opaque RGBA8 image of grey levels (H x W)."""
    out = np.empty(grey.shape + (4,), np.uint8)
    out[..., :3] = np.clip(np.round(grey), 0, 255).astype(np.uint8)[..., None]
    out[..., 3] = 255
    return out


def _png(path, rgba):
    h, w, _ = rgba.shape
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgba", "-s",
                    f"{w}x{h}", "-i", "-", str(path)], input=rgba.tobytes(), check=True)


def test_one_reference_exact():
    compare = _module()
    # Vertical stripes of 50 and 150; the reference is the same stripes 10 levels brighter.
    stripes = np.where(np.arange(8) % 2 == 0, 50.0, 150.0)[None, :].repeat(6, axis=0)
    pelage, reference = _opaque(stripes), _opaque(stripes + 10)
    figures, a, b = compare.measure(pelage, [reference], BACKGROUND)
    assert figures["pixels"] == 48
    assert figures["mae"] == pytest.approx(10.0, abs=1e-9)
    assert figures["luminance_ratio"] == pytest.approx(100.0 / 110.0, rel=1e-9)
    # The same texture: detail and Laplacian spread alike, and the reference's detail is
    # fine-detail.py's own figure of it.
    assert figures["detail_ratio"] == pytest.approx(1.0, abs=1e-9)
    assert figures["laplacian_ratio"] == pytest.approx(1.0, abs=1e-9)
    assert figures["reference_detail"] == pytest.approx(compare.fine_detail(reference)[0])
    assert "reference_noise" not in figures
    assert np.abs(b - a).max() == pytest.approx(10.0, abs=1e-9)
    with pytest.raises(ValueError, match="differ in size"):
        compare.measure(pelage, [reference[:, :7]], BACKGROUND)
    # A flat reference has no detail to compare with: a message, not a division by zero.
    flat = _opaque(np.full((6, 8), 120.0))
    for references in ([flat], [flat, flat]):
        with pytest.raises(ValueError, match="no detail"):
            compare.measure(pelage, references, BACKGROUND)


def test_two_references_mean_in_linear_light():
    compare = _module()
    first = np.zeros((4, 4, 4), np.uint8)
    second = np.zeros((4, 4, 4), np.uint8)
    first[...] = (200, 100, 50, 255)
    second[...] = (0, 0, 0, 255)
    second[0, 0] = (9, 9, 9, 0)  # transparent: the mean there is first's colour at half alpha
    mean = compare.mean_reference([first, second])
    assert mean[0, 0, :3] == pytest.approx([200, 100, 50], abs=1e-9)
    assert mean[0, 0, 3] == pytest.approx(127.5)
    # Elsewhere half of 200's linear value, not 100: the mean is taken in linear light.
    half = 255 * compare.linear_to_srgb(compare.srgb_to_linear(200 / 255) / 2)
    assert mean[1, 1, 0] == pytest.approx(half, abs=1e-9)
    assert mean[1, 1, 0] > 140


def test_reference_noise_is_taken_out_of_its_detail():
    compare = _module()
    rng = np.random.default_rng(29)
    # A known fur-like texture: grey levels 90-150 in 2 x 2 blocks.
    truth = np.kron(rng.uniform(90, 150, (48, 48)), np.ones((2, 2)))
    # Two renders of it with independent noise of 8 levels (a path tracer's, at few samples).
    renders = [_opaque(truth + rng.normal(0, 8, truth.shape)) for _ in range(2)]
    figures, _, _ = compare.measure(_opaque(truth), renders, BACKGROUND)
    # The noise inflates the mean's Laplacian spread and detail; without it they are the
    # truth's (pelage here draws the truth itself): within 3 %.
    assert figures["reference_laplacian_with_noise"] > 1.05 * figures["laplacian"]
    assert figures["reference_detail_with_noise"] > 1.02 * figures["detail"]
    assert figures["laplacian_ratio"] == pytest.approx(1.0, abs=0.03)
    assert figures["detail_ratio"] == pytest.approx(1.0, abs=0.03)
    # The mean's noise: N(0, 8 / sqrt 2) per channel, mean |.| = 8 / sqrt(pi) = 4.51; the
    # truth's MAE against the mean is that floor.
    assert figures["reference_noise"] == pytest.approx(8 / np.sqrt(np.pi), rel=0.05)
    assert figures["mae"] == pytest.approx(figures["reference_noise"], rel=0.05)
    # One render alone keeps its noise in its detail.
    one, _, _ = compare.measure(_opaque(truth), renders[:1], BACKGROUND)
    assert one["laplacian_ratio"] < 0.95


def test_where_the_error_lies():
    compare = _module()
    # 16 x 16 pixels: a 12 x 12 interior (pixels 2-13) of stripes 110 / 130 inside a 2-pixel
    # fringe of half coverage.
    reference = _opaque(np.where(np.arange(16) % 2 == 0, 110.0, 130.0)[None, :].repeat(16, 0))
    reference[:2], reference[-2:], reference[:, :2], reference[:, -2:] = 4 * [(100, 100, 100, 128)]
    # pelage: the interior in a checkerboard of +-6 about the reference's (strand-scale grain,
    # no shading difference), the fringe the same.
    pelage = reference.copy()
    checker = np.where((np.arange(16)[:, None] + np.arange(16)[None, :]) % 2 == 0, 6, -6)
    pelage[2:14, 2:14, :3] = (reference[2:14, 2:14, :3]
                              + checker[2:14, 2:14, None]).astype(np.uint8)
    figures, _, _ = compare.measure(pelage, [reference], BACKGROUND)
    assert figures["mae_interior"] == pytest.approx(6.0, abs=1e-9)
    assert figures["mae_fringe"] == pytest.approx(0.0, abs=1e-9)
    assert figures["fringe_luminance_ratio"] == pytest.approx(1.0, abs=1e-12)
    # Averaged over 2 x 2 and 4 x 4 blocks the grain is gone; no 8 x 8 block lies inside.
    assert figures["mae_block2"] == pytest.approx(0.0, abs=1e-9)
    assert figures["mae_block4"] == pytest.approx(0.0, abs=1e-9)
    assert figures["mae_block8"] is None
    # A shading difference (the interior 5 levels brighter) stays at every scale; a darker
    # fringe shows as the fringe's error and luminance, and the whole MAE is the two's mix.
    pelage = reference.copy()
    pelage[2:14, 2:14, :3] += 5
    pelage[:2, :, :3] = 80
    figures, a, b = compare.measure(pelage, [reference], BACKGROUND)
    for key in ("mae_interior", "mae_block2", "mae_block4"):
        assert figures[key] == pytest.approx(5.0, abs=1e-9), key
    fringe_rows = np.abs(a - b)[:2]
    assert figures["mae_fringe"] == pytest.approx(fringe_rows.mean() * 32 / (256 - 144), rel=1e-9)
    assert figures["fringe_luminance_ratio"] < 1.0
    assert figures["mae"] * 256 == pytest.approx(
        figures["mae_interior"] * 144 + figures["mae_fringe"] * 112, rel=1e-9)


def test_luminance_and_colour_apart():
    compare = _module()
    rng = np.random.default_rng(3)
    reference = _opaque(rng.uniform(60, 200, (12, 12)))
    reference[..., 0] = np.clip(reference[..., 0].astype(float) * 1.2, 0, 255).astype(np.uint8)
    # pelage: the reference at 0.8 of its brightness, its colour kept: all of the interior's
    # error is luminance's, none colour's.
    pelage = reference.copy()
    pelage[..., :3] = np.round(reference[..., :3] * 0.8).astype(np.uint8)
    figures, a, b = compare.measure(pelage, [reference], BACKGROUND)
    ratio = ((a @ compare.LUMA) / (b @ compare.LUMA))[..., None]
    assert figures["mae_luminance_alone"] == pytest.approx(np.abs(b * ratio - b).mean(), rel=1e-12)
    assert figures["mae_luminance_alone"] == pytest.approx(figures["mae_interior"], rel=0.02)
    # (Only the 8-bit rounding of pelage's channels is left: at most 0.5 / 0.8 a channel.)
    assert figures["mae_colour_alone"] < 0.625
    assert figures["mae_colour_alone"] < 0.01 * figures["mae_luminance_alone"]
    # Red and blue swapped, scaled to the reference's luminance: the colour is all of the error.
    pelage = reference.copy()
    pelage[..., 0], pelage[..., 2] = reference[..., 2], reference[..., 0]
    figures, a, b = compare.measure(pelage, [reference], BACKGROUND)
    ratio = ((a @ compare.LUMA) / (b @ compare.LUMA))[..., None]
    assert figures["mae_colour_alone"] == pytest.approx(np.abs(a / ratio - b).mean(), rel=1e-12)
    assert figures["mae_colour_alone"] > 0.5 * figures["mae_interior"]
    assert figures["mae_luminance_alone"] < 0.5 * figures["mae_colour_alone"]


def test_command_line(tmp_path):
    rng = np.random.default_rng(7)
    truth = np.kron(rng.uniform(90, 150, (16, 16)), np.ones((2, 2)))
    paths = []
    for i, image in enumerate([_opaque(truth), _opaque(truth + 4), _opaque(truth - 4)]):
        paths.append(str(tmp_path / f"{i}.png"))
        _png(paths[-1], image)
    out = tmp_path / "figures.json"
    mean = tmp_path / "mean.png"
    run = subprocess.run(["/usr/bin/python3", SCRIPT, *paths, "--background", "0.8", "0.82",
                          "0.86", "--json", str(out), "--reference-mean", str(mean)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "the reference's own noise: 4.0/255" in run.stdout
    figures = json.loads(out.read_text())
    assert figures["reference_noise"] == pytest.approx(4.0, abs=0.01)
    written = _module().read_rgba(str(mean))
    assert written[..., 3].min() == 255
    assert np.abs(written[..., 0].astype(float) - np.round(truth)).max() <= 1
    # Three references, or the mean of one, are refused with a message and exit status 2.
    options = ["--background", "0.8", "0.82", "0.86", "--json", str(out)]
    for args in ([*paths, paths[0]], [*paths[:2], "--reference-mean", str(mean)]):
        bad = subprocess.run(["/usr/bin/python3", SCRIPT, *args, *options],
                             capture_output=True, text=True)
        assert bad.returncode == 2
        assert "reference" in bad.stderr.splitlines()[-1]
    # A file that is not an image: exit 1, the message names the problem, no figures written.
    (tmp_path / "bad.png").write_text("not a png")
    out.unlink()
    bad = subprocess.run(["/usr/bin/python3", SCRIPT, paths[0], str(tmp_path / "bad.png"),
                          "--background", "0.8", "0.82", "0.86", "--json", str(out)],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "compare: error" in bad.stderr
    assert not out.exists()
    # A missing file is named.
    bad = subprocess.run(["/usr/bin/python3", SCRIPT, paths[0], str(tmp_path / "missing.png"),
                          "--background", "0.8", "0.82", "0.86", "--json", str(out)],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "missing.png: no such file" in bad.stderr
    assert not out.exists()
