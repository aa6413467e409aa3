#!/usr/bin/env python3
"""Refits the polynomial tables `ACOS`, `SIN`, `COS`, `ATAN`, `ANGLE2_F32` and `SINC_F32` of
crates/chasles/src/trig.rs.

What is fitted (each table is the polynomial in its own variable, constant term first):
  ACOS  A(y) ~ acos(1 - y)/sqrt(2y),        0 <= y <= 1.0001 (ACOS_OVER_CHORD_MAX), 19 terms;
  SIN   S(z) ~ (sin x - x)/(x z),           z = x^2, 0 <= z <= 0.64 (|x| <= 0.8), 6 terms
        (sin x = x + x z S(z));
  COS   C(z) ~ (cos x - 1 + z/2)/z^2,       same z, 7 terms (cos x = 1 - z/2 + z^2 C(z));
  ATAN  P(z) ~ (atan t - t)/(t z),          z = t^2, 0 <= z <= 1 (0 <= t <= 1), 20 terms
        (atan t = t + t z P(z); the error is counted on atan t);
and, for f32 (coefficients rounded to f32 where used, errors in f32 ulp = 2^-23):
  ANGLE2_F32  Z(y) ~ acos(1 - y)^2/(2y),    0 <= y <= 1.0001, 9 terms (the squared angle);
  SINC_F32    T(u) ~ (sin(sqrt u)/sqrt u - 1)/u, 0 <= u <= acos(-0.0001)^2 (SINC_F32_MAX),
              5 terms (sinc = 1 + u T(u); its error is counted on the sinc).
How: plain (unweighted) least squares in the monomial basis at --nodes Chebyshev nodes (first
kind) of the variable's interval, in 50-digit mpmath arithmetic, each coefficient then rounded
to the nearest f64. All 19 ACOS terms are fitted: the constant comes out 1 + 1.4e-17 and rounds
to exactly 1.0 (so A(0) = 1 in f64). This reproduces trig.rs's tables bit for bit for any
--nodes from 29 up (ATAN from 30 up; at 29 six of its coefficients differ in the last digits,
0.06 ulp in value; fewer nodes, or weighting by 1/f, or fixing the constant at 1 before the
fit, give different coefficients whose values agree to well under 1 ulp; the fits are
near-minimax, hence ill-conditioned in the coefficients).

Errors are relative, in ulp = 2^-52 (f64::EPSILON, as trig.rs's tests count them), of the
angle factor A(y) (the angle is d * A(y)), of sin x, of cos x and of atan t, over a dense
grid: exactly (50 digits, coefficients as f64 values) and evaluated in f64 by Horner without
FMA (trig.rs uses Estrin's scheme, with FMA where the build has it, so its rounding differs a
little).
The f32 tables likewise in ulp = 2^-23, their coefficients rounded to f32, evaluated in
f32 (each operation rounded to f32).

Usage (needs mpmath: pip install mpmath):
  python3 scripts/fit_trig.py            print the refitted tables as Rust source, and errors
  python3 scripts/fit_trig.py --check    compare with trig.rs's tables; exit 1 unless they are
                                         within the documented error (3 ulp angle, 1.5 ulp sin,
                                         cos and atan) and agree in value with the refit to that
"""
import argparse
import pathlib
import re
import struct
import sys

try:
    import mpmath as mp
except ImportError:
    sys.exit(
        "fit_trig.py needs mpmath: pip install mpmath "
        "(e.g. python3 -m venv /tmp/fitvenv && /tmp/fitvenv/bin/pip install mpmath)"
    )

mp.mp.dps = 50
EPS = 2.0**-52
EPS32 = 2.0**-23
TRIG_RS = pathlib.Path(__file__).resolve().parent.parent / "crates" / "chasles" / "src" / "trig.rs"
Y_MAX, X_MAX = "1.0001", "0.8"  # ACOS_OVER_CHORD_MAX, SIN_COS_REDUCED_MAX in trig.rs
U_MAX = mp.acos(-mp.mpf("0.0001")) ** 2  # SINC_F32_MAX in trig.rs


def f32(v):
    """v rounded to the nearest f32."""
    return struct.unpack("f", struct.pack("f", float(v)))[0]


def horner32(c, t):
    """Horner's rule with every coefficient, product and sum rounded to f32."""
    s = 0.0
    for a in reversed(c):
        s = f32(f32(s * t) + f32(a))
    return s


def horner(c, t):
    s = 0 * t
    for a in reversed(c):
        s = s * t + a
    return s


def acos_factor(y):
    return mp.acos(1 - y) / mp.sqrt(2 * y)


def angle2(y):
    return mp.acos(1 - y) ** 2 / (2 * y)


def atan_part(z):
    t = mp.sqrt(z)
    return (mp.atan(t) - t) / (t * z)


def sinc(u):
    return mp.sin(mp.sqrt(u)) / mp.sqrt(u)


# name: (terms, top of the variable's range, the polynomial's target in its variable,
#        grid top (y or x), the function from coefficients c at grid point u exactly and in
#        f64 (f32 for the f32 tables), the true function at u, the documented bound in ulp,
#        the ulp: EPS or EPS32, with coefficients rounded to f32 for the latter).
KERNELS = {
    "ACOS": (
        19, mp.mpf(Y_MAX), acos_factor, float(Y_MAX),
        lambda c, y: horner(c, y),
        lambda c, y: horner(c, y),
        acos_factor, 3.0, EPS,
    ),
    "SIN": (
        6, mp.mpf(X_MAX) ** 2, lambda z: (mp.sin(mp.sqrt(z)) - mp.sqrt(z)) / (mp.sqrt(z) * z),
        float(X_MAX),
        lambda c, x: x + x * x * x * horner(c, x * x),
        lambda c, x: x * (x * x) * horner(c, x * x) + x,
        mp.sin, 1.5, EPS,
    ),
    "COS": (
        7, mp.mpf(X_MAX) ** 2, lambda z: (mp.cos(mp.sqrt(z)) - 1 + z / 2) / z**2,
        float(X_MAX),
        lambda c, x: 1 - x * x / 2 + (x * x) ** 2 * horner(c, x * x),
        lambda c, x: (x * x) * (x * x) * horner(c, x * x) + ((x * x) * -0.5 + 1.0),
        mp.cos, 1.5, EPS,
    ),
    "ATAN": (
        20, mp.mpf(1), atan_part, 1.0,
        lambda c, t: t + t * t * t * horner(c, t * t),
        lambda c, t: t * (t * t) * horner(c, t * t) + t,
        mp.atan, 1.5, EPS,
    ),
    "ANGLE2_F32": (
        9, mp.mpf(Y_MAX), angle2, float(Y_MAX),
        lambda c, y: horner(c, y),
        lambda c, y: horner32(c, f32(y)),
        angle2, 1.5, EPS32,
    ),
    "SINC_F32": (
        5, U_MAX, lambda u: (sinc(u) - 1) / u, float(U_MAX),
        lambda c, u: 1 + u * horner(c, u),
        lambda c, u: f32(1.0 + f32(f32(u) * horner32(c, f32(u)))),
        sinc, 1.5, EPS32,
    ),
}


def fit(terms, top, target, nodes):
    """Least-squares coefficients (mpf, constant first) at `nodes` Chebyshev nodes on [0, top]."""
    ts = [top / 2 * (1 + mp.cos(mp.pi * (2 * k + 1) / (2 * nodes))) for k in range(nodes)]
    a = mp.matrix([[t**j for j in range(terms)] for t in ts])
    coef, _ = mp.qr_solve(a, mp.matrix([target(t) for t in ts]))
    return [float(coef[j]) for j in range(terms)]


def used(name, c):
    """The coefficients as the code uses them: f64 values, or rounded to f32."""
    return [f32(a) for a in c] if KERNELS[name][8] == EPS32 else list(c)


def errors(name, c, grid):
    """Largest relative error in ulp of the table `c` (f64 values): exactly (coefficients as
    used) and evaluated in the table's precision."""
    _, _, _, top, exact, f64, true, _, eps = KERNELS[name]
    c = used(name, c)
    cm = [mp.mpf(a) for a in c]
    e_mp = e_64 = 0.0
    for i in range(1, grid + 1):
        u = top * i / grid
        want = true(mp.mpf(u))
        e_mp = max(e_mp, float(abs(exact(cm, mp.mpf(u)) - want) / abs(want)) / eps)
        e_64 = max(e_64, float(abs(f64(c, u) - want) / abs(want)) / eps)
    return e_mp, e_64


def value_difference(name, c, d, grid):
    """Largest relative difference in ulp between the functions built from tables c and d."""
    _, _, _, top, exact, _, true, _, eps = KERNELS[name]
    cm, dm = [mp.mpf(a) for a in used(name, c)], [mp.mpf(a) for a in used(name, d)]
    return max(
        float(abs(exact(cm, u) - exact(dm, u)) / abs(true(u))) / eps
        for u in (mp.mpf(top * i / grid) for i in range(1, grid + 1))
    )


def current_tables():
    src = TRIG_RS.read_text()
    for const, want in (
        ("ACOS_OVER_CHORD_MAX", Y_MAX),
        ("SIN_COS_REDUCED_MAX", X_MAX),
        ("SINC_F32_MAX", repr(float(U_MAX))),
    ):
        m = re.search(rf"const {const}: f64 = ([^;]+);", src)
        if not m or float(m.group(1).replace("_", "")) != float(want):
            sys.exit(f"{TRIG_RS}: {const} is not {want}; update Y_MAX, X_MAX, U_MAX here")
    tables = {}
    for name in KERNELS:
        m = re.search(rf"const {name}: \[f64; (\d+)\] = \[([^\]]*)\];", src)
        if not m:
            sys.exit(f"{TRIG_RS}: no `const {name}: [f64; N]` table")
        tables[name] = [float(v.replace("_", "")) for v in m.group(2).split(",") if v.strip()]
        if len(tables[name]) != int(m.group(1)) or int(m.group(1)) != KERNELS[name][0]:
            sys.exit(f"{TRIG_RS}: {name} has {m.group(1)} terms, not {KERNELS[name][0]}")
    return tables


def agreement(c, d):
    """How the refit's coefficients c match the table d, in words."""
    same = sum(a == b for a, b in zip(c, d))
    if same == len(d):
        return f"all {same} coefficients bit-identical to the refit"
    digits = -float(mp.log10(max(abs(a - b) / abs(b) for a, b in zip(c, d))))
    return f"{same}/{len(d)} bit-identical to the refit, the others to {digits:.1f}+ digits"


def arguments(doc, source, grid):
    """The fitting scripts' command line: --check against `source`'s tables, --nodes, --grid
    (default `grid`)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--check", action="store_true", help=f"compare with {source}'s tables")
    ap.add_argument("--nodes", type=int, default=64, help="Chebyshev nodes per fit (default 64)")
    ap.add_argument("--grid", type=int, default=grid, help=f"error grid points (default {grid})")
    return ap.parse_args()


def main():
    args = arguments(__doc__, "trig.rs", 4000)
    refit = {n: fit(*KERNELS[n][:3], max(args.nodes, KERNELS[n][0])) for n in KERNELS}
    if not args.check:
        for name, c in refit.items():
            print(f"const {name}: [f64; {len(c)}] = [")
            print("".join(f"    {a!r},\n" for a in c) + "];")
        for name, c in refit.items():
            e_mp, e_64 = errors(name, c, args.grid)
            what = "f32" if KERNELS[name][8] == EPS32 else "f64"
            print(f"// {name}: max error {e_mp:.3f} ulp exactly, {e_64:.3f} ulp in {what} (Horner)")
        return 0
    ok = True
    for name, cur in current_tables().items():
        bound = KERNELS[name][7]
        diff = value_difference(name, refit[name], cur, args.grid)
        e_mp, e_64 = errors(name, cur, args.grid)
        good = diff <= bound and e_64 <= bound
        ok &= good
        print(f"{name}: {agreement(refit[name], cur)}; values differ by <= {diff:.3f} ulp")
        what = "f32" if KERNELS[name][8] == EPS32 else "f64"
        print(
            f"  trig.rs's table: max error {e_mp:.3f} ulp exactly, {e_64:.3f} ulp in {what} (Horner),"
            f" documented {bound} ulp: {'ok' if good else 'FAIL'}"
        )
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
