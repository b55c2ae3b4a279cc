#!/usr/bin/python3
"""Draws Figures 1 and 2 of the study from the JSON error tables (README.md, "The study").

Figure 1: one bar per rule, the mean relative error of K[0][0] on partially visible links
(constant bases), log scale, error bars one standard error of the mean over links.
Figure 2: per rule, two stacked bars (unoccluded left, partial right) of the mean L1 error
bound per unit receiver area, stacked by source basis function, constant at the bottom,
as in the report's Figure 2.
Tables scored against the gold (`--gold`) are drawn against the gold, with the paper's
10,000-sample reference as one more bar (its own error against the gold). Tables of
scene-derived links (fig1-scene.json, fig2-scene.json, when present) are drawn the same way.

Usage: /usr/bin/python3 plots/figures.py --results results --plots plots
"""
import argparse
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# Deterministic SVG output: no random ids, no timestamps.
matplotlib.rcParams["svg.hashsalt"] = "radquad"
METADATA = {"svg": {"Date": None}, "png": {"Software": None}}


def load(path):
    try:
        with open(path) as handle:
            return json.load(handle)
    except (OSError, json.JSONDecodeError) as error:
        sys.exit(f"figures.py: cannot read {path}: {error}")


def save(figure, plots, stem):
    for extension in ("png", "svg"):
        target = os.path.join(plots, f"{stem}.{extension}")
        temporary = target + ".tmp." + extension
        figure.savefig(temporary, dpi=150, metadata=METADATA[extension], bbox_inches="tight")
        os.replace(temporary, target)


def reference_note(table):
    reference = table["reference"]
    error = reference.get("relative_standard_error", {})
    text = f"reference: {reference['name']} ({reference['samples']} samples)"
    if error.get("mean") is not None:
        text += f", own relative std. error mean {error['mean']:.1e}, max {error['max']:.1e}"
    return text


def scene_source(table):
    links = table["options"].get("links")
    return f" of scene {links['scene']} (solver degree {links['degree']})" if links else ""


def figure1(table, plots, stem):
    rules = list(table["rules"])
    gold = "relative_error_vs_gold" in rules[0]
    key = "relative_error_vs_gold" if gold else "relative_error"
    if gold:
        reference = table["reference"]
        rules.append({"name": "Reference", "samples": reference["samples"],
                      key: reference["relative_error_vs_gold"]})
    names = [rule["name"] for rule in rules]
    means = np.array([rule[key]["mean"] for rule in rules])
    sems = np.array([rule[key]["sem"] for rule in rules])
    figure, axes = plt.subplots(figsize=(9.0, 4.4))
    positions = np.arange(len(rules))
    axes.bar(positions, means, color="#4c72b0", yerr=sems, capsize=4, ecolor="black")
    axes.set_yscale("log")
    axes.set_xticks(positions, [f"{n}\n({r['samples']} samples)" for n, r in zip(names, rules)], fontsize=7)
    axes.set_ylabel("mean relative error of K[0][0]" + (" (against gold)" if gold else ""))
    source = scene_source(table)
    axes.set_title(f"Figure 1: constant bases, {table['links']} partially visible links{source}", fontsize=10)
    axes.text(0.0, -0.22, reference_note(table), transform=axes.transAxes, fontsize=7)
    axes.grid(axis="y", which="both", alpha=0.3)
    save(figure, plots, stem)
    plt.close(figure)


def figure2(table, plots, stem):
    classes = table["classes"]
    order = [name for name in ("unoccluded", "partial") if name in classes]
    gold = "l1_error_bound_vs_gold" in classes[order[0]]["rules"][0]
    key = "l1_error_bound_vs_gold" if gold else "l1_error_bound"
    if gold:
        for class_name in order:
            reference = classes[class_name]["reference"]
            if "l1_error_bound_vs_gold" in reference and not any(
                    rule["name"] == "Reference" for rule in classes[class_name]["rules"]):
                classes[class_name]["rules"] = classes[class_name]["rules"] + [
                    {"name": "Reference", key: reference["l1_error_bound_vs_gold"]}]
    names = [rule["name"] for rule in classes[order[0]]["rules"]]
    functions = len(classes[order[0]]["rules"][0][key]["per_source_function"])
    side = int(round(functions ** 0.5))
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.95, functions))
    figure, axes = plt.subplots(figsize=(9.0, 4.6))
    width = 0.38
    for offset, class_name in enumerate(order):
        rules = {rule["name"]: rule for rule in classes[class_name]["rules"]}
        positions = np.arange(len(names)) + (offset - 0.5 * (len(order) - 1)) * (width + 0.02)
        bottom = np.zeros(len(names))
        for b in range(functions):
            heights = np.array([rules[n][key]["per_source_function"][b] for n in names])
            label = f"M({b // side},{b % side})" if offset == 0 else None
            axes.bar(positions, heights, width, bottom=bottom, color=colours[b], label=label,
                     edgecolor="white", linewidth=0.3, hatch=None if class_name == "unoccluded" else "//")
            bottom += heights
    axes.set_xticks(np.arange(len(names)), names, fontsize=8)
    axes.set_ylabel("mean L1 error bound per unit area" + (" (against gold)" if gold else ""))
    counts = ", ".join(f"{c} ({classes[c]['links']} links)" for c in order)
    axes.set_title(f"Figure 2: quadratic bases; left bars {order[0]}, right (hatched) {order[-1]}; {counts}"
                   f"{scene_source(table)}", fontsize=9)
    axes.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0), title="source function", title_fontsize=7)
    floor = ", ".join(f"{c} {classes[c]['reference']['l1_standard_error']['total']:.2g}" for c in order
                      if "l1_standard_error" in classes[c]["reference"])
    note = reference_note(table) + (f"; its own L1 standard error (total): {floor}" if floor else "")
    axes.text(0.0, -0.14, note, transform=axes.transAxes, fontsize=7)
    axes.grid(axis="y", alpha=0.3)
    save(figure, plots, stem)
    plt.close(figure)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="results")
    parser.add_argument("--plots", default="plots")
    arguments = parser.parse_args()
    os.makedirs(arguments.plots, exist_ok=True)
    figure1(load(os.path.join(arguments.results, "fig1.json")), arguments.plots, "fig1")
    figure2(load(os.path.join(arguments.results, "fig2.json")), arguments.plots, "fig2")
    for stem, draw in (("fig1-scene", figure1), ("fig2-scene", figure2)):
        path = os.path.join(arguments.results, stem + ".json")
        if os.path.exists(path):
            draw(load(path), arguments.plots, stem)


if __name__ == "__main__":
    main()
