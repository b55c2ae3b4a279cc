#!/usr/bin/python3
"""The reference radiosities of the committed test scenes (radiosity/scenes/), and their check.

Every scene NAME.json in radiosity/scenes/ has a reference, radiosity/scenes/references/NAME.json:
- "reference": "exact" for the white furnaces (a closed box whose every face emits 1 with
  reflectance rho: the radiosity is 1 / (1 - rho) on every patch, so that is the yardstick
  there, with standard error 0);
- "reference": "trace" for every other scene: the output of `radquad trace NAME.json --seed
  SEED --samples N` (without its elapsed_seconds, so a regeneration with the same binary
  gives the same file byte for byte), N = 2^21 but where WRITE_SAMPLES says otherwise.

Write (regenerate) the references:
  /usr/bin/python3 scripts/scene_references.py write [--scenes a,b] [--samples N] [--seed S]
      [--radquad PATH]
Check that they still describe what `radquad trace` computes: a fresh, short trace of every
scene (another seed) must agree with the committed reference patch by patch (below); exits
1 when it does not, 2 on bad input:
  /usr/bin/python3 scripts/scene_references.py check [--samples N] [--seed S] [--radquad PATH]

The check, per scene, over every patch and channel with a defined score
z = (fresh - reference) / sqrt(se_fresh^2 + se_reference^2):
- no |z| above 5 (for unbiased estimates P(|z| > 5) is 6e-7 per comparison);
- the mean of z^2 over the scene's n patches (each patch's channels averaged, since grey
  patches repeat one value three times) below the 1 - 1e-4 quantile of chi-square(n) / n
  (Wilson and Hilferty's approximation), so a shift of the whole scene by a standard error
  or two of the short trace shows while noise does not.
A furnace's fresh trace is checked against its exact value the same way (se_reference = 0).
"""
import argparse
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

from solver_accuracy import write_atomically  # scripts/: beside this file

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = os.path.join(ROOT, "radiosity/scenes")
REFERENCES = os.path.join(SCENES, "references")
# Paths per patch where the default (2^21 to write, 2^14 to check) does not fit: the office
# would take much longer than the others; block_wallwash, lit only by a hot spot on a wall, has
# several times the others' variance, so it takes sixteen times the paths. The furnaces are
# checked with fewer (their paths at rho = 0.99 are a hundred bounces long).
WRITE_SAMPLES = {"office": 2 ** 20, "block_wallwash": 2 ** 23}
CHECK_SAMPLES = {"office": 2 ** 12, "block_wallwash": 2 ** 18, "furnace_0.5": 2 ** 12,
                 "furnace_0.9": 2 ** 12, "furnace_0.99": 2 ** 12}


def scene_names():
    return sorted(os.path.splitext(os.path.basename(p))[0]
                  for p in glob.glob(os.path.join(SCENES, "*.json")))


def furnace_reflectance(name, scene):
    """rho for a white furnace (a scene named furnace_*: a closed box, scripts/nearfield_scenes.py,
    whose every patch emits 1 with one grey reflectance rho), else None."""
    if not name.startswith("furnace_"):
        return None
    patches = scene["patches"]
    rhos = {tuple(p["reflectance"]) for p in patches}
    rho = rhos.pop()
    if rhos or not all(p.get("emission") == [1, 1, 1] for p in patches) or len(set(rho)) != 1:
        sys.exit(f"scene_references: {name}: not a white furnace (every patch emitting 1 with "
                 "one grey reflectance)")
    return rho[0]


def trace(radquad, path, samples, seed):
    with tempfile.NamedTemporaryFile("r", suffix=".time") as timing:
        result = subprocess.run(["/usr/bin/time", "-f", "%U %S", "-o", timing.name, radquad,
                                 "trace", path, "--samples", str(samples), "--seed", str(seed),
                                 "--quiet"], capture_output=True, text=True)
        if result.returncode != 0:
            sys.stderr.write(result.stderr)
            sys.exit(f"scene_references: radquad trace {path} failed with exit status "
                     f"{result.returncode}")
        user, system = timing.read().split()[-2:]
    return json.loads(result.stdout), float(user) + float(system)


def exact_reference(name, scene, rho):
    value = 1.0 / (1.0 - rho)
    return {"reference": "exact",
            "scene": name + ".json",
            "exact": f"a closed box, every face emitting 1 with reflectance {rho}: "
                     "B = 1 / (1 - rho)",
            "patches": [{"name": p["name"], "mean_radiosity": [value] * 3,
                         "standard_error": [0.0] * 3} for p in scene["patches"]]}


def worst_relative_error(reference):
    worst = (0.0, None, None)
    for p in reference["patches"]:
        for c in range(3):
            mean, error = p["mean_radiosity"][c], p["standard_error"][c]
            if mean > 0 and error / mean > worst[0]:
                worst = (error / mean, p["name"], "rgb"[c])
    return worst


def write(args):
    for name in args.scenes:
        path = os.path.join(SCENES, name + ".json")
        scene = json.load(open(path))
        rho = furnace_reflectance(name, scene)
        if rho is not None:
            reference = exact_reference(name, scene, rho)
            print(f"{name}: exact, {1 / (1 - rho):.6g}", file=sys.stderr)
        else:
            samples = args.samples or WRITE_SAMPLES.get(name, 2 ** 21)
            print(f"{name}: tracing {samples} paths per patch (seed {args.seed})", file=sys.stderr)
            traced, cpu = trace(args.radquad, path, samples, args.seed)
            traced.pop("elapsed_seconds")
            traced["scene"] = name + ".json"  # not the path it was traced from
            reference = {"reference": "trace", **traced}
            se, patch, channel = worst_relative_error(reference)
            print(f"  {cpu:.0f} s CPU, {traced['paths']} paths, worst relative standard error "
                  f"{100 * se:.3f}% ({patch}, {channel})", file=sys.stderr)
        write_atomically(os.path.join(REFERENCES, name + ".json"), reference)


def scores(fresh, reference):
    """Per patch, the channels' z scores (None where both standard errors are 0)."""
    out = []
    for a, b in zip(fresh["patches"], reference["patches"]):
        if a["name"] != b["name"]:
            sys.exit(f"scene_references: patch {a['name']} against {b['name']}: the scene and "
                     "its reference list different patches (regenerate the reference)")
        z = []
        for c in range(3):
            spread = math.hypot(a["standard_error"][c], b["standard_error"][c])
            difference = a["mean_radiosity"][c] - b["mean_radiosity"][c]
            z.append(None if spread == 0 else difference / spread)
            if spread == 0 and difference != 0:
                z[-1] = math.inf
        out.append((a["name"], z))
    return out


def chi_square_mean_bound(n):
    """The 1 - 1e-4 quantile of the mean of n independent chi-square(1) variables, by Wilson
    and Hilferty's cube-root normal approximation (3.719: the normal's 1 - 1e-4 quantile)."""
    h = 2.0 / (9.0 * n)
    return (1.0 - h + 3.719 * math.sqrt(h)) ** 3


def check(args):
    failures = 0
    for name in args.scenes:
        path = os.path.join(SCENES, name + ".json")
        reference_path = os.path.join(REFERENCES, name + ".json")
        if not os.path.exists(reference_path):
            sys.exit(f"scene_references: {reference_path}: no reference (write it)")
        reference = json.load(open(reference_path))
        samples = args.samples or CHECK_SAMPLES.get(name, 2 ** 14)
        fresh, cpu = trace(args.radquad, path, samples, args.seed)
        per_patch = scores(fresh, reference)
        worst = max(((abs(s), patch, "rgb"[c]) for patch, z in per_patch
                     for c, s in enumerate(z) if s is not None), default=(0.0, None, None))
        means = [sum(s * s for s in z if s is not None) / len([s for s in z if s is not None])
                 for _, z in per_patch if any(s is not None for s in z)]
        mean_square = sum(means) / len(means) if means else 0.0
        bound = chi_square_mean_bound(max(1, len(means)))
        bad = worst[0] > 5 or mean_square > bound
        failures += bad
        print(f"{'FAIL' if bad else 'ok'}: {name} ({reference['reference']}, {samples} paths per "
              f"patch, {cpu:.1f} s CPU): worst |z| {worst[0]:.2f} ({worst[1]}, {worst[2]}), "
              f"mean z^2 {mean_square:.2f} (bound {bound:.2f}, {len(means)} patches)")
    if failures:
        print(f"{failures} scene(s) disagree with their committed reference: the tracer changed "
              "(regenerate with scene_references.py write) or the scene did")
        sys.exit(1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("mode", choices=["write", "check"])
    parser.add_argument("--radquad",
                        default=os.path.join(ROOT, "build/release/experiments/radquad"))
    parser.add_argument("--scenes", default=",".join(scene_names()))
    parser.add_argument("--seed", type=int, default=None,
                        help="default 0 for write, 1 for check (a stream apart from the "
                             "reference's)")
    parser.add_argument("--samples", type=int, default=None,
                        help="paths per patch for every scene (default: WRITE_SAMPLES or "
                             "CHECK_SAMPLES, else 2^21 to write and 2^14 to check)")
    args = parser.parse_args()
    args.scenes = args.scenes.split(",")
    unknown = [s for s in args.scenes if s not in scene_names()]
    if unknown:
        print(f"scene_references: no scene {', '.join(unknown)} in {SCENES}", file=sys.stderr)
        sys.exit(2)
    if args.seed is None:
        args.seed = 0 if args.mode == "write" else 1
    if args.samples is not None and args.samples < 2:
        print("scene_references: sample counts must be at least 2", file=sys.stderr)
        sys.exit(2)
    (write if args.mode == "write" else check)(args)


if __name__ == "__main__":
    main()
