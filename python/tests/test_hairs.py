"""Hairs from Python equal `pelage hair`'s PLY; arrays are views of pelage's buffers; results do not
depend on the thread count; the GIL is released while a frame computes."""

import gc
import math
import threading
import time

import numpy as np
import pytest

import pelage
from conftest import bits, read_hair_ply

HAIRS = 20000


def _flat(hairs):
    """Both coats' points and normals as (N, 3) rows in the PLY's order."""
    p = hairs.points.reshape(-1, 3)
    n = hairs.normals.reshape(-1, 3)
    return p, n


def test_clumped_and_frizzed_hairs_equal_the_command_line(monkey, cli, tmp_path):
    # Clumping and frizz (README: Clumping, Frizz) reach Python's arrays and the PLY export alike;
    # the roots stay where the plain coat has them, and the tips gather.
    clump = {"density": 1.0, "strength": 0.6, "radius": 10}
    fur = monkey.fur("default", hairs=HAIRS, overcoat={"clump": clump, "frizz": {"amplitude": 1}})
    hairs = fur.hairs(clip="walk", time=0.5)
    out = tmp_path / "hair.ply"
    cli("hair", "--hairs", HAIRS, "--fur-set", "overcoat.clump.density=1",
        "overcoat.clump.strength=0.6", "overcoat.clump.radius=10", "overcoat.frizz.amplitude=1",
        "--clip", "walk", "--time", 0.5, "--out", out)
    ply = read_hair_ply(out)
    points, _ = _flat(hairs)
    np.testing.assert_array_equal(bits(points), bits(np.stack([ply["x"], ply["y"], ply["z"]], 1)))
    plain = monkey.fur("default", hairs=HAIRS).hairs(clip="walk", time=0.5)
    np.testing.assert_array_equal(bits(hairs.points[:, 0]), bits(plain.points[:, 0]))
    assert fur.params["overcoat"]["clump"]["density"] == 1.0
    over = hairs.coat == 0
    moved = np.linalg.norm(hairs.points[over, -1] - plain.points[over, -1], axis=1)
    assert np.mean(moved > 1e-4) > 0.8  # most overcoat tips moved
    np.testing.assert_array_equal(bits(hairs.points[~over]), bits(plain.points[~over]))


@pytest.mark.parametrize("style", ["polyline", "tube"])
def test_hairs_equal_the_command_line(monkey, cli, tmp_path, style):
    fur = monkey.fur("default", hairs=HAIRS, overcoat={"stiffness": 0.6, "style": style},
                     undercoat={"style": style})
    hairs = fur.hairs(clip="walk", time=0.5)
    out = tmp_path / "hair.ply"
    cli("hair", "--hairs", HAIRS, "--fur-set", "overcoat.stiffness=0.6",
        f"overcoat.style={style}", f"undercoat.style={style}", "--clip", "walk", "--time", 0.5,
        "--out", out)
    ply = read_hair_ply(out)
    points, normals = _flat(hairs)
    assert len(ply) == points.shape[0] > 0
    np.testing.assert_array_equal(bits(points), bits(np.stack([ply["x"], ply["y"], ply["z"]], 1)))
    np.testing.assert_array_equal(bits(normals),
                                  bits(np.stack([ply["nx"], ply["ny"], ply["nz"]], 1)))
    P = hairs.points.shape[1]
    np.testing.assert_array_equal(np.repeat(hairs.hair, P), ply["hair"])
    np.testing.assert_array_equal(np.repeat(hairs.coat, P), ply["coat"])
    assert hairs.styles == (style, style)
    # Colours: the PLY's root and tip points carry the hairs' root and tip colours (8-bit sRGB;
    # the monkey's creature colours vary from hair to hair).
    rgb = np.stack([ply["red"], ply["green"], ply["blue"]], 1).reshape(len(hairs), P, 3)
    assert hairs.colors.shape == (len(hairs), 2, 3) and hairs.colors.dtype == np.uint8
    np.testing.assert_array_equal(hairs.colors[:, 0], rgb[:, 0])
    np.testing.assert_array_equal(hairs.colors[:, 1], rgb[:, -1])
    assert len(np.unique(hairs.colors[:, 0], axis=0)) > 100


def test_dynamic_hairs_equal_the_command_line(monkey, cli, tmp_path):
    fur = monkey.fur(hairs=5000)
    dyn = {"frequency": [6.0, 10.0], "damping": 0.2}
    hairs = fur.hairs(clip="tumble", time=0.4, dynamics=dyn)
    out = tmp_path / "dyn.ply"
    cli("hair", "--hairs", 5000, "--clip", "tumble", "--time", 0.4, "--dynamics", "on",
        "--frequency", 6, 10, "--damping", 0.2, "--out", out)
    ply = read_hair_ply(out)
    points, _ = _flat(hairs)
    np.testing.assert_array_equal(bits(points), bits(np.stack([ply["x"], ply["y"], ply["z"]], 1)))
    assert hairs.frame == 12 and hairs.time == pytest.approx(0.4)
    # The springs moved the ends: the quasi-static frame differs.
    still = fur.hairs(clip="tumble", time=0.4)
    assert not np.array_equal(still.points, hairs.points)


def test_frames_step_dynamics_in_order(monkey):
    fur = monkey.fur(hairs=3000)
    frames = list(fur.frames("shake", fps=30, frames=range(0, 9), dynamics=True))
    assert [h.frame for h in frames] == list(range(9))
    assert [h.time for h in frames] == pytest.approx([f / 30 for f in range(9)])
    # Each frame is the one a single call computes from the clip's start (springs stepped in order).
    for f in (0, 4, 8):
        one = fur.hairs(clip="shake", time=f / 30, dynamics=True)
        np.testing.assert_array_equal(bits(frames[f].points), bits(one.points))
    # Frames kept from the iterator are distinct buffers (the iterator does not overwrite them).
    assert not np.array_equal(frames[1].points, frames[8].points)


def test_arrays_are_views_that_outlive_the_fur(monkey):
    fur = monkey.fur(hairs=4000)
    hairs = fur.hairs(clip="walk", time=0.25)
    points = hairs.points
    assert not points.flags.owndata and points.base is not None
    assert points.dtype == np.float32 and points.ndim == 3 and points.shape[2] == 3
    # No copy: every access and the overcoat's own view share one buffer, and the undercoat's view
    # starts right after the overcoat's hairs.
    address = points.__array_interface__["data"][0]
    assert hairs.points.__array_interface__["data"][0] == address
    over, under = hairs.coat_points(0), hairs.coat_points(1)
    assert over.__array_interface__["data"][0] == address
    assert under.__array_interface__["data"][0] == address + over.nbytes
    assert np.shares_memory(points, hairs.points)
    assert len(over) == int(np.sum(hairs.coat == 0)) and len(under) == int(np.sum(hairs.coat == 1))
    saved = {k: np.array(getattr(hairs, k)) for k in ("points", "normals", "coat", "hair",
                                                       "triangle", "barycentric")}
    views = {k: getattr(hairs, k) for k in saved}
    del fur, hairs, over, under
    gc.collect()
    monkey.fur(hairs=4000).hairs(clip="walk", time=0.75)  # reuse freed memory if it was freed
    for k, v in views.items():
        np.testing.assert_array_equal(v, saved[k])


def test_roots_are_on_their_triangles(monkey):
    hairs = monkey.fur(hairs=3000).hairs()
    positions, _, triangles = monkey.skin()
    b = hairs.barycentric
    assert np.all(b >= -1e-6) and np.allclose(b.sum(1), 1.0, atol=1e-5)
    corners = positions[triangles[hairs.triangle]]  # (n, 3 corners, 3)
    roots = np.einsum("nc,ncx->nx", b, corners)
    np.testing.assert_allclose(hairs.points[:, 0, :], roots, atol=1e-5)


@pytest.mark.parametrize("threads", [1, 2, 3])
def test_same_hairs_for_any_thread_count(monkey, threads):
    fur = monkey.fur(hairs=20000, overcoat={"style": "curve"})
    pelage.set_threads(0)
    reference = fur.hairs(clip="tumble", time=1.1, dynamics=True)
    pelage.set_threads(threads)
    try:
        assert pelage.threads() == threads
        other = fur.hairs(clip="tumble", time=1.1, dynamics=True)
    finally:
        pelage.set_threads(0)
    np.testing.assert_array_equal(bits(reference.points), bits(other.points))
    np.testing.assert_array_equal(bits(reference.normals), bits(other.normals))


def test_the_gil_is_released_while_a_frame_computes(monkey):
    fur = monkey.fur(hairs=200000)
    # Dynamic fur simulates every frame from the clip's start: the clip time sets the call's length.
    # Long enough on any machine: about 0.6 s, scaled from one call's time at 1 s.
    start = time.perf_counter()
    fur.hairs(clip="tumble", time=1.0, dynamics=True)
    clip_time = min(1000.0, max(1.0, math.ceil(0.6 / (time.perf_counter() - start))))
    done = threading.Event()
    result = {}

    def work():
        start = time.perf_counter()
        result["hairs"] = fur.hairs(clip="tumble", time=clip_time, dynamics=True)
        result["seconds"] = time.perf_counter() - start
        done.set()

    # While the worker is inside pelage, this thread keeps running: the longest gap between two
    # of its iterations stays far below the call's duration (a held GIL would stall it throughout).
    worker = threading.Thread(target=work)
    ticks = 0
    longest = 0.0
    last = time.perf_counter()
    worker.start()
    while not done.is_set():
        now = time.perf_counter()
        longest = max(longest, now - last)
        last = now
        ticks += 1
    worker.join()
    assert result["seconds"] > 0.2, ("the frame was too quick to tell", clip_time)
    assert longest < result["seconds"] / 4, (longest, result["seconds"])
    assert ticks > 1000
