#!/usr/bin/env python3
"""Draws plots/adaptive.png and results/plate1.png from results/adaptive.json and the plate's
renders in results/plate1/ (written by `radquad adaptive`).

plots/adaptive.png: (a) kernel-evaluation savings of the adaptive rules against fixed rules
for d = 1, 2, 3 on each built-in scene, beside the theoretical best (d+1)^2 and the report's
observed values (Gershbein 1995, section 5); (b) kernel evaluations against the relative L2
difference from the fixed solution over several ErrThres values, fixed rules as reference.
results/plate1.png: Plate 1 of the report: the cubic cornell scene with adaptive-novis,
adaptive and fixed rules, their kernel-evaluation counts, and the scaled differences.
"""
import argparse
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

CHOICES = ["adaptive-novis", "adaptive", "fixed"]
COLOURS = {"adaptive": "tab:blue", "adaptive-novis": "tab:orange", "fixed": "black"}


def savings_panel(ax, data):
    table = data["table"]
    labels, x = [], 0
    for row in table:
        best = row["theoretical_best"]
        for k, choice in enumerate(["adaptive", "adaptive-novis"]):
            ratio = row[choice]["evaluation_ratio"]
            ax.bar(x + 0.38 * (k - 0.5), ratio, 0.36, color=COLOURS[choice],
                   label=choice if x == 0 else None)
            observed = row["report_observed"][choice]
            if observed is not None:
                ax.plot([x + 0.38 * (k - 0.5) - 0.18, x + 0.38 * (k - 0.5) + 0.18],
                        [observed, observed], color="red", lw=2,
                        label="report, observed" if x == 0 and k == 0 else None)
        ax.plot([x - 0.4, x + 0.4], [best, best], color="grey", ls="--",
                label="theoretical best (d+1)^2" if x == 0 else None)
        labels.append(f"{row['scene']}\nd={row['degree']}")
        x += 1
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("kernel evaluations, fixed / adaptive")
    ax.set_title(f"(a) savings at ErrThres = {data['options']['threshold']:g}", fontsize=10)
    ax.legend(fontsize=7)


def sweep_panel(ax, data):
    sweep = data["sweep"]
    fixed = sweep["fixed"]["kernel_evaluations"]
    for choice in ["adaptive", "adaptive-novis"]:
        points = sorted((p for p in sweep["points"] if p["rules"] == choice),
                        key=lambda p: p["threshold"])
        xs = [max(p["relative_l2_difference"], 1e-7) for p in points]
        ys = [p["kernel_evaluations"] for p in points]
        ax.plot(xs, ys, "o-", color=COLOURS[choice], label=f"{choice}: global L2")
        for p, xv, yv in zip(points, xs, ys):
            ax.annotate(f"{p['threshold']:g}", (xv, yv), fontsize=6, xytext=(3, 3),
                        textcoords="offset points")
        if all("largest_patch_difference" in p for p in points):
            patch_xs = [max(abs(p["largest_patch_difference"]["value"]), 1e-7) for p in points]
            ax.plot(patch_xs, ys, "s--", mfc="none", color=COLOURS[choice],
                    label=f"{choice}: worst patch")
    ax.axhline(fixed, color="black", ls="--", label="fixed (reference, difference 0)")
    ax.axvline(0.01, color="grey", ls=":", label="1% difference")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("difference from the fixed solution (relative)")
    ax.set_ylabel("kernel evaluations")
    ax.set_title(f"(b) ErrThres sweep: {sweep['scene']}, d={sweep['degree']}, "
                 f"bf-eps {sweep['bf_eps']:g} (labels: ErrThres)", fontsize=10)
    ax.legend(fontsize=7)


def plate(data, plate_dir, out_path):
    info = data["plate"]
    counts = info["kernel_evaluations"]
    fig, axes = plt.subplots(2, 3, figsize=(12, 8.6))
    for k, choice in enumerate(CHOICES):
        ax = axes[0][k]
        ax.imshow(mpimg.imread(os.path.join(plate_dir, choice + ".png")))
        ratio = counts["fixed"] / counts[choice]
        ax.set_title(f"{choice}\n{counts[choice]:,} kernel evaluations ({ratio:.1f}x fewer)"
                     if choice != "fixed" else
                     f"fixed\n{counts[choice]:,} kernel evaluations", fontsize=10)
        ax.axis("off")
        ax = axes[1][k]
        ax.axis("off")
        if choice == "fixed":
            continue
        ax.imshow(mpimg.imread(os.path.join(plate_dir, "difference-" + choice + ".png")))
        ax.set_title(f"|{choice} - fixed| x {info['difference_scale']:g}", fontsize=10)
    fig.suptitle(f"Plate 1: {info['scene']}, degree {info['degree']} (cubic), "
                 f"ErrThres {data['options']['threshold']:g}; renders share the fixed render's "
                 "exposure", fontsize=11)
    fig.tight_layout()
    fig.savefig(out_path + ".tmp.png", dpi=100)
    os.replace(out_path + ".tmp.png", out_path)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--results", required=True)
    parser.add_argument("--plots", required=True)
    args = parser.parse_args()
    with open(os.path.join(args.results, "adaptive.json")) as f:
        data = json.load(f)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5))
    savings_panel(axes[0], data)
    sweep_panel(axes[1], data)
    fig.tight_layout()
    out = os.path.join(args.plots, "adaptive.png")
    fig.savefig(out + ".tmp.png", dpi=110)
    os.replace(out + ".tmp.png", out)
    if data.get("plate"):
        plate(data, os.path.join(args.results, "plate1"), os.path.join(args.results, "plate1.png"))


if __name__ == "__main__":
    main()
