"""scripts/fine-detail.py, the fine-detail and fringe measures, on PNGs of known content."""

import importlib.util
import os
import shutil
import subprocess

import numpy as np
import pytest

SOURCE = os.environ.get("PELAGE_SOURCE_DIR",
                        os.path.join(os.path.dirname(__file__), "..", ".."))
pytestmark = pytest.mark.skipif(shutil.which("ffmpeg") is None, reason="needs ffmpeg")


def _module():
    spec = importlib.util.spec_from_file_location(
        "fine_detail", os.path.join(SOURCE, "scripts", "fine-detail.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _png(path, rgba):
    h, w, _ = rgba.shape
    subprocess.run(["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgba", "-s",
                    f"{w}x{h}", "-i", "-", str(path)], input=rgba.tobytes(), check=True)


def test_stripes_flat_and_transparent(tmp_path):
    fd = _module()
    # Alternating black and white columns: every 3 x 3 window holds 3 of one and 6 of the other,
    # std = 255 sqrt(1/3 * 2/3); the image decodes back exactly.
    stripes = np.zeros((6, 9, 4), np.uint8)
    stripes[:, 1::2, :3] = 255
    stripes[..., 3] = 255
    _png(tmp_path / "stripes.png", stripes)
    assert np.array_equal(fd.read_rgba(str(tmp_path / "stripes.png")), stripes)
    detail, windows = fd.fine_detail(stripes)
    assert windows == 4 * 7
    assert detail == pytest.approx(255 * np.sqrt(2) / 3, rel=1e-12)
    # A transparent border is left out: only windows wholly inside alpha 255 count.
    flat = np.full((8, 8, 4), 90, np.uint8)
    flat[..., 3] = 0
    flat[2:6, 2:6, 3] = 255
    assert fd.fine_detail(flat) == (0.0, 4)
    # The fringe: the partly covered pixels against the opaque ones.
    flat[1, 2:6, 3] = 128
    flat[6, 2:4, 3] = 1
    assert fd.fringe(flat) == (6, 6 / 16)
    flat[..., 3] = 0
    with pytest.raises(ValueError, match="no 3 x 3 window"):
        fd.fine_detail(flat)
    with pytest.raises(ValueError, match="no opaque pixel"):
        fd.fringe(flat)
    # The command line: one line per frame; exit 1 and a message for a file that is not a PNG.
    script = os.path.join(SOURCE, "scripts", "fine-detail.py")
    out = subprocess.run(["/usr/bin/python3", script, str(tmp_path / "stripes.png")],
                         capture_output=True, text=True, check=True).stdout
    assert "fine detail 120.21" in out and "fringe 0 pixels (0.00 % of the opaque ones)" in out
    (tmp_path / "bad.png").write_text("not a png")
    bad = subprocess.run(["/usr/bin/python3", script, str(tmp_path / "bad.png")],
                         capture_output=True, text=True)
    assert bad.returncode == 1 and "bad.png" in bad.stderr
