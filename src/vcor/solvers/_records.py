"""Records the kernels take: argument groups as named tuples, the march state's layout and the status
codes.

Inside numba a named tuple is a struct (a kernel reads ``body.m`` at no cost). At numba's Python
boundary, though, typing a named tuple's fields goes through Python and costs ~1 us per record and
call (plain tuples are typed in C), so the kernels that Python calls take their records as *plain*
tuples (``tuple(record)``) and name them again in their first lines (``body = Body(*body)``).

Units (SI): t, h in s; s in m; g = s' in m/s; u = s^{3/2} in m^1.5; F in N; J = int F dt in N s;
kernel weights in N m^-1.5 (per unit step) or N m^-1.5 s, N m^-1.5 s^2 (step integrals, moments);
alpha in m N^-1 s^-1, alpha' in m N^-1 s^-2; m in kg; v0 in m/s.
"""

from __future__ import annotations

from collections import namedtuple

import numpy as np

__all__ = [
    "DECAYED", "FROZEN", "LAST", "LEVEL", "LOADED", "REJECTED", "SEPARATION", "STATUS", "STATUS_DIVERGED",
    "STATUS_END", "STATUS_FULL", "STATUS_RUNNING", "STATUS_SEPARATED", "WAIVED", "AdaptiveControl", "Body",
    "ExponentialModes", "FixedNodes", "Grids", "Internal", "LevelTables", "Modes", "Nodes", "Plate", "PlateArrays",
    "Stop", "Volterra", "fixed_state",
]

# -- the march state: an int64 array, updated in place (so that a march can be resumed) ---------------
#: state[LOADED]: 1 once F > 0 and s > 0 at some node
LOADED = 0
#: state[SEPARATION]: the separation node, -1 before it
SEPARATION = 1
#: state[LAST]: the last node computed
LAST = 2
#: state[STATUS]: one of the STATUS_* codes below
STATUS = 3
#: adaptive only: trial steps rejected, steps accepted at the floor level with the error test waived,
#: the current level, 1 once the level is frozen (after a separation)
REJECTED = 4
WAIVED = 5
LEVEL = 6
FROZEN = 7

STATUS_RUNNING = 0
STATUS_SEPARATED = 1
STATUS_DIVERGED = 2
#: reached the end of the arrays (or of the time horizon) without separating
STATUS_END = 3
#: adaptive march: the arrays are full; grow them and call again (resumable)
STATUS_FULL = 4

#: the step control's motion scale is not below this times v0: a fractional plate that holds the sphere for
#: thousands of seconds at sub-nanometre indentations has a speed scale s / t whose tolerance is below the
#: rounding of the march's velocities, where the local error estimate is noise and the steps shrink without
#: end (``tests/solvers/test_adaptive.py::test_a_creeping_capture_keeps_its_cor``); speeds below
#: ``extrapolation.COR_FLOOR`` v0 do not move the COR's stated digits
MOTION_FLOOR = 1e-9
#: a mode whose decay factor over one step (or whose plate factor exp(-beta t)) is below this has
#: decayed (e^-41.4; far below the rounding of the history it would add to)
DECAYED = 1e-18


def fixed_state() -> np.ndarray:
    """A fresh state of a fixed-step march: [loaded, separation, last, status]."""
    return np.array([0, -1, 0, STATUS_RUNNING], dtype=np.int64)


#: the impact as the implicit step sees it: Dirac weight of the kernel (N s m^-1.5; Kelvin-Voigt),
#: sphere mass (kg), impact speed (m/s)
Body = namedtuple("Body", "eta m v0")
#: when a march stops: the separation rule (0: the force returns to zero, 1: the overlap does), how many
#: steps it marches past the separation node (the separation's cubic needs two), and the kernel's value at
#: lag 0, k(0) (N m^-1.5), where it is finite and the kernel has no Dirac term (else 0): the force's root
#: is then located on k(0) u(s) + (F - k(0) u), the second part smooth (``_separation.separation_point``)
Stop = namedtuple("Stop", "rule n_extra glassy", defaults=(0.0,))
#: plate mobility on a fixed grid: alpha(t_n), alpha'(t_n) per node
PlateArrays = namedtuple("PlateArrays", "alpha alpha_rate")
#: fixed-step node arrays s, s', F, J, u = s^{3/2} and the increments du_j = u_{j+1} - u_j
FixedNodes = namedtuple("FixedNodes", "s g F J u du")
#: the Volterra term of the direct march: on (bool), c2 (m^-1.5), the double cell integrals of k per
#: index c = 2n - 1 - i - j (N m^-1.5 s^2) and the running auto-convolution of du per index i + j
Volterra = namedtuple("Volterra", "on c2 cells autoconvolution")
#: a Prony kernel's internal variables (march_prony): Q_k (N), k(inf) (N m^-1.5), G_k (N m^-1.5),
#: exp(-beta_k dt), the step weights G_k (1 - exp(-beta_k dt)) / (beta_k dt) (N m^-1.5)
Internal = namedtuple("Internal", "Q G_inf G decay weight")
#: the soe march's exponential-sum history: per mode the folded weights at lag n_local + 1 (N m^-1.5),
#: exp(-beta_k dt), the recursive sums S_k (m^1.5) and powers P_k
ExponentialModes = namedtuple("ExponentialModes", "weight slope_weight decay S P")

#: adaptive node arrays: t (s), s, g, F, J, u
Nodes = namedtuple("Nodes", "t s g F J u")
#: per level l (step h_l = h_base 2^l, one row per level): h_l (s), 1 / h_l (1/s), the newest step's
#: exact weights int_0^h k (N m^-1.5 s) and int_0^h k(x) (h/2 - x) dx (N m^-1.5 s^2), per mode k the
#: step weights kappa E_k int_0^h e^{-b x} dx and kappa E_k int_0^h e^{-b x} (h/2 - x) dx, the decay
#: e^{-b_k h}, the number of modes still alive on the level (the rest decay below DECAYED), the
#: newest step's exact weight int_0^h k(x) ((x - h/2)^2 - h^2/12) dx (N m^-1.5 s^3) of the curvature of u',
#: and for a kernel with a t^-1/2 singularity (the march's cubic specialisation, else an empty array) the
#: newest step's weight int_0^h k(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z (N m^-1.5 s^4), of its cubic term
LevelTables = namedtuple("LevelTables", "step inv_step newest_integral newest_moment mode_integral mode_moment "
                         "mode_decay live_modes newest_curvature newest_cubic")
#: the plate's mobility in the adaptive march: kind 0 (rigid target, or a constant mobility: const),
#: 1 (E_b on exponential modes), 2 (E_b = factor (e_inf + coef t^-1/2), the fractional law, in closed
#: form; coef in Pa s^0.5), 3 (E_b = factor (e_inf + coef erfcx(rate sqrt(t))), the CERF law, in closed
#: form; coef in Pa, rate in s^-0.5); alpha = scale / sqrt(E_b) (scale in m N^-1 s^-1 Pa^0.5),
#: kind 1: E_b = factor (e_inf + sum moduli_k X_k) (Pa) with X_k = e^{-b_k t}, rate_moduli_k = b_k
#: moduli_k (Pa/s) and per level the decays e^{-b_k h} (``decay``, rows as the level tables'; the
#: kernel's mode_decay when the plate is of the contact's material)
Plate = namedtuple("Plate", "kind scale factor e_inf coef rate const moduli rate_moduli decay")
#: the adaptive march's step control: step_tol (relative), 1 / contact-time estimate (1/s), the lowest
#: and highest level, the time horizon (s), a separation is located on a step <= sep_fraction t, and
#: the ghost continuation's length (fraction of t0)
AdaptiveControl = namedtuple("AdaptiveControl", "step_tol inv_tc level_floor level_top horizon sep_fraction ghost")
#: the adaptive march's mode variables: the history P_k (N) and the plate's X_k = e^{-b_k t}
Modes = namedtuple("Modes", "history plate")
#: the one-call path's Richardson grids (``_adaptive_kernels.adaptive_grids``): how many (the accepted grid
#: and its replays), the extra table levels below the accepted grid's (``splits``: grid k uses rows from
#: splits - k), and the largest step (s) of an accepted grid on which one grid fewer is marched (0: never)
Grids = namedtuple("Grids", "n_grids splits smooth_step")
