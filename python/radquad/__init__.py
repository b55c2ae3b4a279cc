"""radquad from Python: the command line's computations on links, rules and study suites.

    import radquad
    radquad.rules()                                   # as `radquad rules --json`
    rule = radquad.Rule(points, weights, name="MyRule")          # (N, 4) points in [0, 1]^4
    rule = radquad.Rule.product(rp, rw, sp, sw, name="MyProduct")  # receiver x source
    radquad.integrate(link, "FullGauss", degree=2)    # as `radquad link`
    radquad.integrate(link, rule)
    radquad.reference(link, degree=0, gold=True)      # as `radquad reference`
    radquad.study(config, rules=["FullGauss", rule])  # as `radquad study`, the table as a dict
    radquad.study(config, rules=[lambda trial: radquad.Rule(my_points(trial), w)])
                                                      # a random rule: trial t scores f(t)

A link is a dict in LINK.json form ({"receiver": PATCH, "source": PATCH, "occluders": [...]},
PATCH = {"origin": [x, y, z], "edge_u": [...], "edge_v": [...]}). Results are the command
line's JSON objects as dicts, with the matrices (coupling, standard errors, gold) as NumPy
arrays; the numbers are the command line's, bit for bit. Bad input raises ValueError with the
command line's message; a computation that fails raises ArithmeticError. Python rules are
checked as rule files are (finite, in [0, 1], weights summing to 1, the declared degree) and
give the same numbers as the same rule in a `File:` JSON file. A random rule is a callable
f(trial) -> Rule (or Rule.draws([...])): trial t of a study, or of integrate(..., trials=T),
uses f(t) on every link, as a rule file's listed draws are. docs/cli.md, "Python", and
docs/adding-a-rule.md say more.
"""
import json
import os
import tempfile

import numpy as np

from . import _radquad

__all__ = ["Rule", "rules", "integrate", "reference", "study"]

def _seed(seed, what="seed"):
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)):
        raise ValueError(f"{what} must be an integer, not {type(seed).__name__}")
    seed = int(seed)
    if not 0 <= seed <= 2**64 - 1:
        raise ValueError(f"{what} {seed} outside 0..2^64-1")
    return seed


def _arrays(value):
    """The JSON result with every matrix (a list of equal-length number lists) as an array."""
    if isinstance(value, dict):
        return {key: _arrays(item) for key, item in value.items()}
    if (isinstance(value, list) and value and all(isinstance(row, list) for row in value)
            and all(isinstance(x, (int, float)) for row in value for x in row)):
        return np.array(value, dtype=float)
    if isinstance(value, list):
        return [_arrays(item) for item in value]
    return value


def _link_json(link):
    if not isinstance(link, dict):
        raise ValueError("link must be a dict in LINK.json form")
    return json.dumps(link, allow_nan=False)


def _point_list(array, columns, what):
    array = np.asarray(array, dtype=float)
    if array.ndim != 2 or array.shape[1] != columns:
        raise ValueError(f"{what} must have shape (N, {columns}), not {array.shape}")
    return array.tolist()


def _weight_list(array, count, what):
    array = np.asarray(array, dtype=float)
    if array.shape != (count,):
        raise ValueError(f"{what} must have shape ({count},), not {array.shape}")
    return array.tolist()


class Rule:
    """A deterministic rule from points and weights, checked when made (ValueError)."""

    def __init__(self, points, weights, name="PythonRule", degree=None, citation=""):
        points = _point_list(points, 4, "points")
        data = {"name": name, "degree": degree, "citation": citation, "points": points,
                "weights": _weight_list(weights, len(points), "weights")}
        self._set(data)

    @classmethod
    def product(cls, receiver_points, receiver_weights, source_points, source_weights,
                name="PythonRule", degree=None, citation=""):
        """A receiver x source product rule (integrated as a product, like the Gauss rules)."""
        rule = cls.__new__(cls)
        receiver = _point_list(receiver_points, 2, "receiver_points")
        source = _point_list(source_points, 2, "source_points")
        rule._set({"name": name, "degree": degree, "citation": citation,
                   "receiver": {"points": receiver,
                                "weights": _weight_list(receiver_weights, len(receiver), "receiver_weights")},
                   "source": {"points": source,
                              "weights": _weight_list(source_weights, len(source), "source_weights")}})
        return rule

    @classmethod
    def draws(cls, rules, name=None, citation=""):
        """A random rule given as its draws: trial t uses rules[t] (every one of the same form
        and size, as a rule file's "draws")."""
        rules = list(rules)
        if not rules or not all(isinstance(rule, Rule) for rule in rules):
            raise ValueError("draws must be a non-empty list of radquad.Rule objects")
        listed = []
        for rule in rules:
            data = rule.to_json()
            if "draws" in data:
                raise ValueError(f"draws: rule {data['name']!r} is itself a list of draws")
            listed.append({key: data[key] for key in ("points", "weights", "receiver", "source")
                           if key in data})
        combined = cls.__new__(cls)
        combined._set({"name": name if name is not None else rules[0].name, "citation": citation,
                       "draws": listed})
        return combined

    def _set(self, data):
        self._json = json.dumps(data, allow_nan=False)
        _radquad.check_rule(self._json)  # the rule file's checks
        self.name = data["name"]
        self.degree = data.get("degree")
        self.random = "draws" in data

    def to_json(self):
        """The rule in the rule-file format (`--rule File:PATH` reads it)."""
        return json.loads(self._json)

    def __repr__(self):
        return f"radquad.Rule(name={self.name!r}, degree={self.degree!r})"


def rules():
    """The registered rules: dicts of name, samples, degree (None if random), family, citation."""
    return json.loads(_radquad.rules_json())


def _drawn(function, trials):
    """The rule of listed draws function(0), ..., function(trials - 1)."""
    if trials < 1:
        raise ValueError(f"trials must be at least 1, not {trials}")
    rules = []
    for trial in range(trials):
        rule = function(trial)
        if not isinstance(rule, Rule):
            raise ValueError(f"a rule callable must return a radquad.Rule, not "
                             f"{type(rule).__name__} (trial {trial})")
        rules.append(rule)
    return Rule.draws(rules)


def _rule_argument(rule):
    if isinstance(rule, Rule):
        return rule._json
    if isinstance(rule, str):
        return rule
    raise ValueError("rule must be a name (as radquad.rules() lists, or File:PATH), a radquad.Rule "
                     "or a callable f(trial) -> radquad.Rule")


def integrate(link, rule, degree=0, seed=0, trials=1):
    """One link's coupling with one rule, as `radquad link` prints it. A callable rule
    f(trial) -> Rule is drawn for trials 0..trials-1."""
    if callable(rule) and not isinstance(rule, Rule):
        rule = _drawn(rule, int(trials))
    result = _radquad.integrate(_link_json(link), _rule_argument(rule), int(degree), _seed(seed),
                                int(trials))
    return _arrays(json.loads(result))


def reference(link, degree=0, seed=0, replicates=10, gold=False, gold_method="auto",
              gold_tolerance=1e-7):
    """The paper's reference of one link (and a gold), as `radquad reference` prints it."""
    result = _radquad.reference(_link_json(link), int(degree), _seed(seed), int(replicates),
                                bool(gold), str(gold_method), float(gold_tolerance))
    return _arrays(json.loads(result))


def study(config, rules=None, seed=None, gold=True):
    """A study suite's table, as `radquad study` writes it (without the config's path),
    scored against the gold unless gold=False.

    config: a dict in the study config's form, or the path of a config file. rules: a list of
    names, radquad.Rule objects or callables f(trial) -> Rule, instead of the config's (Rule
    objects are scored as File: rules, under their names, which the table's options record; a
    callable is drawn for the config's trials, default 10, and trial t scores f(t))."""
    if isinstance(config, (str, os.PathLike)):
        with open(config) as handle:
            config = json.load(handle)
    if not isinstance(config, dict):
        raise ValueError("config must be a dict or the path of a study config")
    if rules is not None and not isinstance(rules, (list, tuple)):
        raise ValueError("rules must be a list of names or radquad.Rule objects")
    rules = list(rules or [])
    trials = config.get("trials", 10)
    rules = [_drawn(rule, trials if isinstance(trials, int) else 10)
             if callable(rule) and not isinstance(rule, Rule) else rule for rule in rules]
    labels = [rule.name if isinstance(rule, Rule) else rule for rule in rules]
    repeated = sorted({label for label in labels if labels.count(label) > 1})
    if repeated:
        raise ValueError(f"rules: {', '.join(map(str, repeated))} named twice")
    with tempfile.TemporaryDirectory(prefix="radquad-rules-") as folder:
        names = []
        for k, rule in enumerate(rules):
            if isinstance(rule, Rule):
                path = os.path.join(folder, f"rule{k}.json")
                with open(path, "w") as handle:
                    handle.write(rule._json)
                names.append("File:" + path)
            else:
                names.append(_rule_argument(rule))
        result = _radquad.study(json.dumps(config, allow_nan=False), names, seed is not None,
                                _seed(seed) if seed is not None else 0, bool(gold))
    table = json.loads(result)
    if rules:
        table["options"]["rules"] = labels  # not the temporary files' paths
    return table
