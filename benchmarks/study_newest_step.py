"""The degree of the newest step's representation of u' and the error expansion of product integration
(a design study of the adaptive method's scheme, not a run of it).

A plain NumPy product integration of the model (the hereditary Hertz force on a rigid target or Zener's
plate, the implicit trapezoidal rule for s and J, separation where F returns to zero, located on the
cubic through the last four nodes), on nested graded grids: a coarse grid of steps tc / N_PER, graded
near t = 0 (steps <= t / 4, powers of two down to tc / (64 N_PER)), and the grids with every step divided
by 2, 4, ... 32 (as the adaptive method's replays). On each step u' is a polynomial whose means over the
last K steps are the steps' means d_j (one-sided, fixed when the step is accepted): the newest step is a
quadratic (K = 3, the adaptive method's scheme) or a cubic (K = 4); every older step keeps its mean and
slope (the adaptive method's exponential modes carry those two), or also its curvature; their exact
weights against the kernel are computed by Gauss-Legendre in sqrt(lag), exact for the fractional law's
lag^-1/2. For each
case the table gives the COR's relative error, against the finest extrapolation of the cubic scheme, of
Richardson extrapolations from consecutive grids, and the steps they take (separation included).

The errors do not depend on the machine (one process; the scheme is O(N^2) in Python: minutes per case).

Run: python benchmarks/study_newest_step.py [--quick] [--out FILE]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

import timing
from vcor.solvers.reference import richardson_weights

#: (preset, v0 in m/s, target: "rigid", or a plate half-thickness in m, None for the default plate)
CASES = (("butyl-fc", 1.0, "rigid"), ("butyl-fc", 10.0, "rigid"), ("butyl-cerf", 1.0, "rigid"),
         ("butyl-fc", 1.0, None), ("butyl-cerf", 1.0, None), ("sls", 1.0, "rigid"), ("butyl-prony3", 1.0, "rigid"))
#: coarse steps per contact-time estimate, and the number of nested grids (every step divided by 2^k)
N_PER = 40
LEVELS = 6
#: finer coarse grids (steps per contact-time estimate) of the cubic scheme's three grids, for the second
#: table (the fractional and CERF cases)
FINER = (48, 56, 64)
#: the schemes: (newest-step degree, terms every older step keeps beyond its mean: 1, the slope; 2, also
#: the curvature)
SCHEMES = ((2, 1), (3, 1), (3, 2))
#: (label, scheme, grids used (first, count), exponents removed)
ROWS = (("quadratic, 4 grids (adaptive's plain march)", (2, 1), (0, 4), (2.0, 3.5, 4.0)),
        ("quadratic, 3 grids", (2, 1), (0, 3), (2.0, 4.0)),
        ("cubic, 3 grids", (3, 1), (0, 3), (2.0, 4.0)),
        ("cubic, older steps' curvature, 3 grids", (3, 2), (0, 3), (2.0, 4.0)),
        ("cubic, grids 2 and 3 of 3", (3, 1), (1, 2), (2.0,)),
        ("cubic, 4 grids", (3, 1), (0, 4), (2.0, 3.5, 4.0)))
_GAUSS = np.polynomial.legendre.leggauss(8)


def basis(z, h, degree):
    """The zero-mean polynomials of a step of size h at offsets z from its middle: 1, z, z^2 - h^2/12,
    z^3 - 3/20 h^2 z (up to ``degree``)."""
    out = [np.ones_like(z), z, z * z - h * h / 12.0, z**3 - 0.15 * h * h * z]
    return out[: degree + 1]


def stencil(sizes, degree):
    """The matrix M with (d, a_1, .., a_degree) = M @ (means of the last degree + 1 steps, newest first) for
    the polynomial, in :func:`basis` of the newest step, whose means over those steps are the given ones."""
    offsets = [0.0]
    for k in range(1, degree + 1):
        offsets.append(offsets[-1] - 0.5 * (sizes[k - 1] + sizes[k]))
    y, w = np.polynomial.legendre.leggauss(6)
    means = np.empty((degree + 1, degree + 1))
    for k in range(degree + 1):
        z = offsets[k] + 0.5 * sizes[k] * y
        means[k] = [0.5 * np.sum(w * b) for b in basis(z, sizes[0], degree)]
    return np.linalg.inv(means)


def lag_weights(modulus, lo, hi):
    """Gauss-Legendre nodes in y = sqrt(lag) on [sqrt(lo), sqrt(hi)] (arrays of intervals) and the weights
    of int E(lag) f(lag) dlag = int 2 y E(y^2) f(y^2) dy."""
    y0, y1 = np.sqrt(lo), np.sqrt(hi)
    y = 0.5 * (y1 - y0)[..., None] * _GAUSS[0] + 0.5 * (y1 + y0)[..., None]
    return y * y, (y1 - y0)[..., None] * _GAUSS[1] * y * modulus(y * y)


def cor_on(impact, steps, scheme):
    """The COR of ``impact`` marched on ``steps`` (s) with ``scheme`` (newest step's degree, terms the older
    steps keep: :data:`SCHEMES`), and the steps taken to the separation."""
    degree, terms = scheme
    kappa, m, v0 = float(impact.kappa), float(impact.m), float(impact.v0)
    modulus, mobility = impact.material.relaxation_modulus, impact.mobility_function()
    n_all = len(steps)
    t = np.concatenate(([0.0], np.cumsum(steps)))
    s, g, J, F, u, d = (np.zeros(n_all + 1) for _ in range(6))
    shape = np.zeros((n_all + 1, 3))  # the older steps' slope and curvature terms
    g[0] = v0
    loaded = False
    for n in range(1, n_all + 1):
        h, tn = steps[n - 1], t[n]
        older = np.arange(1, n)
        lag, w = lag_weights(modulus, tn - t[older], tn - t[older - 1])
        z = tn - lag - 0.5 * (t[older] + t[older - 1])[:, None]
        sizes = np.asarray(steps)[older - 1][:, None]
        history = np.sum(d[older] * w.sum(axis=1))
        for p, b in enumerate(basis(z, sizes, terms)[1:], start=1):
            history += np.sum(shape[older, p] * (w * b).sum(axis=1))
        deg = min(degree, n - 1)
        lag0, w0 = lag_weights(modulus, np.array(0.0), np.array(h))
        newest = np.array([np.sum(w0 * b) for b in basis(h / 2.0 - lag0, h, deg)])
        sizes_n = [steps[n - 1 - k] for k in range(deg + 1)]
        weights = newest @ stencil(sizes_n, deg) if deg else newest
        known = history + sum(weights[k] * d[n - k] for k in range(1, deg + 1))
        step = (kappa * known, kappa * weights[0] / h, h, *mobility(tn), m, v0)
        sn = _solve(step, (s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]))
        u[n], F[n], J[n], g[n] = _node(sn, step, (s[n - 1], g[n - 1], u[n - 1], F[n - 1], J[n - 1]))[1]
        s[n], d[n] = sn, (u[n] - u[n - 1]) / h
        kept = min(degree, n - 1)
        if kept:
            sizes_k = [steps[n - 1 - k] for k in range(kept + 1)]
            coefs = stencil(sizes_k, kept) @ np.array([d[n - k] for k in range(kept + 1)])
            shape[n, 1: min(terms, kept) + 1] = coefs[1: min(terms, kept) + 1]
        loaded = loaded or (F[n] > 0.0 and sn > 0.0)
        if loaded and F[n] <= 0.0:
            near = slice(n - 3, n + 1)
            roots = np.roots(np.polyfit(t[near] - tn, F[near], 3))
            t0 = [r.real for r in roots if abs(r.imag) < 1e-12 and t[n - 1] - tn - 1e-15 <= r.real <= 1e-15][0]
            return -np.polyval(np.polyfit(t[near] - tn, g[near], 3), t0) / v0, n
    raise RuntimeError("no separation on the grid")


def _node(sn, step, prev):
    """(residual of the trapezoidal rule for s, (u, F, J, s') at the new node) for s_n = ``sn`` (m);
    ``step``: (known part of F (N), weight of u_n - u_{n-1} in F (N m^-1.5), h (s), alpha, alpha' (plate
    mobility, m/(N s), m/(N s^2)), m (kg), v0 (m/s)); ``prev``: (s, s', u, F, J) at the last node."""
    known, weight, h, alpha, alpha_rate, m, v0 = step
    s0, g0, u0, f0, j0 = prev
    un = np.sign(sn) * abs(sn) ** 1.5
    fn = known + weight * (un - u0)
    jn = j0 + 0.5 * h * (f0 + fn)
    gn = v0 - jn / m - alpha_rate * jn - alpha * fn
    return sn - s0 - 0.5 * h * (g0 + gn), (un, fn, jn, gn)


def _solve(step, prev):
    """s_n (m) where :func:`_node`'s residual vanishes (secant-Newton from the explicit Euler guess)."""
    h, v0 = step[2], step[6]
    sn = prev[0] + h * prev[1]
    for _ in range(60):
        r = _node(sn, step, prev)[0]
        eps = 1e-7 * max(abs(sn), 1e-12)
        ds = r * eps / (_node(sn + eps, step, prev)[0] - r)
        sn -= ds
        if abs(ds) <= 1e-15 * (abs(sn) + v0 * h):
            break
    return sn


def coarse_grid(tc, n_per=N_PER):
    """Steps (s) of tc / n_per, graded near t = 0, to 12 tc."""
    top = tc / n_per
    steps, t = [], 0.0
    while t < 12.0 * tc:
        step = top / 64.0
        while 2.0 * step <= min(top, t / 4.0):
            step *= 2.0
        steps.append(step)
        t += step
    return steps


def measure(quick):
    """Per case: (label, {scheme: [(COR, steps) per grid]}, {n_per in FINER: [(COR, steps) of the cubic
    scheme on three grids]}, the last empty for the Prony kernels)."""
    from vcor.contact.impact import make_impact

    levels = 4 if quick else LEVELS
    out = []
    for name, v0, target in CASES[:3] if quick else CASES:
        geometry = {"rigid": True} if target == "rigid" else ({} if target is None else {"h": target})
        impact = make_impact(name, v0, geometry)
        base = np.array(coarse_grid(impact.contact_time_estimate()))
        runs = {scheme: [cor_on(impact, np.repeat(base / 2**k, 2**k), scheme) for k in range(levels)]
                for scheme in SCHEMES}
        finer = {}
        if not impact.material.is_prony:
            for n_per in FINER:
                grid = np.array(coarse_grid(impact.contact_time_estimate(), n_per))
                finer[n_per] = [cor_on(impact, np.repeat(grid / 2**k, 2**k), (3, 1)) for k in range(3)]
        where = "rigid target" if target == "rigid" else f"plate h = {target or 'default'}"
        out.append((f"{name}, {v0:g} m/s, {where}", runs, finer))
    return out


def report(results, quick):
    levels = 4 if quick else LEVELS
    header = ["case"] + [label for label, *_ in ROWS]
    rows, equal = [], []
    for label, runs, finer in results:
        cubic = np.array([c for c, _ in runs[(3, 1)]])
        ref = richardson_weights((2.0, 3.0, 4.0)) @ cubic[levels - 4:]
        cells = [label]
        for _, scheme, (first, count), exponents in ROWS:
            cells.append(_cell(runs[scheme], first, count, exponents, ref))
        rows.append(cells)
        if finer:
            equal.append([label, cells[1]] + [_cell(finer[n], 0, 3, (2.0, 4.0), ref) for n in FINER])
    blocks = [f"COR relative error (steps of all grids marched, the coarse grid and every replay up to the last "
              f"used) against the extrapolation (h^2, h^3, h^4) of the cubic scheme's {min(levels, 4)} finest of "
              f"{levels} grids; coarse grid tc / {N_PER}, graded near t = 0.",
              timing.table(header, rows)]
    if equal:
        blocks += [f"The fractional and CERF cases again: the quadratic scheme's four grids on the coarse grid "
                   f"tc / {N_PER}, and the cubic scheme's three grids (h^2, h^4 removed) on finer coarse grids; "
                   f"error (steps) against the same reference.",
                   timing.table(["case", f"quadratic, 4 grids, tc / {N_PER}"]
                                + [f"cubic, 3 grids, tc / {n}" for n in FINER], equal)]
    return blocks


def _cell(runs, first, count, exponents, ref):
    """'error (steps)' of the extrapolation from ``runs[first: first + count]`` (the coarser grids are marched
    too: their steps count)."""
    cors = np.array([c for c, _ in runs[first: first + count]])
    steps = sum(n for _, n in runs[:first + count])
    return f"{abs(richardson_weights(exponents) @ cors / ref - 1):.1e} ({steps})"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", type=Path, help="write the table (Markdown) to this file instead of stdout")
    p.add_argument("--quick", action="store_true", help="three rigid-target cases, four grids")
    args = p.parse_args()
    timing.publish(args.out, 1, report(measure(args.quick), args.quick))


if __name__ == "__main__":
    main()
