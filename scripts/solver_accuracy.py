#!/usr/bin/python3
"""The solver's accuracy on the built-in scenes against the path tracer, patch by patch.

For each scene: one `radquad trace` (the yardstick, 2^21 paths per patch), then
`radquad solve --degree D` for D = 0..3 at default settings, each timed with /usr/bin/time
(CPU seconds and peak memory). Writes results/solver_accuracy.json: per scene and degree, the
solve's elements, its worst and mean |relative difference| over patches and channels, and every
patch's relative difference per channel with the trace's relative standard error; the times
and memory, which change from run to run, go to the run record results/solver_accuracy.run.json.
Each JSON is written to a temporary file and renamed, so a failed run leaves the old one.

Usage: /usr/bin/python3 scripts/solver_accuracy.py [--radquad PATH] [--out FILE]
       [--samples N] [--scenes cornell,slats] [--degrees 0,1,2,3]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile


def run_json(command, what):
    """Runs `command` under /usr/bin/time; returns (its JSON stdout, CPU seconds, peak KiB)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as timing:
        result = subprocess.run(["/usr/bin/time", "-f", "%U %S %M", "-o", timing.name] + command,
                                capture_output=True, text=True)
        if result.returncode != 0:
            sys.stderr.write(result.stderr)
            sys.exit(f"solver_accuracy: {what} failed with exit status {result.returncode}")
        user, system, peak = timing.read().split()[-3:]
    return json.loads(result.stdout), float(user) + float(system), int(peak)


def compare(solved, traced):
    patches, differences = [], []
    for solve_patch, trace_patch in zip(solved["patches"], traced["patches"]):
        assert solve_patch["name"] == trace_patch["name"]
        relative, errors = [], []
        for c in range(3):
            reference = trace_patch["mean_radiosity"][c]
            error = trace_patch["standard_error"][c]
            if reference == 0.0:
                relative.append(None)
                errors.append(None)
                continue
            relative.append(solve_patch["mean_radiosity"][c] / reference - 1.0)
            errors.append(error / reference)
            differences.append((abs(relative[-1]), solve_patch["name"], "rgb"[c], relative[-1]))
        patches.append({"name": solve_patch["name"], "relative_difference": relative,
                        "trace_relative_standard_error": errors})
    worst = max(differences)
    return patches, {"value": worst[3], "patch": worst[1], "channel": worst[2]}, \
        sum(d[0] for d in differences) / len(differences)


def built_from(radquad):
    """The commit `radquad --version` names (the tree the binary was built from)."""
    result = subprocess.run([radquad, "--version"], capture_output=True, text=True)
    match = re.search(r"\(commit ([^,]+),", result.stdout)
    if result.returncode != 0 or not match:
        sys.exit(f"solver_accuracy: {radquad} --version did not name a commit: "
                 f"{result.stdout.strip()} {result.stderr.strip()}")
    return match.group(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--radquad", default=os.path.join(root, "build/release/experiments/radquad"))
    parser.add_argument("--out", default=os.path.join(root, "results/solver_accuracy.json"))
    parser.add_argument("--samples", type=int, default=2 ** 21)
    parser.add_argument("--scenes", default="cornell,slats")
    parser.add_argument("--degrees", default="0,1,2,3")
    args = parser.parse_args()
    degrees = [int(d) for d in args.degrees.split(",")]
    if args.samples < 1 or any(d < 0 or d > 3 for d in degrees):
        sys.exit("solver_accuracy: --samples must be >= 1 and --degrees within 0..3")
    out = {"samples": args.samples, "settings": "radquad solve defaults", "scenes": []}
    # What changes from run to run (CPU times, memory) goes to the run record beside the result.
    record = {"result": os.path.basename(args.out), "git_commit": built_from(args.radquad),
              "scenes": []}
    for scene in args.scenes.split(","):
        print(f"solver_accuracy: tracing {scene}", file=sys.stderr)
        traced, trace_cpu, _ = run_json([args.radquad, "trace", scene, "--samples", str(args.samples),
                                         "--quiet"], f"radquad trace {scene}")
        entry = {"scene": scene, "degrees": []}
        timed = {"scene": scene, "trace_cpu_seconds": trace_cpu, "degrees": []}
        for degree in degrees:
            print(f"solver_accuracy: solving {scene} at degree {degree}", file=sys.stderr)
            solved, cpu, peak = run_json([args.radquad, "solve", scene, "--degree", str(degree),
                                          "--quiet"], f"radquad solve {scene} --degree {degree}")
            patches, worst, mean = compare(solved, traced)
            timed["degrees"].append({
                "degree": degree, "cpu_seconds": cpu, "peak_memory_mib": peak / 1024.0,
                "elapsed_seconds": solved["elapsed_seconds"]})
            entry["degrees"].append({
                "degree": degree, "elements": solved["elements"],
                "worst_relative_difference": worst, "mean_absolute_relative_difference": mean,
                "patches": patches})
            print(f"  worst {worst['value']:+.4f} ({worst['patch']}, {worst['channel']}), "
                  f"mean {mean:.4f}, {cpu:.1f} s CPU, {peak / 1024 / 1024:.2f} GiB", file=sys.stderr)
        out["scenes"].append(entry)
        record["scenes"].append(timed)
    write_atomically(args.out, out)
    stem = os.path.splitext(args.out)[0]
    write_atomically(stem + ".run.json", record)


def write_atomically(path, value):
    directory = os.path.dirname(os.path.abspath(path))
    os.makedirs(directory, exist_ok=True)
    with tempfile.NamedTemporaryFile("w", dir=directory, delete=False, suffix=".tmp") as handle:
        json.dump(value, handle, indent=1)
        handle.write("\n")
    os.chmod(handle.name, 0o644)
    os.replace(handle.name, path)


if __name__ == "__main__":
    main()
