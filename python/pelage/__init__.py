"""pelage: animated furred creatures with the fur model of Van Gelder & Wilhelms (1997).

    import pelage
    monkey = pelage.load("monkey")
    fur = monkey.fur("default", hairs=50000, overcoat={"stiffness": 0.6})
    hairs = fur.hairs(clip="walk", time=0.5)
    hairs.points        # (n, P, 3) float32, a view of pelage's buffer

The package is a thin client of pelage's C++ libraries (built with pybind11): every frame is
played by the same frame owner as the command line's, so results equal `pelage hair`, `pelage
analyze`, `pelage render` and `pelage export` for the same inputs. Hair arrays are numpy views of
pelage's buffers (no copy); the GIL is released while pelage computes.
"""

from ._pelage import (  # noqa: F401
    Fur,
    FrameIterator,
    Hairs,
    InputError,
    Model,
    __version__,
    analyze,
    export,
    load,
    set_threads,
    threads,
)

try:  # the renderer is built with the viewer (PELAGE_BUILD_VIEWER)
    from ._pelage import render  # noqa: F401
except ImportError:  # pragma: no cover
    pass

__all__ = ["load", "analyze", "render", "export", "set_threads", "threads", "Model", "Fur",
           "Hairs", "FrameIterator", "InputError"]
