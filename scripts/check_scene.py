#!/usr/bin/python3
"""The solver against the committed reference of a test scene, patch by patch.

Solves radiosity/scenes/SCENE.json with `radquad solve --degree D` (the defaults, plus any
options after `--`) under /usr/bin/time -v, and compares every patch's mean radiosity, every
channel, with the scene's reference (radiosity/scenes/references/SCENE.json: a `radquad
trace`, or the exact 1 / (1 - rho) of a white furnace; scripts/scene_references.py). Prints,
per case: the worst patch (name, channel, signed relative error, and the reference's relative
standard error there), the mean absolute relative error over patches and channels, the
form-factor-sum maximum, whether the solve converged and its exit status, its CPU seconds and
peak memory. A case fails when the solve does not exit 0 with `converged: true`, or a patch
is off by more than the tolerance. Exit status: 0 when every case passes, 1 when one fails,
2 on bad input.

Default tolerances (relative, every patch and channel): 1% at degrees 2 and 3, 2% at degree
1; at degree 0, 5% (piecewise-constant elements take a coarse ancestor's mean irradiance
where a link was accepted high in the hierarchy: cornell's worst patch at degree 0 is 4.9%),
except 2% for square_under_ceiling (its target at every degree); 1% at every degree for the
white furnaces, whose reference is exact.

Usage: /usr/bin/python3 scripts/check_scene.py SCENE[,SCENE...] [--degrees 0,1,2,3]
       [--tolerance T] [--radquad PATH] [--json OUT] [--markdown] [-- SOLVE OPTIONS...]
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "radiosity/scenes")


def default_tolerance(scene, degree, exact):
    if exact:
        return 0.01
    if degree >= 2:
        return 0.01
    if degree == 1:
        return 0.02
    return 0.02 if scene == "square_under_ceiling" else 0.05


def solve(radquad, path, degree, extra):
    """Runs the solve under /usr/bin/time -v: (exit status, its JSON or None, stderr lines,
    CPU seconds, peak resident MiB, wall seconds)."""
    with tempfile.NamedTemporaryFile("r", suffix=".time") as timing:
        command = ["/usr/bin/time", "-v", "-o", timing.name, radquad, "solve", path, "--degree",
                   str(degree), "--quiet"] + extra
        result = subprocess.run(command, capture_output=True, text=True)
        report = timing.read()
    field = lambda label: re.search(re.escape(label) + r": *([0-9.:]+)", report).group(1)
    cpu = float(field("User time (seconds)")) + float(field("System time (seconds)"))
    peak = float(field("Maximum resident set size (kbytes)")) / 1024.0
    wall = 0.0
    for part in field("Elapsed (wall clock) time (h:mm:ss or m:ss)").split(":"):
        wall = 60 * wall + float(part)
    try:
        out = json.loads(result.stdout)
    except json.JSONDecodeError:
        out = None
    return result.returncode, out, result.stderr.strip().splitlines(), cpu, peak, wall


def compare(solved, reference):
    """Per patch and channel, solve / reference - 1; the worst, the mean |error|, and the
    comparisons that cannot be made (a reference of 0 where the solve is not 0)."""
    worst, total, count, undefined = None, 0.0, 0, []
    if [p["name"] for p in solved["patches"]] != [p["name"] for p in reference["patches"]]:
        sys.exit("check_scene: the solve's patches differ from the reference's (regenerate it)")
    for s, r in zip(solved["patches"], reference["patches"]):
        for c in range(3):
            value, expected = s["mean_radiosity"][c], r["mean_radiosity"][c]
            if expected == 0.0:
                if value != 0.0:
                    undefined.append((s["name"], "rgb"[c], value))
                continue
            error = value / expected - 1.0
            total += abs(error)
            count += 1
            if worst is None or abs(error) > abs(worst["error"]):
                worst = {"patch": s["name"], "channel": "rgb"[c], "error": error,
                         "reference_relative_se": r["standard_error"][c] / expected}
    return worst, total / max(count, 1), undefined, count


def check(scene, degree, args):
    path = os.path.join(SCENES, scene + ".json")
    reference = json.load(open(os.path.join(SCENES, "references", scene + ".json")))
    exact = reference["reference"] == "exact"
    tolerance = args.tolerance if args.tolerance is not None else default_tolerance(
        scene, degree, exact)
    status, out, stderr, cpu, peak, wall = solve(args.radquad, path, degree, args.solve)
    record = {"scene": scene, "degree": degree, "tolerance": tolerance,
              "reference": reference["reference"], "exit_status": status, "cpu_seconds": cpu,
              "peak_memory_mib": peak, "wall_seconds": wall, "solve_options": args.solve}
    if out is None:
        record.update({"passed": False, "failure": stderr[-1] if stderr else "no JSON output"})
        print(f"FAIL {scene} d{degree}: exit status {status}, no result: {record['failure']}")
        return record
    worst, mean, undefined, count = compare(out, reference)
    sums = out.get("form_factor_sums", {})
    record.update({
        "converged": out.get("converged"), "failure": out.get("failure"), "worst": worst,
        "mean_absolute_error": mean, "comparisons": count, "undefined": undefined,
        "form_factor_sum_maximum": sums.get("maximum"), "form_factor_sum_patch": sums.get("patch"),
        "elements": out.get("elements"), "iterations": out.get("iterations"),
        "warnings": [line for line in stderr if "warning" in line]})
    beyond = [(p["name"], "rgb"[c], p["mean_radiosity"][c] / r["mean_radiosity"][c] - 1.0)
              for p, r in zip(out["patches"], reference["patches"]) for c in range(3)
              if r["mean_radiosity"][c] != 0.0
              and abs(p["mean_radiosity"][c] / r["mean_radiosity"][c] - 1.0) > tolerance]
    record["beyond_tolerance"] = len(beyond)
    record["passed"] = status == 0 and out.get("converged") is True and not beyond and not undefined
    verdict = "ok  " if record["passed"] else "FAIL"
    print(f"{verdict} {scene} d{degree}: worst {worst['error']:+.2%} ({worst['patch']}, "
          f"{worst['channel']}; reference SE {worst['reference_relative_se']:.2%}), mean "
          f"{mean:.2%}, {len(beyond)}/{count} beyond {tolerance:.0%}; form-factor sum max "
          f"{sums.get('maximum', float('nan')):.3f}; converged {out.get('converged')}, exit "
          f"{status}; {cpu:.1f} s CPU, {wall:.1f} s wall, {peak / 1024:.2f} GiB")
    for name, channel, error in sorted(beyond, key=lambda b: -abs(b[2]))[:args.show]:
        print(f"    {name} ({channel}): {error:+.2%}")
    for name, channel, value in undefined:
        print(f"    {name} ({channel}): {value:.4g} where the reference is 0")
    if out.get("failure"):
        print(f"    failure: {out['failure']}")
    return record


def markdown(records):
    lines = ["| scene | d | worst patch (channel) | error | ref. SE | mean abs. | beyond tol. "
             "| FF-sum max (patch) | converged, exit | iterations | CPU s | wall s | peak GiB |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in records:
        cost = (f"{r['cpu_seconds']:.1f} | {r['wall_seconds']:.1f} | "
                f"{r['peak_memory_mib'] / 1024:.2f} |")
        if "worst" not in r:
            lines.append(f"| {r['scene']} | {r['degree']} | no result | | | | | | exit "
                         f"{r['exit_status']} | | {cost}")
            continue
        w = r["worst"]
        lines.append(
            f"| {r['scene']} | {r['degree']} | {w['patch']} ({w['channel']}) | {w['error']:+.2%} "
            f"| {w['reference_relative_se']:.2%} | {r['mean_absolute_error']:.2%} | "
            f"{r['beyond_tolerance']}/{r['comparisons']} at {r['tolerance']:.0%} | "
            f"{r['form_factor_sum_maximum']:.3f} ({r['form_factor_sum_patch']}) | "
            f"{r['converged']}, {r['exit_status']} | {r['iterations']} | {cost}")
    return "\n".join(lines)


def main():
    argv = sys.argv[1:]
    solve_options = []
    if "--" in argv:
        solve_options = argv[argv.index("--") + 1:]
        argv = argv[:argv.index("--")]
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenes", help="comma-separated names of radiosity/scenes/*.json, or 'all'")
    parser.add_argument("--degrees", default="0,1,2,3")
    parser.add_argument("--tolerance", type=float, default=None)
    parser.add_argument("--radquad",
                        default=os.path.join(ROOT, "build/release/experiments/radquad"))
    parser.add_argument("--json", help="write every case's record to this file")
    parser.add_argument("--markdown", action="store_true", help="print a table at the end")
    parser.add_argument("--show", type=int, default=10, help="patches listed beyond the tolerance")
    args = parser.parse_args(argv)
    args.solve = solve_options
    known = sorted(os.path.basename(p)[:-5] for p in glob.glob(os.path.join(SCENES, "*.json")))
    scenes = known if args.scenes == "all" else args.scenes.split(",")
    try:
        degrees = [int(d) for d in args.degrees.split(",")]
    except ValueError:
        degrees = [-1]
    if any(s not in known for s in scenes) or any(d not in range(4) for d in degrees) or (
            args.tolerance is not None and not args.tolerance > 0):
        print(f"check_scene: scenes must be among {', '.join(known)} (or all), degrees within "
              "0..3 and the tolerance positive", file=sys.stderr)
        sys.exit(2)
    records = [check(scene, degree, args) for scene in scenes for degree in degrees]
    if args.json:
        with open(args.json, "w") as handle:
            json.dump(records, handle, indent=1)
            handle.write("\n")
    if args.markdown:
        print(markdown(records))
    sys.exit(0 if all(r["passed"] for r in records) else 1)


if __name__ == "__main__":
    main()
