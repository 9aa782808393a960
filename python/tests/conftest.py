"""Shared fixtures: the pelage CLI next to the package (PELAGE_BIN, set by CTest), the built-in
monkey, and readers for the files the CLI writes."""

import os
import shutil
import subprocess

import numpy as np
import pytest

import pelage


def _cli():
    path = os.environ.get("PELAGE_BIN") or shutil.which("pelage")
    if not path or not os.path.exists(path):
        pytest.skip("the pelage command line is not built (set PELAGE_BIN)")
    return path


@pytest.fixture(scope="session")
def cli():
    """Runs `pelage ARGS...` (with --quiet unless quiet=False) and returns its completed process
    (checked)."""
    path = _cli()

    def run(*args, quiet=True):
        extra = ["--quiet"] if quiet else []
        return subprocess.run([path, *map(str, args), *extra], check=True, capture_output=True,
                              text=True)

    return run


@pytest.fixture(scope="session")
def monkey():
    return pelage.load("monkey")


def read_hair_ply(path):
    """The vertex element of a hair PLY (fur/hair_ply.h): a structured array with x, y, z, nx, ny,
    nz (float32), hair (int32), coat (uint8) and, when written, red, green, blue (uint8)."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    assert header[1] == "format binary_little_endian 1.0"
    count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    types = {"float": "<f4", "int": "<i4", "uchar": "u1"}
    fields, in_vertex = [], False
    for line in header:
        words = line.split()
        if words[0] == "element":
            in_vertex = words[1] == "vertex"
        elif words[0] == "property" and in_vertex:
            fields.append((words[2], types[words[1]]))
    vertex = np.dtype(fields)
    return np.frombuffer(data, dtype=vertex, count=count, offset=end)


def read_csv_columns(path):
    """A CSV file with a header row as a dict of float columns."""
    with open(path) as f:
        names = f.readline().strip().split(",")
    table = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: table[:, i] for i, name in enumerate(names)}


def bits(a):
    """The bit patterns of a float32 array (compares NaNs and signed zeros exactly)."""
    return np.ascontiguousarray(a).view(np.uint32)
