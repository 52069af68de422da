r"""Adversarial command lines, written from what users type -- not from the derivations' shapes.

Each generator draws one *case*: a plain dict with the system, the strings a user would pass
(``--environment``, ``--controller``, ``--operator``, ``--param NAME=VALUE`` written as decimals,
``1e-300`` ... ``1e300``, zero and negative gains), the discretisation and approximation, the
delay, and for design questions the parameter of ``--range`` / the use of ``--delay-margin`` /
the ``--vary`` of ``boundary``. Nothing here knows how the toolkit derives anything; the
environments are what a designer writes down:

* improper and nearly improper ``H(z)`` (``K*z**2``, ``z/(z-1)*K``, leading coefficients
  ``1e-12``), forward-differenced derivatives (``K + B*(z-1)/T``);
* ``C(s)`` designs (PD, PID with filtered derivative, lead-lag, pure derivative ``B*s``,
  ``M*s**2``, integrators, resonators with poles on the imaginary axis) on every
  ``--discretize`` with every ``--approximation``;
* trigonometric real parts: Dirichlet kernels (moving averages ``(1 + z^-1 + ... + z^-N)``),
  products of sines (``(z - 1)(z^k - 1)/z^k``), shifted cosines (``z^-k``, ``(z^k + z^-k)/2``);
* poles on and just off the unit circle, double poles, delays up to 60 samples, ``w -> 0``
  (resonances at ``w = 1e-9``);
* teleoperators with unequal dampers ``b_m != b_s`` and scalings ``alpha != 1``;
* multi-user scenes with per-user dampers, couplings and delays;
* n-port impedance matrices ``Z(s)`` (``derive network``): improper by one or two, double poles
  at 0 and on the axis, all-pass, nearly improper ``R + 1e-12 s^2``, non-reciprocal 2-ports.

``case_argv(case)`` turns a case into the argument list of the command-line tool.

>>> import random
>>> case = single_user_environment(random.Random(3))
>>> case["family"], case_argv(case)[:2]
('su-env', ['derive', 'single-user'])
"""

from __future__ import annotations

import random
import re
from fractions import Fraction


__all__ = [
    "number", "magnitude", "single_user_environment", "single_user_design", "single_user_range",
    "single_user_margin", "single_user_boundary", "teleoperator", "multi_user", "FAMILIES", "case_argv",
]

APPROXIMATIONS = ("forward", "backward", "tustin")
METHODS = ("forward", "backward", "tustin", "zoh", "matched")


# ---------------------------------------------------------------------------------------------
# numbers as users write them
# ---------------------------------------------------------------------------------------------
def number(rng: random.Random, value: Fraction | float | int) -> str:
    """A decimal spelling of ``value`` (``0.015``, ``1.5e-2``, ``15E-3``, an integer...)."""
    if isinstance(value, str):
        return value
    v = Fraction(value)
    if v.denominator == 1 and abs(v) < 10**6:
        return str(v.numerator)
    f = float(v) if abs(v) < Fraction(10) ** 300 else None
    style = rng.randrange(3)
    if f is not None and 1e-4 <= abs(f) < 1e6 and style == 0:
        return repr(f) if "e" not in repr(f) else f"{f:.6f}"
    text = f"{f:.6g}" if f is not None else str(v)
    if style == 2:
        text = text.replace("e", "E")
    return text


def magnitude(rng: random.Random, profile: str | None = None, signed: float = 0.0, zero: float = 0.0) -> str:
    """A positive magnitude (``typical`` 1e-4..1e3, ``extreme`` 1e-300..1e300, ``tiny``,
    ``huge``), sometimes exactly zero or negative, as a decimal string."""
    if rng.random() < zero:
        return "0"
    profile = profile or rng.choice(["typical"] * 6 + ["extreme", "tiny", "huge"])
    lo, hi = {"typical": (-4, 3), "extreme": (-300, 300), "tiny": (-300, -30), "huge": (30, 300)}[profile]
    exponent = rng.randint(lo, hi)
    mant = rng.choice(["1", "2", "2.5", "3", "5", "7.5", "9.99", "1.001", str(rng.randint(11, 99) / 10)])
    text = f"{mant}e{exponent}" if profile != "typical" or rng.random() < 0.5 else number(rng, Fraction(mant) * Fraction(10) ** exponent)
    if rng.random() < signed:
        text = "-" + text
    return text


def _period(rng: random.Random) -> str:
    return rng.choice(["0.001", "0.001", "1e-3", "0.0005", "0.002", "0.01", "0.05", "1", "1e-6", "1e-300", "1e300",
                       magnitude(rng)])


def _power(rng: random.Random) -> str:
    return rng.choice(["**", "**", "^"])


# ---------------------------------------------------------------------------------------------
# environments H(z) and designs C(s)
# ---------------------------------------------------------------------------------------------
def _environment(rng: random.Random) -> tuple[str, str, dict[str, str]]:
    """``(kind, H(z) text, its parameters)``."""
    p = _power(rng)
    kind = rng.choice(["wall", "improper", "improper", "nearly-improper", "fwd-damper", "circle-pole", "double-pole",
                       "outside-pole", "dirichlet", "sines", "shifted-cos", "msd", "filtered", "near-circle", "integrator"])
    K = magnitude(rng, signed=0.15, zero=0.05)
    B = magnitude(rng, signed=0.2, zero=0.2)
    if kind == "wall":
        return kind, rng.choice(["K + B*(z-1)/(T*z)", "K + B*(1 - z" + p + "-1)/T", "(K*T*z + B*(z - 1))/(T*z)"]), {"K": K, "B": B}
    if kind == "improper":
        k = rng.choice([1, 2, 2, 3])
        return kind, rng.choice([f"K*z{p}{k}", f"K*z{p}{k} + B", f"z{p}{k + 1}/(z-1)*K", f"K*z{p}{k}/(z - a)",
                                 f"K + B*z{p}{k}"]), {"K": K, "B": B, "a": rng.choice(["0.5", "-0.9", "2", "1"])}
    if kind == "nearly-improper":
        eps = rng.choice(["1e-12", "1e-30", "1e-300", "-1e-12", "1e-6"])
        return kind, rng.choice([f"{eps}*z{p}2 + K", f"K + {eps}*z{p}3/(z - 1)", f"K*(1 + {eps}*z)",
                                 f"K + B*(z-1)/(T*z) + {eps}*z{p}2"]), {"K": K, "B": B}
    if kind == "fwd-damper":
        return kind, rng.choice(["K + B*(z-1)/T", "K + B*(z - 1)/T + M*(z-1)**2/T**2"]), {"K": K, "B": B,
                                                                                          "M": magnitude(rng)}
    if kind == "circle-pole":
        c = rng.choice(["0", "0.5", "-0.5", "0.9", "-1", "1"])
        return kind, rng.choice([f"K*z/(z{p}2 - 2*{c}*z + 1)", "K/(z + 1)", "K*(z + 1)/(z - 1)", "K*z/(z - 1)",
                                 f"K*(z{p}2 - 1)/(z{p}2 - 2*{c}*z + 1)", "K/(z**2 + 1)"]), {"K": K}
    if kind == "double-pole":
        return kind, rng.choice(["K*z/(z - 1)", "K/(z - 1)", "K*z**2/(z-1)**2", "K/(z + 1)**2"]), {"K": K}
    if kind == "outside-pole":
        r = rng.choice(["1.0000001", "1.5", "2", "-1.001", "10"])
        return kind, rng.choice([f"K/(z - {r})", f"K*(z - 0.5)/(z - {r})", f"K + B*(z-1)/(T*(z - {r}))"]), {"K": K, "B": B}
    if kind == "dirichlet":
        N = rng.choice([1, 2, 3, 5, 8, 13])
        terms = " + ".join(["1"] + [f"z{p}-{j}" for j in range(1, N + 1)])
        return kind, f"K*({terms})/{N + 1}", {"K": K}
    if kind == "sines":
        k = rng.choice([1, 2, 3, 5])
        return kind, rng.choice([f"K + M*(z - 1)*(z{p}{k} - 1)/(T**2*z{p}{k})", f"M*(z{p}{k} - 1)*(z - 1)/z{p}{k + 1}"]), \
            {"K": K, "M": magnitude(rng, signed=0.3)}
    if kind == "shifted-cos":
        k = rng.choice([1, 2, 3, 7])
        return kind, rng.choice([f"K*z{p}-{k}", f"K*(z{p}{k} + z{p}-{k})/2", f"K + B*z{p}-{k}", f"K*z{p}-{k} + B*(z - 1)/(T*z)"]), \
            {"K": K, "B": B}
    if kind == "msd":
        return kind, "K + B*(z-1)/(T*z) + M*(z-1)" + p + "2/(T" + p + "2*z" + p + "2)", {"K": K, "B": B, "M": magnitude(rng, signed=0.2)}
    if kind == "filtered":
        return kind, "K + B*(1 - a)*(z - 1)/(T*(z - a))", {"K": K, "B": B,
                                                           "a": rng.choice(["0.5", "0.9", "0.99", "-0.5", "1", "1.5", "-1", "0"])}
    if kind == "near-circle":
        r = rng.choice(["0.999999", "0.9999999999", "0.99"])
        return kind, f"K*(1 - {r})/(z - {r})", {"K": K}
    return kind, rng.choice(["K*T*z/(z - 1)", "K + K_i*T/(z - 1)", "K_i*T*(z + 1)/(2*(z - 1))"]), {"K": K, "K_i": magnitude(rng, signed=0.2)}


def _design(rng: random.Random) -> tuple[str, str, dict[str, str]]:
    """``(kind, C(s) text, parameters)``: what a designer writes in continuous time."""
    p = _power(rng)
    kind = rng.choice(["pd", "pd", "pid", "lead", "derivative", "mass", "integrator", "resonator", "lowpass", "second-order",
                       "pi", "double-integrator", "constant"])
    K = magnitude(rng, signed=0.15, zero=0.05)
    B = magnitude(rng, signed=0.2, zero=0.1)
    w = rng.choice(["1e-9", "1", "100", "0.001", magnitude(rng)])
    forms = {
        "pd": ("K + B*s", {"K": K, "B": B}),
        "pid": ("K_p + K_i/s + K_d*s/(tau*s + 1)", {"K_p": K, "K_i": magnitude(rng, signed=0.1), "K_d": B,
                                                    "tau": rng.choice(["0.001", "0.01", "1e-6", "0"])}),
        "lead": ("K*(s + a)/(s + c)", {"K": K, "a": magnitude(rng), "c": magnitude(rng, signed=0.1)}),
        "derivative": ("B*s", {"B": B}),
        "mass": (f"M*s{p}2", {"M": magnitude(rng, signed=0.2)}),
        "integrator": ("K_i/s", {"K_i": magnitude(rng, signed=0.2)}),
        "resonator": (f"K*s/(s{p}2 + w{p}2)", {"K": K, "w": w}),
        "lowpass": ("K/(tau*s + 1)", {"K": K, "tau": magnitude(rng, signed=0.1)}),
        "second-order": (f"K*w{p}2/(s{p}2 + 2*zeta*w*s + w{p}2)", {"K": K, "w": w, "zeta": rng.choice(["0", "0.1", "0.7", "1", "2", "-0.1"])}),
        "pi": ("K + K_i/s", {"K": K, "K_i": magnitude(rng, signed=0.2)}),
        "double-integrator": (f"K/s{p}2", {"K": K}),
        "constant": ("K", {"K": K}),
    }
    text, params = forms[kind]
    return kind, text, params


def _device(rng: random.Random, params: dict[str, str]) -> None:
    params.setdefault("T", _period(rng))
    params["b"] = rng.choice([magnitude(rng), magnitude(rng), "0", magnitude(rng, "extreme")])


def _operator(rng: random.Random) -> tuple[str, dict[str, str]] | None:
    if rng.random() > 0.15:
        return None
    return rng.choice([("-z_a + 1/s", {"z_a": magnitude(rng)}), ("d + k/s", {"d": magnitude(rng, signed=0.5), "k": magnitude(rng)}),
                       ("M_h*s + d", {"M_h": magnitude(rng), "d": magnitude(rng, signed=0.5)}),
                       ("d/(tau*s + 1)", {"d": magnitude(rng, signed=0.3), "tau": magnitude(rng)}),
                       ("d*(s - c)/(s + c)", {"d": magnitude(rng), "c": magnitude(rng)})])


# ---------------------------------------------------------------------------------------------
# families
# ---------------------------------------------------------------------------------------------
#: Names a user may well choose that the toolkit also uses (cosine variable, delay, frequency,
#: SymPy's constants...): the oracle reads them literally.
CLASHING_NAMES = ("c", "n", "w", "omega", "I", "E", "pi", "S", "N", "x", "t_d", "theta", "Q", "oo", "zoo")


def _rename(rng: random.Random, text: str, params: dict[str, str]) -> tuple[str, dict[str, str]]:
    """Rename one parameter of the environment to a clashing name (``K`` -> ``c``)."""
    names = [n for n in params if n not in ("b", "T") and re.search(rf"\b{n}\b", text)]
    if not names:
        return text, params
    old, new = rng.choice(names), rng.choice(CLASHING_NAMES)
    if new in params:
        return text, params
    text = re.sub(rf"\b{old}\b", new, text)
    return text, {(new if k == old else k): v for k, v in params.items()}


def single_user_environment(rng: random.Random) -> dict:
    kind, text, params = _environment(rng)
    if rng.random() < 0.12:
        text, params = _rename(rng, text, params)
        kind += "+renamed"
    _device(rng, params)
    case = {"family": "su-env", "kind": kind, "system": "single-user", "environment": text, "discretize": None,
            "approximation": rng.choice(APPROXIMATIONS), "delay": rng.choice([0, 0, 0, 1, 2, 3, 5, 10, 20, 40]),
            "params": params, "operator": None}
    op = _operator(rng)
    if op:
        case["operator"], extra = op
        params.update(extra)
    elif rng.random() < 0.15:
        case["active"] = True
        params["z_a"] = magnitude(rng, zero=0.2)
    return case


def single_user_design(rng: random.Random) -> dict:
    kind, text, params = _design(rng)
    _device(rng, params)
    return {"family": "su-design", "kind": kind, "system": "single-user", "environment": text,
            "discretize": rng.choice(METHODS), "approximation": rng.choice(APPROXIMATIONS),
            "delay": rng.choice([0, 0, 0, 1, 2, 5]), "params": params, "operator": None}


def single_user_range(rng: random.Random) -> dict:
    case = single_user_environment(rng) if rng.random() < 0.6 else single_user_design(rng)
    case["family"] = "su-range"
    names = [n for n in case["params"] if n not in ("T",)]
    name = rng.choice(names)
    case["range"] = name
    case["params"] = {k: v for k, v in case["params"].items() if k != name}
    return case


def single_user_margin(rng: random.Random) -> dict:
    case = single_user_environment(rng) if rng.random() < 0.7 else single_user_design(rng)
    case["family"] = "su-margin"
    case["delay"] = 0
    case["margin"] = True
    # keep the margin small enough to re-check: KT/b of order 1..20
    if rng.random() < 0.7:
        case["params"]["b"] = number(rng, Fraction(rng.randint(1, 60), 10) * Fraction(case["params"].get("T", "0.001")))
        case["params"]["K"] = rng.choice(["1", "2", "0.5", "10", "3"])
        case["params"]["T"] = case["params"].get("T", "0.001")
    return case


def single_user_boundary(rng: random.Random) -> dict:
    p = rng.random()
    params = {"m": rng.choice(["0.015", "0.15", magnitude(rng), magnitude(rng, "extreme")]),
              "T": _period(rng), "b": magnitude(rng, zero=0.05), "K": magnitude(rng), "B": magnitude(rng, zero=0.4)}
    env = None
    if p < 0.25:
        env = rng.choice(["K*(1 - a)/(1 - a/z)", "K + B*(z-1)/(T*z) + M*(z-1)**2/(T**2*z**2)", "K*z**-2",
                          "K*(1 + z**-1)/2", "K*(z + 1)/(2*z)"])
        params.update({"a": rng.choice(["0.5", "0.9", "-0.5"]), "M": magnitude(rng)})
    vary = rng.choice(["K", "K", "b", "b", "B", "T", "m"])
    params.pop(vary, None)
    case = {"family": "su-boundary", "system": "single-user", "environment": env, "params": params, "vary": vary,
            "delay": rng.choice([0, 0, 1, 2, 5, 10]), "operator": None}
    if rng.random() < 0.2:
        case["operator"] = "-z_a + 1/s"
        params["z_a"] = number(rng, Fraction(params["b"]) / rng.choice([2, 4, 10])) if vary != "b" else "0.001"
    return case


def teleoperator(rng: random.Random) -> dict:
    params: dict[str, str] = {"T": _period(rng), "b_m": magnitude(rng), "b_s": magnitude(rng),
                              "alpha": rng.choice(["1", "1", "2", "0.5", "10", "0.01", magnitude(rng)])}
    r = rng.random()
    discretize = None
    if r < 0.3:
        controller = rng.choice(["pd", "filtered-pd"])
        params.update({"K": magnitude(rng, signed=0.1, zero=0.05), "B": magnitude(rng, signed=0.1, zero=0.2),
                       "a": rng.choice(["0", "0.5", "0.9", "0.99"])})
        if controller == "pd":
            params.pop("a")
    elif r < 0.6:
        kind, controller, extra = _environment(rng)
        params.update(extra)
    else:
        kind, controller, extra = _design(rng)
        params.update(extra)
        discretize = rng.choice(METHODS)
    if rng.random() < 0.3:
        params["b_s"] = params["b_m"]
    return {"family": "tele", "system": "teleoperator", "controller": controller, "discretize": discretize, "params": params}


def multi_user(rng: random.Random) -> dict:
    users = rng.choice([2, 2, 3])
    params: dict[str, str] = {"T": _period(rng) if rng.random() < 0.3 else "0.001"}
    for i in range(1, users + 1):
        params[f"b_{i}"] = magnitude(rng)
        params[f"K_0{i}"] = magnitude(rng, zero=0.2)
        params[f"B_0{i}"] = magnitude(rng, zero=0.4)
    for i in range(1, users + 1):
        for j in range(i + 1, users + 1):
            params[f"K_{i}{j}"] = magnitude(rng, zero=0.1, signed=0.1)
            params[f"B_{i}{j}"] = magnitude(rng, zero=0.4)
    delays = [rng.choice([0, 0, 1, 2, 3]) for _ in range(users)]
    return {"family": "multi", "system": "multi-user", "users": users, "params": params, "delays": delays,
            "approximation": rng.choice(APPROXIMATIONS)}


def _impedance(rng: random.Random, tag: str) -> tuple[str, dict[str, str]]:
    """A one-port impedance ``Z(s)`` as a user writes it (names suffixed by ``tag``)."""
    p = _power(rng)
    R, L, C = (f"{n}{tag}" for n in ("R", "L", "C"))
    w, e = f"w{tag}", f"e{tag}"
    forms = [
        (f"{R} + {L}*s", {R: magnitude(rng, signed=0.2, zero=0.1), L: magnitude(rng, signed=0.2)}),
        (f"{L}*s + 1/({C}*s)", {L: magnitude(rng, signed=0.1), C: magnitude(rng, signed=0.1)}),
        (f"{L}*s{p}2 + {R}", {L: magnitude(rng), R: magnitude(rng)}),                       # improper by 2
        (f"{R}/s{p}2", {R: magnitude(rng)}),                                                   # double pole at 0
        (f"{R}*(s - {w})/(s + {w})", {R: magnitude(rng), w: magnitude(rng)}),                 # all-pass
        (f"{R}*s/(s{p}2 + {w}{p}2)", {R: magnitude(rng, signed=0.2), w: rng.choice(["1e-9", "1", magnitude(rng)])}),
        (f"{R}*s/(s{p}2 + {w}{p}2){p}2", {R: magnitude(rng), w: magnitude(rng)}),               # double axis pair
        (f"({R}*s + 1)/(s{p}2 + {e}*s + 1)", {R: magnitude(rng), e: rng.choice(["1e-12", "-1e-12", "0", "1", "1e-300"])}),
        (f"{R}/({L}*s + 1)", {R: magnitude(rng, signed=0.2), L: magnitude(rng, signed=0.1)}),
        (f"{R}/(s + {w}){p}3", {R: magnitude(rng), w: magnitude(rng)}),
        (f"{R} + {e}*s{p}2", {R: magnitude(rng), e: rng.choice(["1e-12", "1e-300", "-1e-12"])}),  # nearly improper
    ]
    return rng.choice(forms)


def network(rng: random.Random) -> dict:
    """``derive network``: a 1-port or a 2-port impedance matrix typed into a matrix file."""
    n = rng.choice([1, 1, 2])
    params: dict[str, str] = {}
    rows = []
    for i in range(n):
        row = []
        for j in range(n):
            if i == j or rng.random() < 0.6:
                text, extra = _impedance(rng, f"{i + 1}{j + 1}")
                params.update(extra)
                row.append(text if i == j or rng.random() < 0.5 else f"-({text})")
            else:
                row.append("0")
        rows.append(row)
    return {"family": "net", "system": "network", "matrix": rows, "params": params}


FAMILIES = {
    "su-env": single_user_environment,
    "su-design": single_user_design,
    "su-range": single_user_range,
    "su-margin": single_user_margin,
    "su-boundary": single_user_boundary,
    "tele": teleoperator,
    "multi": multi_user,
    "net": network,
}


_NAME = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def used_names(case: dict) -> set[str]:
    """The parameter names the case's scene uses (the toolkit rejects unknown ones)."""
    texts = [case.get("environment") or ("K + B*(z-1)/(T*z)" if case["system"] == "single-user" else ""),
             case.get("operator") or ""]
    names = {"T"}
    if case["system"] == "teleoperator":
        ctrl = case["controller"]
        texts.append({"pd": "K + B*(z-1)/(T*z)", "filtered-pd": "K + B*(1-a)*(z-1)/(T*(z-a))"}.get(ctrl, ctrl))
        names |= {"b_m", "b_s", "alpha"}
    elif case["system"] in ("multi-user", "network"):
        return set(case["params"])
    else:
        names |= {"b"}
        if case.get("active") or case.get("operator"):
            names.add("z_a")
        if case["family"] == "su-boundary":
            names.add("m")
    for text in texts:
        names |= set(_NAME.findall(text)) - {"z", "s"}
    return names


def case_argv(case: dict) -> list[str]:
    """The command-line arguments of a case (``--format json`` for derive); parameters the
    scene does not use are dropped from the case."""
    keep = used_names(case)
    case["params"] = {k: v for k, v in case["params"].items() if k in keep}
    params = [f"--param={k}={v}" for k, v in case["params"].items()]
    fam = case["family"]
    if fam == "su-boundary":
        argv = ["boundary", "single-user", "--vary", case["vary"], "--json", "-", "--no-progress"]
        if case.get("environment"):
            argv += ["--environment", case["environment"]]
        if case.get("delay"):
            argv += ["--delay", str(case["delay"])]
        if case.get("operator"):
            argv += ["--operator", case["operator"]]
        return argv + params
    if case["system"] == "teleoperator":
        argv = ["derive", "teleoperator", "--controller", case["controller"], "--format", "json"]
        if case.get("discretize"):
            argv += ["--discretize", case["discretize"]]
        return argv + params
    if case["system"] == "network":
        import json
        import tempfile
        with tempfile.NamedTemporaryFile("w", suffix=".json", delete=False, prefix="matrix-case-") as fh:
            json.dump({"matrix": case["matrix"]}, fh)
        case["matrix_file"] = fh.name
        return ["derive", "network", "--matrix", fh.name, "--format", "json", "--no-search"] + params
    if case["system"] == "multi-user":
        argv = ["derive", "multi-user", "--users", str(case["users"]), "--approximation", case["approximation"],
                "--delay", ",".join(map(str, case["delays"])), "--format", "json"]
        return argv + params
    argv = ["derive", "single-user", "--format", "json", "--approximation", case["approximation"]]
    if case.get("environment"):
        argv += ["--environment", case["environment"]]
    if case.get("discretize"):
        argv += ["--discretize", case["discretize"]]
    if case.get("delay"):
        argv += ["--delay", str(case["delay"])]
    if case.get("operator"):
        argv += ["--operator", case["operator"]]
    if case.get("active"):
        argv += ["--active"]
    if case.get("range"):
        argv += ["--range", case["range"]]
    if case.get("margin"):
        argv += ["--delay-margin"]
    return argv + params
