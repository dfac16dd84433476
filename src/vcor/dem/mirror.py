"""A NumPy mirror of what LAMMPS computes with vcor's plugin and the deck ``in.hereditary``: the COR
of one collision in LAMMPS, without LAMMPS.

It repeats the deck's set-up (``units si``; the bodies ``10 v0 dt`` apart, each atom's mass
4/3 pi r^3 rho, the time step of :func:`vcor.dem.hereditary_law.time_step`) and LAMMPS's steps:
``fix nve/sphere``'s velocity Verlet (half kick, drift, force, half kick) with the plugin's force
(:mod:`vcor.dem.hereditary_law`): at first touch the internal variables start at zero with u = 0 one
step before; each step ``q_i <- exp(-beta_i dt) q_i + E_i (1 - exp(-beta_i dt)) / (beta_i dt) du``;
the force is clipped at zero; the contact ends when the overlap does. Two spheres head-on (atoms at
-x and +x, the COR (vx2 - vx1) / v0) or a sphere on the wall x = 0 (the COR vx / v0). All speeds march
together, each with its own step. ``tests/dem/test_lammps_plugin.py`` checks it against LAMMPS itself
(equal to 1e-9); the dataset's ``lammps-hereditary`` law is this COR.
"""

from __future__ import annotations

import math

import numpy as np

from .hereditary_law import NSTEPS, HereditaryLaw, time_step

__all__ = ["MAX_CONTACT_STEPS", "plugin_cor"]

#: a contact still touching after this many steps (times nsteps) is reported as NaN (it does not end)
MAX_CONTACT_STEPS = 50


def _masses(radii, densities):
    return [4.0 / 3.0 * math.pi * r**3 * rho for r, rho in zip(radii, densities)]


def plugin_cor(law: HereditaryLaw, kind: str, radii, densities, v0, nsteps: int = NSTEPS) -> np.ndarray:
    """The COR (1) that ``lmp -in in.hereditary -var v0 <v0>`` prints, at each speed ``v0`` (m/s):
    ``kind`` ``pair`` (two spheres of ``radii`` (m) and ``densities`` (kg/m^3)) or ``wall`` (one
    sphere); NaN where the contact does not end within MAX_CONTACT_STEPS x nsteps steps.

    Examples
    --------
    Two 5 mm spheres of the paper's SLS at 1 m/s (vcor's COR: 0.79087):

    >>> from vcor.dem.hereditary_law import contact_law
    >>> from vcor.dem.mirror import plugin_cor
    >>> law = contact_law("sls", 1.0 / 1.5)
    >>> plugin_cor(law, "pair", (0.005, 0.005), (1100.0, 1100.0), [1.0]).round(5)
    array([0.79087])
    """
    v0 = np.atleast_1d(np.asarray(v0, dtype=float))
    pair = kind == "pair"
    masses = _masses(radii[:2] if pair else radii[:1], densities[:2] if pair else densities[:1])
    if pair:
        m_eff = masses[0] * masses[1] / (masses[0] + masses[1])
        r_eff = radii[0] * radii[1] / (radii[0] + radii[1])
        radsum = radii[0] + radii[1]
    else:
        m_eff, r_eff, radsum = masses[0], radii[0], radii[0]
    dt = time_step(law, m_eff, r_eff, v0, nsteps)
    gap = 10.0 * v0 * dt
    e = np.asarray(law.e, dtype=float)
    beta = np.asarray(law.beta, dtype=float)
    x = np.multiply.outer(dt, beta)
    a = np.exp(-x)
    w = e * (-np.expm1(-x) / x) if e.size else np.zeros_like(x)
    k = 4.0 / 3.0 * math.sqrt(r_eff)
    n = v0.size
    if pair:
        x1, x2 = -(radii[0] + 0.5 * gap), radii[1] + 0.5 * gap
        v1, v2 = 0.5 * v0, -0.5 * v0
    else:
        x1, x2 = np.zeros(n), radii[0] + gap  # the wall at 0; the sphere is atom 2
        v1, v2 = np.zeros(n), -v0.copy()
    q, u_prev = np.zeros((n, e.size)), np.zeros(n)
    force = np.zeros(n)
    touched, done = np.zeros(n, bool), np.zeros(n, bool)
    m1 = masses[0] if pair else math.inf
    m2 = masses[-1]
    for _ in range(MAX_CONTACT_STEPS * nsteps):
        live = ~done
        # half kick and drift (a finished lane keeps its velocities: it is in free flight)
        v1 = np.where(live, v1 - 0.5 * dt * force / m1, v1)
        v2 = np.where(live, v2 + 0.5 * dt * force / m2, v2)
        x1 = np.where(live, x1 + dt * v1, x1)
        x2 = np.where(live, x2 + dt * v2, x2)
        delta = radsum - np.abs(x2 - x1)
        contact = live & (delta > 0)
        first = contact & ~touched
        q[first], u_prev[first] = 0.0, 0.0
        u = np.where(contact, np.maximum(delta, 0.0) ** 1.5, 0.0)
        q = np.where(contact[:, None], a * q + w * (u - u_prev)[:, None], q)
        u_prev = np.where(contact, u, u_prev)
        g = law.e_inf * u + q.sum(axis=1)
        force = np.where(contact & (g > 0), k * g, 0.0)
        ended = live & touched & ~contact
        touched |= contact
        done |= ended
        v1 = np.where(live, v1 - 0.5 * dt * force / m1, v1)
        v2 = np.where(live, v2 + 0.5 * dt * force / m2, v2)
        if done.all():
            break
    cor = (v2 - v1) / v0 if pair else v2 / v0
    return np.where(done, cor, np.nan)
