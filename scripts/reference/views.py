#!/usr/bin/python3
"""pelage's frames on fixed views against their committed Cycles references.

  views.py render [NAME...]   path-traces the views' references (Blender; scripts/reference-render.sh)
                              into docs/reference/NAME_a.png and NAME_b.png (two renders with
                              different seeds: their mean is the reference, their difference
                              its noise) and records pelage's figures against them in
                              docs/reference/figures.json
  views.py check [NAME...]    renders pelage's frames again and measures them against the
                              committed references (make test runs this; no Blender): each
                              figure must stay within its tolerance of the recorded one
  views.py record [NAME...]   renders pelage's frames again and records their figures against
                              the committed references, with new side-by-sides (no Blender):
                              after a change of pelage's look that leaves the hairs as they were
                              (shading, lighting)
  views.py parts OUT [NAME...]
                              the light's two parts apart (Blender; nothing committed): each view
                              path-traced and drawn by pelage once lit by the key light alone
                              (--ambient 0) and once by the ambient alone (--light-color 0), into
                              OUT/NAME_key/ and OUT/NAME_ambient/ (reference-render.sh's files);
                              prints each part's mean linear luminance over the creature in
                              pelage and Cycles, their ratio and the part's MAE, and writes them
                              to OUT/parts.json. A shading model is calibrated part by part with
                              it: a wrong balance between the parts cancels in the full frame
  views.py passes OUT [NAME...]
                              each part again with Cycles' light passes (Blender; nothing
                              committed; reference-render.sh with PASSES=1, into OUT/NAME_key/ and
                              OUT/NAME_ambient/): prints the mean linear luminance over the
                              creature of the light Cycles' hairs scatter once (straight from the
                              light), of what they scatter more than once, and of the skin seen,
                              beside pelage's part and its light passes (pelage render --pass
                              fibre, coat, skin: the physical model's fibre part, its coat part,
                              the skin), and writes them to OUT/passes.json

The views are scripts/reference/views.txt. Environment: PELAGE (the pelage binary, default
build/bin/pelage), PELAGE_SHARED_MODELS_DIR (the shared models, default ../shared/models),
SAMPLES (Cycles samples per pixel for render, both renders together; default 1024; parts and
passes: 256).
"""
import json
import os
import shutil
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import compare  # noqa: E402 (next to this file)

REFERENCES = os.path.join(ROOT, "docs", "reference")
FIGURES = os.path.join(REFERENCES, "figures.json")
BACKGROUND = (0.80, 0.82, 0.86)  # pelage's default background (sRGB)
MAX_REFERENCE_BYTES = 300_000
REFERENCE_HALVES = ("_a", "_b")  # NAME_a.png, NAME_b.png: Cycles' seeds 0 and 1
# How far a recorded figure may move before check fails: a change of pelage's look shows here
# (and is then recorded again with `render`, saying why in the commit).
TOLERANCE = {"mae": 0.5, "luminance_ratio": 0.01, "detail_ratio": 0.05, "laplacian_ratio": 0.05,
             "mae_fringe": 1.0, "mae_block8": 0.5, "mae_luminance_alone": 0.5,
             "mae_colour_alone": 0.5}


def references(name):
    """The view's two committed reference renders (RGBA8)."""
    return [compare.read_rgba(os.path.join(REFERENCES, name + half + ".png"))
            for half in REFERENCE_HALVES]


def views():
    out = []
    with open(os.path.join(HERE, "views.txt")) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                name, model, *options = line.split()
                out.append((name, model, options))
    return out


def selected(names):
    all_views = views()
    unknown = set(names) - {v[0] for v in all_views}
    if unknown:
        sys.exit("views.py: unknown view(s) %s (views.txt has %s)"
                 % (", ".join(sorted(unknown)), ", ".join(v[0] for v in all_views)))
    return [v for v in all_views if not names or v[0] in names]


def shared_models():
    return os.environ.get("PELAGE_SHARED_MODELS_DIR",
                          os.path.join(ROOT, "..", "shared", "models"))


def model_path(model):
    return model.replace("$SHARED", shared_models())


def pelage():
    return os.environ.get("PELAGE", os.path.join(ROOT, "build", "bin", "pelage"))


def render_pelage(model, options, out_dir):
    """pelage's frame as users render it (culling on), straight alpha; its PNG's path."""
    subprocess.run([pelage(), "render", model_path(model), "--out", out_dir, "--background",
                    "transparent", "--quiet"] + options, check=True)
    return only_frame(out_dir)


def only_frame(out_dir):
    """The path of the one PNG frame in out_dir (exits otherwise)."""
    frames = sorted(f for f in os.listdir(out_dir) if f.endswith(".png"))
    if len(frames) != 1:
        sys.exit("views.py: expected one frame in %s, got %d" % (out_dir, len(frames)))
    return os.path.join(out_dir, frames[0])


def render(names):
    figures = {}
    if os.path.exists(FIGURES):
        with open(FIGURES) as f:
            figures = json.load(f)
    for name, model, options in selected(names):
        with tempfile.TemporaryDirectory() as tmp:
            env = dict(os.environ, SAMPLES=os.environ.get("SAMPLES", "1024"))
            subprocess.run([os.path.join(ROOT, "scripts", "reference-render.sh"),
                            model_path(model), tmp] + options, check=True, env=env)
            for half in REFERENCE_HALVES:
                size = os.path.getsize(os.path.join(tmp, "cycles%s.png" % half))
                if size > MAX_REFERENCE_BYTES:
                    sys.exit("views.py: %s's reference%s is %d bytes (at most %d)"
                             % (name, half, size, MAX_REFERENCE_BYTES))
            for half in REFERENCE_HALVES:
                shutil.copyfile(os.path.join(tmp, "cycles%s.png" % half),
                                os.path.join(REFERENCES, name + half + ".png"))
            shutil.copyfile(os.path.join(tmp, "side_by_side.png"),
                            os.path.join(REFERENCES, name + "_side_by_side.png"))
            with open(os.path.join(tmp, "figures.json")) as f:
                figures[name] = json.load(f)
        with open(FIGURES + ".tmp", "w") as f:
            json.dump(figures, f, indent=1, sort_keys=True)
            f.write("\n")
        os.replace(FIGURES + ".tmp", FIGURES)
    return 0


# The light's parts: the option that leaves each alone (pelage render's --ambient, --light-color).
PARTS = (("key", "--ambient"), ("ambient", "--light-color"))


def part_luminance(rgba):
    """The mean linear luminance of a straight-alpha RGBA8 image's creature, premultiplied, over
    its pixels with alpha above half."""
    alpha = rgba[..., 3].astype(np.float64) / 255.0
    lum = compare.srgb_to_linear(rgba[..., :3].astype(np.float64) / 255.0) @ compare.LUMA
    return lum, alpha


def render_part(model, options, option, folder, **env):
    """One light part of a view path-traced and drawn by pelage (reference-render.sh into folder,
    the other part's light off with option 0): the mean linear luminance over the creature in
    pelage and in Cycles, and the creature's mask."""
    env = dict(os.environ, SAMPLES=os.environ.get("SAMPLES", "256"), **env)
    subprocess.run([os.path.join(ROOT, "scripts", "reference-render.sh"),
                    model_path(model), folder] + options + [option, "0"],
                   check=True, env=env, stdout=subprocess.DEVNULL)
    pel = compare.read_rgba(only_frame(os.path.join(folder, "pelage")))
    cyc = compare.read_rgba(os.path.join(folder, "cycles.png"))
    (lp, ap), (lc, ac) = part_luminance(pel), part_luminance(cyc)
    creature = (ap > 0.5) | (ac > 0.5)
    entry = {"pelage": float((lp * ap)[creature].mean()),
             "cycles": float((lc * ac)[creature].mean())}
    return entry, creature


def parts(out, names):
    chosen = selected(names)  # unknown names exit before anything is written
    os.makedirs(out, exist_ok=True)
    table = {}
    print("%-14s %-8s %9s %9s %7s %8s" % ("view", "part", "pelage", "Cycles", "ratio", "MAE/255"))
    for name, model, options in chosen:
        table[name] = {}
        for part, option in PARTS:
            folder = os.path.join(out, "%s_%s" % (name, part))
            entry, _ = render_part(model, options, option, folder)
            with open(os.path.join(folder, "figures.json")) as f:
                entry["mae"] = json.load(f)["mae"]
            entry["ratio"] = entry["cycles"] / max(entry["pelage"], 1e-12)
            table[name][part] = entry
            print("%-14s %-8s %9.4f %9.4f %7.2f %8.1f" % (
                name, part, entry["pelage"], entry["cycles"], entry["ratio"], entry["mae"]))
    with open(os.path.join(out, "parts.json"), "w") as f:
        json.dump(table, f, indent=1, sort_keys=True)
        f.write("\n")
    return 0


def read_passes(folder):
    """reference-render.sh's light passes (PASSES=1) as {name: linear RGBA float array, rows
    top-down}."""
    index = os.path.join(folder, "passes.json")
    try:
        with open(index) as f:
            meta = json.load(f)
        w, h, names = int(meta["width"]), int(meta["height"]), list(meta["passes"])
    except (OSError, ValueError, KeyError, TypeError) as e:
        sys.exit("views.py: %s: no light passes' index (written by cycles_render.py --passes): %s"
                 % (index, e))
    missing = {"GlossCol", "GlossDir", "GlossInd", "DiffCol", "DiffDir", "DiffInd"} - set(names)
    if missing:
        sys.exit("views.py: %s lists no %s pass" % (index, ", ".join(sorted(missing))))
    out = {}
    for name in names:
        path = os.path.join(folder, name + ".f32")
        if not os.path.isfile(path):
            sys.exit("views.py: %s is missing (listed in %s)" % (path, index))
        data = np.fromfile(path, dtype="<f4")
        if data.size != 4 * w * h:
            sys.exit("views.py: %s/%s.f32 has %d values, expected %d" % (folder, name, data.size,
                                                                         4 * w * h))
        out[name] = data.reshape(h, w, 4)[::-1].astype(np.float64)
    return out


def light_paths(passes):
    """The light of a frame by the path that brought it (linear RGB): scattered once by a hair the
    eye sees, scattered more than once, and the skin seen."""
    rgb = {k: v[..., :3] for k, v in passes.items()}
    return {"once": rgb["GlossCol"] * rgb["GlossDir"], "many": rgb["GlossCol"] * rgb["GlossInd"],
            "skin": rgb["DiffCol"] * (rgb["DiffDir"] + rgb["DiffInd"])}


# pelage's light passes (pelage render --pass) set beside Cycles' light paths by `passes`.
PELAGE_PASSES = ("fibre", "coat", "skin")


def pelage_passes(model, options, option, creature):
    """pelage's fibre, coat and skin passes of one light part (the other part's light off with
    option 0): each one's mean linear luminance over the creature, premultiplied."""
    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for p in PELAGE_PASSES:
            folder = os.path.join(tmp, p)
            lum, alpha = part_luminance(compare.read_rgba(render_pelage(
                model, options + [option, "0", "--pass", p], folder)))
            out["pelage_" + p] = float((lum * alpha)[creature].mean())
    return out


def passes(out, names):
    chosen = selected(names)
    os.makedirs(out, exist_ok=True)
    table = {}
    print("%-14s %-8s %8s %8s | %8s %8s %8s | %8s %8s %8s" % (
        "view", "part", "pelage", "Cycles", "fibre", "coat", "skin", "once", "many", "skin"))
    for name, model, options in chosen:
        table[name] = {}
        for part, option in PARTS:
            folder = os.path.join(out, "%s_%s" % (name, part))
            entry, creature = render_part(model, options, option, folder, PASSES="1")
            paths = light_paths(read_passes(os.path.join(folder, "passes")))
            for k, v in paths.items():
                entry[k] = float((v @ compare.LUMA)[creature].mean())
            entry.update(pelage_passes(model, options, option, creature))
            table[name][part] = entry
            print("%-14s %-8s %8.4f %8.4f | %8.4f %8.4f %8.4f | %8.4f %8.4f %8.4f" % (
                name, part, entry["pelage"], entry["cycles"], entry["pelage_fibre"],
                entry["pelage_coat"], entry["pelage_skin"], entry["once"], entry["many"],
                entry["skin"]))
    with open(os.path.join(out, "passes.json"), "w") as f:
        json.dump(table, f, indent=1, sort_keys=True)
        f.write("\n")
    return 0


def check(names, record=False):
    with open(FIGURES) as f:
        recorded = json.load(f)
    failed = []
    print("%-14s %8s %10s %8s %10s %8s %8s %8s %8s %8s" % (
        "view", "MAE/255", "luminance", "detail", "Laplacian", "inside", "fringe", "8x8",
        "lum.", "colour"))
    for name, model, options in selected(names):
        if "$SHARED" in model and not os.path.isdir(shared_models()):
            print("%-14s skipped: the shared models are not here" % name)
            continue
        with tempfile.TemporaryDirectory() as tmp:
            frame = render_pelage(model, options, tmp)
            got, a, b = compare.measure(compare.read_rgba(frame), references(name), BACKGROUND)
        if record:
            recorded[name] = got
            compare.write_side_by_side(os.path.join(REFERENCES, name + "_side_by_side.png"), a, b)
        was = recorded[name]
        split = ["%8s" % ("-" if got[k] is None else "%.1f" % got[k])
                 for k in ("mae_interior", "mae_fringe", "mae_block8", "mae_luminance_alone",
                           "mae_colour_alone")]
        print("%-14s %8.1f %+9.1f%% %7.0f%% %9.0f%% %s" % (
            name, got["mae"], 100 * (got["luminance_ratio"] - 1), 100 * got["detail_ratio"],
            100 * got["laplacian_ratio"], " ".join(split)))
        for key, tolerance in TOLERANCE.items():
            if got[key] is None or was.get(key) is None:
                if got[key] != was.get(key):
                    failed.append("%s: %s %s, recorded %s" % (name, key, got[key], was.get(key)))
            elif abs(got[key] - was[key]) > tolerance:
                failed.append("%s: %s %.4f, recorded %.4f (tolerance %g)"
                              % (name, key, got[key], was[key], tolerance))
    if record:
        with open(FIGURES + ".tmp", "w") as f:
            json.dump(recorded, f, indent=1, sort_keys=True)
            f.write("\n")
        os.replace(FIGURES + ".tmp", FIGURES)
    for f in failed:
        print("views.py: " + f, file=sys.stderr)
    return 1 if failed else 0


def main(argv):
    if (not argv or argv[0] not in ("render", "check", "record", "parts", "passes")
            or argv in (["parts"], ["passes"])):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    if argv[0] == "render":
        return render(argv[1:])
    if argv[0] == "parts":
        return parts(argv[1], argv[2:])
    if argv[0] == "passes":
        return passes(argv[1], argv[2:])
    return check(argv[1:], record=argv[0] == "record")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
