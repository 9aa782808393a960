#!/usr/bin/python3
"""One frame of fur as numpy arrays: what a pipeline tool or a notebook starts from.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/hairs_to_numpy.py [--out hairs.npz]

Grows the default fur on the built-in monkey, poses its 'walk' clip at 0.5 s, and saves every
hair's points, normals, coat, root triangle and barycentric coordinates into one .npz file. The
arrays are views of pelage's buffers (no copy) until numpy writes them.
"""

import argparse

import numpy as np

import pelage


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--model", default="monkey", help="monkey, a creature .json, glTF or mesh")
    parser.add_argument("--clip", default="walk")
    parser.add_argument("--time", type=float, default=0.5, help="clip time (s)")
    parser.add_argument("--hairs", type=float, default=50000)
    parser.add_argument("--out", default="hairs.npz")
    args = parser.parse_args()

    model = pelage.load(args.model)
    fur = model.fur("default", hairs=args.hairs)
    hairs = fur.hairs(clip=args.clip, time=args.time)
    points = hairs.points  # (n, P, 3) float32, metres, Z up, root first
    lengths = np.linalg.norm(np.diff(points, axis=1), axis=2).sum(axis=1)
    print(f"{model}: {len(hairs)} hairs of {points.shape[1]} points ({hairs.styles[0]})")
    for coat, name in enumerate(("overcoat", "undercoat")):
        mine = lengths[hairs.coat == coat]
        print(f"  {name}: {mine.size} hairs, length {1000 * mine.mean():.2f} mm mean, "
              f"{1000 * mine.max():.2f} mm longest")
    np.savez_compressed(args.out, points=points, normals=hairs.normals, coat=hairs.coat,
                        hair=hairs.hair, triangle=hairs.triangle, barycentric=hairs.barycentric)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
