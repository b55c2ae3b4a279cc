#!/usr/bin/python3
"""Writes docs/results.md, every table of the committed results, from results/*.json.

docs/study.md's reading of the figures quotes these tables; they are generated here so that no
number in them is typed by hand. Run by scripts/run-figures.sh after the results are made.

Usage: /usr/bin/python3 plots/results_md.py --results results --out docs/results.md
"""
import argparse
import json
import os
import sys


def load(results, name):
    path = os.path.join(results, name)
    if not os.path.exists(path):
        return None
    try:
        with open(path) as handle:
            return json.load(handle)
    except (OSError, json.JSONDecodeError) as error:
        sys.exit(f"results_md.py: cannot read {path}: {error}")


def g(value, digits=3):
    """A number with `digits` significant digits, as text."""
    if value is None:
        return "-"
    return f"{value:.{digits}g}"


def ratio_text(ratio):
    if ratio is None:
        return "-"
    if isinstance(ratio, dict):
        ratio = [ratio["ratio"], ratio["low95"], ratio["high95"]]
    return f"{ratio[0]:.2f} ({ratio[1]:.2f} to {ratio[2]:.2f})"


def wins_text(ratio):
    """The sign test of a paired ratio: links where the rule is below / above FullGauss, p."""
    if not isinstance(ratio, dict) or "links_below" not in ratio:
        return "-"
    return f"{ratio['links_below']}/{ratio['links_above']} (p {ratio['sign_test_p']:.2g})"


def share(value):
    return "-" if value is None else f"{100 * value:.0f}%"


def table(header, rows):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(cell) for cell in row) + " |" for row in rows]
    return "\n".join(lines) + "\n"


def gold_suffix(rules):
    return "_vs_gold" if rules and "relative_error_vs_gold" in rules[0] else ""


def scene_source(links):
    if not links:
        return "generated links"
    scenes = links["scene"] if isinstance(links["scene"], list) else [links["scene"]]
    return f"links of degree-{links['degree']} solves of {' and '.join(scenes)}"


def figure1(name, data):
    out = [f"## Figure 1: {name}\n"]
    links = data["options"].get("links")
    source = scene_source(links)
    rules = data["rules"]
    suffix = gold_suffix(rules)
    against = "the gold" if suffix else "the paper's reference"
    out.append(f"{data['links']} partial links ({source}), constant bases; relative error of "
               f"K[0][0] against {against}; largest link: its share of the rule's mean; ratio: the "
               f"rule's mean over FullGauss's on the same links, with its 95% bootstrap interval "
               f"over links; below/above: links where the rule errs less/more than FullGauss, "
               f"with the sign test's p-value.\n")
    rows = []
    for rule in rules:
        stats = rule["relative_error" + suffix]
        ratio = rule.get("ratio_to_fullgauss", {}).get("relative_error" + suffix)
        rows.append([rule["name"], rule["samples"], g(stats["mean"]), g(stats["sem"], 2), g(stats["median"]),
                     g(stats["p90"]), g(stats["max"]), share(stats.get("largest_share")), ratio_text(ratio),
                     wins_text(ratio)])
    out.append(table(["rule", "samples", "mean", "sem", "median", "p90", "max", "largest link",
                      "ratio to FullGauss", "below/above"], rows))
    reference = data["reference"]["relative_standard_error"]
    if reference.get("mean") is not None:
        out.append(f"\nThe reference's own relative standard error: mean {g(reference['mean'], 2)}, "
                   f"max {g(reference['max'], 2)}.\n")
    out.append(breakdown(data, [rule["name"] for rule in rules], "relative_error" + suffix))
    return "\n".join(out)


def breakdown(part, names, metric):
    out = []
    groups = [(kind, entry) for kind, entry in sorted(part["breakdown"]["by_occluder"].items())]
    for band in part["breakdown"]["by_distance"]:
        low, high = band["distance_factor"]
        groups.append((f"distance {low:g} to {high:g}" if high is not None else f"distance >= {low:g}", band))
    rows = []
    for label, entry in groups:
        if entry.get("links", 0) == 0 or metric not in entry:
            continue
        means = entry[metric]["mean"]
        best = min(range(len(means)), key=lambda r: means[r])
        rows.append([label, entry["links"]] + [f"**{g(m)}**" if r == best else g(m) for r, m in enumerate(means)])
    if rows:
        out.append(f"\nMean {metric.replace('_', ' ')} by occluder kind and by distance band "
                   f"(centre distance over the longest side; the smallest in bold):\n")
        out.append(table(["group", "links"] + names, rows))
    return "\n".join(out)


def figure2(name, data):
    out = [f"## Figure 2: {name}\n"]
    links = data["options"].get("links")
    source = scene_source(links)
    for class_name, part in data["classes"].items():
        rules = part["rules"]
        suffix = "_vs_gold" if "l1_error_bound_vs_gold" in rules[0] else ""
        against = "the gold" if suffix else "the paper's reference"
        out.append(f"### {class_name}: {part['links']} links ({source}), quadratic bases, against {against}\n")
        out.append("U_tot: the sum over the 9 source functions of the L1 error bound per unit area "
                   "(the report's Figure 2); largest link: its share of the rule's mean U_tot; "
                   "Frobenius: the relative Frobenius error of K (scale-free); ratios: the rule's "
                   "mean over FullGauss's on the same links, with their 95% bootstrap intervals "
                   "over links; below/above: links where the rule's U_tot is below/above "
                   "FullGauss's, with the sign test's p-value.\n")
        rows = []
        for rule in rules:
            bound = rule["l1_error_bound" + suffix]
            frobenius = rule.get("relative_frobenius_error" + suffix, {})
            ratios = rule.get("ratio_to_fullgauss", {})
            bound_ratio = ratios.get("l1_error_bound_total" + suffix)
            rows.append([rule["name"], g(bound["total"]), g(bound.get("total_median")), g(bound.get("total_p90")),
                         g(bound.get("total_max")), share(bound.get("total_largest_share")),
                         g(bound["per_source_function"][0]), ratio_text(bound_ratio), wins_text(bound_ratio),
                         g(frobenius.get("mean")), g(frobenius.get("median")),
                         share(frobenius.get("largest_share")),
                         ratio_text(ratios.get("relative_frobenius_error" + suffix))])
        out.append(table(["rule", "U_tot mean", "median", "p90", "max", "largest link", "M(0,0) mean",
                          "U_tot ratio", "below/above", "Frobenius mean", "median", "largest link",
                          "Frobenius ratio"], rows))
        floor = part["reference"].get("l1_standard_error")
        if floor:
            out.append(f"\nThe reference's own L1 standard error (total): {g(floor['total'], 2)}.\n")
        out.append(breakdown(part, [rule["name"] for rule in rules], "l1_error_bound_total" + suffix))
    return "\n".join(out)


def influence_text(name, comparison):
    """A comparison's ratio, and its most influential link: share and ratio without it."""
    link = comparison.get("most_influential_link")
    if link is None:  # claims written before the influence was recorded
        return f"{name} {ratio_text(comparison)}"
    shares = (f"{share(link['share_of_numerator'])}/{share(link['share_of_denominator'])}"
              if "share_of_numerator" in link else f"{share(link['share_of_its_class'])} of {link['class']}")
    return (f"{name} {ratio_text(comparison)}, link {link.get('candidate', link['link'])} "
            f"({shares}): {ratio_text([link['ratio_without'], link['low95_without'], link['high95_without']])}")


def claims(data):
    out = ["## The report's claims on the scene-derived suites (results/claims.json)\n",
           f"Scored against {data['scored_against']}; verdicts as experiments/study/claims.h defines them, "
           f"from {data.get('interval', 'the 95% intervals')}. Each ratio is followed by its most "
           f"influential link (the candidate whose removal moves the ratio most; its share of the "
           f"two sums, or of its class's) and the ratio without it. Fragile: the verdict changes "
           f"when each comparison loses its most influential link.\n"]
    rows = []

    def verdict(claim, prefix=""):
        text = claim[prefix + "verdict"]
        if claim.get(prefix + "fragile"):
            text += f" (fragile: {claim[prefix + 'verdict_without_most_influential_links']} without)"
        return text

    first = data["fig1_stratified_best"]
    rows.append(["Figure 1: Stratified best", verdict(first),
                 "; ".join(influence_text(k, v) for k, v in first["against"].items())])
    second = data["fig2_gauss_best"]
    rows.append(["Figure 2: FullGauss better than every Monte Carlo rule", verdict(second),
                 "; ".join(f"{c}: " + ", ".join(influence_text(k, v) for k, v in part["against"].items())
                           for c, part in second["classes"].items())])
    third = data["fig2_partial_more_error"]
    rows.append(["Figure 2: partial links carry more error (U_tot)", verdict(third),
                 "; ".join(influence_text(k, v["l1_error_bound_total"]) for k, v in third["rules"].items())])
    rows.append(["... in the scale-free Frobenius error", verdict(third["scale_free"]),
                 "; ".join(influence_text(k, v["relative_frobenius_error"]) for k, v in third["rules"].items())])
    out.append(table(["claim", "verdict", "ratios (95% interval), most influential link, ratio without it"], rows))
    return "\n".join(out)


def adaptive(data):
    out = ["## The adaptive rules (results/adaptive.json)\n",
           f"ErrThres {data['options']['threshold']}, BF threshold {data['options']['bf_eps']}, "
           f"kernel check {data['options'].get('kernel_curvature', '-')}, dropped orders "
           f"{data['options'].get('dropped_orders', '-')}. Savings: fixed-rule kernel evaluations over "
           f"the adaptive ones; worst patch: the largest difference of a patch's mean radiosity to the "
           f"fixed solution's, any channel. Near-field links (touching, plane-cut or nearer than "
           f"their sizes) are integrated alike with either rule choice, through exact inner "
           f"integrals at the receiver points counted here, not as kernel evaluations.\n"]
    rows = []
    for row in data["table"]:
        for rules in ("adaptive", "adaptive-novis"):
            entry = row[rules]
            worst = entry["largest_patch_difference"]
            rows.append([row["scene"], row["degree"], rules, f"{entry['kernel_evaluations']:,}",
                         f"{entry['evaluation_ratio']:.2f}",
                         f"{entry.get('near_field_links', 0):,} / {entry.get('near_field_points', 0):,}",
                         f"{100 * entry['relative_l2_difference']:.2f}%",
                         f"{100 * worst['value']:+.2f}% ({worst['patch']}, {worst['channel']})"])
    out.append(table(["scene", "d", "rules", "evaluations", "savings", "near-field links / points",
                      "L2 difference", "worst patch"], rows))
    out.append("\nTimes change from run to run and are not part of the committed results: "
               "`radquad adaptive` writes them to results/adaptive.run.json (docs/performance.md "
               "reads them).\n")
    return "\n".join(out)


def solver_accuracy(data):
    out = ["## The solver against the path tracer (results/solver_accuracy.json)\n",
           f"{data['settings']}; the tracer with {data['samples']:,} samples per patch.\n"]
    rows = []
    for scene in data["scenes"]:
        for degree in scene["degrees"]:
            worst = degree["worst_relative_difference"]
            rows.append([scene["scene"], degree["degree"], degree["elements"],
                         f"{100 * degree['mean_absolute_relative_difference']:.2f}%",
                         f"{100 * worst['value']:+.2f}% ({worst['patch']}, {worst['channel']})"])
    out.append(table(["scene", "d", "elements", "mean abs. difference", "worst patch"], rows))
    out.append("\nCPU times and peak memory: results/solver_accuracy.run.json, beside the result "
               "(not committed).\n")
    return "\n".join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--results", default="results")
    parser.add_argument("--out", default="docs/results.md")
    arguments = parser.parse_args()
    sections = ["# Results\n",
                "Generated by plots/results_md.py from results/*.json (scripts/run-figures.sh); "
                "do not edit by hand. docs/study.md reads these tables against the report.\n"]
    for stem, title, draw in (("fig1.json", "generated links", figure1),
                              ("fig1-scene.json", "scene-derived links", figure1),
                              ("fig2.json", "generated links", figure2),
                              ("fig2-scene.json", "scene-derived links", figure2)):
        data = load(arguments.results, stem)
        if data is not None:
            sections.append(draw(title, data))
    for stem, draw in (("claims.json", claims), ("adaptive.json", adaptive),
                       ("solver_accuracy.json", solver_accuracy)):
        data = load(arguments.results, stem)
        if data is not None:
            sections.append(draw(data))
    text = "\n".join(sections)
    temporary = arguments.out + ".tmp"
    with open(temporary, "w") as handle:
        handle.write(text)
    os.replace(temporary, arguments.out)


if __name__ == "__main__":
    main()
