#!/usr/bin/env python3
"""Refits the polynomial tables `H` and `H_S` of DIB's lane logarithm,
crates/chasles-skin/src/fast/lane/dib.rs.

What is fitted (each table the polynomial in v, constant term first, coefficients rounded to
f32 as the kernels use them), with v = 1 - w = 1 - cos(theta) for the angle
theta = atan2(n, w) in [0, pi/2] of a unit quaternion (w, a), n = |a| = sin(theta), w >= 0:
  H    h(v) = theta/n = acos(1 - v)/sqrt(v (2 - v)),            0 <= v <= 1, 10 terms;
  H_S  dh/ds at fixed w, s = n^2: (w - h)/(2 s)
       = ((1 - v) - h(v))/(2 v (2 - v)),                        same v, 11 terms
     (the logarithm's vector part is h a, and its dual part takes dh/ds). Both are smooth
     on [0, 1] (their singularity is at v = 2, w = -1).
The kernels take v = 1 - w: no square root, no reduction of the angle and no division on
the logarithm's chain from w to h, which is the subtraction and Horner's rule.
How: as scripts/fit_trig.py (whose helpers this uses) — plain least squares in the monomial
basis at --nodes Chebyshev nodes of [0, 1], in 50-digit mpmath arithmetic: near minimax.
They replace `Q` and `G` in t^2, t = n/w reduced to t <= tan(pi/8) by three rows of
formulas with a square root, ten selects and four divisions.

Errors are relative, in f32 ulp = 2^-23, of h and dh/ds over a dense grid: exactly (50
digits, the coefficients rounded to f32) and evaluated in f32 by Horner's rule (each
operation rounded to f32; the kernels fuse each step into one multiply-add, which rounds
once: measured rather than bounded). Near v = 0 H_S's closed form cancels, so it is taken
at three times the working precision (and as its limit -1/3 at 0). The fits rely on
fit_trig's 50-digit mpmath precision (mp.mp.dps, set when it is imported).

Usage (needs mpmath: pip install mpmath):
  python3 scripts/fit_dib_log.py          print the refitted tables as Rust source, and errors
  python3 scripts/fit_dib_log.py --check  compare with dib.rs's tables; exit 1 unless they are
                                          the refit's f32 values and within the documented
                                          error (H 0.3 ulp exactly and 1 in f32, H_S 0.3
                                          and 1)
"""
import pathlib
import re
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from fit_trig import arguments, f32, fit, horner, horner32, mp  # noqa: E402  (mpmath, checked there)

DIB_RS = (
    pathlib.Path(__file__).resolve().parent.parent
    / "crates" / "chasles-skin" / "src" / "fast" / "lane" / "dib.rs"
)
EPS32 = 2.0**-23
V_MAX = mp.mpf(1)  # 1 - cos(pi/2): angles up to pi/2 (w >= 0)


def h_true(v):
    if v == 0:
        return mp.mpf(1)
    n = mp.sqrt(v * (2 - v))
    return mp.atan2(n, 1 - v) / n


def h_s_true(v):
    if v == 0:
        return mp.mpf(-1) / 3
    with mp.workdps(3 * mp.mp.dps):
        v = mp.mpf(v)
        return ((1 - v) - h_true(v)) / (2 * v * (2 - v))


# name: (terms, the function, the documented bounds in f32 ulp: exactly and in f32)
TABLES = {"H": (10, h_true, 0.3, 1.0), "H_S": (11, h_s_true, 0.3, 1.0)}


def errors(name, c, grid):
    """Largest relative errors in f32 ulp of the table `c` (f32 values): exactly, in f32."""
    true = TABLES[name][1]
    cm = [mp.mpf(a) for a in c]
    e_mp = e_32 = 0.0
    for i in range(grid + 1):
        v = V_MAX * i / grid
        want = true(v)
        e_mp = max(e_mp, float(abs((horner(cm, v) - want) / want)) / EPS32)
        want = true(mp.mpf(f32(v)))
        e_32 = max(e_32, float(abs((mp.mpf(horner32(c, f32(v))) - want) / want)) / EPS32)
    return e_mp, e_32


def shortest(a):
    """The shortest decimal that reads back as the f32 `a` (as Rust prints it)."""
    for digits in range(1, 10):
        text = f"{a:.{digits}g}"
        if f32(text) == a:
            return text if ("." in text or "e" in text) else text + ".0"
    return repr(a)


def current_tables():
    src = DIB_RS.read_text()
    tables = {}
    for name, (terms, _, _, _) in TABLES.items():
        m = re.search(rf"const {name}: \[f32; (\d+)\] = \[([^\]]*)\];", src)
        if not m:
            sys.exit(f"{DIB_RS}: no `const {name}: [f32; N]` table")
        tables[name] = [f32(v.replace("_", "")) for v in m.group(2).split(",") if v.strip()]
        if len(tables[name]) != int(m.group(1)) or int(m.group(1)) != terms:
            sys.exit(f"{DIB_RS}: {name} has {m.group(1)} terms, not {terms}")
    return tables


def main():
    args = arguments(__doc__, "dib.rs", 2000)
    refit = {
        n: [f32(a) for a in fit(terms, V_MAX, true, max(args.nodes, terms))]
        for n, (terms, true, _, _) in TABLES.items()
    }
    if not args.check:
        for name, c in refit.items():
            print(f"const {name}: [f32; {len(c)}] = [")
            print("".join(f"    {shortest(a)},\n" for a in c) + "];")
        for name, c in refit.items():
            e_mp, e_32 = errors(name, c, args.grid)
            print(f"// {name}: max error {e_mp:.4f} ulp exactly, {e_32:.3f} ulp in f32 (Horner)")
        return 0
    ok = True
    for name, cur in current_tables().items():
        _, _, bound_mp, bound_32 = TABLES[name]
        e_mp, e_32 = errors(name, cur, args.grid)
        same = cur == refit[name]
        good = same and e_mp <= bound_mp and e_32 <= bound_32
        ok &= good
        print(
            f"{name}: {'the refit, bit for bit' if same else 'NOT the refit'}; max error"
            f" {e_mp:.4f} ulp exactly (documented {bound_mp}), {e_32:.3f} in f32"
            f" (documented {bound_32}): {'ok' if good else 'FAIL'}"
        )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
