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
    droop = [c for c in columns if c.startswith("qs_droop_mean_deg[")]
    assert droop == ["qs_droop_mean_deg[stiffness=0.2]", "qs_droop_mean_deg[stiffness=0.5]",
                     "qs_droop_mean_deg[stiffness=0.8]"]


def test_default_fur_and_whole_clip(monkey):
    columns = pelage.analyze(monkey, "walk")
    n = int(round(monkey.clips["walk"] * 30)) + 1
    assert all(len(c) == n for c in columns.values())


def test_values_are_the_librarys_not_six_digits(monkey):
    columns = pelage.analyze(monkey, "tumble", fur=monkey.fur(hairs=1500), frames=(0, 8))
    droop = columns["qs_droop_mean_deg"]
    assert droop.dtype == np.float64
    # Doubles as computed: rounding to 6 significant digits changes them.
    rounded = np.array([float("%.6g" % v) for v in droop])
    assert np.any(rounded != droop)


def test_sweep_as_a_dict_of_values_or_a_range(monkey):
    fur = monkey.fur(hairs=1500)
    text = pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 4), sweep="stiffness=0.2:0.8:3")
    listed = pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 4),
                            sweep={"stiffness": [0.2, 0.5, 0.8]})
    ranged = pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 4),
                            sweep={"stiffness": (0.2, 0.8, 3)})
    _assert_columns_equal(listed, text)
    _assert_columns_equal(ranged, text)
    with pytest.raises(ValueError, match="stiffness 1.5"):
        pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 4), sweep={"stiffness": [0.2, 1.5]})
    with pytest.raises(ValueError, match="one parameter"):
        pelage.analyze(monkey, "tumble", fur=fur, sweep={"stiffness": [0.2], "damping": [1.0]})


def test_dynamic_sweep_columns_are_prefixed_dyn(monkey):
    columns = pelage.analyze(monkey, "shake", fur=monkey.fur(hairs=1000), frames=(0, 3),
                             dynamics=True, sweep={"damping": [0.3, 0.9]})
    assert "dyn_droop_mean_deg[damping=0.3]" in columns
    assert "dyn_tip_height_mm[damping=0.9]" in columns
    assert not any(c.startswith("droop_mean_deg") for c in columns)


def test_frames_with_a_step_are_rows_of_the_whole_run(monkey):
    fur = monkey.fur(hairs=1500)
    whole = pelage.analyze(monkey, "walk", fur=fur, frames=(0, 25))
    stepped = pelage.analyze(monkey, "walk", fur=fur, frames=range(0, 30, 5))
    np.testing.assert_array_equal(stepped["frame"], [0, 5, 10, 15, 20, 25])
    for name, column in stepped.items():
        np.testing.assert_array_equal(column, whole[name][::5], err_msg=name)


def test_a_misspelt_keyword_lists_the_accepted_ones(monkey):
    with pytest.raises(ValueError, match=r"analyze\(\): unknown keyword 'frame'.*frames"):
        pelage.analyze(monkey, "walk", frame=3)
    with pytest.raises(ValueError, match=r"export\(\): unknown keyword 'fromat'.*format"):
        pelage.export(monkey, "walk", out="x", fromat="ply")


def test_plot_equals_the_command_lines(monkey, cli, tmp_path):
    fur = monkey.fur(hairs=2000)
    for name, extra_py, extra_cli in (("a", {}, []),
                                      ("s", {"sweep": "stiffness=0.2:0.8:3"},
                                       ["--sweep", "stiffness=0.2:0.8:3"])):
        plot = tmp_path / (name + "_py.png")
        pelage.analyze(monkey, "tumble", fur=fur, frames=(0, 6), plot=str(plot), **extra_py)
        cli("analyze", "--clip", "tumble", "--hairs", 2000, "--frames", "0:6", *extra_cli,
            "--out", tmp_path / (name + ".csv"), "--plot", tmp_path / (name + "_cli.png"))
        assert plot.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        assert plot.read_bytes() == (tmp_path / (name + "_cli.png")).read_bytes(), name


def test_a_plot_that_is_not_png_is_refused_before_the_run(monkey, tmp_path):
    with pytest.raises(pelage.InputError, match=r"plot '.*p\.jpg' must name a \.png file"):
        pelage.analyze(monkey, "tumble", fur=monkey.fur(hairs=500), frames=(0, 2),
                       plot=str(tmp_path / "p.jpg"))
    assert not (tmp_path / "p.jpg").exists()
