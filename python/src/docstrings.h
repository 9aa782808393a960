// The Python package's docstrings (Google style: Args, Returns, Raises), kept apart from the
// bindings in module.cpp so that the bindings read as code.
#pragma once

namespace pelage::python::doc {

inline constexpr const char* kModelDoc = R"doc(A creature: body, skin and clips (constant).

Made by pelage.load(); pass it to Model.fur(), analyze(), render() and export().)doc";

inline constexpr const char* kFurDoc =
    R"doc(A creature's fur: its parameters and the roots grown on the skin (constant).

Made by Model.fur(); its hairs are recomputed for any frame by Fur.hairs() and Fur.frames().)doc";

inline constexpr const char* kSetThreadsDoc =
    R"doc(Sets the worker threads of pelage's computations.

Args:
    n: threads, 0 to 1024; 0 uses every core. Results are bit-identical whatever the count.)doc";

inline constexpr const char* kSkinDoc = R"doc(The posed skin.

Args:
    clip: a clip name, or None for the rest pose.
    time: seconds into the clip.

Returns:
    (positions, normals, triangles): (nV, 3) float32 metres (Z up), (nV, 3) float32 unit
    normals, (nT, 3) int32 vertex indices.)doc";

inline constexpr const char* kWriteGroomDoc = R"doc(Writes a groom file for this model's mesh.

A groom file holds per-vertex values (fur/groom.h) that any command loads with --groom FILE and
fur() with groom=FILE; the preset's regions apply on top of it. It names the mesh (vertex and
triangle counts, a hash), so loading it on another model is an error.

Args:
    path: the file to write (atomically: never half-written).
    length: None, or an array of shape (vertices,): the fur length at each vertex in metres
        [0, 10] (0 grows none), in place of the model's.
    density: None, or shape (vertices,): multiplies the hairs per area [0, 100] (the total kept).
    tint: None, or shape (vertices, 3): multiplies the hairs' linear colour [0, 10].
    comb: None, or shape (vertices, 3): the combed direction times the comb amount (length at
        most 1; rest pose, in the skin's tangent plane): the hairs' weightless direction turns
        toward it by the amount (1: lies along it; gravity still applies), 0: not combed.
    clump: None, or shape (vertices,): multiplies the coats' clump strength [0, 1] (0: out of
        its clump); only where a coat clumps.
    stiffness: None, or shape (vertices, 2): each coat's stiffness (overcoat, undercoat) [0, 1]
        at the vertex, in place of the coat's: gravity bends a hair as a coat of the stiffness
        interpolated at its root (floppiness 1 - stiffness, at least 0.02; sec. 3.5).
    segment_direction_weight: None, or shape (vertices, 2): each coat's segment direction weight
        w (overcoat, undercoat) [0, 1] at the vertex, in place of the coat's: a hair's weightless
        direction is normalize((1 - w) n + w s) with the w interpolated at its root (0: along
        the skin normal n, 1: along the body segment's direction s; sec. 3.4).
    curl_radius, curl_turns: None, or shape (vertices, 2): each coat's helix (overcoat,
        undercoat) at the vertex, radius [0, 0.5] (a fraction of the hair's length) and turns
        [0, 20], in place of the coat's: a curve or tube hair winds with the values interpolated
        at its root (either alone keeps the coat's other; sec. 3.8).
    width_scale: None, or shape (vertices, 2): multiplies each coat's hair width (overcoat,
        undercoat) [0, 10] at the vertex: a hair is drawn and exported (a tube grown) at the
        coat's width times the scale interpolated at its root.
    color_source_weight: None, or a dict of all five colour sources ("material", "creature",
        "texture", "vertex", "map") to arrays of shape (vertices, 2): each coat's weight of that
        source at the vertex (overcoat, undercoat) [0, 1], a coat's summing to 1: a hair's root
        colour blends the sources' colours at its root by the weights interpolated there.
    strokes: None, or grooming strokes applied on top of the arrays (those they need and that
        are absent start from the model's lengths, density 1, tint 1, no comb): a strokes file's
        path, or its JSON as a dict, {"strokes": [{"tool": "length" | "density" | "color" | "comb",
        "points": [[x, y, z], ...] (rest pose, metres), "radius": metres, "strength": s,
        "color": [r, g, b] (color only), "mirror": "x" | "y" | "z"}, ...]}, as `pelage groom`
        reads it (README, "Grooming strokes").

Vertices are in Model.skin()'s order. A wrong shape or a value out of range is a ValueError
naming the argument, and nothing is written.)doc";

inline constexpr const char* kGrowFurDoc = R"doc(Grows fur on the creature.

Args:
    preset: a built-in preset name ("default", "fig9", ...) or a preset .json file (which states
        what differs from its "base", else from "default").
    **fields: any preset field by its file name, e.g. hairs=50000, coverage=0.9, seed=3,
        overcoat={"stiffness": 0.6} (nested objects set field by field), regions=[{"match":
        "b_Tail*", "lengthScale": 2}], groom="fox.groom.json". hairs, density and coverage
        replace each other. An unknown field is a ValueError naming it. Fur.params holds every
        field resolved; Fur.groom the per-vertex values the regions and groom file gave.

Returns:
    Fur: the parameters and the roots, grown once; hairs are recomputed per frame.)doc";

inline constexpr const char* kHairsDoc = R"doc(One frame's hairs (every hair: no culling).

Args:
    clip: a clip name, or None for the rest pose.
    time: seconds into the clip.
    dynamics: None or False (the paper's quasi-static hairs), True (damped springs with the
        defaults), or {"frequency": Hz, "damping": ratio, "preroll": frames} (one value, or one
        per coat): the clip's frames are played from its start up to `time`, as
        `pelage hair --dynamics on` does.
    fps: frames per second of that play.

Returns:
    Hairs: points, normals, colours and roots as numpy views.)doc";

inline constexpr const char* kFramesDoc = R"doc(Iterates over a clip's frames in order.

Args:
    clip: a clip name.
    fps: frame f shows clip time time + f / fps.
    frames: None (the whole clip), an int, a (first, last) pair (both included) or a range
        (any positive step).
    dynamics: as Fur.hairs(); the springs step from one frame to the next (skipped frames are
        played through, so a frame equals what a whole run gives).
    time: the clip time of frame 0, seconds.

Returns:
    FrameIterator: yields one Hairs per frame.)doc";

inline constexpr const char* kLoadDoc = R"doc(Loads a creature.

Args:
    model: "monkey" (built-in), a creature .json, a .gltf/.glb, or a mesh (.obj, .ply, .off, .stl).
    **options: triangles (skin size of shape creatures), unit_scale (metres per file unit),
        no_fur (region patterns without fur), directions (per-joint directions file),
        subdivide ("auto" or 0 to 3 levels of a glTF or mesh skin; auto: a skin under 4000
        triangles until it has 4000), as the command line's options. An unknown keyword is a
        ValueError listing these.

Returns:
    Model.

Raises:
    FileNotFoundError: the file does not exist.
    pelage.InputError: the file is malformed or a value is out of range.)doc";

inline constexpr const char* kAnalyzeDoc =
    R"doc(`pelage analyze` in Python: the fur's droop under gravity, frame by frame.

Args:
    model: a Model.
    clip: a clip name, or None for the still pose.
    fur: a Fur grown on `model` (None: the default preset).
    frames: None (the whole clip), an int, a (first, last) pair (both included) or a range
        (any positive step: every frame is played, the frames on the step are reported).
    dynamics: as Fur.hairs(); adds the dyn_ columns.
    hold: seconds the last pose is held still afterwards, [0, 1000].
    groups: "region" (skin regions, the default) or "segment" (body segments).
    fps: frames per second (frame f shows clip time time + f / fps).
    time: the clip time of frame 0, seconds.
    sweep: one parameter over several values: "stiffness=0.2:0.8:4" (as the command line's),
        {"stiffness": [0.2, 0.5, 0.8]} (the values) or {"stiffness": (0.2, 0.8, 4)} (first,
        last, count); parameters stiffness [0, 1], frequency (0, 100] Hz, damping [0, 10]
        (frequency and damping need dynamics).
    plot: a .png path: also draws the main curves against time there, the plot of
        `pelage analyze --plot` (None or "": no plot).

An unknown keyword is a ValueError listing these.

Returns:
    dict: column name -> numpy array, one value per frame, in the CSV's order and with its
    names ("frame" and "held" int64, the rest float64 at full precision): frame, time_s, held,
    pitch_deg, ..., qs_droop_mean_deg, ... (dyn_ columns with dynamics); with a sweep,
    qs_droop_mean_deg[stiffness=0.2], ... (dyn_ with dynamics).)doc";

inline constexpr const char* kExportDoc =
    R"doc(`pelage export` in Python: writes hair geometry per frame.

Args:
    model: a Model.
    clip: a clip name, or None for the rest pose.
    fur: a Fur grown on `model` (None: the default preset).
    out: the directory for frame_NNNNN.ply/.glb, or the .usda file (required).
    frames: None (the whole clip), an int, a (first, last) pair or a range (any positive step).
    format: "ply" (default), "glb" or "usda".
    fps: frames per second; time: the clip time of frame 0.
    dynamics: as Fur.hairs().
    resume: keep complete frame files already there (ply, glb).

Files are written atomically: Ctrl-C (KeyboardInterrupt) leaves only complete files.

Returns:
    list of str: the files written.)doc";

inline constexpr const char* kRenderDoc =
    R"doc(`pelage render` of one frame in Python (EGL, no display).

Args:
    model: a Model.
    clip: a clip name, or None for the rest pose.
    fur: a Fur grown on `model` (None: the default preset).
    frame: the frame (clip time time + frame / fps); fps, time as analyze().
    size: (width, height), 16 to 16384 each; default (1280, 720).
    camera: "three-quarter" (default), "side", "front", "top", ...; fov: degrees; follow: bool.
    hair_source: "gpu" (default) or "cpu"; shading: "physical" (default), "paper", "kajiya-kay" or "marschner".
    lines, transparency, shadows, self_shadowing: bools as the command line's switches.
    light: (azimuth, elevation) of the key light, degrees (azimuth about +Z from +X in
        [-360, 360], elevation above the ground in [-90, 90]); default (35, 50).
    light_color, ambient: the key light's colour and the ambient light, linear: one intensity or
        (r, g, b), each in [0, 16]; default 1 and 0.35. The frame is linear in them: with one
        of them 0 it holds the other's part of the light.
    samples: MSAA samples (-1: 4 on a GPU, none on a software rasteriser).
    dynamics: as Fur.hairs(); skin_color: (r, g, b) in [0, 1].
    background: None (the default colour), (r, g, b) sRGB in [0, 1], or "transparent".

Returns:
    numpy.ndarray: (H, W, 3) uint8 sRGB, or (H, W, 4) with straight alpha for
    background="transparent" (0 where nothing is drawn).)doc";

}  // namespace pelage::python::doc
