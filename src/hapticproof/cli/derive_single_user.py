"""``hapticproof derive single-user``: the exact conditions of a 1-DOF haptic scene."""

from __future__ import annotations

import argparse

import sympy as sp

from hapticproof.cli._common import add_param_option, parse_params
from hapticproof.errors import InputFormatError
from hapticproof.scene import APPROXIMATIONS, SYMBOLS, SingleUserScene
from hapticproof.summary import summarize_single_user
from hapticproof.symbols import z

__all__ = ["register"]


def register(systems: argparse._SubParsersAction) -> None:
    parser = systems.add_parser(
        "single-user",
        help="1-DOF device on a discrete environment (HVE paper, Fig. 4)",
        description="G^-1(z), poles, residues, the exact Hermitian part as a function of c = cos(wT) "
        "and the worst case over w. Parameters (b, K, B, T, z_a) are symbolic unless fixed with "
        "--param; when all are numbers the verdict is decided exactly (root isolation).",
    )
    parser.add_argument("--approximation", choices=APPROXIMATIONS, default="forward")
    parser.add_argument("--delay", default="0", help="integer n = t_d/T, or 'n' for a symbolic delay (default 0)")
    parser.add_argument("--environment", metavar="H(z)",
                        help="custom real-rational H(z) in z and the parameter names (default: K + B*(z-1)/(T*z))")
    parser.add_argument("--active", action="store_true", help="include the operator's shortage of passivity z_a")
    parser.add_argument("--format", choices=("text", "latex", "json"), default="text",
                        help="text (default), latex (a complete document) or json")
    parser.add_argument("--fragment", action="store_true",
                        help="with --format latex: only the displays (amsmath), not a complete document")
    parser.add_argument("--profile", action="store_true", help="print the time of each computed stage")
    add_param_option(parser)
    parser.set_defaults(handler=run)


def _environment(text: str | None, T: sp.Expr) -> sp.Expr | None:
    if text is None:
        return None
    names = {name: symbol for name, symbol in SYMBOLS.items()}
    names["z"] = z
    try:
        expr = sp.parse_expr(text, local_dict=names, global_dict={"__builtins__": {}, "Integer": sp.Integer,
                                                                  "Rational": sp.Rational, "Float": sp.Float, "Symbol": sp.Symbol})
    except Exception as err:  # noqa: BLE001 - any parse failure is the user's input
        raise InputFormatError(f"--environment: cannot read {text!r} as an expression in z") from err
    unknown = expr.free_symbols - set(names.values())
    if unknown:
        raise InputFormatError(f"--environment: unknown names {sorted(map(str, unknown))}; use z and b, K, B, T, z_a")
    return expr


def run(args: argparse.Namespace) -> int:
    if args.fragment and args.format != "latex":
        raise InputFormatError("--fragment needs --format latex")
    params = parse_params(args.param)
    unknown = set(params) - {"b", "K", "B", "T", "z_a", "t_d"}
    if unknown:
        raise InputFormatError(f"unknown parameter(s) {sorted(unknown)}; single-user scenes have b, K, B, T, z_a, t_d")
    delay: object = SYMBOLS["n"] if args.delay.strip() == "n" else args.delay.strip()
    if "t_d" in params:
        delay = params.pop("t_d")
        t_d_given = True
    else:
        t_d_given = False
    base = SingleUserScene.virtual_wall(
        approximation=args.approximation,
        z_a=SYMBOLS["z_a"] if args.active else 0,
        **({"t_d": delay, "T": params.get("T")} if t_d_given else {"delay": delay}),
    )
    H = _environment(args.environment, base.T)
    if H is not None:
        base = SingleUserScene(b=base.b, T=base.T, H=H, approximation=base.approximation, delay=base.delay, z_a=base.z_a)
    scene = base.with_values({k: v for k, v in params.items() if k != "T" or not t_d_given})
    print(summarize_single_user(scene, with_profile=args.profile).dumps(args.format, fragment=args.fragment))
    return 0
