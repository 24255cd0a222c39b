"""The characteristic function C(M, ω) = 1/L(jω; M) + D(M) of the harmonic balance (eq. 36, 40, 41).

For the half-delay and Padé models 1/L = e^{jφ(ω)}·(−μω² + jωβ_eq): the device times an all-pass phase
lead φ (the inverse of the hold's delay); the exact ZOH model uses the closed-form pulse transfer function
(:mod:`dfa.analysis.loop`). Scalars take a plain-complex path (the bracketing root finders call it thousands of times).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

import numpy as np

from ...core import dfcore
from ...core.zoh import zoh_coefficients
from ...grids import geometric_grid
from ...model.device import Params
from ...model.elements import CommandPolynomials, Element
from ...model.wall import WallParams

DF_CHOICES = ("exact", "small", "unity")

#: Amplitudes below this (ticks) are not searched: there F ≈ (2 − 4σ)/(πM) keeps its sign.
M_FLOOR = 1e-9


#: Frequency grid (rad per sample) on which the phase curve is scanned before bracketing.
W_GRID = np.concatenate([geometric_grid(1e-5, 0.05, 600, endpoint=False), np.linspace(0.05, math.pi - 1e-9, 3000)])
W_GRID.flags.writeable = False


# ------------------------------------------------------------ loop inverse
# For the half-delay and Padé models 1/L = e^{jφ(ω)}·(−μω² + jωβ_eq): the device times an
# all-pass phase lead φ (the inverse of the hold's delay). Half-delay: φ = ω(d + ½). Padé:
# the diagonal approximant of e^{−sτ} has num(s) = den(−s), so den(jω)/num(jω) = e^{2j·arg den(jω)}.
# Scalars take a plain-complex path (the bracketing root finders call it thousands of times).


@lru_cache(maxsize=64)
def grid_lead(model: str, delay: int, pade_order: int) -> tuple[np.ndarray, np.ndarray]:
    """(φ, e^{jφ}) on W_GRID, cached: the grid is scanned once per solve."""
    lead = _lead_eval(W_GRID, model, delay, pade_order)
    return lead, np.exp(1j * lead)


def phase_lead(w: float | np.ndarray, model: str, delay: int, pade_order: int) -> Any:
    """Phase lead φ(ω) of 1/L over the device's inverse (half-delay and Padé models), rad."""
    if w is W_GRID:
        return grid_lead(model, delay, pade_order)[0]
    return _lead_eval(w, model, delay, pade_order)


def _rotation(w: float | np.ndarray, model: str, delay: int, pade_order: int) -> Any:
    """e^{jφ(ω)} (vectorised), cached on W_GRID."""
    if w is W_GRID:
        return grid_lead(model, delay, pade_order)[1]
    return np.exp(1j * _lead_eval(w, model, delay, pade_order))


def _lead_eval(w: float | np.ndarray, model: str, delay: int, pade_order: int) -> Any:
    if model == "half-delay":
        return w * (delay + 0.5)
    den = pade_denominator(delay + 0.5, pade_order)
    if np.ndim(w) == 0:
        s, pd = 1j * float(w), 0j
        for c in den:
            pd = pd * s + c
        return 2.0 * cmath.phase(pd)
    return 2.0 * np.angle(np.polyval(den, 1j * np.asarray(w, dtype=float)))


def inv_loop(
    mu: float,
    beq: float | np.ndarray,
    omega: float | np.ndarray,
    model: str,
    delay: int,
    pade_order: int,
    wall: WallParams | None = None,
) -> Any:
    """1/L(jω) for an equivalent damping β_eq (broadcast), time in samples; plain complex for scalars.

    ``wall`` (groups the spring's fast path does not cover; None for the paper's spring, any delay) divides by
    the wall's command C(e^{jω}) and its plant factor (:func:`wall_ratio`, :func:`dfa.analysis.loop.loop_response`).
    """
    if wall is not None:
        return _inv_loop_wall(mu, beq, omega, model, delay, pade_order, wall)
    if (isinstance(omega, float) or np.ndim(omega) == 0) and (isinstance(beq, float) or np.ndim(beq) == 0):
        return _inv_loop_scalar(mu, float(beq), float(omega), model, delay, pade_order)
    w = omega if omega is W_GRID else np.asarray(omega, dtype=float)
    b = np.asarray(beq, dtype=float)
    if model != "zoh":
        return _rotation(w, model, delay, pade_order) * (-mu * w * w + 1j * w * b)
    z = np.exp(1j * w)
    c1, c0, p = zoh_coefficients(b / mu)
    return z**delay * mu * (z - 1.0) * (z - p) / (c1 * z + c0)


def _inv_loop_scalar(mu: float, b: float, w: float, model: str, delay: int, pade_order: int) -> complex:
    """1/L(jω) for one (β_eq, ω), in plain complex arithmetic."""
    if model != "zoh":
        return cmath.exp(1j * phase_lead(w, model, delay, pade_order)) * complex(-mu * w * w, w * b)
    c1, c0, p = (float(x) for x in zoh_coefficients(b / mu))
    z = cmath.exp(1j * w)
    return complex(z**delay * mu * (z - 1.0) * (z - p) / (c1 * z + c0))


def wall_ratio(wall: WallParams, omega: float | np.ndarray) -> complex | np.ndarray:
    """R(ω) = 1/(P(ω)·C(e^{jω})): what the wall multiplies 1/L by in the half-delay and Padé models (the delay
    stays in the hold's phase lead): C the command without its delay (the elements' polynomials,
    :meth:`dfa.model.wall.WallParams.command`), P the continuous factor between hold and device
    (:meth:`~dfa.model.wall.WallParams.plant_response`, 1/(1 + jωα) with an amplifier lag)."""
    w = np.asarray(omega, dtype=float)
    return 1.0 / (wall.plant_response(w) * wall_command(wall).response(w))


@lru_cache(maxsize=64)
def wall_command(wall: WallParams) -> CommandPolynomials:
    """The wall's command polynomials (:meth:`dfa.model.wall.WallParams.command`), formed once per wall: the
    root finders of a limit-cycle search evaluate the wall's response thousands of times."""
    return wall.command()


def _inv_loop_wall(
    mu: float,
    beq: float | np.ndarray,
    omega: float | np.ndarray,
    model: str,
    delay: int,
    pade_order: int,
    wall: WallParams,
) -> Any:
    """1/L(jω) with a wall (see :func:`inv_loop`); plain complex for scalars."""
    scalar = np.ndim(omega) == 0 and np.ndim(beq) == 0
    if scalar and model != "zoh":
        return _inv_loop_wall_scalar(mu, float(beq), float(omega), model, delay, pade_order, wall)
    w = omega if omega is W_GRID else np.asarray(omega, dtype=float)
    g = wall.zoh_response(mu, beq, w) if model == "zoh" else None
    if g is None:
        out = inv_loop(mu, beq, omega, model, delay, pade_order)
        if wall.hand_stiffness > 0.0:  # the hand spring acts on the device behind the hold: + κ_h in its inverse
            out = out + _rotation(w, model, delay, pade_order) * wall.hand_stiffness
        out = out * (wall_ratio(wall, w) if model != "zoh" else 1.0 / wall_command(wall).response(w))
    else:
        z = np.exp(1j * w)
        out = z**delay / (g * wall_command(wall).response(w))
    return complex(out) if scalar else out


def _inv_loop_wall_scalar(
    mu: float, b: float, w: float, model: str, delay: int, pade_order: int, wall: WallParams
) -> complex:
    """:func:`_inv_loop_wall` for one (β_eq, ω) of the half-delay and Padé models, in plain complex arithmetic:
    the same terms as the vector path (the hand spring's κ_h e^{jφ}, then :func:`wall_ratio_scalar`)."""
    out = _inv_loop_scalar(mu, b, w, model, delay, pade_order)
    kap = _command_coefficients(wall)[2]
    if kap > 0.0:  # the hand spring acts on the device behind the hold: + κ_h in its inverse
        out += cmath.exp(1j * phase_lead(w, model, delay, pade_order)) * kap
    return out * wall_ratio_scalar(wall, w)


def wall_ratio_scalar(wall: WallParams, w: float) -> complex:
    """:func:`wall_ratio` at one frequency ω (rad per sample), in plain complex arithmetic.

    The command C(e^{jω}) = N(w)/D(w) at w = e^{jω} − 1 = −2 sin²(ω/2) + j sin ω by Horner's rule on the
    polynomials' coefficients (:class:`~dfa.model.elements.CommandPolynomials`): the root finders of a limit-cycle
    search call this tens of thousands of times, where numpy's per-call overhead on scalars was most of the
    search's time. The value agrees with :func:`wall_ratio`'s to rounding (numpy's array arithmetic may fuse
    multiply-adds).
    """
    num, den, _kap, plain = _command_coefficients(wall)
    s = math.sin(0.5 * w)
    z1 = complex(-2.0 * s * s, math.sin(w))
    n, d = 0j, 0j
    for c in num:
        n = n * z1 + c
    for c in den:
        d = d * z1 + c
    plant = 1.0 if plain else complex(wall.plant_response(w))
    return 1.0 / (plant * (n / d))


@lru_cache(maxsize=64)
def _command_coefficients(wall: WallParams) -> tuple[tuple[float, ...], tuple[float, ...], float, bool]:
    """The command's numerator and denominator coefficients in w (floats, highest power first), κ_h, and whether
    the plant factor between hold and device is 1 (no element overrides :meth:`Element.plant_response`), formed
    once per wall."""
    cmd = wall_command(wall)
    base = Element.plant_response.__func__  # type: ignore[attr-defined]
    plain = all(getattr(k.plant_response, "__func__", None) is base for k, _ in wall.groups)
    return tuple(map(float, cmd.numerator)), tuple(map(float, cmd.denominator)), float(wall.hand_stiffness), plain


@lru_cache(maxsize=64)
def pade_denominator(t: float, order: int) -> tuple[float, ...]:
    """Denominator of python-control's Padé approximant of e^{−st} (its numerator is den(−s))."""
    import control

    num, den = control.pade(t, order)
    den = np.asarray(den, dtype=float)
    if not np.allclose(np.asarray(num, dtype=float), den * (-1.0) ** np.arange(den.size)[::-1], rtol=1e-12, atol=0):
        raise RuntimeError("control.pade returned a non-diagonal approximant")  # pragma: no cover
    return tuple(float(c) for c in den / den[0])


@dataclass(frozen=True)
class HarmonicLoop:
    params: Params
    model: str
    delay: int
    pade_order: int
    df: str = "exact"
    wall: WallParams | None = None

    def beq(self, m: float | np.ndarray, w: float | np.ndarray) -> float | np.ndarray:
        if isinstance(m, float) and isinstance(w, float):
            return self.params.beta + 4.0 * self.params.sigma / (math.pi * m * w)
        return self.params.beta + 4.0 * self.params.sigma / (math.pi * np.asarray(m) * np.asarray(w))

    def inv(self, m: float | np.ndarray, w: float | np.ndarray) -> Any:
        if self.wall is not None and self.model != "zoh" and isinstance(m, float) and isinstance(w, float):
            p = self.params  # one (M, ω) of a root finder: the plain-complex path, without the dispatch
            beq = p.beta + 4.0 * p.sigma / (math.pi * m * w)
            return _inv_loop_wall_scalar(p.mu, beq, w, self.model, self.delay, self.pade_order, self.wall)
        return inv_loop(self.params.mu, self.beq(m, w), w, self.model, self.delay, self.pade_order, self.wall)

    def d(self, m: float | np.ndarray) -> float | np.ndarray:
        """D(M) (compiled eq. 41 for the exact describing function; M > 0 is the solver's own)."""
        if self.df == "exact" and isinstance(m, float):  # one amplitude of a root finder: no array made
            return dfcore.df_value(m)
        m = np.asarray(m, dtype=float)
        if self.df == "exact":
            return dfcore.df_array(m.ravel()).reshape(m.shape) if m.ndim else dfcore.df_value(float(m))
        if self.df == "small":
            return 2.0 / (math.pi * m)
        return np.ones_like(m) if m.ndim else 1.0

    def dprime(self, m: float | np.ndarray) -> float | np.ndarray:
        m = np.asarray(m, dtype=float)
        if self.df == "exact":
            return dfcore.df_array(m.ravel(), True).reshape(m.shape) if m.ndim else dfcore.df_derivative(float(m))
        if self.df == "small":
            return -2.0 / (math.pi * m * m)
        return np.zeros_like(m) if m.ndim else 0.0

    def char(self, m: float | np.ndarray, w: float | np.ndarray) -> Any:
        return self.inv(m, w) + self.d(m)
