#!/usr/bin/python3
"""Measures a pelage frame against its path-traced reference (scripts/reference-render.sh).

Both images have straight alpha (pelage: `--background transparent`; Cycles: film transparent)
and are composited over the same background colour. Over the creature's pixels (either image's
alpha above half):
- MAE: the mean absolute difference of the 8-bit sRGB channels (/255);
- luminance: the mean Rec. 709 luminance of the 8-bit sRGB values, and pelage's relative to the
  reference's;
- detail: scripts/fine-detail.py's fine detail (the mean 3 x 3 standard deviation of luminance
  inside the creature, where alpha is 255);
- Laplacian spread: the standard deviation of the luminance's 4-neighbour Laplacian over the
  pixels wholly inside the creature;
- coverage: the creature's pixels in each image.
Writes the figures as JSON and a side-by-side PNG: pelage | reference | |difference| x 4.

usage: compare.py PELAGE.png REFERENCE.png --background R G B (sRGB 0-1) --json OUT.json
                  [--side-by-side OUT.png]
Needs numpy and ffmpeg (no imaging library).
"""
import argparse
import importlib.util
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
_spec = importlib.util.spec_from_file_location(
    "fine_detail", os.path.join(HERE, "..", "fine-detail.py"))
fine_detail_module = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(fine_detail_module)
read_rgba = fine_detail_module.read_rgba
fine_detail = fine_detail_module.fine_detail

LUMA = np.array([0.2126, 0.7152, 0.0722])


def srgb_to_linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c):
    c = np.clip(c, 0.0, 1.0)
    return np.where(c <= 0.0031308, c * 12.92, 1.055 * c ** (1 / 2.4) - 0.055)


def over(rgba, background):
    """Straight-alpha sRGB8 over an sRGB background, blended in linear light: sRGB floats 0-255."""
    a = rgba[..., 3:4].astype(np.float64) / 255.0
    fg = srgb_to_linear(rgba[..., :3].astype(np.float64) / 255.0)
    bg = srgb_to_linear(np.asarray(background, np.float64))
    return 255.0 * linear_to_srgb(fg * a + bg * (1.0 - a))


def laplacian_spread(lum, inside):
    lap = (4 * lum[1:-1, 1:-1] - lum[:-2, 1:-1] - lum[2:, 1:-1] - lum[1:-1, :-2]
           - lum[1:-1, 2:])
    core = inside[1:-1, 1:-1] & inside[:-2, 1:-1] & inside[2:, 1:-1] & inside[1:-1, :-2] \
        & inside[1:-1, 2:]
    if not core.any():
        raise ValueError("no pixel lies wholly inside the creature")
    return float(lap[core].std())


def measure(pelage, reference, background):
    if pelage.shape != reference.shape:
        raise ValueError("the images differ in size: %s and %s" % (pelage.shape, reference.shape))
    a, b = over(pelage, background), over(reference, background)
    mask = (pelage[..., 3] > 127) | (reference[..., 3] > 127)
    if not mask.any():
        raise ValueError("neither image shows the creature")
    la, lb = a @ LUMA, b @ LUMA
    out = {
        "pixels": int(mask.sum()),
        "pelage_coverage": int((pelage[..., 3] > 127).sum()),
        "reference_coverage": int((reference[..., 3] > 127).sum()),
        "mae": float(np.abs(a - b)[mask].mean()),
        "luminance": float(la[mask].mean()),
        "reference_luminance": float(lb[mask].mean()),
    }
    out["luminance_ratio"] = out["luminance"] / out["reference_luminance"]
    out["detail"] = fine_detail(pelage)[0]
    out["reference_detail"] = fine_detail(reference)[0]
    out["detail_ratio"] = out["detail"] / out["reference_detail"]
    out["laplacian"] = laplacian_spread(la, pelage[..., 3] == 255)
    out["reference_laplacian"] = laplacian_spread(lb, reference[..., 3] == 255)
    out["laplacian_ratio"] = out["laplacian"] / out["reference_laplacian"]
    return out, a, b


def write_png(path, rgb):
    """Writes an RGB8 image as a PNG, atomically (a temporary file renamed)."""
    h, w, _ = rgb.shape
    tmp = path + ".tmp.png"
    subprocess.run(
        ["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
         "%dx%d" % (w, h), "-i", "-", "-frames:v", "1", tmp],
        input=np.ascontiguousarray(rgb).tobytes(), check=True)
    os.replace(tmp, path)


def write_side_by_side(path, a, b):
    """pelage's frame, the reference and 4 x their difference, side by side (measure's a, b)."""
    diff = np.clip(4.0 * np.abs(a - b), 0, 255)
    write_png(path, np.round(np.concatenate([a, b, diff], axis=1)).astype(np.uint8))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.strip().splitlines()[0])
    parser.add_argument("pelage")
    parser.add_argument("reference")
    parser.add_argument("--background", nargs=3, type=float, required=True)
    parser.add_argument("--json", required=True)
    parser.add_argument("--side-by-side")
    args = parser.parse_args(argv)
    if not all(0.0 <= c <= 1.0 for c in args.background):
        parser.error("--background: each of R G B in [0, 1]")
    try:
        figures, a, b = measure(read_rgba(args.pelage), read_rgba(args.reference),
                                args.background)
    except (ValueError, subprocess.CalledProcessError) as e:
        print("compare: error: %s" % e, file=sys.stderr)
        return 1
    tmp = args.json + ".tmp"
    with open(tmp, "w") as f:
        json.dump(figures, f, indent=1)
        f.write("\n")
    os.replace(tmp, args.json)
    if args.side_by_side:
        write_side_by_side(args.side_by_side, a, b)
    print("MAE %.1f/255, luminance %.1f vs %.1f (%+.1f %%), detail %.2f vs %.2f (%.0f %%), "
          "Laplacian spread %.2f vs %.2f (%.0f %%), %d px" % (
              figures["mae"], figures["luminance"], figures["reference_luminance"],
              100 * (figures["luminance_ratio"] - 1), figures["detail"],
              figures["reference_detail"], 100 * figures["detail_ratio"], figures["laplacian"],
              figures["reference_laplacian"], 100 * figures["laplacian_ratio"], figures["pixels"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
