"""The ``adaptive`` method's tables: what the march needs of the kernel and of the plate per step level.

The adaptive march (``_adaptive_kernels.march_adaptive``) takes steps h_l = h_base 2^l only, so everything it
needs of the kernel k(t) = kappa E(t) on a step depends on the level alone and is computed here once per
level (:func:`level_tables`): the newest step's exact product-integration weights (which hold the t^-1/2
singularity of the fractional and CERF laws), and the step weights and decays of the exponential modes that
carry the older history. The plate's mobility is the record :func:`plate_record` (constant, on exponential
modes with their own per-level decays, :func:`plate_tables`, or a closed form). They depend on the material,
the geometry and the step range, not on the speed: the tables are cached and shared by a sweep's points
(``vcor.solvers.adaptive.impact_tables`` keys them). The march itself, its error control and the Richardson
grids are :mod:`vcor.solvers.adaptive`'s.

Units (SI) as in ``_records``: h in s, kernel weights in N m^-1.5 s^k, moduli in Pa.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..materials.base import second_moment_rule
from ..materials.expsums import soe
from ..materials.fractional import FractionalPower
from ._records import DECAYED, LevelTables, Plate

__all__ = ["PlateTables", "Tables", "level_tables", "plate_record", "plate_tables", "singular_kernel"]

#: LevelTables.newest_cubic of a kernel without the cubic specialisation
_NO_CUBIC = np.zeros(0)


def singular_kernel(material) -> bool:
    """Whether ``material``'s kernel has a t^-1/2 singularity at t = 0 (a fractional or CERF law with E1 > 0:
    with E1 = 0 it is elastic), the kernels that march_adaptive's cubic specialisation is for."""
    return not material.is_elastic and (material.sqrt_law() is not None or material.erfcx_law() is not None)


@dataclass(kw_only=True, frozen=True)
class Tables:
    """Level tables of one (material, step range, horizon): ``levels`` (the kernel record,
    :class:`~._records.LevelTables`), the plate modulus's constant ``e_inf`` (Pa), its modes'
    ``moduli`` (Pa) and ``rate_moduli`` (moduli times rates, Pa/s), the exponential sum's number of
    terms and its checked relative error, the end of its window ``t_max`` (s) and its tolerance."""

    levels: LevelTables
    e_inf: float
    moduli: np.ndarray
    rate_moduli: np.ndarray
    n_terms: int
    soe_error: float
    t_max: float
    tol: float
    #: march_adaptive's ``singular``: True where ``levels.newest_cubic`` holds the cubic specialisation's
    #: weights, None where the kernel has no t^-1/2 singularity or the tables were made without them
    singular: bool | None = None

    @functools.cached_property
    def plain_levels(self) -> tuple:
        """``levels`` as the plain tuple the kernels take (``_records``)."""
        return tuple(self.levels)


@functools.lru_cache(maxsize=64)
def level_tables(material, kappa: float, h_base: float, n_levels: int, t_max: float, tol: float,
                 cubic: bool = False) -> Tables:
    """(Cached: a sweep's points share them.) Per level l (step h_l = h_base 2^l): the newest step's
    exact weights int_0^h k, int_0^h k(x) (h/2 - x) dx and int_0^h k(x) ((x - h/2)^2 - h^2/12) dx
    (N m^-1.5 s, N m^-1.5 s^2, N m^-1.5 s^3), and per
    exponential mode k of the kernel's sum on [h_base, t_max] (column 0: the constant E(inf) plus the
    slow modes, rate 0) the step weights kappa E_k int_0^h e^{-b x} dx, kappa E_k int_0^h e^{-b x}
    (h/2 - x) dx and the decay e^{-b h}, and the number of modes alive on the level (every later mode
    decays below ``DECAYED`` within one step). ``kappa``: k(t) = kappa E(t), m^0.5.
    ``cubic`` (True, for a kernel with a t^-1/2 singularity: :func:`singular_kernel`): the table of
    march_adaptive's cubic specialisation, ``levels.newest_cubic``: per level the newest step's weight
    int_0^h k(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z (N m^-1.5 s^4), and ``Tables.singular`` True
    (else an empty array and None)."""
    mat = material
    rep = soe(mat, h_base, t_max, tol)
    pr = rep.material
    e_inf, e, b = pr.prony_terms()
    hl = h_base * 2.0 ** np.arange(n_levels)
    nk = e.size + 1
    # per mode, all levels at once (the closed forms broadcast over a column of step sizes)
    ti = pr.term_step_integrals(hl[:, None], 1)[0]
    tm = pr.term_step_moments(hl[:, None], 1)[0]
    GA, GB, R = np.zeros((n_levels, nk)), np.zeros((n_levels, nk)), np.ones((n_levels, nk))
    GA[:, 0] = kappa * e_inf * hl
    GA[:, 1:] = kappa * ti
    GB[:, 1:] = -kappa * tm
    R[:, 1:] = np.exp(-np.multiply.outer(hl, b))
    alive = R >= DECAYED
    live = nk - np.argmax(alive[:, ::-1], axis=1)
    # the newest step: the material's own kernel (for Prony kinds the same terms as the sum; when the sum
    # is the material itself, its first step is the sums of the columns just computed)
    if pr is mat:
        i0, m0 = e_inf * hl + ti.sum(axis=-1), tm.sum(axis=-1)
    else:
        i0, m0 = mat.first_step(hl)
    q0 = mat.first_step_second_moment(hl)
    extra, singular = _NO_CUBIC, None
    if cubic and singular_kernel(mat):
        extra, singular = kappa * _newest_cubic(mat, hl), True
    levels = LevelTables(hl, 1.0 / hl, kappa * i0, -kappa * m0, GA, GB, R, live, kappa * q0, extra)
    return Tables(levels=levels, e_inf=float(e_inf), moduli=np.concatenate(([0.0], e)),
                  rate_moduli=np.concatenate(([0.0], b * e)), n_terms=rep.n_terms, soe_error=rep.checked_error,
                  t_max=t_max, tol=tol, singular=singular)


def _newest_cubic(mat, hl):
    """int_0^h E(x) P3(h/2 - x) dx, P3(z) = z^3 - 0.15 h^2 z (Pa s^4): closed form for the fractional law,
    else Gauss-Legendre in y = sqrt(x / h) (:func:`vcor.materials.base.second_moment_rule`)."""
    hl = np.asarray(hl, dtype=float)
    if isinstance(mat, FractionalPower):
        return mat.E1 / (70.0 * math.sqrt(math.pi)) * hl**3 * np.sqrt(hl)
    y, w = second_moment_rule()
    z = 0.5 - y * y
    poly = 2.0 * y * (z**3 - 0.15 * z) * w
    e = mat.relaxation_modulus(np.multiply.outer(hl, y * y))
    return hl**4 * (e @ poly)


@dataclass(kw_only=True, frozen=True)
class PlateTables:
    """A plate material's modulus as exponential modes for the march: the constant ``e_inf`` (Pa), per mode
    (column 0: the constant, rate 0) the ``moduli`` (Pa), ``rate_moduli`` (moduli times rates, Pa/s) and
    per level the ``decay`` e^{-b h_l}, and the exponential sum's checked relative error."""

    e_inf: float
    moduli: np.ndarray
    rate_moduli: np.ndarray
    decay: np.ndarray
    soe_error: float


@functools.lru_cache(maxsize=64)
def plate_tables(material, h_base: float, n_levels: int, t_max: float, tol: float) -> PlateTables:
    """(Cached.) :class:`PlateTables` of a plate material whose modulus is not the contact kernel's
    (vcor.contact.bodies: a deformable sphere on a viscoelastic plate), on the levels h_base 2^l
    (l < n_levels) of the kernel's tables and its exponential sum's window [h_base, t_max] (s)."""
    rep = soe(material, h_base, t_max, tol)
    e_inf, e, b = rep.material.prony_terms()
    hl = h_base * 2.0 ** np.arange(n_levels)
    decay = np.ones((n_levels, e.size + 1))
    decay[:, 1:] = np.exp(-np.multiply.outer(hl, b))
    return PlateTables(e_inf=float(e_inf), moduli=np.concatenate(([0.0], e)),
                       rate_moduli=np.concatenate(([0.0], b * e)), decay=decay, soe_error=rep.checked_error)


def plate_record(impact, tables: Tables, kind: int) -> tuple[Plate, float]:
    """The march's :class:`~._records.Plate` for ``kind`` (:func:`vcor.solvers.adaptive.plate_kind`) and the kernel's
    ``tables``, and the relative error of the plate modulus's exponential sum (0: exact or closed form)."""
    g = impact.geometry
    same = (tables.moduli, tables.rate_moduli, tables.levels.mode_decay)
    if kind == 0:
        const = 0.0 if g.rigid else float(impact.alpha(0.0))
        return Plate(0, 0.0, 0.0, 0.0, 0.0, 0.0, const, *same), 0.0
    own = g.plate_material is not None
    plate = g.plate_material if own else impact.material
    factor = 1.0 / (1.0 - (g.nu_plate if own else g.nu) ** 2)
    if kind == 2:
        e0, c = plate.sqrt_law()
        return Plate(2, impact.mobility_scale, factor, float(e0), float(c), 0.0, 0.0, *same), 0.0
    if kind == 3:
        e0, e1, b1 = plate.erfcx_law()
        return Plate(3, impact.mobility_scale, factor, e0, e1, b1, 0.0, *same), 0.0
    if not own:
        return Plate(1, impact.mobility_scale, factor, tables.e_inf, 0.0, 0.0, 0.0, *same), tables.soe_error
    lv = tables.levels
    pt = plate_tables(plate, float(lv.step[0]), int(lv.step.size), tables.t_max, tables.tol)
    return (Plate(1, impact.mobility_scale, factor, pt.e_inf, 0.0, 0.0, 0.0, pt.moduli, pt.rate_moduli, pt.decay),
            pt.soe_error)
