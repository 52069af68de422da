r"""Classic sampled-data haptic results as a "paper": each published statement (recorded in
:mod:`hapticproof.classics` with its source) is audited against the toolkit's derivation of the
same result from its model.

* Colgate & Schenkel 1997: the frequency form (derived by the energy-leak route: ZOH of the
  impulse sampler, alias weight, Cauchy-Schwarz) and the virtual-wall form ``b > KT/2 + |B|``.
* Gil, Avello, Rubio & Florez 2004: ``b > KT/2 - B`` as the small-damping limit of the exact
  ZOH stability boundary (Jury closed form in ``alpha, delta, beta``), and where it is sufficient.
* Gil, Sanchez, Hulin, Preusche & Hirzinger 2009: ``K(T/2 + t_d) < b + B`` as the leading order
  of the exact delayed boundary, for every integer delay.
* Llewellyn 1952: the criterion as implemented by :func:`hapticproof.networks.llewellyn` on a
  passive and on a non-passive continuous teleoperator, each cross-checked by its terminations.
"""

from __future__ import annotations

import sympy as sp

from hapticproof import boundary as bnd
from hapticproof import classics
from hapticproof.audit import AuditContext, Paper
from hapticproof.certify import compare_bounds, is_identically_zero
from hapticproof.evidence import Evidence, Finding, Method, Verdict
from hapticproof.latex import to_latex
from hapticproof.parse import SymbolTable
from hapticproof.scene import SYMBOLS
from hapticproof.symbols import c as C_SYM
from hapticproof.symbols import z as Z_SYM

K, B, b, T, t_d = (SYMBOLS[name] for name in ("K", "B", "b", "T", "t_d"))
B_REAL = sp.Symbol("B", real=True)
omega = sp.Symbol("omega", real=True)
H_FUN = sp.Function("H")

TABLE = SymbolTable(
    symbols={"K": K, "B": B, "b": b, "T": T, "t_d": t_d, r"\omega": omega, "z": Z_SYM,
             "b_h": classics.OPERATOR["b_h"], "k_h": classics.OPERATOR["k_h"]},
    functions={"H": H_FUN},
)
#: Colgate's wall form is stated for a virtual damper of either sign.
SIGNED_TABLE = TABLE.with_symbols({"B": B_REAL})

SRC = classics.SOURCES


def _conditions() -> list[tuple[str, str, str]]:
    cf = bnd.closed_form_boundary()
    names = {bnd.ALPHA: r"\alpha", bnd.DELTA: r"\delta", bnd.BETA: r"\beta", bnd.P: r"e^{-\alpha}"}
    return [
        ("Colgate-Schenkel, passivity (frequency form)", SRC["colgate-schenkel-1997"].statement,
         SRC["colgate-schenkel-1997"].citation()),
        ("Colgate-Schenkel, virtual wall", r"b > \frac{KT}{2} + |B|", SRC["colgate-schenkel-1997"].citation()),
        ("Gil et al. 2004, small damping", r"b + B > \frac{KT}{2}", SRC["gil-2004"].citation()),
        ("exact ZOH boundary, n = 0 (complex pair)",
         r"\beta < " + to_latex(cf.complex_pair, names) + r",\ l_0 = 1 - (1+\alpha)e^{-\alpha}",
         "derived (hapticproof.boundary, Jury)"),
        ("exact ZOH boundary, n = 0 (flip, damping limit)",
         r"\beta < " + to_latex(cf.flip, names) + r",\quad \delta\,(1 - (1+\alpha)e^{-\alpha}) < \alpha^2",
         "derived (hapticproof.boundary, Jury)"),
        ("Gil et al. 2009, delayed linear", r"K\left(\frac{T}{2} + t_d\right) < b + B", SRC["gil-2009"].citation()),
        ("Minsky et al., with operator (as quoted)", SRC["minsky-1990"].statement, SRC["minsky-1990"].citation()),
        ("operator, leading order (derived)", r"b + b_h + B > \frac{KT}{2}", "derived (hapticproof.classics)"),
        ("Llewellyn", SRC["llewellyn-1952"].statement, SRC["llewellyn-1952"].citation()),
    ]


PAPER = Paper(
    "classics",
    title="Classic sampled-data haptic stability and passivity conditions",
    source="hapticproof.classics (published statements with their sources)",
    authors="Colgate & Schenkel 1997; Gil et al. 2004; Gil et al. 2009; Llewellyn 1952",
    symbols=TABLE,
    aliases=("classic", "literature"),
)
PAPER.deferred_conditions.append(_conditions)


# ---------------------------------------------------------------------------------------------
# Colgate & Schenkel
# ---------------------------------------------------------------------------------------------


@PAPER.equation("colgate-frequency", kind="condition", printed=SRC["colgate-schenkel-1997"].statement, section="1997",
                assumptions="1-DOF display, damping b, impulse sampler + ZOH, any real-rational H(z); 0 < omega < pi/T",
                derivation="energy-leak route (classics.leak_bound) for a general H, and the HVE circle-criterion route")
def colgate_frequency(ctx: AuditContext) -> Finding:
    (rel,) = ctx.statement.relations()
    u, v = sp.symbols("u v", real=True)
    kernel = classics.sampling_kernel(H_FUN(Z_SYM), T).subs(Z_SYM, sp.exp(sp.I * omega * T))
    derived = -sp.re(kernel) * classics.alias_weight(T).subs(C_SYM, sp.cos(omega * T))
    value = H_FUN(sp.exp(sp.I * omega * T))
    generic = is_identically_zero(sp.expand_complex(sp.expand((rel.rhs - derived).subs(value, u + sp.I * v))))
    # second route: the HVE paper's G_1^-1 (forward difference) has Re G^-1 = b - bound
    from hapticproof.positivereal import hermitian
    from hapticproof.scene import SingleUserScene
    from hapticproof.teleoperator import filtered_pd_controller

    routes = []
    for H in (K + B * (Z_SYM - 1) / (T * Z_SYM), filtered_pd_controller(K, B, T, sp.Rational(1, 2))):
        circle = sp.cancel(b - hermitian(SingleUserScene(b=b, T=T, H=H)).expr())
        routes.append(is_identically_zero(circle - classics.leak_bound(H, T))
                      and is_identically_zero(classics.colgate_bound(H, T) - classics.leak_bound(H, T)))
    error = classics.check_alias_weight([(1, "0.1"), ("0.3", 2)])
    if generic and all(routes) and error < 1e-25:
        return Finding(Verdict.CONFIRMED, "derived for a general H(z): ZOH of the impulse sampler (1 - e^(-sT))/s, kernel "
                       "-(1 - e^(-jwT)) H/T, alias weight T^2/(2(1 - cos wT)) (mpmath check "
                       f"{error:.0e}), Cauchy-Schwarz; the HVE circle-criterion route gives the same bound exactly for the "
                       "wall and a filtered PD", Evidence(Method.CANONICAL_FORM, instances=2, facts={"alias_weight_error": error}),
                       derived=sp.Ge(b, derived))
    return Finding(Verdict.WRONG, "the published frequency form differs from the derivation",
                   Evidence(Method.CANONICAL_FORM, facts={"generic": generic, "routes": routes}))


@PAPER.equation("colgate-wall", kind="condition", printed=r"b > \frac{KT}{2} + |B|", section="1997",
                assumptions="H(z) = K + B(z-1)/(Tz), B of either sign",
                derivation="supremum over c of KT/2 - Bc (endpoint analysis, classics.colgate_wall)")
def colgate_wall(ctx: AuditContext) -> Finding:
    from hapticproof.parse import parse_printed

    (rel,) = parse_printed(ctx.equation.printed, SIGNED_TABLE).relations()
    return compare_bounds(rel.as_sympy(), classics.colgate_wall(), b, what="Colgate's virtual-wall condition",
                          note="the minimiser is c = -sign(B)")


# ---------------------------------------------------------------------------------------------
# Gil et al. 2004 and 2009
# ---------------------------------------------------------------------------------------------


@PAPER.equation("gil-2004", kind="condition", printed=SRC["gil-2004"].statement, section="2004",
                assumptions="small alpha = bT/m, delta = BT/m, beta = KT^2/m (the small-damping limit)",
                derivation="leading order of the exact ZOH boundary (classics.leading_order_boundary, n = 0)")
def gil_2004(ctx: AuditContext) -> Finding:
    derived = classics.gil_linear_condition(0)
    finding = compare_bounds(ctx.relation(), sp.Ge(derived.lhs, derived.rhs), b, what="Gil et al.'s condition")
    if finding.verdict != Verdict.CONFIRMED:
        return finding
    lo = classics.leading_order_boundary(0)
    return Finding(Verdict.CONFIRMED, "it is exactly the leading order of the exact boundary: at the unit-circle crossing "
                   f"w^2 = {sp.sstr(lo.frequency)} and g = {sp.sstr(lo.critical)}, i.e. beta* = 2(alpha + delta) + O(2) (see "
                   "gil-2004-region for where it is sufficient)", finding.evidence, derived=derived)


@PAPER.equation("gil-2004-region", kind="claim", after="0", section="2004",
                printed="the condition b > KT/2 - B is valid for low values of the virtual damping B",
                derivation="closed-form Jury boundary: expansion of beta*/(2(alpha + delta)) and certified instances")
def gil_2004_region(ctx: AuditContext) -> Finding:
    region, expansion = classics.gil_sufficiency_region()
    checks = {}
    for Bv in (sp.Integer(0), sp.Rational(1, 10), sp.Integer(1), sp.Integer(300)):
        cs = bnd.critical_stiffness(1, 1, sp.Rational(1, 100), Bv)
        linear = 2 * (1 + Bv) / sp.Rational(1, 100)
        checks[str(Bv)] = {"mode": cs.mode, "K*": cs.K.str(12), "linear": linear,
                           "sufficient": bool(cs.mode != "unstable" and cs.K > bnd._arb(linear))}
    expected = {"0": True, "1/10": True, "1": False, "300": False}
    ok = all(checks[k]["sufficient"] == v for k, v in expected.items())
    return Finding(Verdict.CONFIRMED if ok else Verdict.UNDECIDED,
                   f"beta*/(2(alpha + delta)) = {sp.sstr(expansion)} + O(2): the linear condition is sufficient near the origin "
                   "exactly when B <= b/6 (first order); at m = b = 1, T = 0.01 it is sufficient for B = 0, 0.1 and not for "
                   "B = 1 (K* below the linear bound) or B = 300 (no stable stiffness): 'low B' means B below about b/6",
                   Evidence(Method.INTERVAL_ARITHMETIC, instances=len(checks), facts={"instances": checks, "exact_region": region}),
                   derived=region)


@PAPER.equation("gil-2009", kind="condition", printed=SRC["gil-2009"].statement, section="2009",
                assumptions="t_d = nT, short delay, fast sampling, low damping (leading order)",
                derivation="leading order of the exact delayed ZOH boundary for symbolic n (classics.leading_order_boundary)")
def gil_2009(ctx: AuditContext) -> Finding:
    derived = classics.gil_linear_condition(SYMBOLS["n"])
    finding = compare_bounds(ctx.relation(), sp.Ge(derived.lhs, derived.rhs), b, what="the delayed linear condition")
    if finding.verdict != Verdict.CONFIRMED:
        return finding
    ratios = {}
    for n in (1, 5):
        for Bv in (sp.Integer(0), sp.Rational(1, 1000)):
            cs = bnd.critical_stiffness(1, sp.Rational(1, 1000), sp.Rational(1, 1000), Bv, n)
            ratios[f"n={n},B={Bv}"] = float(cs.value / float((sp.Rational(1, 1000) + Bv) / (sp.Rational(1, 2000) + n * sp.Rational(1, 1000))))
    return Finding(Verdict.CONFIRMED, "the crossing of the exact delayed loop expands to g = 2(a + d)/(2n + 1), i.e. "
                   "K (T/2 + nT) < b + B, for every integer n (the delay enters only through exp(j(n+1)w sqrt(eps)), "
                   "polynomial in n at each order); certified exact boundaries at alpha = 1e-6 agree to within "
                   f"{max(abs(r - 1) for r in ratios.values()):.1e}",
                   Evidence(Method.CANONICAL_FORM, facts={"exact_over_linear": ratios}), derived=derived)


# ---------------------------------------------------------------------------------------------
# Llewellyn
# ---------------------------------------------------------------------------------------------


@PAPER.equation("llewellyn", kind="condition", printed=SRC["llewellyn-1952"].statement, section="1952", parse=False,
                assumptions="2-port immittance matrix P(s) (impedance form)",
                derivation="networks.llewellyn on two continuous PEB teleoperators, cross-checked by their terminations")
def llewellyn(ctx: AuditContext) -> Finding:
    from hapticproof.networks import llewellyn as criterion
    from hapticproof.symbols import s

    m, bb, Kv, Bv = sp.Rational(15, 1000), sp.Rational(1822, 100000), 2, sp.Rational(1, 100)
    results = {}
    for name, sign in (("restoring", 1), ("anti-restoring", -1)):
        Zc = sign * (Kv + Bv * s) / s
        Z = sp.Matrix([[m * s + bb + Zc, -Zc], [-Zc, m * s + bb + Zc]])
        verdict = criterion(Z)
        # free/free terminations (zero force): the loop's characteristic polynomial is det Z
        roots = sp.Poly(sp.numer(sp.together(Z.det())), s).nroots(n=30)
        results[name] = {"llewellyn": verdict.decision.value, "reason": verdict.reason,
                         "free_free_max_real_root": max(sp.re(r) for r in roots)}
    ok = (results["restoring"]["llewellyn"] == "proved" and results["anti-restoring"]["llewellyn"] == "disproved"
          and results["anti-restoring"]["free_free_max_real_root"] > 0 and results["restoring"]["free_free_max_real_root"] <= 0)
    return Finding(Verdict.CONFIRMED if ok else Verdict.UNDECIDED,
                   "as implemented exactly by networks.llewellyn the criterion proves the passive spring-damper teleoperator "
                   "absolutely stable and rejects the anti-restoring one (the sign of the teleoperator paper's (7)), which the "
                   "passive free/free terminations indeed destabilise (a characteristic root with positive real part)",
                   Evidence(Method.ROOT_ISOLATION, instances=2, facts=results))
