"""pelage.analyze equals `pelage analyze`'s CSV, column by column."""

import numpy as np
import pytest

import pelage
from conftest import read_csv_columns


def _assert_columns_equal(py, csv):
    assert list(py.keys()) == list(csv.keys())
    for name, column in csv.items():
        np.testing.assert_array_equal(py[name], column, err_msg=name)


def test_analyze_equals_the_csv(monkey, cli, tmp_path):
    fur = monkey.fur(hairs=4000)
    columns = pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 20), groups="segment")
    out = tmp_path / "a.csv"
    cli("analyze", "--clip", "tumble", "--hairs", 4000, "--frames", "0:20", "--groups", "segment",
        "--out", out)
    _assert_columns_equal(columns, read_csv_columns(out))
    assert columns["frame"].dtype == np.int64
    np.testing.assert_array_equal(columns["frame"], np.arange(21))


def test_dynamic_analysis_with_hold_equals_the_csv(monkey, cli, tmp_path):
    fur = monkey.fur(hairs=3000, overcoat={"stiffness": 0.4})
    columns = pelage.analyze(monkey, "shake", fur=fur, frames=range(5, 16),
                             dynamics={"frequency": 5.0, "damping": [0.3, 0.5]}, hold=0.2,
                             time=0.1)
    out = tmp_path / "d.csv"
    cli("analyze", "--clip", "shake", "--hairs", 3000, "--fur-set", "overcoat.stiffness=0.4",
        "--frames", "5:15", "--dynamics", "on", "--frequency", 5, "--damping", 0.3, 0.5,
        "--hold", 0.2, "--time", 0.1, "--out", out)
    _assert_columns_equal(columns, read_csv_columns(out))
    assert np.count_nonzero(columns["held"]) == 6  # 0.2 s at 30 fps after frame 15


def test_sweep_equals_the_csv(monkey, cli, tmp_path):
    fur = monkey.fur(hairs=2000)
    columns = pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 6), sweep="stiffness=0.2:0.8:3")
    out = tmp_path / "s.csv"
    cli("analyze", "--clip", "tumble", "--hairs", 2000, "--frames", "0:6", "--sweep",
        "stiffness=0.2:0.8:3", "--out", out)
    _assert_columns_equal(columns, read_csv_columns(out))
    droop = [c for c in columns if c.startswith("droop_mean_deg")]
    assert len(droop) == 3


def test_default_fur_and_whole_clip(monkey):
    columns = pelage.analyze(monkey, "walk")
    n = int(round(monkey.clips["walk"] * 30)) + 1
    assert all(len(c) == n for c in columns.values())
