"""The Python module against the command line: the same numbers, bit for bit, for registered
rules, Python rules (against the same rule in a File: JSON file) and study tables; errors as
ValueError with the command line's message. Run by ctest (`python_module`) with PYTHONPATH
set to build/<preset>/python and RADQUAD to the radquad binary."""
import json
import os
import subprocess

import numpy as np
import pytest

import radquad

RADQUAD = os.environ["RADQUAD"]
ROOT = os.path.join(os.path.dirname(__file__), "..", "..")
HALF = os.path.join(ROOT, "experiments", "links", "half_blocked.json")


def cli(*arguments):
    return json.loads(subprocess.run([RADQUAD, *arguments], check=True, capture_output=True,
                                     text=True).stdout)


def same(python, command):
    """Equal entry for entry, arrays bit for bit (NaN never allowed)."""
    if isinstance(command, dict):
        assert set(python) == set(command), (sorted(python), sorted(command))
        for key in command:
            same(python[key], command[key])
    elif isinstance(python, np.ndarray):
        assert np.array_equal(python, np.array(command, dtype=float)), (python, command)
    elif isinstance(command, list):
        assert len(python) == len(command)
        for a, b in zip(python, command):
            same(a, b)
    else:
        assert python == command, (python, command)


def half_link():
    with open(HALF) as handle:
        return json.load(handle)


def test_rules_are_the_command_lines():
    assert radquad.rules() == cli("rules", "--json")


@pytest.mark.parametrize("rule,degree,seed,trials", [
    ("FullGauss", 2, 0, 1), ("Stroud65", 1, 0, 1), ("Stratified", 0, 12345678901234567890, 5),
    ("Gauss:2x3x4x1", 1, 0, 1)])
def test_integrate_matches_radquad_link(rule, degree, seed, trials):
    python = radquad.integrate(half_link(), rule, degree=degree, seed=seed, trials=trials)
    command = cli("link", HALF, "--rule", rule, "--degree", str(degree), "--seed", str(seed),
                  "--trials", str(trials))
    same(python, command)
    assert python["coupling"].shape == ((degree + 1) ** 2, (degree + 1) ** 2)


def test_python_rules_match_the_same_rules_in_files(tmp_path):
    # A 4D rule (a random draw written out) and a product rule (FullGauss's points).
    draw = cli("rules", "--dump", "Stratified", "--seed", "7")
    four = radquad.Rule(np.array(draw["points"]), np.array(draw["weights"]), name="Drawn")
    path = tmp_path / "drawn.json"
    path.write_text(json.dumps(four.to_json()))
    same(radquad.integrate(half_link(), four, degree=1),
         cli("link", HALF, "--rule", f"File:{path}", "--degree", "1"))
    gauss = cli("rules", "--dump", "FullGauss")
    product = radquad.Rule.product(np.array(gauss["receiver"]["points"]), gauss["receiver"]["weights"],
                                   np.array(gauss["source"]["points"]), gauss["source"]["weights"],
                                   name="FullGauss", degree=gauss["degree"])
    python = radquad.integrate(half_link(), product, degree=2)
    registered = cli("link", HALF, "--rule", "FullGauss", "--degree", "2")
    assert np.array_equal(python["coupling"], np.array(registered["coupling"]))
    assert python["kernel_evaluations"] == registered["kernel_evaluations"]


def test_reference_and_gold_match_radquad_reference():
    python = radquad.reference(half_link(), degree=1, seed=3, gold=True)
    command = cli("reference", HALF, "--degree", "1", "--seed", "3", "--gold", "--quiet")
    assert python.pop("link") == "link" and command.pop("link") == HALF  # what names the link
    same(python, command)
    assert python["gold"]["method"] == "exact visibility"
    # The blocker halfway covers x < 0.5: by the mirror x -> 1 - x it leaves exactly half of
    # the opposed unit squares' form factor (parallel rectangles, Howell's catalogue C-11).
    x = y = 1.0
    unoccluded = 2.0 / (np.pi * x * y) * (
        np.log(np.sqrt((1 + x * x) * (1 + y * y) / (1 + x * x + y * y)))
        + x * np.sqrt(1 + y * y) * np.arctan(x / np.sqrt(1 + y * y))
        + y * np.sqrt(1 + x * x) * np.arctan(y / np.sqrt(1 + x * x))
        - x * np.arctan(x) - y * np.arctan(y))
    assert abs(python["gold"]["form_factor"] - 0.5 * unoccluded) < 1e-7


def test_study_with_a_python_rule_matches_the_command_line(tmp_path):
    config = {"figure": "fig2", "seed": 4, "classes": {"unoccluded": 2, "partial": 2},
              "rules": ["FullGauss"], "trials": 2, "reference": {"replicates": 2}}
    draw = cli("rules", "--dump", "NRook", "--seed", "2")
    rule = radquad.Rule(np.array(draw["points"]), np.array(draw["weights"]), name="Rooks")
    python = radquad.study(config, rules=["FullGauss", rule])
    config_path, rule_path, out = tmp_path / "c.json", tmp_path / "r.json", tmp_path / "t.json"
    config_path.write_text(json.dumps(config))
    rule_path.write_text(json.dumps(rule.to_json()))
    subprocess.run([RADQUAD, "study", str(config_path), "--rules", f"FullGauss,File:{rule_path}",
                    "--out", str(out), "--quiet"], check=True)
    command = json.loads(out.read_text())
    for table in (python, command):
        table["options"].pop("config_path", None)
    assert python["options"]["rules"] == ["FullGauss", "Rooks"]
    command["options"]["rules"] = ["FullGauss", "Rooks"]  # the command line names the file
    assert python == command
    assert [r["name"] for r in python["classes"]["partial"]["rules"]] == ["FullGauss", "Rooks"]
    assert "l1_error_bound_vs_gold" in python["classes"]["partial"]["rules"][0]


def test_errors_are_value_errors_with_the_command_lines_messages(tmp_path):
    with pytest.raises(ValueError, match="unknown rule 'Nope'"):
        radquad.integrate(half_link(), "Nope")
    with pytest.raises(ValueError, match="sum"):
        radquad.Rule(np.full((2, 4), 0.5), [0.5, 0.6])
    with pytest.raises(ValueError, match="shape"):
        radquad.Rule(np.full((2, 3), 0.5), [0.5, 0.5])
    with pytest.raises(ValueError, match="named twice"):
        radquad.study({}, rules=["FullGauss", "FullGauss"])
    with pytest.raises(ValueError, match="a list"):
        radquad.study({}, rules="FullGauss")
    with pytest.raises(ValueError, match="outside 0..2"):
        radquad.integrate(half_link(), "MonteCarlo", seed=-1)
    bad = half_link()
    del bad["source"]
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(bad))
    message = subprocess.run([RADQUAD, "link", str(path), "--rule", "FullGauss"],
                             capture_output=True, text=True).stderr
    assert "missing key 'source'" in message
    with pytest.raises(ValueError, match="missing key 'source'"):
        radquad.integrate(bad, "FullGauss")


def four_point_rule(trial):
    """A deterministic rule of its own for each trial (points in [0, 1]^4, equal weights)."""
    points = np.full((4, 4), 0.5)
    points[:, 0] = [0.2, 0.4, 0.6, 0.8]
    points[:, 2] = (np.arange(4) + 0.3 + 0.1 * trial) / 4
    return radquad.Rule(points, np.full(4, 0.25), name=f"Four{trial}")


def test_a_random_rule_from_a_callable_scores_trial_t_with_f_of_t(tmp_path):
    # Two trials: per link, a random rule's errors are the means over its trials, so the
    # callable's table is the mean of the two deterministic rules' tables, metric by metric.
    config = {"figure": "fig2", "seed": 5, "classes": {"unoccluded": 2, "partial": 2},
              "rules": ["FullGauss"], "trials": 2, "reference": {"replicates": 2}}
    drawn = radquad.study(config, rules=[four_point_rule], gold=False)
    apart = radquad.study(config, rules=[four_point_rule(0), four_point_rule(1)], gold=False)
    for linkclass in ("unoccluded", "partial"):
        entry = drawn["classes"][linkclass]["rules"][0]
        first, second = apart["classes"][linkclass]["rules"]
        assert entry["name"] == "Four0" and entry["trials"] == 2, entry
        for metric in ("relative_error", "relative_frobenius_error"):
            expected = 0.5 * (first[metric]["mean"] + second[metric]["mean"])
            assert abs(entry[metric]["mean"] - expected) <= 1e-13 * expected, (metric, entry[metric])
    # The same rule as a File: rule of listed draws, from JSON and from NumPy's .npz.
    listed = radquad.Rule.draws([four_point_rule(0), four_point_rule(1)], name="Four0")
    json_path, npz_path = tmp_path / "four.json", tmp_path / "four.npz"
    json_path.write_text(json.dumps(listed.to_json()))
    draws = listed.to_json()["draws"]
    np.savez(npz_path, name="Four0", points=np.array([d["points"] for d in draws]),
             weights=np.array([d["weights"] for d in draws]))
    for path in (json_path, npz_path):
        table = radquad.study(config, rules=[f"File:{path}"], gold=False)
        assert table["classes"] == drawn["classes"], path
    # Too few draws for the trials asked: refused, naming the rule.
    with pytest.raises(ValueError, match="lists 2 draws but 3 trials"):
        radquad.study(dict(config, trials=3), rules=[listed], gold=False)
    with pytest.raises(ValueError, match="must return a radquad.Rule"):
        radquad.study(config, rules=[lambda trial: "FullGauss"])


def test_dumped_draws_reproduce_a_random_rules_trials(tmp_path):
    # `rules --dump NAME --seed S --draws T` holds the draws of seeds S..S+T-1: the link's T
    # trials with the file and with the registered rule are the same numbers.
    path = tmp_path / "rooks.json"
    path.write_text(json.dumps(cli("rules", "--dump", "NRook:50", "--seed", "9", "--draws", "3")))
    from_file = cli("link", HALF, "--rule", f"File:{path}", "--seed", "9", "--trials", "3",
                    "--degree", "1")
    built_in = cli("link", HALF, "--rule", "NRook:50", "--seed", "9", "--trials", "3",
                   "--degree", "1")
    for key in ("coupling", "mean_coupling", "standard_deviation", "form_factor"):
        same(from_file[key], built_in[key])
    python = radquad.integrate(half_link(), lambda t: radquad.Rule(
        np.array(json.loads(path.read_text())["draws"][t]["points"]), np.full(50, 0.02)),
        degree=1, trials=3)
    assert np.allclose(python["mean_coupling"], np.array(built_in["mean_coupling"]), rtol=1e-14)
