"""The linearised haptic loop (paper Fig. 6, eq. 36-40) built with python-control.

A limit cycle ξ = M sin ωτ of the quantized, frictional loop satisfies the
harmonic balance (eq. 36)::

    1 + D(M) · L(jω; M) = 0,

where D is the quantizer describing function (eq. 41) and L the linear part:
the device with Coulomb friction replaced by its equivalent viscous damping
(eq. 40)::

    G(s; M, ω) = 1/(μ s² + β_eq s),   β_eq = β + 4σ/(π M ω),

in series with the zero-order hold and an optional computational delay of d
samples. Three models of the hold are offered (time in samples, T = 1):

``"half-delay"`` (the paper's)
    L = e^{−jω(d + ½)} G(jω), exact in the frequency response.
``"pade"``
    the delay e^{−s(d + ½)} replaced by a Padé approximation of order
    ``pade_order``: a rational model for tools that need one.
``"zoh"`` (exact)
    L = z^{−d} G_d(z) at z = e^{jω}, with G_d the ZOH-discretised device
    (``control.c2d(G, 1, 'zoh')``), here in closed form::

        G_d(z) = (c₁ z + c₀) / (μ (z − 1)(z − p)),   a = β_eq/μ, p = e^{−a},
        c₁ = (a − 1 + p)/a²,   c₀ = (1 − p − a p)/a²     (c₁ = c₀ = ½ at a = 0).

Examples
--------
>>> import numpy as np
>>> from dfa.model.device import Params
>>> p = Params(mu=5.0, beta=0.1, sigma=0.0)
>>> L = loop_response(p, [0.1, 1.0])                      # half-delay model
>>> bool(np.allclose(L, np.exp(-0.5j * np.array([0.1, 1.0])) / (5.0 * (1j * np.array([0.1, 1.0]))**2 + 0.1j * np.array([0.1, 1.0]))))
True
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ..checks import (
    check_nonempty,
    check_positive,
    check_positive_array,
    check_real_array,
    check_type,
)
from ..core.zoh import zoh_coefficients
from ..errors import DFAValueError
from ..grids import geometric_grid
from ..model.device import Params
from ..model.loop import LOOP_FIX, Loop, loop_first
from ..model.wall import WallParams
from ..results.cycles import LimitCycleResult, SearchEvidence
from ..results.loop import CycleMark, NyquistLocusResponse
from ..results.status import NyquistStatus, SearchStatus
from .cycles.characteristic import inv_loop
from .cycles.controlled import WALL_FIX, resolve_wall
from .describing import coulomb_equivalent_damping, quantizer_df
from .loop_models import LOOP_MODELS, check_model, check_params

if TYPE_CHECKING:
    import control

__all__ = [
    "LOOP_MODELS",
    "equivalent_damping",
    "device_tf",
    "hold_delay_tf",
    "device_zoh_tf",
    "zoh_pulse_response",
    "loop_response",
    "loop_system",
    "CycleMark",
    "NyquistLocusResponse",
    "nyquist_locus_response",
]


def _omega(omega: ArrayLike, name: str = "omega") -> np.ndarray:
    return check_positive_array(name, omega, "give frequencies in rad per sample")


def _nonempty(name: str, value: ArrayLike, fix: str) -> np.ndarray:
    """``value`` as a 1-d float array of finite values holding at least one (one number: one point)."""
    return check_nonempty(name, np.atleast_1d(check_real_array(name, value, fix)), fix)


def equivalent_damping(
    params: Params, amplitude: ArrayLike | None = None, omega: ArrayLike | None = None
) -> float | np.ndarray:
    """β_eq = β + 4σ/(πMω) of eq. 40, broadcast over ``amplitude`` M and ``omega`` ω.

    With σ = 0, ``amplitude`` and ``omega`` may be omitted (β_eq = β).
    """
    p = check_params(params)
    if p.sigma == 0.0:
        shape = np.broadcast_shapes(
            np.shape(amplitude) if amplitude is not None else (), np.shape(omega) if omega is not None else ()
        )
        return np.full(shape, p.beta) if shape else p.beta
    if amplitude is None or omega is None:
        raise DFAValueError(
            f"amplitude = {amplitude!r} is invalid here: with sigma = {p.sigma} > 0 the loop depends on the "
            "cycle's amplitude M and frequency ω (eq. 40); give both"
        )
    return p.beta + coulomb_equivalent_damping(p.sigma, amplitude, omega)


def device_tf(params: Params, amplitude: float | None = None, omega: float | None = None) -> control.TransferFunction:
    """Continuous device G(s) = 1/(μ s² + β_eq s) (time in samples) as a python-control TransferFunction.

    Examples
    --------
    >>> from dfa.model.device import Params
    >>> G = device_tf(Params(2.0, 0.5, 0.0))
    >>> G.num[0][0].tolist(), G.den[0][0].tolist()
    ([1.0], [2.0, 0.5, 0.0])
    """
    import control  # imported where used: python-control takes over a second to load

    p = check_params(params)
    b = float(equivalent_damping(p, amplitude, omega))
    return control.tf([1.0], [p.mu, b, 0.0])


def hold_delay_tf(delay: int = 0, pade_order: int = 4) -> control.TransferFunction:
    """Padé approximation of the hold's half sample plus ``delay`` samples, e^{−s(d + ½)}."""
    import control  # imported where used: python-control takes over a second to load

    _m, d, n = check_model("pade", delay, pade_order)
    num, den = control.pade(d + 0.5, n)
    return control.tf(num, den)


def device_zoh_tf(
    params: Params, amplitude: float | None = None, omega: float | None = None
) -> control.TransferFunction:
    """Exact ZOH discretisation (T = 1) of the device: ``control.c2d(device_tf(...), 1, 'zoh')``."""
    import control  # imported where used: python-control takes over a second to load

    return control.c2d(device_tf(params, amplitude, omega), 1.0, method="zoh")


def zoh_pulse_response(mu: ArrayLike, beta_eq: ArrayLike, omega: ArrayLike) -> complex | np.ndarray:
    """G_d(e^{jω}) of the ZOH-discretised device 1/(μ s² + β_eq s), closed form (vectorised).

    Parameters
    ----------
    mu : float or array_like
        Dimensionless mass μ > 0.
    beta_eq : float or array_like
        (Equivalent) damping >= 0.
    omega : float or array_like
        Frequency in rad per sample, in (0, π].
    """
    mu = np.asarray(mu, dtype=float)
    a = np.asarray(beta_eq, dtype=float) / mu
    c1, c0, p = zoh_coefficients(a)
    z = np.exp(1j * np.asarray(omega, dtype=float))
    return (c1 * z + c0) / (mu * (z - 1.0) * (z - p))


@loop_first("params, *, wall", wall_fix=WALL_FIX)
def loop_response(
    loop: Loop,
    omega: ArrayLike,
    amplitude: ArrayLike | None = None,
    *,
    model: str = "half-delay",
    pade_order: int = 4,
) -> complex | np.ndarray:
    """Frequency response L(jω; M) of the linear part of the loop (eq. 36).

    Parameters
    ----------
    loop : Loop
        The loop: its groups (μ, β, σ) and its wall's (delay d, damper β_B, filter ν_c, amplifier lag α),
        ``Loop.dimensionless(mu, beta, sigma, wall_params)`` or ``Loop(device, wall)``. The former call
        ``loop_response(params, ..., wall=wall_params)`` still works. The wall (issue 15): its computational
        delay d in whole samples multiplies L by
        e^{−jωd}; a damper and filter by the command C(e^{jω}) = 1 + β_B(1 − e^{−jω})F(e^{jω}) (F the
        ZOH-exact velocity filter (1 − a)e^{−jω}/(1 − a e^{−jω}), a = e^{−2πν_c}; 1 without filter); an
        amplifier lag enters as 1/(jωα + 1) (half-delay, Padé) or exactly inside the ZOH-sampled amplifier +
        device (``"zoh"``, :mod:`dfa.core.zohlag`). No wall groups: the paper's spring.
    omega : float or array_like
        Frequencies ω > 0 in rad per sample (ω < π for a sampled cycle).
    amplitude : float or array_like, optional
        Cycle amplitude M in ticks (needed when σ > 0: it sets β_eq); broadcast with ``omega``.
    model : {"half-delay", "pade", "zoh"}
        Model of the zero-order hold (module docstring).
    pade_order : int, optional
        Order of the Padé approximation for ``model="pade"`` (default 4).

    Returns
    -------
    complex or numpy.ndarray of complex
        L with the broadcast shape of ``omega`` and ``amplitude``.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``loop`` is not a :class:`Loop` with groups, a frequency or amplitude is not a finite number > 0, the
        model is unknown, or the delay or Padé order is not a valid whole number.

    See Also
    --------
    loop_system : The same loop as a python-control system.
    nyquist_locus_response : The loop against the critical locus −1/D(M).
    """

    p, wall = check_type("loop", loop, Loop, LOOP_FIX).groups("loop_response")
    _w, ctl, d = resolve_wall(wall)
    m, d, n = check_model(model, d, pade_order)
    w = _omega(omega)
    if amplitude is not None:
        amplitude = check_real_array("amplitude", amplitude, "give the cycle amplitude M in ticks")
        try:
            np.broadcast_shapes(w.shape, amplitude.shape)
        except ValueError:
            raise DFAValueError(
                f"amplitude of shape {amplitude.shape} is invalid with omega of shape {w.shape}: they must broadcast "
                "together; give one amplitude per frequency or a single amplitude"
            ) from None
    beq = (
        equivalent_damping(p, amplitude, w)
        if p.sigma > 0
        else np.full(np.broadcast_shapes(w.shape, np.shape(amplitude) if amplitude is not None else ()), p.beta)
    )
    w = np.broadcast_to(w, np.shape(beq))
    if ctl is not None:
        out = 1.0 / inv_loop(p.mu, beq, w, m, d, n, ctl)
    elif m == "zoh":
        out = zoh_pulse_response(p.mu, beq, w) * np.exp(-1j * w * d)
    else:
        s = 1j * w
        g = 1.0 / (p.mu * s**2 + beq * s)
        if m == "half-delay":
            out = g * np.exp(-s * (d + 0.5))
        else:
            import control  # imported where used: python-control takes over a second to load

            num, den = control.pade(d + 0.5, n)
            out = g * np.polyval(num, s) / np.polyval(den, s)
    out = np.asarray(out, dtype=complex)
    if not np.all(np.isfinite(out)):
        bad = float(np.broadcast_to(w, out.shape)[~np.isfinite(out)].ravel()[0])
        raise DFAValueError(
            f"omega = {bad!r} is invalid here: L(jω) over- or underflows a float at this frequency; "
            "give frequencies in rad per sample (a sampled cycle has ω < π)"
        )
    return complex(out) if out.ndim == 0 else out


@loop_first("params, *, wall", wall_fix=WALL_FIX)
def loop_system(
    loop: Loop,
    amplitude: float | None = None,
    omega: float | None = None,
    *,
    model: str = "pade",
    pade_order: int = 4,
    omega_grid: ArrayLike | None = None,
) -> control.TransferFunction | control.FrequencyResponseData:
    """The linear part as a python-control system, for python-control's own tools.

    ``"pade"`` gives a continuous TransferFunction, ``"zoh"`` a discrete one
    (dt = 1), and ``"half-delay"`` a FrequencyResponseData on ``omega_grid``
    (the exact delay is not rational). With σ > 0 the rational models are
    linearised at the given ``amplitude`` and ``omega`` (eq. 40); the FRD only
    needs the amplitude, because the Coulomb term adds j·4σ/(πM) to 1/G at
    every frequency.

    Parameters
    ----------
    loop : Loop
        The loop: its groups (μ, β, σ) and its wall, the paper's spring with a computational delay d in whole
        samples (``Loop.dimensionless(mu, beta, sigma, WallParams.of(delay=d))``); a damper, filter or lag is
        refused: use :func:`loop_response`. The former call ``loop_system(params, ..., wall=wall_params)`` still
        works.
    amplitude : float, optional
        Cycle amplitude M in ticks at which the Coulomb friction is linearised (needed when σ > 0).
    omega : float, optional
        Frequency ω in rad per sample at which the rational models linearise the friction (σ > 0).
    model : {"pade", "zoh", "half-delay"}
        Model of the zero-order hold (module docstring); default ``"pade"``.
    pade_order : int, optional
        Order of the Padé approximation for ``model="pade"`` (default 4).
    omega_grid : array_like, optional
        Frequencies in rad per sample of the ``"half-delay"`` FRD; default 2000 points from 1e-3 to π.

    Returns
    -------
    control.TransferFunction or control.FrequencyResponseData
        Continuous (``"pade"``) or discrete with dt = 1 (``"zoh"``) transfer function, or the FRD.

    Raises
    ------
    DFAValueError, DFATypeError
        If ``loop`` is not a :class:`Loop` with groups, a frequency or amplitude is invalid, the model is
        unknown, or the delay or Padé order is not a valid whole number.

    See Also
    --------
    loop_response : The frequency response itself, vectorised.
    """

    import control  # imported where used: python-control takes over a second to load

    p, wall = check_type("loop", loop, Loop, LOOP_FIX).groups("loop_system")
    _w, ctl, d = resolve_wall(wall)
    if ctl is not None:
        raise DFAValueError(
            f"wall = {ctl.to_dict()} is invalid for loop_system: it builds the spring's loop with a delay only; "
            "use loop_response(..., wall=...) for a wall with a damper, filter or amplifier lag"
        )
    m, d, n = check_model(model, d, pade_order)
    if amplitude is not None:
        amplitude = check_positive("amplitude", amplitude, "give one cycle amplitude M in ticks")
    if omega is not None:
        omega = check_positive("omega", omega, "give one frequency in rad per sample")
    if m == "pade":
        return device_tf(p, amplitude, omega) * hold_delay_tf(d, n)
    if m == "zoh":
        gd = device_zoh_tf(p, amplitude, omega)
        return gd * control.tf([1.0], [1.0] + [0.0] * d, dt=1.0) if d else gd
    w = _omega(geometric_grid(1e-3, np.pi, 2000) if omega_grid is None else omega_grid, "omega_grid")
    amp = None if p.sigma == 0.0 or amplitude is None else np.full_like(w, amplitude)
    return control.frd(loop_response(loop, w, amp, model=m), w)


def _solver_crossings(
    p: Params, model: str, pade_order: int, omega: np.ndarray, max_amplitude: float, wall: WallParams
) -> tuple[list[tuple[float, float, complex]], NyquistStatus, SearchEvidence]:
    """σ = 0: the harmonic-balance roots of the limit-cycle solver (one implementation, residual <= 1e-10).

    Returns ((M, ω, −1/D(M)) for every root with ω in the plotted range and M <= ``max_amplitude``, status,
    the solver's evidence): ``OK`` when the search is complete up to ``max_amplitude``, else ``SEARCH_INCOMPLETE``.
    """
    from .cycles.solve import limit_cycles  # imported here: it loads scipy.optimize

    res = limit_cycles(Loop.dimensionless(p.mu, p.beta, p.sigma, wall), model=model, pade_order=pade_order,
                       max_amplitude=max_amplitude)  # fmt: skip
    lo, hi = float(np.min(omega)), float(np.max(omega))
    out = [
        (c.amplitude, c.frequency, complex(-1.0 / quantizer_df(c.amplitude), 0.0))
        for c in res.cycles
        if lo <= c.frequency <= hi
    ]
    assert res.search is not None  # set on construction
    if res.complete or res.status is SearchStatus.MAX_AMPLITUDE:
        return out, NyquistStatus.OK, res.search
    return out, NyquistStatus.SEARCH_INCOMPLETE, res.search


@loop_first("params, *, wall", wall_fix=WALL_FIX)
def nyquist_locus_response(
    loop: Loop,
    amplitudes: ArrayLike | None = None,
    omega: ArrayLike | None = None,
    *,
    model: str = "half-delay",
    pade_order: int = 4,
    locus_amplitude: ArrayLike | None = None,
    cycles: LimitCycleResult | None = None,
) -> NyquistLocusResponse:
    """Nyquist data of the loop L(jω; M) and the critical locus −1/D(M) (paper Fig. 6).

    Parameters
    ----------
    loop : Loop
        The loop: its groups (μ, β, σ) and its wall's, delay included (see :func:`loop_response`),
        ``Loop.dimensionless(mu, beta, sigma, wall_params)`` or ``Loop(device, wall)``. The former call
        ``nyquist_locus_response(params, ..., wall=wall_params)`` still works.
    amplitudes : array_like, optional
        Amplitudes M (ticks) at which to linearise the Coulomb friction; needed
        when σ > 0 (one curve per amplitude), ignored when σ = 0.
    omega : array_like, optional
        Frequencies (rad per sample); default 2000 points from 1e-3 to π.
    model : {"half-delay", "pade", "zoh"}
        Model of the zero-order hold (see :func:`loop_response`).
    pade_order : int, optional
        Order of the Padé approximation for ``model="pade"`` (default 4).
    locus_amplitude : array_like, optional
        Amplitudes of the critical locus; default 0.05 to 50 ticks.
    cycles : LimitCycleResult, optional
        Limit cycles to mark on the figure (from :func:`~dfa.analysis.cycles.limit_cycles` with the same loop
        model): each is placed at its point L(jω; M) of this loop (``cycle_marks``).

    Returns
    -------
    NyquistLocusResponse
        The curves, the locus, (σ = 0) the crossings from the limit-cycle solver and the cycles to mark;
        ``.plot()`` draws them.

    Raises
    ------
    DFAValueError, DFATypeError
        If an input is invalid, or σ > 0 and no ``amplitudes`` are given.

    See Also
    --------
    loop_response : The loop's frequency response.
    limit_cycles : The harmonic-balance solutions the crossings come from.

    Examples
    --------
    >>> from dfa.model.device import Params
    >>> r = nyquist_locus_response(Loop.dimensionless(mu=5.0, beta=0.4, sigma=0.0))
    >>> [(round(m, 4), round(w, 4)) for m, w, pt in r.crossings]
    [(0.7905, 0.3974), (1.0098, 0.3974)]
    """

    p, wall = check_type("loop", loop, Loop, LOOP_FIX).groups("nyquist_locus_response")
    wp, _ctl, d = resolve_wall(wall)
    m, d, n = check_model(model, d, pade_order)
    w = check_nonempty("omega", _omega(geometric_grid(1e-3, np.pi, 2000) if omega is None else omega))
    la = _nonempty(  # one amplitude: a locus of one point (a 0-d array was refused by the result's shape check)
        "locus_amplitude",
        geometric_grid(0.05, 50.0, 1500) if locus_amplitude is None else locus_amplitude,
        "give the describing function's amplitudes in ticks",
    )
    locus = -1.0 / quantizer_df(la)
    crossings: list[tuple[float, float, complex]] = []
    if p.sigma == 0.0:
        amps = np.array([np.nan])
        curves = np.atleast_2d(loop_response(loop, w, model=m, pade_order=n))
        crossings, status, evidence = _solver_crossings(p, m, n, w, float(la.max()), wp)
    else:
        if amplitudes is None:
            raise DFAValueError(
                f"amplitudes = None is invalid here: with sigma = {p.sigma} > 0 the loop depends on M (eq. 40); "
                "give the amplitudes (ticks) at which to draw it"
            )
        amps = _nonempty("amplitudes", amplitudes, "give the amplitudes M in ticks")
        curves = np.vstack([loop_response(loop, w, np.full_like(w, a), model=m, pade_order=n) for a in amps])
        status, evidence = NyquistStatus.CROSSINGS_NOT_COMPUTED, None
    marks = None if cycles is None else _cycle_marks(cycles, Loop(None, params=p, wall_params=wp), m, n)
    return NyquistLocusResponse(
        p, m, wp, n, w, amps, curves, la, locus, tuple(sorted(crossings)), status, evidence, marks
    )


def _cycle_marks(cycles: LimitCycleResult, loop: Loop, model: str, pade_order: int) -> tuple[CycleMark, ...]:
    """Each cycle at its point L(jω; M) of ``loop`` (the response's groups and resolved wall), where the Nyquist
    figure marks it."""
    check_type("cycles", cycles, LimitCycleResult, "give the result of limit_cycles with the same loop model")
    return tuple(
        CycleMark(c.amplitude, c.frequency, bool(c.stable),
                  complex(loop_response(loop, c.frequency, c.amplitude, model=model, pade_order=pade_order)))
        for c in cycles.cycles
    )  # fmt: skip
