#!/usr/bin/env python3
"""Refits the polynomial tables `H` and `H_S` of DIB's lane logarithm,
crates/chasles-skin/src/fast/lane/dib.rs.

What is fitted (each table the polynomial in z, constant term first, coefficients rounded to
f32 as the kernels use them), with z = tan^2(theta/2) for the rotation's half-angle
theta = atan2(n, w) in [0, pi/2] of a unit quaternion (w, a), n = |a|, w >= 0:
  H    h(z) = theta/n = (1 + z) atan(sqrt z)/sqrt z,                    0 <= z <= 1, 8 terms;
  H_S  dh/ds at fixed w, s = n^2: (w - h)/(2 s)
       = ((1 - z^2) - (1 + z)^3 atan(sqrt z)/sqrt z)/(8 z),             same z, 7 terms
     (on the unit sphere w = (1 - z)/(1 + z), n = 2 sqrt z/(1 + z); the logarithm's vector
     part is h a, and its dual part takes dh/ds).
The kernels take z = s/(1 + w)^2: no square root, no reduction of the angle, one division.
How: as scripts/fit_trig.py (whose helpers this uses) — plain least squares in the monomial
basis at --nodes Chebyshev nodes of [0, 1], in 50-digit mpmath arithmetic: near minimax.
They replace `Q` and `G` in t^2, t = n/w reduced to t <= tan(pi/8) by three rows of
formulas with a square root, ten selects and two more divisions.

Errors are relative, in f32 ulp = 2^-23, of h(z) and dh/ds over a dense grid: exactly (50
digits, the coefficients rounded to f32) and evaluated in f32 by Horner's rule (each
operation rounded to f32; the kernels fuse each step into one multiply-add, which rounds
once: measured rather than bounded). H_S's true value near z = 0 comes from its own series
(its closed form cancels there). The fits rely on fit_trig's 50-digit mpmath precision
(mp.mp.dps, set when it is imported).

Usage (needs mpmath: pip install mpmath):
  python3 scripts/fit_dib_log.py          print the refitted tables as Rust source, and errors
  python3 scripts/fit_dib_log.py --check  compare with dib.rs's tables; exit 1 unless they are
                                          the refit's f32 values and within the documented
                                          error (H 0.4 ulp exactly and 1 in f32, H_S 0.5
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
Z_MAX = mp.mpf(1)  # tan^2(pi/4): half-angles up to pi/2 (w >= 0)


def atan_over(z):
    """atan(sqrt z)/sqrt z."""
    if z == 0:
        return mp.mpf(1)
    r = mp.sqrt(z)
    return mp.atan(r) / r


def h_true(z):
    return (1 + z) * atan_over(z)


def h_s_true(z):
    if z < mp.mpf("0.01"):
        # atan(sqrt z)/sqrt z = sum (-z)^k/(2k+1); times (1 + z)^3, then the closed form's
        # numerator over 8z term by term.
        terms = 80
        c = [mp.mpf(-1) ** k / (2 * k + 1) for k in range(terms)]
        b = [sum(m * c[k - j] for j, m in enumerate([1, 3, 3, 1]) if k >= j) for k in range(terms)]
        num = [-x for x in b]
        num[0] += 1
        num[2] -= 1
        return mp.fsum(num[k + 1] * z**k for k in range(terms - 1)) / 8
    return ((1 - z * z) - (1 + z) ** 3 * atan_over(z)) / (8 * z)


# name: (terms, the function, the documented bounds in f32 ulp: exactly and in f32)
TABLES = {"H": (8, h_true, 0.4, 1.0), "H_S": (7, h_s_true, 0.5, 1.0)}


def errors(name, c, grid):
    """Largest relative errors in f32 ulp of the table `c` (f32 values): exactly, in f32."""
    true = TABLES[name][1]
    cm = [mp.mpf(a) for a in c]
    e_mp = e_32 = 0.0
    for i in range(grid + 1):
        z = Z_MAX * i / grid
        want = true(z)
        e_mp = max(e_mp, float(abs((horner(cm, z) - want) / want)) / EPS32)
        want = true(mp.mpf(f32(z)))
        e_32 = max(e_32, float(abs((mp.mpf(horner32(c, f32(z))) - want) / want)) / EPS32)
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
        n: [f32(a) for a in fit(terms, Z_MAX, true, max(args.nodes, terms))]
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
