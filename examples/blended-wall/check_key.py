#!/usr/bin/env python3
"""Re-verify every entry of key.json for paper.tex (examples/blended-wall).

Independent of hapticproof: SymPy for exact algebra, NumPy for frequency sweeps.
Prints one line per key entry: OK/FAIL, number, verdict, what was checked.
"""
import json, os, random, re, sys
import numpy as np
import sympy as sp

HERE = os.path.dirname(os.path.abspath(__file__))
KEY = json.load(open(os.path.join(HERE, 'key.json')))
TEX = open(os.path.join(HERE, 'paper.tex')).read()
R = sp.Rational
z, c = sp.symbols('z c')
al, Kw, dw, h, cd, g0, g1 = sp.symbols('alpha K_w d_w h c_d g_0 g_1', real=True)
random.seed(1)


def Q(x):
    return sp.Rational(x)


def rnd(lo=0, hi=3, den=8):
    """random rational in [lo, hi]"""
    return R(random.randint(int(lo * den), int(hi * den)), den)


# ---------------------------------------------------------------- helpers
def same_on_circle(G, printed_c):
    """exact: Re G(e^{jt}) == printed(c) for all t (printed uses c=cos t, cos2t=2c^2-1)."""
    Rz = (G + G.subs(z, 1 / z)) / 2
    d = sp.simplify(sp.together(Rz - printed_c.subs(c, (z + 1 / z) / 2)))
    return d == 0


def poles(G):
    num, den = sp.fraction(sp.cancel(sp.together(G)))
    P = sp.Poly(num, z)
    D = sp.Poly(den, z)
    return P, D, sp.roots(D)


def is_pr(G, N=4001, tol=1e-10, detail=False):
    """Definition-level check of discrete positive realness for a numeric scalar G(z):
    proper, poles in |z| <= 1, unit-circle poles simple with Res/z0 real >= 0,
    Re G(e^{jt}) >= 0 on a grid of 0 < t <= pi (G has real coefficients)."""
    P, D, rts = poles(G)
    if P.degree() > D.degree():
        return (False, 'pole at infinity') if detail else False
    if sum(rts.values()) != D.degree():
        raise RuntimeError('roots not found exactly')
    for p, m in rts.items():
        mag = abs(complex(sp.N(p)))
        if mag > 1 + 1e-12:
            return (False, f'pole {p} outside') if detail else False
        if abs(mag - 1) <= 1e-12:
            if m > 1:
                return (False, f'multiple pole {p}') if detail else False
            res = sp.nsimplify(sp.simplify(P.as_expr().subs(z, p) / D.diff(z).as_expr().subs(z, p) / p))
            resn = complex(sp.N(res))
            if abs(resn.imag) > 1e-12 or resn.real < -tol:
                return (False, f'Res/z0 = {res} at {p}') if detail else False
    t = np.linspace(0, np.pi, N)[1:]
    zz = np.exp(1j * t)
    pc = [complex(x) for x in P.all_coeffs()]
    dc = [complex(x) for x in D.all_coeffs()]
    with np.errstate(all='ignore'):
        v = np.real(np.polyval(pc, zz) / np.polyval(dc, zz))
    ok = np.isfinite(v) & (np.abs(np.polyval(dc, zz)) > 1e-9)
    m = float(np.min(v[ok]))
    if m < -tol:
        return (False, f'min Re = {m:.4g}') if detail else False
    return (True, f'min Re = {m:.4g}') if detail else True


def minimum_on_circle(expr_c):
    """exact minimum over c in [-1,1] of a polynomial/rational expression in c"""
    cands = [R(-1), R(1)]
    d = sp.diff(expr_c, c)
    num = sp.fraction(sp.together(d))[0]
    if sp.Poly(num, c).degree() > 0:
        for r in sp.Poly(num, c).real_roots():
            if -1 <= r <= 1:
                cands.append(r)
    vals = [sp.nsimplify(sp.simplify(expr_c.subs(c, x))) for x in cands]
    return min(vals, key=lambda v: float(v))


def sweep(cond, G, params_gen, n=200, margin_fn=None, eps=1e-6):
    """compare printed condition with PR by definition on random rational instances.
    returns (agree_when_cond_true, agree_when_cond_false) counts and mismatches"""
    mism = []
    cnt = 0
    for _ in range(n):
        p = params_gen()
        if margin_fn is not None and abs(float(margin_fn(p))) < eps:
            continue
        cnt += 1
        lhs = bool(cond(p))
        pr = is_pr(G.subs(p))
        if lhs != pr:
            mism.append((p, lhs, pr))
    return cnt, mism


CHECKS = {}


def check(num, verdict):
    def deco(f):
        CHECKS[num] = (verdict, f)
        return f
    return deco


def key_entry(num):
    return next(e for e in KEY if e['number'] == num)


def W(num):
    """witness parameters of an entry as a dict name->Rational"""
    w = key_entry(num)['witness']
    return {k: Q(v) for k, v in w.get('params', {}).items()}


def corrected_is(num, s):
    return key_entry(num)['corrected'] == s


def ident(expr):
    return sp.simplify(sp.together(expr)) == 0



# ---------------------------------------------------------------- model
Wz = Kw + dw * (z - 1) / (h * z)
Ia = h * (al * z + 1 - al) / (z - 1)
G = cd + Wz * Ia
Gam = g0 + g1 / z
GG = cd + Gam * Ia
GD = cd + Wz * Ia / z
ReG = cd - (1 - 2 * al) / 2 * Kw * h + dw * (al + (1 - al) * c)                       # derived
ReGG = cd + h * (al * g0 - (g0 + g1) / 2 - (1 - al) * g1 * c)                         # derived
ReGD = cd - Kw * h / 2 - (1 - al) * Kw * h * c + al * dw * c + (1 - al) * dw * (2 * c**2 - 1)  # derived


def params(two_tap=False, alpha=None):
    def gen():
        p = {al: rnd(0, R(15, 16), 16) if alpha is None else alpha, h: rnd(R(1, 8), 2), cd: rnd(-1, 6)}
        if two_tap:
            p[g0] = rnd(-3, 3)
            p[g1] = rnd(-p[g0], 3) if p[g0] < 3 else rnd(-3, 3)
        else:
            p[Kw], p[dw] = rnd(0, 4), rnd(0, 3)
        return p
    return gen


def WP(num):
    w = key_entry(num)['witness']
    m = {'alpha': al, 'Kw': Kw, 'dw': dw, 'h': h, 'cd': cd, 'g0': g0, 'g1': g1}
    return {m[k]: Q(v) for k, v in w['params'].items()}


@check('inline-theta', 'confirmed')
def _():
    return True, 'definition (normalised frequency)'


@check('1', 'confirmed')
def _():
    both = '\\mathrm{w}' in key_entry('1')['latex'] and 'K_w' in key_entry('1')['latex']
    return both and ident(Wz.subs(z, 1) - Kw), 'spring + damper; K_{\\mathrm{w}} and K_w both used (same symbol)'


@check('inline-Ialpha', 'confirmed')
def _():
    ok = ident(Ia.subs(al, 0) - h / (z - 1)) and ident(Ia.subs(al, R(1, 2)) - h / 2 * (z + 1) / (z - 1))
    ok = ok and ident(Ia.subs(al, 1) - h * z / (z - 1)) and ident(Ia - h * (al + 1 / (z - 1)))
    return ok, 'alpha=0 forward, 1/2 Tustin, 1 backward'


@check('2', 'confirmed')
def _():
    return True, 'definition'


@check('3', 'confirmed')
def _():
    printed = cd + al * (Kw * h + dw) + Kw * h / (z - 1) + (1 - al) * dw / z
    return ident(G - printed), 'expansion exact'


@check('4', 'typo')
def _():
    printed = cd - (1 - 2 * al) * Kw * h + dw * (al + (1 - al) * c)
    ok = same_on_circle(G, ReG) and not same_on_circle(G, printed)
    w = key_entry('4')['witness']
    p = WP('4'); p[c] = Q(w['at']['c'])
    ok = ok and printed.subs(p) == Q(w['values']['printed']) and ReG.subs(p) == Q(w['values']['derived'])
    ok = ok and corrected_is('4', key_entry('4')['latex'].replace('(1 - 2\\alpha)\\,K_{\\mathrm{w}}h', '\\frac{1 - 2\\alpha}{2}\\,K_{\\mathrm{w}}h'))
    return ok, 'factor 1/2 dropped on the stiffness term'


def thr5(p):
    return (1 - 2 * p[al]) * (p[Kw] * p[h] / 2 + p[dw])


@check('5', 'confirmed')
def _():
    ok = ident(sp.residue(G, z, 1) - Kw * h)
    ok = ok and ident(ReG.subs(c, -1) - (cd - (1 - 2 * al) * (Kw * h / 2 + dw))) and ident(sp.diff(ReG, c) - dw * (1 - al))
    n, mism = sweep(lambda p: p[cd] >= thr5(p), G, params(), 200, margin_fn=lambda p: p[cd] - thr5(p))
    return ok and not mism, f'min at c=-1; iff agrees with PR on {n} random instances'


@check('inline-tustin', 'confirmed')
def _():
    n, mism = sweep(lambda p: p[cd] >= 0, G, params(alpha=R(1, 2)), 100, margin_fn=lambda p: p[cd])
    return thr5({al: R(1, 2), Kw: Kw, h: h, dw: dw}) == 0 and not mism, f'threshold 0 at alpha=1/2; {n} instances'


@check('6', 'confirmed')
def _():
    gap = (Kw * h / 2 + dw) - (1 - 2 * al) * (Kw * h / 2 + dw)
    ok = ident(gap - 2 * al * (Kw * h / 2 + dw))        # >= 0 for alpha >= 0, Kw, dw >= 0
    bad = 0
    gen = params()
    for _ in range(150):
        p = gen()
        if p[cd] >= p[Kw] * p[h] / 2 + p[dw]:
            bad += not is_pr(G.subs(p))
    return ok and bad == 0, 'implies (5) (gap 2 alpha (Kw h/2 + dw) >= 0); no violation on random instances'


@check('7', 'confirmed')
def _():
    return ident(sp.residue(Gam * Ia, z, 1) - h * (g0 + g1)), 'residue h(g0+g1) at z=1'


@check('inline-wall-two-tap', 'confirmed')
def _():
    return ident(Gam.subs({g0: Kw + dw / h, g1: -dw / h}) - Wz), 'wall = two-tap with g0 = Kw + dw/h, g1 = -dw/h'


@check('inline-GGamma', 'confirmed')
def _():
    return ident(GG - (cd + h * (al * g0 + (g0 + g1) / (z - 1) - (1 - al) * g1 / z))), 'expansion exact'


@check('8', 'typo')
def _():
    ok = same_on_circle(GG, ReGG)
    printed = cd + h * (al * g0 - (g0 + g1) / 2 - (1 - al) * sp.Abs(g1) * c)
    w = key_entry('8')['witness']
    p = WP('8'); p[c] = Q(w['at']['c'])
    ok = ok and printed.subs(p) == Q(w['values']['printed']) and ReGG.subs(p) == Q(w['values']['derived'])
    p0 = {k: v for k, v in p.items() if k != c}
    ok = ok and same_on_circle(GG.subs(p0), ReGG.subs(p0)) and not same_on_circle(GG.subs(p0), printed.subs(p0))
    ok = ok and corrected_is('8', key_entry('8')['latex'].replace('|g_1|', 'g_1'))
    return ok, 'no |.| on g1 (differs for g1 < 0, e.g. the wall itself)'


def thr9_exact(p):
    return p[h] * ((p[g0] + p[g1]) / 2 - p[al] * p[g0] + (1 - p[al]) * abs(p[g1]))


def thr9_printed(p):
    return p[h] * ((p[g0] + p[g1]) / 2 + p[al] * abs(p[g0]) + (1 - p[al]) * abs(p[g1]))


@check('9', 'conservative')
def _():
    # exact threshold: Re linear in c, worst at c = sign(g1)
    ok = ident(ReGG.subs(c, 1) - (cd - h * ((g0 + g1) / 2 - al * g0 + (1 - al) * g1)))
    ok = ok and ident(ReGG.subs(c, -1) - (cd - h * ((g0 + g1) / 2 - al * g0 - (1 - al) * g1)))
    gap = sp.simplify(h * ((g0 + g1) / 2 + al * sp.Abs(g0)) - h * ((g0 + g1) / 2 - al * g0))
    ok = ok and ident(gap - h * al * (sp.Abs(g0) + g0))          # >= 0: printed implies exact
    n, mism = sweep(lambda p: p[cd] >= thr9_exact(p), GG, params(True), 200, margin_fn=lambda p: p[cd] - thr9_exact(p))
    bad = 0
    gen = params(True)
    for _ in range(150):
        p = gen()
        if p[cd] >= thr9_printed(p):
            bad += not is_pr(GG.subs(p))
    p = WP('9')
    ok = ok and is_pr(GG.subs(p)) and not (p[cd] >= thr9_printed(p))
    ok = ok and corrected_is('9', 'c_d \\ge h\\Bigl(\\frac{g_0 + g_1}{2} - \\alpha g_0 + (1-\\alpha)|g_1|\\Bigr).')
    return ok and not mism and bad == 0, f'printed => exact (gap h alpha(|g0|+g0)); exact iff on {n}; witness PR but printed fails'


@check('inline-GD', 'confirmed')
def _():
    return ident(sp.residue(GD, z, 1) - Kw * h), 'delayed rendering; residue Kw h'


@check('10', 'typo')
def _():
    printed = cd - Kw * h / 2 + (1 - al) * Kw * h * c + al * dw * c + (1 - al) * dw * (2 * c**2 - 1)
    ok = same_on_circle(GD, ReGD) and not same_on_circle(GD, printed)
    w = key_entry('10')['witness']
    p = WP('10'); p[c] = Q(w['at']['c'])
    ok = ok and printed.subs(p) == Q(w['values']['printed']) and ReGD.subs(p) == Q(w['values']['derived'])
    ok = ok and corrected_is('10', key_entry('10')['latex'].replace('+ (1-\\alpha)K_{\\mathrm{w}}h\\cos', '- (1-\\alpha)K_{\\mathrm{w}}h\\cos'))
    return ok, 'sign of the (1-alpha) Kw h cos term'


@check('11', 'confirmed')
def _():
    gap = sp.expand(ReGD - (cd - (R(3, 2) - al) * Kw * h - dw))
    ok = ident(gap - ((1 - al) * Kw * h * (1 - c) + al * dw * (1 + c) + 2 * (1 - al) * dw * c**2))
    bad = 0
    gen = params()
    for _ in range(150):
        p = gen()
        if p[cd] >= (R(3, 2) - p[al]) * p[Kw] * p[h] + p[dw]:
            bad += not is_pr(GD.subs(p))
    return ok and bad == 0, 'gap (1-a)Kwh(1-c) + a dw(1+c) + 2(1-a)dw c^2 >= 0; sufficient on random instances'


def thr12_exact(p):
    return -minimum_on_circle(sp.expand(ReGD.subs(p).subs(cd, 0)))


@check('12', 'wrong')
def _():
    w = key_entry('12')['witness']
    p = WP('12')
    printed = p[cd] >= (1 - 2 * p[al]) * (p[Kw] * p[h] / 2 + p[dw]) + p[Kw] * p[h]
    val = ReGD.subs(p).subs(c, Q(w['at']['c']))
    ok = printed and val == Q(w['value']) and not is_pr(GD.subs(p))
    pe = {k: v for k, v in p.items() if k != cd}
    ok = ok and thr12_exact(pe) == Q(w['exact_bound'])
    # exact (max over c) form agrees with PR; spring alone: exactly Kw h more than (5)
    n, mism = sweep(lambda q: q[cd] >= thr12_exact({k: v for k, v in q.items() if k != cd}), GD, params(), 120,
                    margin_fn=lambda q: q[cd] - thr12_exact({k: v for k, v in q.items() if k != cd}))
    ok = ok and ident(-minimum_on_circle(sp.expand(ReGD.subs({dw: 0, cd: 0, Kw: 1, h: 1, al: R(1, 4)}))) - R(5, 4))
    return ok and not mism, f'printed holds, Re = {val} at c = -1/8 (exact bound {thr12_exact(pe)}); max-form exact on {n}'

# ---------------------------------------------------------------- driver
def main():
    fails = 0
    seen = set()
    for e in KEY:
        num = e['number']
        seen.add(num)
        if e['latex'] not in TEX:
            print(f'FAIL {num:>18} latex not found verbatim in paper.tex'); fails += 1; continue
        if num not in CHECKS:
            print(f'FAIL {num:>18} no check'); fails += 1; continue
        verdict, f = CHECKS[num]
        if verdict != e['verdict']:
            print(f'FAIL {num:>18} key verdict {e["verdict"]} but check establishes {verdict}'); fails += 1; continue
        try:
            ok, msg = f()
        except Exception as ex:  # a crash is a failure
            ok, msg = False, f'exception {ex!r}'
        ok = bool(ok)
        fails += not ok
        print(f'{"OK  " if ok else "FAIL"} {num:>18} {verdict:17s} {msg}')
    extra = set(CHECKS) - seen
    if extra:
        print('FAIL checks without key entries:', extra); fails += 1
    print(f'{len(KEY)} entries, {fails} failures')
    return 1 if fails else 0


if __name__ == '__main__':
    sys.exit(main())
