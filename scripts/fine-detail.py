#!/usr/bin/python3
"""The fine-detail and fringe measures of rendered fur frames (README: Frizz).

For each PNG rendered with `--background transparent`:
- fine detail: the mean, over the creature's 3 x 3 pixel windows that lie wholly inside it (alpha
  255), of the standard deviation of the window's luminance (Rec. 709 weights on the 8-bit sRGB
  values, 0-255). Velvet-smooth fur gives a low value, strands that stand apart a higher one;
- fringe: the pixels the creature covers only in part (0 < alpha < 255), the stray hairs around
  its silhouette, as a count and as a share of the opaque (alpha 255) pixels.
Decodes with ffmpeg (no imaging library needed); numpy only.

usage: scripts/fine-detail.py FRAME.png [FRAME.png ...]
"""
import subprocess
import sys

import numpy as np


def read_rgba(path):
    probe = subprocess.run(
        ["ffprobe", "-v", "error", "-select_streams", "v:0", "-show_entries",
         "stream=width,height", "-of", "csv=p=0", path],
        check=True, capture_output=True, text=True).stdout.strip()
    width, height = (int(x) for x in probe.split(",")[:2])
    raw = subprocess.run(
        ["ffmpeg", "-v", "error", "-i", path, "-f", "rawvideo", "-pix_fmt", "rgba", "-"],
        check=True, capture_output=True).stdout
    return np.frombuffer(raw, np.uint8).reshape(height, width, 4)


def window_variance(lum, inside):
    """The variance of `lum` in each 3 x 3 window, and which windows lie wholly `inside`."""
    h, w = lum.shape
    windows = np.stack([lum[dy:h - 2 + dy, dx:w - 2 + dx] for dy in range(3) for dx in range(3)])
    full = np.stack([inside[dy:h - 2 + dy, dx:w - 2 + dx]
                     for dy in range(3) for dx in range(3)]).all(axis=0)
    if not full.any():
        raise ValueError("no 3 x 3 window lies wholly inside the creature (alpha 255)")
    return windows.var(axis=0), full


def fine_detail(rgba):
    rgb = rgba[..., :3].astype(np.float64)
    lum = rgb @ np.array([0.2126, 0.7152, 0.0722])
    variance, full = window_variance(lum, rgba[..., 3] == 255)
    return float(np.sqrt(variance[full]).mean()), int(full.sum())


def fringe(rgba):
    """(partly covered pixels, their count over the opaque pixels' count)."""
    alpha = rgba[..., 3]
    opaque = int((alpha == 255).sum())
    if opaque == 0:
        raise ValueError("no opaque pixel (alpha 255): nothing to measure against")
    partial = int(((alpha > 0) & (alpha < 255)).sum())
    return partial, partial / opaque


def main(paths):
    if not paths:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    for path in paths:
        try:
            rgba = read_rgba(path)
            detail, windows = fine_detail(rgba)
            partial, share = fringe(rgba)
        except (subprocess.CalledProcessError, ValueError) as e:
            print(f"fine-detail: {path}: {e}", file=sys.stderr)
            return 1
        print(f"{path}: fine detail {detail:.2f} (mean 3x3 luminance std over {windows} windows); "
              f"fringe {partial} pixels ({100 * share:.2f} % of the opaque ones)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
