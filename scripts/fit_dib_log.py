#!/usr/bin/env python3
"""Refits the polynomial tables `Q` and `G` of DIB's lane logarithm,
crates/chasles-skin/src/fast/lane/dib.rs.

What is fitted (each table the polynomial in z, constant term first, coefficients rounded to
f32 as the kernels use them):
  Q  Q(z) ~ atan(sqrt z)/sqrt z,                           0 <= z <= tan^2(pi/8), 6 terms;
  G  G(z) ~ (atan(sqrt z) - sqrt z/(1 + z))/z^(3/2),       same z, 7 terms
     (h = atan2(n, w)/n = Q(t^2)/w and dh/ds = -G(t^2)/(2 w^3) for t = n/w <= tan(pi/8):
     the logarithm's reduced angle, and the derivative its dual part takes).
How: as scripts/fit_trig.py (whose helpers this uses) — plain least squares in the monomial
basis at --nodes Chebyshev nodes of [0, tan^2(pi/8)], in 50-digit mpmath arithmetic: near
minimax. They replace the Taylor series, Q's ten terms and G's eleven (exact to 1e-9 and
4e-9 at z's top), with six and seven (exact to 6.1e-10 and 2.7e-10 before their
coefficients are rounded to f32), as accurate where the kernels use them: with f32
coefficients Q within 0.011 ulp (the Taylor table's 0.023) and G within 0.34 (0.32: mostly
2/3 rounded to f32, which both share), and evaluated in f32 0.30 and 0.88 ulp (0.31 and
0.88) — four multiply-adds fewer on each of the two chains of every logarithm.

Errors are relative, in f32 ulp = 2^-23, of Q(z) and G(z) over a dense grid: exactly (50
digits, the coefficients rounded to f32) and evaluated in f32 by Horner's rule (each
operation rounded to f32; the kernels fuse each step into one multiply-add, which rounds
once: emulated, 0.29 and 0.79 ulp, measured rather than bounded). G's true value near
z = 0 comes from its own series (its closed form cancels there). The fits and Z_MAX rely on
fit_trig's 50-digit mpmath precision (mp.mp.dps, set when it is imported).

Usage (needs mpmath: pip install mpmath):
  python3 scripts/fit_dib_log.py          print the refitted tables as Rust source, and errors
  python3 scripts/fit_dib_log.py --check  compare with dib.rs's tables; exit 1 unless they are
                                          the refit's f32 values and within the documented
                                          error (Q 0.02 ulp exactly and 0.5 in f32, G 0.4
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
Z_MAX = (mp.sqrt(2) - 1) ** 2  # tan^2(pi/8): TAN_PI_8 in dib.rs, squared


def q_true(z):
    if z == 0:
        return mp.mpf(1)
    r = mp.sqrt(z)
    return mp.atan(r) / r


def g_true(z):
    if z < mp.mpf("0.01"):
        return mp.nsum(lambda k: (-1) ** k * 2 * (k + 1) / (2 * k + 3) * z**k, [0, mp.inf])
    r = mp.sqrt(z)
    return (mp.atan(r) - r / (1 + z)) / (z * r)


# name: (terms, the function, the documented bounds in f32 ulp: exactly and in f32)
TABLES = {"Q": (6, q_true, 0.02, 0.5), "G": (7, g_true, 0.4, 1.0)}


def errors(name, c, grid):
    """Largest relative errors in f32 ulp of the table `c` (f32 values): exactly, in f32."""
    true = TABLES[name][1]
    cm = [mp.mpf(a) for a in c]
    e_mp = e_32 = 0.0
    for i in range(grid + 1):
        z = Z_MAX * i / grid
        want = true(z)
        e_mp = max(e_mp, float(abs(horner(cm, z) - want) / want) / EPS32)
        e_32 = max(e_32, float(abs(mp.mpf(horner32(c, f32(z))) - want) / want) / EPS32)
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
    m = re.search(r"const TAN_PI_8: f32 = ([^;]+);", src)
    if not m or f32(m.group(1).replace("_", "")) != f32(mp.sqrt(Z_MAX)):
        sys.exit(f"{DIB_RS}: TAN_PI_8 is not tan(pi/8) in f32; update Z_MAX here")
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
