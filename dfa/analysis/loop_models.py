"""The hold models of the linearised loop and the checks of its inputs (paper eq. 36-40).

Shared by the loop's frequency response (:mod:`dfa.analysis.loop`) and the limit-cycle solver
(:mod:`dfa.analysis.cycles`), so that neither imports the other for them.

Examples
--------
>>> check_model("zoh", 1, 4)
('zoh', 1, 4)
>>> check_model("exact", 0, 4)
Traceback (most recent call last):
...
dfa.errors.DFAValueError: model = 'exact' is invalid: it must be one of 'half-delay', 'pade', 'zoh'
"""

from __future__ import annotations

from ..checks import check_choice, check_delay, check_int, check_type
from ..model.device import Params

__all__ = ["LOOP_MODELS", "check_params", "check_model"]

#: The hold models of the loop (eq. 36-40): ``"half-delay"`` (the paper's e^{−jω(d + ½)}), ``"pade"`` (that
#: delay as a Padé approximation) and ``"zoh"`` (the exact zero-order-hold discretisation).
LOOP_MODELS = ("half-delay", "pade", "zoh")


def check_params(params: object) -> Params:
    """The loop's dimensionless parameters, checked to be :class:`~dfa.model.device.Params`.

    Parameters
    ----------
    params : Params
        μ, β, σ of the loop (paper Table 1).

    Returns
    -------
    Params
        ``params`` itself.

    Raises
    ------
    DFATypeError
        If ``params`` is not :class:`~dfa.model.device.Params`.
    """
    return check_type("params", params, Params, "build it with dfa.Params(mu, beta, sigma) or device.params(stiffness)")


def check_model(model: str, delay: int, pade_order: int) -> tuple[str, int, int]:
    """The hold model, the delay and the Padé order of a loop, checked.

    Parameters
    ----------
    model : str
        One of :data:`LOOP_MODELS`.
    delay : int
        Computational delay d, samples (>= 0).
    pade_order : int
        Order of the Padé approximation (>= 1; used by ``"pade"`` only).

    Returns
    -------
    tuple of (str, int, int)
        The model, d and the order.

    Raises
    ------
    DFAValueError, DFATypeError
        If the model is unknown, or the delay or the order is not a valid whole number.
    """
    m = check_choice("model", model, LOOP_MODELS)
    d = check_delay(delay)
    n = check_int("pade_order", pade_order, minimum=1, fix="use an order of 1 or more (4 is usually enough)")
    return m, d, n
