#!/usr/bin/python3
"""Draws Figures 1 and 2 of the study from the JSON error tables (docs/study.md).

Figure 1: one bar per rule, the mean relative error of K[0][0] on partially visible links
(constant bases), log scale, error bars one standard error of the mean over links.
Figure 2: per rule, one bar per class of links (unoccluded, partially occluded, singular:
touching or cut by the other's plane) of the mean L1 error bound per unit receiver area, on a
log axis (the classes differ by orders); below it the share of each source basis function in
that bound, stacked as in the report's Figure 2 (constant at the bottom); below that the
scale-free relative Frobenius error of K, which compares the classes fairly where U_b follows
each link's size of K. Error bars: one standard error of the mean over links.
Breakdowns (<stem>-breakdown): every rule's mean error over FullGauss's on the same links,
with its 95% interval, by occluder kind and by distance band (centre distance over the
longest side), one row per class; in Figure 1's metric for Figure 1, in the L1 bound for
Figure 2. Below 1 the rule beats FullGauss there.
Tables scored against the gold (the default; not with `--no-gold`) are drawn against the gold, with the paper's
10,000-sample reference as one more bar (its own error against the gold). Tables of
scene-derived links (fig1-scene.json, fig2-scene.json, when present) are drawn the same way.

Usage: /usr/bin/python3 plots/figures.py --results results --plots plots [--only fig1 ...]
       /usr/bin/python3 plots/figures.py --results results --plots plots --serve  (stems on stdin)
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
    # The tight bounding box is measured once, in the PNG's resolution (what
    # bbox_inches="tight" measures for each file, with a draw of its own), and used for both.
    figure.set_dpi(150)
    renderer = figure.canvas.get_renderer()
    with renderer._draw_disabled():  # lay out every artist, rasterize nothing
        figure.draw(renderer)
    bbox = figure.get_tightbbox(renderer).padded(matplotlib.rcParams["savefig.pad_inches"])
    for extension in ("png", "svg"):
        target = os.path.join(plots, f"{stem}.{extension}")
        temporary = target + ".tmp." + extension
        figure.savefig(temporary, dpi=150, metadata=METADATA[extension], bbox_inches=bbox)
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
    if not links:
        return ""
    scenes = links["scene"] if isinstance(links["scene"], list) else [links["scene"]]
    return f" of {'scenes' if len(scenes) > 1 else 'scene'} {', '.join(scenes)} (solver degree {links['degree']})"


# Titles of log-scale axes are set at y=1.0: matplotlib then does not measure every tick
# label to place them (the same place, since nothing is drawn above those axes).
def figure1(table, plots, stem):
    rules = list(table["rules"])
    gold = "relative_error_vs_gold" in rules[0]
    key = "relative_error_vs_gold" if gold else "relative_error"
    if gold and not any(rule["name"] == "Reference" for rule in rules):
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
    axes.set_title(f"Figure 1: constant bases, {table['links']} partially visible links{source}", fontsize=10, y=1.0)
    axes.text(0.0, -0.22, reference_note(table), transform=axes.transAxes, fontsize=7)
    axes.grid(axis="y", which="both", alpha=0.3)
    save(figure, plots, stem)
    plt.close(figure)


CLASS_STYLE = {"unoccluded": ("#4c72b0", None), "partial": ("#dd8452", "//"),
               "singular": ("#55a868", "..")}


def figure2(table, plots, stem):
    """Three panels sharing the rules: the mean L1 error bound per unit area (the report's
    Figure 2, totals on a log axis, since the classes differ by orders), the share of each
    source function in it (the report's stacking, each bar scaled to 1), and the scale-free
    relative Frobenius error of K."""
    classes = table["classes"]
    order = [name for name in ("unoccluded", "partial", "singular") if name in classes]
    gold = "l1_error_bound_vs_gold" in classes[order[0]]["rules"][0]
    key = "l1_error_bound_vs_gold" if gold else "l1_error_bound"
    frobenius = "relative_frobenius_error_vs_gold" if gold else "relative_frobenius_error"
    # The bars of each class: its rules and, scored against the gold, the paper's reference
    # (the table itself is left as it is: the breakdown figure reads it afterwards).
    bars = {name: list(classes[name]["rules"]) for name in order}
    if gold:
        for class_name in order:
            reference = classes[class_name]["reference"]
            if key in reference and not any(rule["name"] == "Reference" for rule in bars[class_name]):
                bars[class_name].append({"name": "Reference", **{
                    k: reference[k] for k in (key, frobenius) if k in reference}})
    names = [rule["name"] for rule in bars[order[0]]]
    functions = len(bars[order[0]][0][key]["per_source_function"])
    side = int(round(functions ** 0.5))
    colours = plt.get_cmap("viridis")(np.linspace(0.0, 0.95, functions))
    figure, (totals, shares, scale_free) = plt.subplots(
        3, 1, figsize=(11.0, 10.5), sharex=True, gridspec_kw={"height_ratios": [1.2, 1.0, 1.0]})
    width = 0.8 / len(order)
    top = 0.0  # the highest whisker of the totals

    def positions(offset):
        return np.arange(len(names)) + (offset - 0.5 * (len(order) - 1)) * width

    for offset, class_name in enumerate(order):
        rules = {rule["name"]: rule for rule in bars[class_name]}
        colour, hatch = CLASS_STYLE[class_name]
        label = f"{class_name} ({classes[class_name]['links']} links)"
        means = np.array([rules[n][key]["total"] for n in names])
        sems = np.array([rules[n][key].get("total_sem", 0.0) for n in names])
        # A log axis cannot show a bar reaching 0: the lower whisker stops short of it.
        totals.bar(positions(offset), means, width * 0.95, color=colour, hatch=hatch,
                   edgecolor="white", linewidth=0.3, label=label,
                   yerr=[np.minimum(sems, 0.95 * means), sems], capsize=2, ecolor="black")
        top = max(top, float(np.max(means + sems)))
        bottom = np.zeros(len(names))
        for b in range(functions):
            heights = np.array([rules[n][key]["per_source_function"][b] for n in names])
            heights = np.divide(heights, means, out=np.zeros_like(heights), where=means > 0)
            shares.bar(positions(offset), heights, width * 0.95, bottom=bottom, color=colours[b],
                       label=f"M({b // side},{b % side})" if offset == 0 else None,
                       edgecolor="white", linewidth=0.3, hatch=hatch)
            bottom += heights
        shown = [n for n in names if frobenius in rules[n]]
        scale_free.bar(positions(offset)[[names.index(n) for n in shown]],
                       [rules[n][frobenius]["mean"] for n in shown], width * 0.95,
                       yerr=[[min(rules[n][frobenius]["sem"], 0.95 * rules[n][frobenius]["mean"])
                              for n in shown], [rules[n][frobenius]["sem"] for n in shown]],
                       capsize=2, ecolor="black", color=colour, hatch=hatch, edgecolor="white",
                       linewidth=0.3, label=class_name)
    against = " (against gold)" if gold else ""
    totals.set_yscale("log")
    totals.set_ylabel("mean L1 error bound\nper unit area" + against, fontsize=8)
    totals.set_ylim(top=1.5 * top)
    totals.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.005, 1.0), title="links",
                  title_fontsize=7)
    floor = ", ".join(f"{c} {classes[c]['reference']['l1_standard_error']['total']:.2g}" for c in order
                      if "l1_standard_error" in classes[c]["reference"])
    note = reference_note(table) + (f";\nits own L1 standard error (total): {floor}" if floor else "")
    totals.set_title(f"Figure 2: quadratic bases{scene_source(table)}\n{note}", fontsize=9, y=1.0)
    shares.set_ylim(0.0, 1.0)
    shares.set_ylabel("share of each source\nfunction in the bound", fontsize=8)
    shares.legend(fontsize=6, loc="upper left", bbox_to_anchor=(1.005, 1.0), title="source function",
                  title_fontsize=7)
    scale_free.set_yscale("log")
    scale_free.set_ylabel("mean ||K~ - K||_F / ||K||_F" + against, fontsize=8)
    scale_free.set_xticks(np.arange(len(names)), names, fontsize=8, rotation=30, ha="right")
    for axes in (totals, scale_free):
        axes.grid(axis="y", which="both", alpha=0.3)
        axes.set_axisbelow(True)
    figure.align_ylabels()
    save(figure, plots, stem)
    plt.close(figure)


def breakdown_figure(table, plots, stem):
    """Paired ratios to FullGauss with 95% intervals, by occluder kind and by distance band."""
    if "classes" in table:
        groups = [(f"{c}: ", table["classes"][c]) for c in ("unoccluded", "partial", "singular")
                  if c in table["classes"]]
        metric = "l1_error_bound_total"  # the metric of Figure 2's bars
    else:
        groups = [("", table)]
        metric = "relative_error"
    if "relative_error_vs_gold" in groups[0][1]["rules"][0]:
        metric += "_vs_gold"  # tables scored against the gold are drawn against it
    names = [rule["name"] for rule in (groups[0][1]["rules"])]
    rows = []
    for prefix, part in groups:
        occluders = part["breakdown"]["by_occluder"]
        bands = []
        for band in part["breakdown"]["by_distance"]:
            low, high = band["distance_factor"]
            bands.append((f"{low:g}-{high:g}" if high is not None else f">= {low:g}", band))
        rows.append([(prefix + "by occluder", [(kind, occluders[kind]) for kind in sorted(occluders)]),
                     (prefix + "by distance / longest side", bands)])
    figure, axes_grid = plt.subplots(len(rows), 2, figsize=(11.0, 3.6 * len(rows)), squeeze=False)
    colours = plt.get_cmap("tab10")(np.arange(len(names)))
    for axes, (title, entries) in zip(axes_grid.flat, [panel for row in rows for panel in row]):
        entries = [(label, entry) for label, entry in entries
                   if entry.get("links", 0) >= 2 and "ratio_to_fullgauss" in entry.get(metric, {})]
        spread = 0.8 / max(1, len(names))
        for r, name in enumerate(names):
            if name == "FullGauss":
                continue
            xs, ys, low, high = [], [], [], []
            for g, (label, entry) in enumerate(entries):
                ratio, lo, hi = entry[metric]["ratio_to_fullgauss"][r]
                xs.append(g - 0.4 + (r + 0.5) * spread)
                ys.append(ratio)
                low.append(ratio - max(lo, 1e-3 * ratio))
                high.append(hi - ratio)
            axes.errorbar(xs, ys, yerr=[low, high], fmt="o", markersize=3, capsize=2,
                          color=colours[r], label=name)
        axes.axhline(1.0, color="black", linewidth=0.8)
        axes.set_yscale("log")
        axes.set_xticks(np.arange(len(entries)),
                        [f"{label}\n({entry['links']} links)" for label, entry in entries], fontsize=7)
        axes.set_title(title, fontsize=9, y=1.0)
        axes.grid(axis="y", which="both", alpha=0.3)
    for axes in axes_grid[:, 0]:
        axes.set_ylabel(f"mean {metric.replace('_', ' ')}\n/ FullGauss's (95% interval)", fontsize=8)
    axes_grid[0][-1].legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    figure.suptitle(f"{stem}: where each rule wins against FullGauss (below 1: the rule is better)",
                    fontsize=10, y=1.0 - 0.1 / figure.get_figheight())
    figure.subplots_adjust(top=1.0 - 0.55 / figure.get_figheight(), hspace=0.35)
    save(figure, plots, stem + "-breakdown")
    plt.close(figure)


FIGURES = {"fig1": figure1, "fig2": figure2, "fig1-scene": figure1, "fig2-scene": figure2}


def draw(stem, results, plots):
    table = load(os.path.join(results, stem + ".json"))
    FIGURES[stem](table, plots, stem)
    breakdown_figure(table, plots, stem)


def serve(results, plots):
    """Draws the tables whose stems come on standard input, one a line, in turn; answers
    "drawn STEM" or "failed STEM" on standard output (radquad figures asks while it computes
    the next table). Exits with status 1 if any failed."""
    failures = 0
    for line in sys.stdin:
        stem = line.strip()
        if not stem:
            continue
        try:
            if stem not in FIGURES:
                raise ValueError(f"unknown table {stem!r} (valid: {', '.join(sorted(FIGURES))})")
            draw(stem, results, plots)
            answer = "drawn"
        except (Exception, SystemExit) as error:  # load() exits with its message
            print(f"figures.py: {stem}: {error}", file=sys.stderr)
            answer = "failed"
            failures += 1
        sys.stdout.write(f"{answer} {stem}\n")
        sys.stdout.flush()
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="results")
    parser.add_argument("--plots", default="plots")
    parser.add_argument("--only", action="append", choices=sorted(FIGURES),
                        help="draw this table's figures alone (repeatable; default: every table, "
                        "the scene-derived ones when present)")
    parser.add_argument("--serve", action="store_true",
                        help="draw the tables named on standard input, one a line, answering "
                        "'drawn STEM' or 'failed STEM' on standard output")
    arguments = parser.parse_args()
    os.makedirs(arguments.plots, exist_ok=True)
    if arguments.serve:
        sys.exit(serve(arguments.results, arguments.plots))
    for stem in FIGURES:
        if arguments.only and stem not in arguments.only:
            continue
        path = os.path.join(arguments.results, stem + ".json")
        if stem.endswith("-scene") and not arguments.only and not os.path.exists(path):
            continue
        draw(stem, arguments.results, arguments.plots)


if __name__ == "__main__":
    main()
