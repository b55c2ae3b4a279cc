#!/usr/bin/env python3
"""Unoccluded over partial mean U_tot, by rule family and by distance band.

The report's Figure 2 says partially occluded links carry more error than unoccluded ones.
results/claims.json tests it over whole classes; this script splits the same comparison by
the link's distance (centre distance over the longest side, the bands of the tables'
`breakdown.by_distance`), so that a ratio carried by the closest links, which the unoccluded
class holds more of, is told apart from a ratio that holds at equal distance.

It reads the committed tables only (results/fig2.json, results/fig2-scene.json: each class's
`per_link` scores `l1_error_bound_total_vs_gold`, U_tot, the report's metric, or without a
gold `l1_error_bound_total`) and prints, per table, rule and band, the unoccluded class's mean
over the partial class's, with each band's link counts, and then each rule family's range
over its rules. A ratio above 1 means the unoccluded links carry more error (the claim fails
there); below 1, the partial links do, as the report says. Beside each ratio, in parentheses:
the ratio without the unoccluded class's largest link, then without the partial class's, so
that no band's verdict rests on one link unseen. A band where either class has fewer than
`--min-links` links prints "-". `--metric relative_frobenius_error` compares the scale-free
error instead, which does not follow the size of each link's coupling as U_tot does. The
singular class (scene tables) is on neither side, as in results/claims.json.

    /usr/bin/python3 scripts/partial_vs_unoccluded.py [--results results] [--min-links 5]
        [--metric l1_error_bound_total|relative_frobenius_error]
"""

import argparse
import json
import os
import sys

FAMILIES = [
    ("Gauss products", ["FullGauss", "LinSrcGauss", "ConstSrcGauss"]),
    ("Stroud", ["Stroud65", "HierStroud"]),
    ("Monte Carlo", ["MonteCarlo", "NRook", "Stratified"]),
]
# Lower bounds of the tables' distance bands; the last band has no upper bound.
BANDS = [(0.0, 0.5), (0.5, 1.0), (1.0, 2.0), (2.0, None)]
BAND_NAMES = ["all", "< 0.5", "0.5 to 1", "1 to 2", ">= 2"]


def band_of(distance):
    for index, (low, high) in enumerate(BANDS):
        if distance >= low and (high is None or distance < high):
            return index
    raise ValueError(f"distance factor {distance} outside every band")


def class_values(table_class, metric):
    """Per band (index 0: all links): each rule's list of per-link `metric` values."""
    names = [rule["name"] for rule in table_class["rules"]]
    values = [[[] for _ in names] for _ in range(len(BANDS) + 1)]
    for link in table_class["per_link"]:
        for slot in (0, 1 + band_of(link["distance_factor"])):
            for index, value in enumerate(link[metric]):
                values[slot][index].append(value)
    return names, values


def mean_ratio(unoccluded, partial):
    """Mean over mean, and the same without each side's largest link in turn."""
    def mean(values):
        return sum(values) / len(values)
    ratio = mean(unoccluded) / mean(partial)
    without_u = mean(sorted(unoccluded)[:-1]) / mean(partial)
    without_p = mean(unoccluded) / mean(sorted(partial)[:-1])
    return ratio, without_u, without_p


def ratios(path, metric, min_links):
    with open(path) as f:
        table = json.load(f)
    classes = table["classes"]
    if "unoccluded" not in classes or "partial" not in classes:
        raise ValueError(f"{path}: needs an unoccluded and a partial class")
    first = classes["partial"]["per_link"][0]
    metric = metric if metric + "_vs_gold" not in first else metric + "_vs_gold"
    names, unoccluded = class_values(classes["unoccluded"], metric)
    names_p, partial = class_values(classes["partial"], metric)
    if names != names_p:
        raise ValueError(f"{path}: the classes list different rules")
    counts = [(len(u[0]), len(p[0])) for u, p in zip(unoccluded, partial)]
    result = {}
    for index, name in enumerate(names):
        row = []
        for slot, (n_u, n_p) in enumerate(counts):
            if n_u < min_links or n_p < min_links or sum(partial[slot][index]) == 0:
                row.append(None)
            else:
                row.append(mean_ratio(unoccluded[slot][index], partial[slot][index]))
        result[name] = row
    return metric, counts, result


def cell(value):
    return "-" if value is None else "{:.3g} ({:.3g}, {:.3g})".format(*value)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", default="results", help="folder of the tables")
    parser.add_argument("--metric", default="l1_error_bound_total",
                        choices=["l1_error_bound_total", "relative_frobenius_error"],
                        help="the per-link score compared (U_tot, or the scale-free error)")
    parser.add_argument("--min-links", type=int, default=5,
                        help="fewest links of each class for a band's ratio")
    args = parser.parse_args()
    for name in ("fig2.json", "fig2-scene.json"):
        path = os.path.join(args.results, name)
        try:
            metric, counts, result = ratios(path, args.metric, args.min_links)
        except (OSError, ValueError, KeyError, json.JSONDecodeError) as error:
            print(f"{path}: {error}", file=sys.stderr)
            return 2
        print(f"{path}: unoccluded / partial mean {metric}")
        print("| rule | " + " | ".join(BAND_NAMES) + " |")
        print("|---" * (len(BAND_NAMES) + 1) + "|")
        print("| links (unoccluded, partial) | "
              + " | ".join(f"{u}, {p}" for u, p in counts) + " |")
        for rule, row in result.items():
            print(f"| {rule} | " + " | ".join(cell(v) for v in row) + " |")
        for family, rules in FAMILIES:
            present = [result[r] for r in rules if r in result]
            cells = []
            for slot in range(len(BAND_NAMES)):
                values = [row[slot][0] for row in present if row[slot] is not None]
                cells.append("-" if not values else
                             f"{min(values):.3g} to {max(values):.3g}")
            print(f"| {family} | " + " | ".join(cells) + " |")
        print()
    return 0


if __name__ == "__main__":
    sys.exit(main())
