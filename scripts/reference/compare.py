#!/usr/bin/python3
"""Measures a pelage frame against its path-traced reference (scripts/reference-render.sh).

The images have straight alpha (pelage: `--background transparent`; Cycles: film transparent)
and are composited over the same background colour. The reference may come as two independent
renders of the same scene (Cycles seeds 0 and 1): it is then their mean (in linear light), and
half their difference, which has the same Monte Carlo noise as the mean and none of the image,
measures that noise: the reference's detail and Laplacian spread are given without it (their
variances less the noise's), since a path tracer's noise would otherwise count as fur detail.
Over the creature's pixels (either image's alpha above half):
- MAE: the mean absolute difference of the 8-bit sRGB channels (/255);
- luminance: the mean Rec. 709 luminance of the 8-bit sRGB values, and pelage's relative to the
  reference's;
- detail: scripts/fine-detail.py's fine detail (the mean 3 x 3 standard deviation of luminance
  inside the creature, where alpha is 255); with two references, the reference's is scaled by
  sqrt(1 - noise variance / variance), both summed over the same windows;
- Laplacian spread: the standard deviation of the luminance's 4-neighbour Laplacian over the
  pixels wholly inside the creature; with two references, the reference's is
  sqrt(var(Laplacian of the mean) - var(Laplacian of the half difference));
- reference noise (two references): the mean absolute half difference of the channels (/255),
  about the MAE a perfect frame would still show against the mean;
- where the MAE comes from: over the fringe (the creature's pixels that are not wholly inside
  both images: the partly covered outline) and the interior apart, with the fringe's luminance
  ratio; and at coarser scales, the MAE of the images' means over B x B pixel blocks (B = 2, 4,
  8) lying wholly inside both, which strand-scale differences (where each hair lands, its grain)
  average out of and the shading's differences over the body keep;
- what the interior's MAE owes to luminance and to colour: the MAE were pelage's pixels recoloured
  to the reference's colour at their own luminance (the reference's pixel scaled to pelage's
  luminance: luminance alone) and were they brought to the reference's luminance in their own
  colour (pelage's pixel scaled to the reference's: colour alone);
- coverage: the creature's pixels in each image.
Writes the figures as JSON and a side-by-side PNG: pelage | reference | |difference| x 4, and
with two references their mean as a straight-alpha PNG (--reference-mean).

usage: compare.py PELAGE.png REFERENCE.png [REFERENCE2.png] --background R G B (sRGB 0-1)
                  --json OUT.json [--side-by-side OUT.png] [--reference-mean OUT.png]
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
window_variance = fine_detail_module.window_variance

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


def block_mae(a, b, inside, block):
    """The mean absolute difference of the images' `block` x `block` pixel means (channels)
    over the blocks wholly `inside` (None without one)."""
    h, w = inside.shape[0] // block * block, inside.shape[1] // block * block

    def blocks(x):
        return x[:h, :w].reshape(h // block, block, w // block, block, *x.shape[2:])

    full = blocks(inside).all(axis=(1, 3))
    if not full.any():
        return None
    diff = blocks(a).mean(axis=(1, 3)) - blocks(b).mean(axis=(1, 3))
    return float(np.abs(diff[full]).mean())


def mean_reference(references):
    """One or two straight-alpha RGBA8 renders of the same scene as one straight-alpha image (the
    mean of two in linear light, premultiplied): floats, sRGB 0-255 and alpha 0-255."""
    if len(references) == 1:
        return references[0].astype(np.float64)
    first, second = references
    if first.shape != second.shape:
        raise ValueError("the references differ in size: %s and %s" % (first.shape, second.shape))
    alphas = [r[..., 3:4].astype(np.float64) / 255.0 for r in references]
    premultiplied = sum(srgb_to_linear(r[..., :3].astype(np.float64) / 255.0) * a
                        for r, a in zip(references, alphas)) / 2.0
    alpha = (alphas[0] + alphas[1]) / 2.0
    colour = np.divide(premultiplied, alpha, out=np.zeros_like(premultiplied), where=alpha > 0)
    return np.concatenate([255.0 * linear_to_srgb(colour), 255.0 * alpha], axis=2)


def measure(pelage, references, background):
    """pelage's frame against its reference (a list of one or two renders of the same scene):
    (the figures, pelage's frame and the reference composited, sRGB floats 0-255)."""
    if any(pelage.shape != r.shape for r in references):
        raise ValueError("the images differ in size: %s and %s"
                         % (pelage.shape, [r.shape for r in references]))
    reference = mean_reference(references)
    a, b = over(pelage, background), over(reference, background)
    alpha = reference[..., 3]
    mask = (pelage[..., 3] > 127) | (alpha > 127)
    if not mask.any():
        raise ValueError("neither image shows the creature")
    la, lb = a @ LUMA, b @ LUMA
    error = np.abs(a - b)
    inside = alpha > 254.5
    out = {
        "pixels": int(mask.sum()),
        "pelage_coverage": int((pelage[..., 3] > 127).sum()),
        "reference_coverage": int((alpha > 127).sum()),
        "mae": float(error[mask].mean()),
        "luminance": float(la[mask].mean()),
        "reference_luminance": float(lb[mask].mean()),
    }
    out["luminance_ratio"] = out["luminance"] / out["reference_luminance"]
    both = (pelage[..., 3] == 255) & inside
    fringe = mask & ~both
    out["mae_interior"] = float(error[both].mean()) if both.any() else None
    out["mae_fringe"] = float(error[fringe].mean()) if fringe.any() else None
    fringe_reference = float(lb[fringe].mean()) if fringe.any() else 0.0
    out["fringe_luminance_ratio"] = (float(la[fringe].mean()) / fringe_reference
                                     if fringe_reference > 0 else None)
    for block in (2, 4, 8):
        out["mae_block%d" % block] = block_mae(a, b, both, block)
    lit = both & (la > 0) & (lb > 0)
    if lit.any():
        ratio = (la[lit] / lb[lit])[:, None]
        out["mae_luminance_alone"] = float(np.abs(b[lit] * ratio - b[lit]).mean())
        out["mae_colour_alone"] = float(np.abs(a[lit] / ratio - b[lit]).mean())
    else:
        out["mae_luminance_alone"] = out["mae_colour_alone"] = None
    out["detail"] = fine_detail(pelage)[0]
    variance, full = window_variance(lb, inside)
    out["reference_detail"] = float(np.sqrt(variance[full]).mean())
    out["laplacian"] = laplacian_spread(la, pelage[..., 3] == 255)
    out["reference_laplacian"] = laplacian_spread(lb, inside)
    if len(references) == 2:
        # Half the difference of two independent renders: the mean's noise, without the image.
        noise = (over(references[0], background) - over(references[1], background)) / 2.0
        noise_variance, _ = window_variance(noise @ LUMA, inside)
        total = variance[full].sum()
        kept = max(0.0, 1.0 - noise_variance[full].sum() / total) if total > 0 else 0.0
        out["reference_detail_with_noise"] = out["reference_detail"]
        out["reference_detail"] *= float(np.sqrt(kept))
        noise_spread = laplacian_spread(noise @ LUMA, inside)
        out["reference_laplacian_with_noise"] = out["reference_laplacian"]
        out["reference_laplacian"] = float(
            np.sqrt(max(0.0, out["reference_laplacian"] ** 2 - noise_spread ** 2)))
        out["reference_noise"] = float(np.abs(noise)[mask].mean())
    if out["reference_detail"] == 0.0 or out["reference_laplacian"] == 0.0:
        raise ValueError("the reference shows no detail inside the creature (flat, or nothing "
                         "but its own noise): its detail cannot be compared with")
    out["detail_ratio"] = out["detail"] / out["reference_detail"]
    out["laplacian_ratio"] = out["laplacian"] / out["reference_laplacian"]
    return out, a, b


def write_png(path, rgb):
    """Writes an RGB8 or RGBA8 image as a PNG, atomically (a temporary file renamed)."""
    h, w, channels = rgb.shape
    tmp = path + ".tmp.png"
    subprocess.run(
        ["ffmpeg", "-v", "error", "-y", "-f", "rawvideo", "-pix_fmt",
         "rgba" if channels == 4 else "rgb24", "-s",
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
    parser.add_argument("reference", nargs="+", help="one render, or two with different seeds")
    parser.add_argument("--background", nargs=3, type=float, required=True)
    parser.add_argument("--json", required=True)
    parser.add_argument("--side-by-side")
    parser.add_argument("--reference-mean", help="write the two references' mean here (PNG)")
    args = parser.parse_args(argv)
    if not all(0.0 <= c <= 1.0 for c in args.background):
        parser.error("--background: each of R G B in [0, 1]")
    if len(args.reference) > 2:
        parser.error("give one reference or two (independent renders of the same scene)")
    if args.reference_mean and len(args.reference) != 2:
        parser.error("--reference-mean needs two references")
    for path in [args.pelage] + args.reference:
        if not os.path.isfile(path):
            print("compare: error: %s: no such file" % path, file=sys.stderr)
            return 1
    try:
        references = [read_rgba(r) for r in args.reference]
        figures, a, b = measure(read_rgba(args.pelage), references, args.background)
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
    if args.reference_mean:
        write_png(args.reference_mean,
                  np.clip(np.round(mean_reference(references)), 0, 255).astype(np.uint8))
    print("MAE %.1f/255, luminance %.1f vs %.1f (%+.1f %%), detail %.2f vs %.2f (%.0f %%), "
          "Laplacian spread %.2f vs %.2f (%.0f %%), %d px" % (
              figures["mae"], figures["luminance"], figures["reference_luminance"],
              100 * (figures["luminance_ratio"] - 1), figures["detail"],
              figures["reference_detail"], 100 * figures["detail_ratio"], figures["laplacian"],
              figures["reference_laplacian"], 100 * figures["laplacian_ratio"], figures["pixels"]))
    if figures["mae_interior"] is not None and figures["fringe_luminance_ratio"] is not None:
        print("MAE inside %.1f, over the fringe %.1f (its luminance %+.1f %%)" % (
            figures["mae_interior"], figures["mae_fringe"],
            100 * (figures["fringe_luminance_ratio"] - 1)))
    if figures["mae_luminance_alone"] is not None:
        print("MAE inside from luminance alone %.1f, from colour alone %.1f" % (
            figures["mae_luminance_alone"], figures["mae_colour_alone"]))
    coarse = ["%d px %.1f" % (k, figures["mae_block%d" % k]) for k in (2, 4, 8)
              if figures["mae_block%d" % k] is not None]
    if coarse:
        print("MAE of block means: " + ", ".join(coarse))
    if "reference_noise" in figures:
        print("the reference's own noise: %.1f/255 (detail %.2f and Laplacian spread %.2f with it)"
              % (figures["reference_noise"], figures["reference_detail_with_noise"],
                 figures["reference_laplacian_with_noise"]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
