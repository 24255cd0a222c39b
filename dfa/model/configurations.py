"""Configurations of one device: the dynamics felt along a wall's normal at a pose (issue 46).

A multi-joint device feels a different mass, friction and encoder resolution along a wall's normal at each pose
and for each direction of the wall. A device file may list them as ``[[devices.configurations]]`` tables; each
is a :class:`Configuration`:

- **values**: a ``name`` and any of ``mass``, ``damping``, ``coulomb``, ``resolution`` that differ from the
  device's own (SI units, the rules of :data:`~dfa.model.device.DEVICE_FIELDS`);
- **an inertia matrix** ``inertia`` (3 × 3, kg, Cartesian at the pose, symmetric positive definite), optionally
  per-axis ``damping``, ``coulomb`` and ``resolution`` (three numbers each, along x, y, z) and a wall normal
  ``normal = [nx, ny, nz]``. Along the unit normal n the device is a one-axis device with

  - the effective mass m_n = 1/(nᵀ M⁻¹ n) (the mass that resists a force along n, exact);
  - the damping b_n = nᵀ B n = Σ n_i² b_i, with B = diag(b_x, b_y, b_z) (the viscous force along n of a motion
    along n, exact for a diagonal B);
  - the Coulomb friction c_n = Σ n_i² c_i, the *smaller* of the two usual projections (a motion along n meets
    Σ|n_i| c_i along n, and Σ n_i² c_i <= Σ|n_i| c_i as |n_i| <= 1): friction helps the criterion (eq. 11 grows
    with c/Δ), so the worst case takes the smaller;
  - the resolution Δ_n = Σ|n_i| Δ_i, the *larger* projection (the worst sum of the per-axis quantization steps
    along n; it is >= sqrt(Σ n_i² Δ_i²)): a coarser resolution hurts the criterion, so the worst case takes
    the larger.

  On an axis (n = e_i) every projection is that axis's value, and m_n = 1/(M⁻¹)_ii. Without ``normal`` the
  analyses search the worst direction (:mod:`dfa.analysis.configurations`); ``pose = [x, y, z]`` (m) places the
  configuration on a pose grid (its figure).

:meth:`Configuration.device_at` gives the one-axis :class:`~dfa.model.device.Device` of a configuration (along a
normal); :func:`effective_mass`, :func:`project` and :func:`fibonacci_normals` are the pieces.

Examples
--------
>>> from dfa.model.device import Device
>>> base = Device(0.25, 0.01, 0.883, 30e-6, 1 / 3000, name="Delta")
>>> far = Configuration("far", mass=0.5, coulomb=0.6)
>>> dev = far.device_at(base)
>>> dev.name, dev.mass, dev.damping, dev.coulomb
('Delta [far]', 0.5, 0.01, 0.6)
>>> pose = Configuration("p1", inertia=((0.4, 0.0, 0.0), (0.0, 0.2, 0.0), (0.0, 0.0, 0.1)), normal=(0.0, 0.0, 1.0))
>>> round(pose.device_at(base).mass, 12)
0.1
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..checks import format_value
from ..errors import DFATypeError, DFAValueError
from .device import DEVICE_FIELDS, Device

__all__ = [
    "Configuration",
    "CONFIGURATION_KEYS",
    "PER_AXIS",
    "MAX_CONFIGURATIONS",
    "effective_mass",
    "project",
    "fibonacci_normals",
    "configurations_from_toml",
]

#: The device fields a configuration may give (the rest are the device's: the period, the force limit, the travel).
_VALUE_KEYS = ("mass", "damping", "coulomb", "resolution")
#: The fields that may be per axis (three numbers) beside an inertia matrix.
PER_AXIS = ("damping", "coulomb", "resolution")
#: Every key of a ``[[devices.configurations]]`` table.
CONFIGURATION_KEYS = ("name", *_VALUE_KEYS, "inertia", "normal", "pose")
#: Most configurations a device file may list (a pose grid of 30 × 30 is 900).
MAX_CONFIGURATIONS = 1000
_FIELDS = {f.name: f for f in DEVICE_FIELDS}
_UNIT = 4.0 * float(np.finfo(float).eps)  # a length this close to 1 is a unit vector's (unit_normal)
_SYMMETRY = 1e-9  # relative asymmetry of an inertia matrix refused (above rounding of printed values)

Vector = tuple[float, float, float]
Matrix = tuple[Vector, Vector, Vector]


def _vector(name: str, value: object, fix: str) -> Vector:
    """Three finite numbers as a tuple of floats, or the package's error naming ``name``."""
    arr = _numbers(name, value, fix)
    if arr.shape != (3,):
        raise DFAValueError(f"{name} = {format_value(value)} is invalid: it must be three numbers (x, y, z); {fix}")
    return (float(arr[0]), float(arr[1]), float(arr[2]))


def _numbers(name: str, value: object, fix: str) -> np.ndarray:
    """``value`` as a float array of finite numbers (booleans and text refused)."""
    try:
        arr = np.asarray(value, dtype=float)
        bad_type = np.asarray(value).dtype.kind not in "iuf"
    except (TypeError, ValueError):
        arr, bad_type = np.zeros(0), True
    if bad_type:
        raise DFATypeError(f"{name} = {format_value(value)} is invalid: it must hold numbers only; {fix}")
    if not np.all(np.isfinite(arr)):
        raise DFAValueError(f"{name} = {format_value(value)} is invalid: every number must be finite; {fix}")
    return arr


def check_inertia(value: object, name: str = "inertia") -> Matrix:
    """An inertia matrix: 3 × 3, finite, symmetric and positive definite (a Cholesky factor exists), in kg.

    Parameters
    ----------
    value : array-like
        The matrix M (kg, Cartesian at the pose; rotary kg·m²).
    name : str, optional
        How messages call it.

    Returns
    -------
    tuple of tuples
        M as three rows of floats.

    Raises
    ------
    DFAValueError, DFATypeError
        Not 3 × 3 numbers, not symmetric (relative 1e-9), or not positive definite.
    """
    fix = "give the Cartesian inertia matrix at the pose in kg, e.g. inertia = [[0.4, 0, 0], [0, 0.3, 0], [0, 0, 0.2]]"
    m = _numbers(name, value, fix)
    if m.shape != (3, 3):
        raise DFAValueError(f"{name} = {format_value(value)} is invalid: it must be a 3 × 3 matrix (three rows of "
                            f"three numbers); {fix}")  # fmt: skip
    scale = float(np.max(np.abs(m)))
    if float(np.max(np.abs(m - m.T))) > _SYMMETRY * scale:
        raise DFAValueError(f"{name} = {m.tolist()} is invalid: an inertia matrix must be symmetric (M = Mᵀ); {fix}")
    try:
        np.linalg.cholesky(m)
    except np.linalg.LinAlgError:
        raise DFAValueError(
            f"{name} = {m.tolist()} is invalid: an inertia matrix must be positive definite (its Cholesky factor "
            f"does not exist; eigenvalues {', '.join(f'{e:.3g}' for e in np.linalg.eigvalsh(m))}); {fix}"
        ) from None
    sym = (m + m.T) / 2.0
    return tuple(tuple(float(x) for x in row) for row in sym)  # type: ignore[return-value]


def unit_normal(value: object, name: str = "normal") -> Vector:
    """A wall normal as a unit vector (three finite numbers, not all zero; its length is divided out, unless it is
    1 to within 4 ulps: a normal written back from a unit vector reads back as the same doubles)."""
    fix = "give the wall's normal as three numbers, e.g. normal = [0, 0, 1]"
    v = np.array(_vector(name, value, fix))
    norm = float(np.linalg.norm(v))
    if not norm > 0.0 or not math.isfinite(norm):
        raise DFAValueError(f"{name} = {format_value(value)} is invalid: a normal must have a length > 0; {fix}")
    u = v if abs(norm - 1.0) <= _UNIT else v / norm  # a unit vector kept: normalising twice changes the last bits
    return (float(u[0]), float(u[1]), float(u[2]))


def effective_mass(inertia: Sequence[Sequence[float]] | np.ndarray, normal: Sequence[float] | np.ndarray) -> float:
    """The mass felt along the unit normal n: m_n = 1/(nᵀ M⁻¹ n), in kg (rotary kg·m²).

    Parameters
    ----------
    inertia : array-like
        M, 3 × 3, symmetric positive definite (kg).
    normal : array-like
        n, three numbers (normalised here).

    Returns
    -------
    float
        m_n; it lies between the smallest and largest eigenvalue of M.

    Examples
    --------
    >>> round(effective_mass([[2.0, 0, 0], [0, 1.0, 0], [0, 0, 4.0]], [1, 1, 0]), 12)  # 1/(0.5·½ + 1·½)
    1.333333333333
    """
    m = np.array(check_inertia(inertia))
    n = np.array(unit_normal(normal))
    c = np.linalg.cholesky(m)
    y = np.linalg.solve(c, n)  # nᵀ M⁻¹ n = |L⁻¹ n|²
    return float(1.0 / float(y @ y))


def project(values: Sequence[float], normal: Sequence[float] | np.ndarray, how: str) -> float:
    """A per-axis value along the unit normal: ``"quadratic"`` Σ n_i² v_i or ``"absolute"`` Σ |n_i| v_i.

    The module docstring says which each field takes (damping and friction ``quadratic``, resolution
    ``absolute``: the conservative projections for the criterion).

    Examples
    --------
    >>> s = 0.5 ** 0.5
    >>> round(project([1.0, 3.0, 5.0], [s, s, 0.0], "quadratic"), 12), round(project([1.0, 3.0, 5.0], [s, s, 0.0], "absolute"), 12)
    (2.0, 2.828427124746)
    """
    n = np.array(unit_normal(normal))
    v = np.asarray(values, dtype=float)
    weights = n * n if how == "quadratic" else np.abs(n)
    return float(weights @ v)


#: The projection each per-axis field takes (module docstring).
PROJECTIONS = {"damping": "quadratic", "coulomb": "quadratic", "resolution": "absolute"}


def fibonacci_normals(count: int) -> np.ndarray:
    """``count`` unit normals spread evenly over the upper hemisphere (z >= 0; n and −n are one wall direction).

    Parameters
    ----------
    count : int
        Number of normals, >= 1.

    Returns
    -------
    ndarray, shape (count, 3)
        Unit vectors on a Fibonacci spiral (the same doubles on every machine).

    Examples
    --------
    >>> n = fibonacci_normals(50)
    >>> n.shape, bool(np.allclose(np.linalg.norm(n, axis=1), 1.0)), bool((n[:, 2] >= 0).all())
    ((50, 3), True, True)
    """
    i = np.arange(count, dtype=float) + 0.5
    z = 1.0 - i / count  # uniform in z over (0, 1]: uniform area on the hemisphere
    r = np.sqrt(np.maximum(0.0, 1.0 - z * z))
    phi = i * math.pi * (3.0 - math.sqrt(5.0))
    return np.stack([r * np.cos(phi), r * np.sin(phi), z], axis=1)


@dataclass(frozen=True)
class Configuration:
    """One configuration of a device: values that differ from its own, or an inertia matrix (module docstring).

    Parameters
    ----------
    name : str
        Its name (1 to 100 printable characters), unique in its device.
    mass : float, optional
        The moving mass m in kg (rotary kg·m²), > 0; not with ``inertia``.
    damping, coulomb, resolution : float or three floats, optional
        The viscous friction b (N·s/m), Coulomb friction c (N) and encoder resolution Δ (m) felt here; three
        numbers (per axis x, y, z) only with ``inertia``. None: the device's own.
    inertia : 3 × 3 floats, optional
        The Cartesian inertia matrix M at the pose, kg, symmetric positive definite.
    normal : three floats, optional
        The wall's normal (made a unit vector); only with ``inertia``. None with ``inertia``: the analyses search
        the worst direction.
    pose : three floats, optional
        Where the pose lies (m), for the pose grid's figure; only with ``inertia``.
    """

    name: str
    mass: float | None = None
    damping: float | Vector | None = None
    coulomb: float | Vector | None = None
    resolution: float | Vector | None = None
    inertia: Matrix | None = None
    normal: Vector | None = None
    pose: Vector | None = None

    def __post_init__(self) -> None:
        if (
            not isinstance(self.name, str)
            or not self.name.strip()
            or len(self.name) > 100
            or not self.name.isprintable()
        ):
            raise DFAValueError(
                f"name = {format_value(self.name)} is invalid: a configuration's name must be printable text of 1 to "
                "100 characters; give it a name such as 'far left'"
            )
        object.__setattr__(self, "name", self.name.strip())
        if self.inertia is not None:
            object.__setattr__(self, "inertia", check_inertia(self.inertia))
        elif any(v is not None for v in (self.normal, self.pose)):
            key = "normal" if self.normal is not None else "pose"
            raise DFAValueError(
                f"{key} = {format_value(getattr(self, key))} is invalid without inertia: a configuration's {key} "
                "belongs to an inertia matrix; give inertia = [[...], [...], [...]] or drop it"
            )
        if self.mass is not None and self.inertia is not None:
            raise DFAValueError(
                f"mass = {format_value(self.mass)} is invalid beside inertia: the mass along the normal is "
                "1/(nᵀ M⁻¹ n); give either mass or inertia"
            )
        for key in _VALUE_KEYS:
            object.__setattr__(self, key, self._checked(key, getattr(self, key)))
        if self.normal is not None:
            object.__setattr__(self, "normal", unit_normal(self.normal))
        if self.pose is not None:
            object.__setattr__(self, "pose", _vector("pose", self.pose, "give the pose as x, y, z in m"))

    def _checked(self, key: str, value: object) -> float | Vector | None:
        """One value by its device field's rule: a number, or three (per axis) beside an inertia matrix."""
        if value is None:
            return None
        f = _FIELDS[key]
        if isinstance(value, (list, tuple, np.ndarray)):
            if self.inertia is None or key not in PER_AXIS:
                raise DFAValueError(
                    f"{key} = {format_value(value)} is invalid: three numbers (per axis) need inertia; give one "
                    f"number in {f.units}, or an inertia matrix"
                )
            v = _vector(key, value, f"give three numbers (x, y, z) in {f.units}")
            return tuple(f.check(x, key, f"give each axis's {f.what} in {f.units}") for x in v)  # type: ignore[return-value]
        return f.check(value, key)

    @property
    def directional(self) -> bool:
        """True for an inertia matrix without a normal: the analyses search the worst direction."""
        return self.inertia is not None and self.normal is None

    def along(self, base: Device, normal: Sequence[float] | np.ndarray | None = None) -> dict[str, float]:
        """The one-axis values (mass, damping, coulomb, resolution) along ``normal`` (default :attr:`normal`).

        Parameters
        ----------
        base : Device
            The device whose own values fill the fields the configuration does not give (its bare values: a
            hand is added by :meth:`device_at`).
        normal : array-like, optional
            The wall's normal; needed for a directional configuration, refused for one without inertia.

        Returns
        -------
        dict of str to float
            ``mass``, ``damping``, ``coulomb``, ``resolution`` in SI units (module docstring's projections).
        """
        own = base.bare
        values = {k: float(getattr(own, k)) for k in _VALUE_KEYS}
        if self.inertia is None:
            if normal is not None:
                raise DFAValueError(f"normal = {format_value(normal)} is invalid for configuration {self.name!r}: "
                                    "it has no inertia matrix; drop the normal")  # fmt: skip
            return values | {k: float(v) for k in _VALUE_KEYS if (v := getattr(self, k)) is not None}
        n = self.normal if normal is None else unit_normal(normal)
        if n is None:
            raise DFAValueError(
                f"normal = None is invalid for configuration {self.name!r}: its inertia matrix needs a wall normal; "
                "give normal = [nx, ny, nz] in the device file, or let dfa stiffness / dfa check search the worst "
                "direction"
            )
        values["mass"] = effective_mass(self.inertia, n)
        for key in PER_AXIS:
            v = getattr(self, key)
            if isinstance(v, tuple):
                values[key] = project(v, n, PROJECTIONS[key])
            elif v is not None:
                values[key] = float(v)
        return values

    def device_at(self, base: Device, normal: Sequence[float] | np.ndarray | None = None) -> Device:
        """The one-axis device of this configuration (along ``normal`` for an inertia matrix).

        Parameters
        ----------
        base : Device
            The device; its period, force limit, travel, units and hand are kept.
        normal : array-like, optional
            The wall's normal (default :attr:`normal`; needed for a directional configuration).

        Returns
        -------
        Device
            Named ``"<device> [<configuration>]"``, with :meth:`along`'s values (plus the hand's, when held).
        """
        if not isinstance(base, Device):
            raise DFATypeError(f"base = {format_value(base)} has type {type(base).__name__}: it must be a Device")
        values = self.along(base, normal)
        dev = dataclasses.replace(
            base.bare, name=f"{base.name} [{self.name}]", mass=values["mass"], damping=values["damping"],
            coulomb=values["coulomb"], resolution=values["resolution"],
        )  # fmt: skip
        return dev if base.hand is None else dev.held_by(base.hand)

    def to_dict(self) -> dict[str, Any]:
        """The configuration as JSON (its given keys only; SI units)."""
        out: dict[str, Any] = {"name": self.name}
        for key in CONFIGURATION_KEYS[1:]:
            v = getattr(self, key)
            if v is not None:
                out[key] = [list(r) for r in v] if key == "inertia" else (list(v) if isinstance(v, tuple) else v)
        return out


def configurations_from_toml(value: object, where: str) -> tuple[Configuration, ...]:
    """The ``[[devices.configurations]]`` tables of a device file, checked (names unique).

    Parameters
    ----------
    value : list of dict
        The tables as the TOML reader gives them.
    where : str
        How messages name the file (``"device file 'arm.toml'"``).

    Returns
    -------
    tuple of Configuration

    Raises
    ------
    DFAValueError
        Naming the file, the configuration and the key: not a list of tables, an unknown or missing key, a value
        outside its rule, two configurations of one name, more than :data:`MAX_CONFIGURATIONS`.
    """
    if not isinstance(value, list) or not value or not all(isinstance(r, dict) for r in value):
        raise DFAValueError(
            f"{where} has configurations that are not tables: write each as a [[devices.configurations]] table "
            "with a name and the values that differ (see docs/cli.md, configurations)"
        )
    if len(value) > MAX_CONFIGURATIONS:
        raise DFAValueError(f"{where} has {len(value)} configurations: at most {MAX_CONFIGURATIONS}; split the grid")
    out: list[Configuration] = []
    for i, row in enumerate(value, 1):
        label = f"configuration {row.get('name', i)!r}"
        unknown = [k for k in row if k not in CONFIGURATION_KEYS]
        if unknown:
            raise DFAValueError(f"{where}, {label}: unknown key {unknown[0]!r}; the keys are "
                                f"{', '.join(CONFIGURATION_KEYS)}")  # fmt: skip
        if "name" not in row:
            raise DFAValueError(f"{where}, configuration {i}: it lacks name; give each configuration a name")
        try:
            out.append(Configuration(**row))
        except (DFAValueError, DFATypeError) as exc:
            raise DFAValueError(f"{where}, {label}: {exc}") from None
    names = [c.name for c in out]
    twice = sorted({n for n in names if names.count(n) > 1})
    if twice:
        raise DFAValueError(f"{where} names two configurations {twice[0]!r}: give each configuration its own name")
    return tuple(out)
