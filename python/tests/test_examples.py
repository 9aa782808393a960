"""The examples run as a user runs them and write what they say."""

import os
import subprocess
import sys

import numpy as np

import pelage

EXAMPLES = os.path.join(os.path.dirname(__file__), "..", "examples")


def _run(script, *args, cwd):
    env = os.environ.copy()  # the package this test imported, wherever the test runs
    env["PYTHONPATH"] = os.path.dirname(os.path.dirname(os.path.abspath(pelage.__file__)))
    return subprocess.run([sys.executable, os.path.join(EXAMPLES, script), *args], cwd=cwd,
                          check=True, capture_output=True, text=True, env=env)


def test_stiffness_sweep_writes_its_plot(tmp_path):
    from PIL import Image

    r = _run("stiffness_sweep.py", "--hairs", "1500", "--values", "3", "--out", "s.png",
             cwd=tmp_path)
    droops = [float(line.split()[4]) for line in r.stdout.splitlines()
              if line.startswith("stiffness")]
    assert len(droops) == 3 and droops[0] > droops[1] > droops[2] > 0  # stiffer hairs droop less
    image = np.asarray(Image.open(tmp_path / "s.png").convert("RGB"))
    assert image.shape[0] > 300 and image.shape[1] > 800
    assert (image.std(axis=(0, 1)) > 10).all()  # not a blank image


def test_hairs_to_numpy_saves_the_frame(tmp_path):
    _run("hairs_to_numpy.py", "--hairs", "2000", "--out", "h.npz", cwd=tmp_path)
    saved = np.load(tmp_path / "h.npz")
    n = saved["points"].shape[0]
    assert n > 1500 and saved["points"].shape[2] == 3 and saved["points"].dtype == np.float32
    assert saved["barycentric"].shape == (n, 3) and saved["coat"].shape == (n,)
