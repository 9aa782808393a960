"""Ctrl-C during a long call raises KeyboardInterrupt within half a second and leaves no partial
file; pelage's warnings go through Python's `warnings`."""

import _thread
import os
import threading
import time
import warnings

import pytest

import pelage


def test_export_stops_on_keyboard_interrupt(monkey, tmp_path):
    fur = monkey.fur(hairs=60000)
    out = tmp_path / "frames"
    state = {}

    def interrupt_soon():
        # Once the first frames are written, as a user presses Ctrl-C mid-run.
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (out / "frame_00001.ply").exists():
            time.sleep(0.002)
        state["at"] = time.monotonic()
        _thread.interrupt_main()

    t = threading.Thread(target=interrupt_soon)
    t.start()
    with pytest.raises(KeyboardInterrupt):
        pelage.export(monkey, "walk", fur=fur, frames=(0, 119), out=out)
    raised = time.monotonic()
    t.join()
    assert "at" in state
    assert raised - state["at"] < 0.5, f"KeyboardInterrupt came {raised - state['at']:.2f} s late"
    names = sorted(os.listdir(out))
    assert 2 <= len(names) < 120
    assert all(not n.startswith(".") for n in names), names  # no temporary (partial) file
    # Every file left is complete: --resume keeps them and writes the rest.
    written = pelage.export(monkey, "walk", fur=fur, frames=(0, 119), out=out, resume=True)
    assert len(written) == 120 - len(names)
    assert len(os.listdir(out)) == 120


def test_warnings_are_python_warnings(monkey):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        monkey.fur(hairs=100, overcoat={"stiffness": 1.0})
    messages = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    assert any("floppiness" in m for m in messages), messages
    # And a filter can make them errors, as for any Python warning.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="floppiness"):
            monkey.fur(hairs=100, overcoat={"stiffness": 1.0})


def test_docstrings_document_arguments_and_show_public_names():
    for f in (pelage.load, pelage.analyze, pelage.export, pelage.Model.fur, pelage.Fur.hairs,
              pelage.Fur.frames):
        assert "Args:" in f.__doc__ and "Returns:" in f.__doc__, f.__name__
    for f in (pelage.Fur.hairs, pelage.Fur.frames, pelage.Model.fur, pelage.load):
        assert "anonymous" not in f.__doc__ and "pelage::" not in f.__doc__, f.__doc__


def test_frames_iterator_with_a_step(monkey):
    fur = monkey.fur(hairs=500)
    got = [h.frame for h in fur.frames("walk", frames=range(0, 30, 5))]
    assert got == [0, 5, 10, 15, 20, 25]
