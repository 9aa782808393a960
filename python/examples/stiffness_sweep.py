#!/usr/bin/python3
"""Droop against stiffness over the monkey's tumble (Van Gelder & Wilhelms 1997, sec. 3.4-3.5).

The paper bends each hair by gravity in proportion to its floppiness, 1 - stiffness. This script
sweeps the overcoat's stiffness over the built-in monkey's 'tumble' clip (the body rolls over, so
gravity turns against the skin), and plots the mean droop angle against time for each stiffness,
and the droop averaged over the clip against stiffness, for the paper's quasi-static hairs and for
dynamic ones (each end following through a damped spring).

    PYTHONPATH=build/python /usr/bin/python3 python/examples/stiffness_sweep.py [--out sweep.png]
"""

import argparse

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import pelage  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="stiffness_sweep.png", help="the plot (.png)")
    parser.add_argument("--hairs", type=float, default=20000, help="hairs over the monkey")
    parser.add_argument("--values", type=int, default=5, help="stiffness values in [0.1, 0.9]")
    args = parser.parse_args()

    monkey = pelage.load("monkey")
    stiffness = np.linspace(0.1, 0.9, args.values)
    quasi_static, dynamic = {}, {}
    for s in stiffness:
        fur = monkey.fur("default", hairs=args.hairs, overcoat={"stiffness": float(s)},
                         undercoat={"stiffness": float(s)})
        # One clip, both models of the ends: the paper's (qs_) and the damped spring's (dyn_).
        columns = pelage.analyze(monkey, "tumble", fur=fur, dynamics=True, hold=0.5)
        quasi_static[s] = columns["qs_droop_mean_deg"]
        dynamic[s] = columns["dyn_droop_mean_deg"]
        t = columns["time_s"]
        print(f"stiffness {s:.2f}: mean droop {quasi_static[s].mean():5.2f} deg (quasi-static), "
              f"{dynamic[s].mean():5.2f} deg (dynamic)")

    figure, (over_time, against) = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = plt.cm.viridis(np.linspace(0, 0.9, len(stiffness)))
    for s, colour in zip(stiffness, colours):
        over_time.plot(t, quasi_static[s], color=colour, label=f"stiffness {s:.1f}")
        over_time.plot(t, dynamic[s], color=colour, linestyle="--", linewidth=0.9)
    over_time.axvspan(t[-1] - 0.5, t[-1], color="0.92", zorder=0)
    over_time.set(xlabel="clip time (s); grey: body held still", ylabel="mean droop angle (deg)",
                  title="monkey 'tumble': droop over time (dashed: dynamic)")
    over_time.legend(fontsize=8)
    against.plot(stiffness, [quasi_static[s].mean() for s in stiffness], "o-",
                 label="quasi-static (paper)")
    against.plot(stiffness, [dynamic[s].mean() for s in stiffness], "s--", label="dynamic")
    against.set(xlabel="stiffness (floppiness = 1 - stiffness)",
                ylabel="mean droop over the clip (deg)", title="droop against stiffness")
    against.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
