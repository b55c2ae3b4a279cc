#!/usr/bin/python3
"""The key tables of docs/cli.md against what the code writes.

A table whose header's first cell names an output ("results/adaptive.json", "`radquad solve`")
lists that output's keys in backticks in its rows' first cells. Checked both ways:
- results/adaptive.json and results/solver_accuracy.json: every key in the committed file, at
  any depth (list elements included), is listed (adaptive.json's solve statistics in the table
  of `radquad solve`), and every key listed is in the file;
- their run records (not committed): the keys listed are the ones the writers name
  (experiments/commands/adaptive_command.cpp, scripts/solver_accuracy.py);
- `radquad solve` and `radquad trace` (no committed output): the keys listed are the JSON keys
  their sources write (experiments/solve_report.cpp, trace_report.cpp, commands/).
Usage: result_schemas_test.py SOURCE_DIR
"""
import json
import re
import sys

root = sys.argv[1]
KEY = re.compile(r"^[a-z][a-z0-9_-]*$")


def read(path):
    with open(f"{root}/{path}") as handle:
        return handle.read()


def tables(markdown):
    """{header's first cell (backticks removed): set of keys in the rows' first cells}."""
    found, header, rows = {}, None, None
    for line in markdown.splitlines() + [""]:
        if not line.startswith("|"):
            header = rows = None
            continue
        first = line.split("|")[1].strip()
        if header is None:
            header, rows = first.replace("`", ""), 0
            found.setdefault(header, set())
        elif rows == 0 and set(first) <= set("-: "):
            rows = 1
        else:
            found[header] |= set(re.findall(r"`([^`]*)`", first))
    return found


def keys(value):
    """Every object key in a JSON value, at any depth."""
    if isinstance(value, dict):
        return set(value).union(*(keys(v) for v in value.values()))
    if isinstance(value, list):
        return set().union(*(keys(v) for v in value))
    return set()


failures = []


def same(what, documented, actual, extra_allowed=frozenset()):
    for key in sorted(actual - documented - extra_allowed):
        failures.append(f"{what}: key `{key}` is written but not documented")
    for key in sorted(documented - actual):
        failures.append(f"{what}: key `{key}` is documented but not written")


doc = tables(read("docs/cli.md"))
names = ["results/adaptive.json", "results/adaptive.run.json", "results/solver_accuracy.json",
         "results/solver_accuracy.run.json", "radquad solve", "radquad trace"]
for name in names:
    if not doc.get(name):
        failures.append(f"docs/cli.md has no table of {name}")
    for token in sorted(doc.get(name, set())):
        if not KEY.match(token):
            failures.append(f"docs/cli.md, table of {name}: `{token}` is not a key")
if failures:
    sys.exit("FAILED:\n  " + "\n  ".join(failures))
solve = doc["radquad solve"] | doc["radquad trace"]

# The committed results.
for name, allowed in (("results/adaptive.json", solve), ("results/solver_accuracy.json", set())):
    same(name, doc[name], keys(json.loads(read(name))), allowed)

# The run records: adaptive.json's keys moved out (splitRunRecord) and writeRunRecord's own.
lists = re.search(r"timingKeys = \{([^}]*)\}", read("experiments/commands/adaptive_command.cpp"))
lists = lists.group(1) + re.search(r"kSolveTimingKeys\[\] = \{([^}]*)\}",
                                   read("experiments/solve_report.h")).group(1)
record = set(re.findall(r'"([a-z][a-z0-9_]*)"', lists))
record |= set(re.findall(r'record\["([a-z][a-z0-9_]*)"\] =',
                         read("experiments/study/study_output.cpp")))
same("results/adaptive.run.json", doc["results/adaptive.run.json"], record)
# solver_accuracy.py writes the result and its record with dict literals only.
script = set(re.findall(r'"([a-z][a-z0-9_]*)":', read("scripts/solver_accuracy.py")))
same("scripts/solver_accuracy.py (result and run record)",
     doc["results/solver_accuracy.json"] | doc["results/solver_accuracy.run.json"], script)

# `radquad solve` and `radquad trace`: {"key", value} pairs (not `= {"red", ...}` arrays of
# names) and out["key"] assignments.
written = set()
for path in ("experiments/solve_report.cpp", "experiments/commands/solve_command.cpp",
             "experiments/trace_report.cpp", "experiments/commands/trace_command.cpp"):
    text = read(path)
    written |= set(re.findall(r'(?<!= )\{"([a-z][a-z0-9_]*)",', text))
    written |= set(re.findall(r'\["([a-z][a-z0-9_]*)"\]', text))
same("radquad solve and trace", solve, written)

if failures:
    sys.exit("FAILED:\n  " + "\n  ".join(failures))
print(f"result_schemas: the {sum(len(doc[name]) for name in names)} keys of {len(names)} tables "
      "match the outputs")
