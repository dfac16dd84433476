"""Calibration from measured COR(v0): material parameters and their uncertainty.

A calibration (``calibrations.<name>`` in ``config.yaml``, or :func:`calibrate` from Python) fits
free parameters of a material to COR data at several impact speeds with the forward model of a sweep
(``vcor.simulate``, the sweep's default method unless ``solver`` says otherwise):

* data: CSV ``v0,cor[,cor_std]`` (m/s, dimensionless; a units row ``m/s,-,-`` or ``cm/s`` is allowed);
* free parameters: any parameter of the material (``Material.params()``: E_glassy, alpha, beta for
  sls; E0, E1 for fractional; a Prony term's modulus or rate as ``E[i]``, ``beta[i]``; ...), and
  for any material ``modulus_scale`` (all moduli times a factor) and ``log_aT`` (the time scale:
  E(t) -> E(t / a_T), log10 a_T); each with bounds ``[lo, hi]`` that contain its start value;
* weighted least squares (``scipy.optimize.least_squares``, trust-region reflective, central
  differences) on ln(p / p_start) for positive parameters (log_aT as it is), residual
  (COR_model - COR) / cor_std (cor_std omitted: unweighted).

Uncertainty (linearised at the estimate): J the Jacobian of the weighted residuals in the fitted
coordinates, cov = s^2 (J^T J)^-1 with s^2 = RSS / (m - n) when the data carry no cor_std, and
cov = (J^T J)^-1 when they do (the stated standard deviations are taken as known). The 95 % interval is
x +- q sigma_x in the fitted coordinates (Student t with m - n degrees of freedom when s^2 is
estimated, normal otherwise), mapped back (asymmetric for positive parameters); ``stderr`` is the
delta-method standard error of the parameter itself. The band of the fitted curve propagates cov
through the model's sensitivities on a grid of speeds.

Identifiability (flag and note, in the dataset and the log): no parameter with fewer distinct speeds than
free parameters; else not one whose Jacobian direction is rank-deficient or ill-conditioned (singular
value below ``COND_LIMIT`` times the largest), whose estimate ends at a bound, or whose standard error
exceeds a factor of 10 (sigma of ln p > ln 10; of log_aT, a decade); its interval is then reported as infinite.

During the search, a trial point where the material refuses its parameters (e.g. an SLS with
beta < alpha) returns a large residual so that the trust region rejects it; a trial point where the
forward model does not end ``ok`` stops the calibration with the point's status and message.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..io.csvfile import named_by, project_file
from ..materials import REGISTRY
from ..materials import models as _materials
from ..materials.presets import get as _preset
from ..materials.specs import from_spec
from ..solvers import validity as _validity
from ..solvers.common import UNITS
from .cor_data import CorData, read_cor_data

__all__ = ["COND_LIMIT", "Calibration", "CorData", "band", "calibrate", "calibration_dataset", "check_spec",
           "read_cor_data", "run_calibration", "scaled"]

#: scale parameters every material has (besides its own scalar parameters)
SCALE_PARAMS = ("modulus_scale", "log_aT")
#: relative singular value below which a direction of the parameters is not identified
COND_LIMIT = 1e-6
#: a parameter whose 1-sigma uncertainty is more than this factor is reported as not identified
FACTOR_LIMIT = 10.0
#: relative difference step of the fit's Jacobian (scipy's ``diff_step``, in the fitted coordinates)
DIFF_STEP = 1e-4
#: keys of a calibration spec
SPEC_KEYS = {"data", "material", "free", "geometry", "solver"}
#: residual of a trial point the material refuses (large against any COR misfit)
_REFUSED = 10.0


def scaled(material, modulus_scale: float = 1.0, log_aT: float = 0.0):
    """``material`` with every modulus times ``modulus_scale`` and time stretched by a_T = 10^log_aT:
    E(t) -> modulus_scale E(t / a_T) (:meth:`vcor.materials.Material.scaled`).

    Examples
    --------
    >>> from vcor import materials
    >>> from vcor.fitting.calibrate import scaled
    >>> sls = materials.get("sls")
    >>> slow = scaled(sls, modulus_scale=2.0, log_aT=1.0)
    >>> round(float(slow.relaxation_modulus(1e-2) / sls.relaxation_modulus(1e-3)), 12)
    2.0
    """
    return material.scaled(modulus_scale, 10.0 ** float(log_aT))


def _flat_params(material) -> dict:
    """Scalar parameters by name; list parameters (Prony E, beta) element-wise as ``E[0]``, ``beta[1]``."""
    out = {}
    for k, v in material.params().items():
        if isinstance(v, (list, tuple)):
            out.update({f"{k}[{i}]": float(x) for i, x in enumerate(v)})
        else:
            out[k] = float(v)
    return out


def _free_names(material) -> list[str]:
    return [*_flat_params(material), *SCALE_PARAMS]


def _check_free(material, free: dict, m: int, where: str = "free") -> tuple[list, np.ndarray, np.ndarray, np.ndarray]:
    """(names, start values, lower, upper) of the free parameters, checked: known names, bounds
    lo < hi (> 0 for positive parameters), start inside, no more parameters than data points."""
    if not isinstance(free, dict) or not free:
        raise ValueError(f"{where}: a mapping parameter -> [lower, upper] with at least one parameter, got {free!r}")
    allowed = _free_names(material)
    params = _flat_params(material)
    names, start, lo, hi = [], [], [], []
    for name, bounds in free.items():
        if name not in allowed:
            raise ValueError(f"{where}.{name}: not a free parameter of a {material.kind!r} material; "
                             f"allowed: {allowed}")
        if not (isinstance(bounds, (list, tuple)) and len(bounds) == 2
                and all(isinstance(b, (int, float)) and not isinstance(b, bool) and math.isfinite(b) for b in bounds)
                and bounds[0] < bounds[1]):
            raise ValueError(f"{where}.{name}: bounds must be [lower, upper], finite numbers, lower < upper; "
                             f"got {bounds!r}")
        value = {"modulus_scale": 1.0, "log_aT": 0.0}.get(name, params.get(name))
        if name != "log_aT" and bounds[0] <= 0:
            raise ValueError(f"{where}.{name}: bounds of a positive parameter must be > 0 (fitted in log space), "
                             f"got {bounds!r}")
        if not bounds[0] <= value <= bounds[1]:
            raise ValueError(f"{where}.{name}: the start value {value:g} is outside its bounds "
                             f"[{bounds[0]:g}, {bounds[1]:g}]")
        names.append(name)
        start.append(float(value))
        lo.append(float(bounds[0]))
        hi.append(float(bounds[1]))
    if m < len(names):
        raise ValueError(f"{where}: {len(names)} free parameters but only {m} data points: at least as many points "
                         f"as free parameters are needed")
    return names, np.array(start), np.array(lo), np.array(hi)


@dataclass(frozen=True, kw_only=True)
class Calibration:
    """Result of :func:`calibrate` (SI; module docstring for the statistics)."""

    names: list
    estimate: np.ndarray
    stderr: np.ndarray
    lower95: np.ndarray
    upper95: np.ndarray
    correlation: np.ndarray
    identified: np.ndarray
    notes: list
    start: np.ndarray
    bounds: np.ndarray
    material: _materials.Material
    data: CorData
    cor_fit: np.ndarray
    residual: np.ndarray
    chi2: float
    dof: int
    sigma_known: bool
    singular_values: np.ndarray
    cov_x: np.ndarray
    nfev: int
    wall_time: float
    message: str
    geometry: dict = field(default_factory=dict)
    options: dict = field(default_factory=dict)
    base: _materials.Material | None = None
    #: per data point, the validity of the calibrated model's result there (``vcor.solvers.validity``: an ok
    #: result outside the model's stated range, e.g. an indentation beyond 0.1 r) and why
    validity: np.ndarray | None = None
    validity_message: list = field(default_factory=list)

    def units(self) -> list[str]:
        """Per free parameter, the UDUNITS unit of its estimate, stderr, interval, start and bounds."""
        fixed = {"modulus_scale": "1", "log_aT": "1 (log10 of a_T)"}
        kind = self.base.kind if self.base else ""
        return [fixed.get(n, _param_unit(n, kind)) for n in self.names]

    def report(self) -> str:
        """A plain-text table of the estimates (for logs)."""
        lines = [(f"# calibration: {len(self.data.v0)} points, {len(self.names)} free, chi2 = {self.chi2:.4g}, "
                  f"dof = {self.dof}, {'stated' if self.sigma_known else 'estimated'} COR errors, "
                  f"{self.nfev} model evaluations, {self.wall_time:.2f} s; {self.message}"),
                 f"{'parameter':14s} {'unit':>8s} {'estimate':>13s} {'stderr':>11s} {'lower95':>13s} {'upper95':>13s}"
                 f"  identified"]
        for i, (n, unit) in enumerate(zip(self.names, self.units())):
            lines.append(f"{n:14s} {unit.split(' (')[0]:>8s} {self.estimate[i]:13.6g} {self.stderr[i]:11.4g} "
                         f"{self.lower95[i]:13.6g} {self.upper95[i]:13.6g}  "
                         f"{'yes' if self.identified[i] else 'NO: ' + self.notes[i]}")
        flagged = [i for i, v in enumerate(self.validity if self.validity is not None else []) if v]
        if flagged:
            lines.append(f"# {len(flagged)} of {len(self.data.v0)} data points lie outside the model's stated range "
                         f"at the estimate (the calibration fits them as it fits the others):")
            lines += [f"#   v0 = {self.data.v0[i]:g} m/s: {self.validity_message[i]}" for i in flagged]
        return "\n".join(lines) + "\n"


class _Model:
    """The forward model in fitted coordinates x: p = start * exp(x) (positive) or start + x (log_aT)."""

    def __init__(self, base, names, start, geometry, options):
        self.base, self.names, self.start = base, names, start
        self.geometry, self.options = dict(geometry), dict(options)
        self.linear = np.array([n == "log_aT" for n in names])
        self.nfev = 0

    def params(self, x):
        return np.where(self.linear, self.start + x, self.start * np.exp(np.where(self.linear, 0.0, x)))

    def to_x(self, p):
        p = np.asarray(p, float)
        with np.errstate(divide="ignore"):
            return np.where(self.linear, p - self.start, np.log(np.where(self.linear, 1.0, p / self.start)))

    def material(self, x):
        values = dict(zip(self.names, self.params(x)))
        d = self.base.to_dict()
        for k, v in values.items():
            if k in SCALE_PARAMS:
                continue
            if k.endswith("]"):  # a Prony term, e.g. E[1]
                key, i = k[:-1].split("[")
                d[key] = list(d[key])
                d[key][int(i)] = float(v)
            else:
                d[k] = float(v)
        mat = _materials.from_dict(d)
        return scaled(mat, values.get("modulus_scale", 1.0), values.get("log_aT", 0.0))

    def cor(self, x, v0s, mat=None):
        return np.array([r.cor for r in self.results(x, v0s, mat)])

    def results(self, x, v0s, mat=None) -> list:
        """The forward model's results (``vcor.simulate``) at the speeds ``v0s``; ValueError when one is not ok."""
        from ..solvers.simulate import simulate  # the kernels load on use: the workflow reads this module

        mat = self.material(x) if mat is None else mat
        out = []
        for v in v0s:
            r = simulate(mat, float(v), options=self.options, **self.geometry)
            self.nfev += 1
            if r.status != "ok":
                at = ", ".join(f"{k} = {float(p):.6g}" for k, p in zip(self.names, self.params(x)))
                raise ValueError(f"calibration: the forward model at v0 = {v:g} m/s, {at}: {r.status}: {r.message}")
            out.append(r)
        return out


def _covariance(J, r, sigma_known, dof):
    """(cov of x, singular values, right singular vectors, which are below :data:`COND_LIMIT`): the
    Gauss-Newton covariance, directions the data do not constrain left out; scaled by chi2/dof unless
    the COR errors are stated."""
    _, sv, Vt = np.linalg.svd(J, full_matrices=False)
    small = sv < COND_LIMIT * (sv[0] if sv.size and sv[0] > 0 else 1.0)
    inv = np.where(small, 0.0, 1.0 / np.where(small, 1.0, sv) ** 2)
    cov = (Vt.T * inv) @ Vt
    if not sigma_known:
        cov = cov * (float(r @ r) / dof if dof > 0 else math.nan)
    return cov, sv, Vt, small


def _identified(names, fit, box, sx, linear, svd, n_speeds):
    """(identified, notes) per parameter (module docstring: fewer distinct speeds ``n_speeds`` than free
    parameters, a singular direction, a bound, no degrees of freedom, more than a factor FACTOR_LIMIT)."""
    sv, Vt, small = svd
    n = len(names)
    if n_speeds < n:  # a COR per speed constrains at most n_speeds combinations, whatever the null direction
        return np.zeros(n, dtype=bool), [f"the data constrain only a combination of {names}: {n_speeds} distinct "
                                         f"speed(s) for {n} free parameters"] * n
    notes = [""] * n
    identified = np.ones(n, dtype=bool)
    for k in np.flatnonzero(small):
        involved = [names[i] for i in range(n) if abs(Vt[k, i]) > 0.1]
        for i in range(n):
            if abs(Vt[k, i]) > 0.1:
                identified[i] = False
                notes[i] = (f"the data constrain only a combination of {involved} (Jacobian singular value "
                            f"{sv[k]:.2e} of {sv[0]:.2e})")
    x, (xlo, xhi) = fit.x, box
    span = xhi - xlo
    for i in range(n):
        if identified[i] and (fit.active_mask[i] != 0 or min(x[i] - xlo[i], xhi[i] - x[i]) < 1e-6 * span[i]):
            identified[i], notes[i] = False, "the estimate is at its bound: the data push it beyond the allowed range"
        elif identified[i] and not math.isfinite(sx[i]):
            identified[i], notes[i] = False, "no degrees of freedom left to estimate the COR errors (give cor_std)"
        elif identified[i] and sx[i] > (math.log10 if linear[i] else math.log)(FACTOR_LIMIT):  # log_aT: decades
            identified[i], notes[i] = False, f"1-sigma uncertainty larger than a factor {FACTOR_LIMIT:g}"
    return identified, notes


def _material_limits(model, x) -> list[tuple[int, str]]:
    """(parameter index, why) for each fitted parameter whose estimate lies within the fit's difference step
    (``DIFF_STEP``) of an invalid material (SLS alpha > beta, say): the fit refused that side (``_REFUSED``),
    so its Jacobian there says nothing about the data."""
    out = []
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = DIFF_STEP * max(1.0, abs(float(x[i])))
        for sign in (1.0, -1.0):
            try:
                model.material(x + sign * e)
            except ValueError as exc:
                out.append((i, str(exc)))
                break
    return out


def _intervals(model, x, sx, identified, q):
    """(estimate, stderr, lower95, upper95) in the parameters' own units; where not identified, the interval is
    the whole range (-inf, inf), or (0, inf) for a positive parameter (fitted in log), and stderr inf."""
    p = model.params(x)
    lower, upper = model.params(x - q * sx), model.params(x + q * sx)
    stderr = np.where(model.linear, sx, p * sx)
    return (p, np.where(identified, stderr, np.inf), np.where(identified, lower, np.where(model.linear, -np.inf, 0.0)),
            np.where(identified, upper, np.inf))


def _correlation(cov, sx):
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(sx, sx)
    corr[~np.isfinite(corr)] = np.nan
    np.fill_diagonal(corr, 1.0)
    return corr


def _solve(model, data, box):
    """The weighted least-squares fit in x (``scipy.optimize.least_squares``) and its wall time, s."""
    from scipy.optimize import least_squares

    w = 1.0 / data.cor_std if data.cor_std is not None else np.ones_like(data.cor)

    def residual(x):
        try:
            mat = model.material(x)
        except ValueError:
            return np.full(data.cor.size, _REFUSED)
        return (model.cor(x, data.v0, mat) - data.cor) * w

    t_start = time.perf_counter()
    fit = least_squares(residual, np.zeros(len(model.names)), bounds=box, jac="3-point", diff_step=DIFF_STEP,
                        x_scale=1.0, xtol=1e-12, ftol=1e-12, gtol=1e-12, max_nfev=200)
    return fit, time.perf_counter() - t_start


def calibrate(data: CorData, material, free: dict, *, geometry: dict | None = None, options: dict | None = None,
              where: str = "free") -> Calibration:
    """Fit the ``free`` parameters (name -> [lower, upper]) of ``material`` (its values are the start) to
    ``data`` (module docstring). ``geometry``: keywords of ``vcor.simulate``; ``options``: solver options
    (default: ``adaptive``, as everywhere).

    Examples
    --------
    Four measured COR values (here: the SLS preset with its time scale stretched by a_T = 10^0.3,
    rounded to two digits), and the time scale of the preset fitted to them:

    >>> import numpy as np
    >>> from vcor.fitting.calibrate import CorData, calibrate
    >>> data = CorData(v0=np.array([0.5, 1.0, 2.0, 4.0]), cor=np.array([0.53, 0.54, 0.56, 0.56]),
    ...                cor_std=np.full(4, 0.01))
    >>> cal = calibrate(data, "sls", {"log_aT": [-1.0, 1.0]})
    >>> cal.names, f"{cal.estimate[0]:.2f} +- {cal.stderr[0]:.2f}", bool(cal.identified[0])
    (['log_aT'], '0.30 +- 0.01', True)
    """
    from scipy.stats import norm
    from scipy.stats import t as student_t

    base = _preset(material) if isinstance(material, str) else material
    geometry = dict(geometry or {})
    options = dict(options or {})
    names, start, lo, hi = _check_free(base, free, len(data.v0), where)
    model = _Model(base, names, start, geometry, options)
    model.material(np.zeros(len(names)))  # the start must be a valid material (else: an error now)
    box = (model.to_x(lo), model.to_x(hi))
    fit, wall = _solve(model, data, box)
    x, J, r = fit.x, fit.jac, fit.fun
    dof = J.shape[0] - J.shape[1]
    sigma_known = data.cor_std is not None
    cov, sv, Vt, small = _covariance(J, r, sigma_known, dof)
    sx = np.sqrt(np.clip(np.diag(cov), 0.0, None))
    identified, notes = _identified(names, fit, box, sx, model.linear, (sv, Vt, small), np.unique(data.v0).size)
    for i, why in _material_limits(model, x):
        identified[i], notes[i] = False, (f"the estimate is on the material's own limit (a step of the fit's "
                                          f"difference beyond it is not a valid material: {why}): the data push "
                                          f"it beyond what the model allows")
    q = float(norm.ppf(0.975) if sigma_known else (student_t.ppf(0.975, dof) if dof > 0 else math.nan))
    p, stderr, lower, upper = _intervals(model, x, sx, identified, q)
    mat = model.material(x)
    fitted = model.results(x, data.v0)
    cor_fit = np.array([r.cor for r in fitted])
    return Calibration(names=names, estimate=p, stderr=stderr, lower95=lower, upper95=upper,
                       correlation=_correlation(cov, sx), identified=identified, notes=notes, start=start,
                       bounds=np.stack([lo, hi], axis=1), material=mat, data=data, cor_fit=cor_fit,
                       residual=data.cor - cor_fit, chi2=float(r @ r), dof=dof, sigma_known=sigma_known,
                       singular_values=sv, cov_x=cov, nfev=model.nfev, wall_time=wall, message=str(fit.message),
                       geometry=geometry, options=options, base=base,
                       validity=np.array([r.validity for r in fitted], dtype=np.int8),
                       validity_message=[r.validity_message for r in fitted])


def _slope(model, x, e, c, v0s):
    """d COR / d x along ``e`` at x (``c``: the COR there): central, or one-sided where one side leaves the
    materials' own range (an estimate on a constraint such as an SLS's alpha = beta, whose fit had the other
    side refused)."""
    sides = []
    for sign in (1.0, -1.0):
        try:
            sides.append((sign, model.material(x + sign * e)))
        except ValueError:
            continue
    h = float(np.max(np.abs(e)))
    if len(sides) == 2:
        return (model.cor(x + e, v0s, sides[0][1]) - model.cor(x - e, v0s, sides[1][1])) / (2 * h)
    if not sides:
        raise ValueError(f"calibration: no material within {h:g} (fitted coordinate) of the estimate along one "
                         f"parameter is valid")
    sign, mat = sides[0]
    return sign * (model.cor(x + sign * e, v0s, mat) - c) / h


def band(cal: Calibration, v0s) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(COR, lower, upper) of the fitted curve at ``v0s`` (m/s) with the 95 % band from the parameters'
    covariance (linearised; directions not identified are left out, so the band is then too narrow: the
    dataset flags them).

    Examples
    --------
    >>> import numpy as np
    >>> from vcor.fitting.calibrate import CorData, band, calibrate
    >>> data = CorData(v0=np.array([0.5, 1.0, 2.0, 4.0]), cor=np.array([0.53, 0.54, 0.56, 0.56]),
    ...                cor_std=np.full(4, 0.01))
    >>> cor, lower, upper = band(calibrate(data, "sls", {"log_aT": [-1.0, 1.0]}), [1.0, 3.0])
    >>> np.round(cor, 3), np.round(upper - lower, 3)
    (array([0.543, 0.561]), array([0.02 , 0.018]))
    """
    from scipy.stats import norm
    from scipy.stats import t as student_t

    model = _Model(cal.base, cal.names, cal.start, cal.geometry, cal.options)
    x = model.to_x(cal.estimate)
    v0s = np.asarray(v0s, float)
    c = model.cor(x, v0s)
    h = 1e-4
    G = np.empty((v0s.size, x.size))
    for i in range(x.size):
        e = np.zeros_like(x)
        e[i] = h
        G[:, i] = _slope(model, x, e, c, v0s)
    cov = np.nan_to_num(cal.cov_x, nan=0.0)
    sd = np.sqrt(np.clip(np.einsum("ij,jk,ik->i", G, cov, G), 0.0, None))
    q = float(norm.ppf(0.975) if cal.sigma_known else (student_t.ppf(0.975, cal.dof) if cal.dof > 0 else math.nan))
    return c, c - q * sd, c + q * sd


def _start_material(spec, where, catalogue):
    mat = spec["material"]
    if isinstance(mat, dict):
        return from_spec(mat, where=f"{where}.material", base_dir=catalogue.base_dir)
    if not isinstance(mat, str):
        raise ValueError(f"{where}.material: a material name or a spec {{model: ...}}, got {mat!r}")  # noqa: TRY004 (config values)
    catalogue.check(mat, f"{where}.material")
    return catalogue.material(mat)


def check_spec(spec: dict, *, catalogue, where: str = "calibration", pending=()) -> CorData:
    """A calibration spec's keys, the data file (file, line, column), the start material (a name of
    ``catalogue``, a :class:`vcor.materials.Catalogue`, or an inline spec), the free parameters' names, bounds
    and start values, and the number of points (its geometry and solver: the config's schema and
    ``vcor.study.config``). ``pending``: material names whose files do not exist yet (fits,
    calibrations): only their names are checked. Returns the data."""
    if not isinstance(spec, dict):
        raise ValueError(f"{where}: a mapping with keys {sorted(SPEC_KEYS)}, got {spec!r}")  # noqa: TRY004 (config values)
    unknown = set(spec) - SPEC_KEYS
    missing = {"data", "material", "free"} - set(spec)
    if unknown or missing:
        raise ValueError(f"{where}: keys {sorted(SPEC_KEYS)} (data, material, free required); "
                         f"unknown {sorted(unknown)}, missing {sorted(missing)}")
    if not isinstance(spec["data"], str):
        raise ValueError(f"{where}.data: the path of a CSV file (v0,cor[,cor_std]), got {spec['data']!r}")  # noqa: TRY004 (config values)
    path = project_file(f"{where}.data", spec["data"], catalogue.base_dir, "the COR data file")
    with named_by(f"{where}.data"):
        data = read_cor_data(path, "the COR data file")
    if isinstance(spec["material"], str) and spec["material"] in pending:
        catalogue.check(spec["material"], f"{where}.material")
        return data
    material = _start_material(spec, where, catalogue)
    _check_free(material, spec["free"], len(data.v0), f"{where}.free")
    return data


def run_calibration(spec: dict, *, catalogue, where="calibration") -> Calibration:
    """A calibration from a config spec (``data``, ``material``: a spec {model: ...} or a name of
    ``catalogue``, ``free``, optional ``geometry`` and ``solver``); errors name ``<where>.<key>`` or the
    data file's line and column."""
    data = check_spec(spec, where=where, catalogue=catalogue)
    material = _start_material(spec, where, catalogue)
    return calibrate(data, material, spec["free"], geometry=spec.get("geometry"), options=spec.get("solver"),
                     where=f"{where}.free")


def calibration_dataset(cal: Calibration, spec: dict | None = None, n_curve: int = 40):
    """NetCDF-ready record: dimension ``parameter`` (estimate, stderr, 95 % interval, start, bounds,
    identified, note; ``correlation`` parameter x parameter_2), the data with the fitted COR and the
    residuals, the fitted curve with its 95 % band; attribute ``material`` = the calibrated material
    (``vcor.materials.from_file`` reads the file like a fit)."""
    import json

    import xarray as xr

    param_units = cal.units()
    label = {"long_name": "free parameter of the calibration"}
    ds = xr.Dataset(coords={d: (d, cal.names, label) for d in ("parameter", "parameter_2")})
    for name, values, long in (("estimate", cal.estimate, "estimate"), ("stderr", cal.stderr, "standard error"),
                               ("lower95", cal.lower95, "95 % interval, lower end"),
                               ("upper95", cal.upper95, "95 % interval, upper end"),
                               ("start", cal.start, "start value"), ("lower_bound", cal.bounds[:, 0], "lower bound"),
                               ("upper_bound", cal.bounds[:, 1], "upper bound")):
        ds[name] = ("parameter", np.asarray(values, float), {"long_name": long, "units_by_parameter": json.dumps(
            dict(zip(cal.names, param_units)))})
    ds["unit"] = ("parameter", np.array(param_units, dtype=str),
                  {"long_name": "unit (UDUNITS) of the parameter's estimate, stderr, interval, start and bounds"})
    ds["identified"] = ("parameter", cal.identified.astype(np.int8),
                        {"long_name": "1: identified by the data; 0: see note", "units": "1",
                         "flag_values": np.array([0, 1], dtype=np.int8), "flag_meanings": "not_identified identified"})
    ds["note"] = ("parameter", np.array(cal.notes, dtype=str), {"long_name": "why a parameter is not identified"})
    ds["correlation"] = (("parameter", "parameter_2"), cal.correlation, {"units": "1", "long_name": "correlation"})
    ds = ds.assign_coords(point=("point", np.arange(cal.data.v0.size), {"units": "1", "long_name": "data point"}))
    ds["v0"] = ("point", cal.data.v0, {"units": UNITS.get("v0", "m s-1"), "long_name": "impact speed (data)"})
    ds["cor"] = ("point", cal.data.cor, {"units": "1", "long_name": "COR, data"})
    if cal.data.cor_std is not None:
        ds["cor_std"] = ("point", cal.data.cor_std, {"units": "1", "long_name": "COR standard deviation, data"})
    ds["cor_fit"] = ("point", cal.cor_fit, {"units": "1", "long_name": "COR, calibrated model"})
    ds["residual"] = ("point", cal.residual, {"units": "1", "long_name": "data - model"})
    if cal.validity is not None:
        ds["validity"] = ("point", cal.validity, _validity.cf_attrs())
        ds["validity_message"] = ("point", np.array(cal.validity_message, dtype=object),
                                  {"long_name": "why the calibrated model's result at a data point is outside the "
                                                "model's stated range"})
    lo, hi = cal.data.v0.min(), cal.data.v0.max()
    grid = np.geomspace(lo, hi, n_curve) if hi > lo else np.array([lo])
    c, cl, ch = band(cal, grid)
    ds = ds.assign_coords(v0_curve=("v0_curve", grid, {"units": "m s-1", "long_name": "impact speed (curve)"}))
    ds["cor_curve"] = ("v0_curve", c, {"units": "1", "long_name": "COR, calibrated model"})
    ds["cor_lower95"] = ("v0_curve", cl, {"units": "1", "long_name": "95 % band of the model (parameters)"})
    ds["cor_upper95"] = ("v0_curve", ch, {"units": "1", "long_name": "95 % band of the model (parameters)"})
    ds.attrs.update({
        "material": json.dumps(cal.material.to_dict(), sort_keys=True),
        "calibration_spec": json.dumps(spec or {}, sort_keys=True, default=str), "chi2": cal.chi2, "dof": cal.dof,
        "cor_errors": "stated (cor_std)" if cal.sigma_known else "estimated from the residuals",
        "model_evaluations": cal.nfev, "optimizer_message": cal.message,
        "singular_values": json.dumps(cal.singular_values.tolist()),
        "not_identified": json.dumps({n: note for n, note, ok in zip(cal.names, cal.notes, cal.identified) if not ok}),
        "data": str((spec or {}).get("data", cal.data.path)),  # as the spec names it, not as it was opened
    })
    return ds


def _param_unit(name: str, kind: str = "") -> str:
    """The UDUNITS unit of a calibrated parameter (``E[2]``: an element of ``E``), from the material
    registry; "1" for a name the model does not have."""
    base, family = name.split("[")[0], REGISTRY.get(kind)
    return family.unit(base) if family is not None and base in family.names else "1"
