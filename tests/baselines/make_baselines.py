#!/usr/bin/python3
"""Writes tests/baselines/quick_bounds.json from the quick-suite tables.

Run `radquad figures --quick` first (it writes results/quick/fig1.json and fig2.json from
experiments/configs/fig{1,2}-quick.json), then
    /usr/bin/python3 tests/baselines/make_baselines.py results/quick tests/baselines/quick_bounds.json

Each bound is  measured mean + 3 * (its standard error over links) + 5% of the mean.
The standard error over links is the spread a mean would show on another draw of links of
the same size; 3 of them make a false alarm from a legitimate change that only reshuffles
which links qualify (a ray flipped by rounding on another CPU) improbable, and the 5% covers
deterministic rules whose errors barely vary. A broken rule (a wrong weight or point) changes
errors by factors, far beyond.
"""
import json
import sys


def bound(mean, sem):
    return mean + 3.0 * sem + 0.05 * mean


def main():
    results, target = sys.argv[1], sys.argv[2]
    fig1 = json.load(open(f"{results}/fig1.json"))
    fig2 = json.load(open(f"{results}/fig2.json"))
    out = {
        "_doc": __doc__.strip().splitlines()[0] + " Bound = mean + 3 sem + 0.05 mean; see make_baselines.py.",
        "suites": {"fig1": fig1["options"], "fig2": fig2["options"]},
        "measured_at_commit": {"fig1": fig1["git_commit"], "fig2": fig2["git_commit"]},
        "fig1": {"relative_error_mean": {r["name"]: bound(r["relative_error"]["mean"], r["relative_error"]["sem"])
                                         for r in fig1["rules"]}},
        "fig2": {},
    }
    for name, table in fig2["classes"].items():
        rules = table["rules"]
        out["fig2"][name] = {
            "l1_total": {r["name"]: bound(r["l1_error_bound"]["total"], r["l1_error_bound"]["total_sem"]) for r in rules},
            "l1_constant_source": {r["name"]: bound(r["l1_error_bound"]["per_source_function"][0],
                                                    r["l1_error_bound"]["per_source_function_sem"][0]) for r in rules},
        }
    with open(target, "w") as handle:
        json.dump(out, handle, indent=2)
        handle.write("\n")


if __name__ == "__main__":
    main()
