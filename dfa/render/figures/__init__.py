"""Figures of dfa: the only package, with the rest of the rendering layer, that imports matplotlib.

Every function takes a result object and an optional ``ax`` (or ``axes``)
and returns the axes it drew on, in the style of python-control's ``*_plot``
functions. Axis labels carry units: dimensionless quantities are marked (–),
positions are in encoder ticks, time in samples (or seconds when a sample
period is given). Given a device (``device=``), trajectories get a second axis
in m (rotary rad) and map panels axes of damping b and Coulomb friction c at K.
Legends sit beside the axes (below a row of panels), never over the data; the operating point has one
style (``POINT_STYLE``) and each outcome class one colour in every figure.

One module per thing drawn: :mod:`~dfa.render.figures.regions` (Fig. 3), :mod:`~dfa.render.figures.maps`
(Fig. 4), :mod:`~dfa.render.figures.trajectory` (Fig. 5), :mod:`~dfa.render.figures.nyquist` (Fig. 6),
:mod:`~dfa.render.figures.contours` (Fig. 7), :mod:`~dfa.render.figures.stiffness` and
:mod:`~dfa.render.figures.speed_chart` (stiffness limits, with :mod:`~dfa.render.figures.bounds`),
:mod:`~dfa.render.figures.zwidth`, :mod:`~dfa.render.figures.identify`, :mod:`~dfa.render.figures.validation`,
:mod:`~dfa.render.figures.passivity`; the shared look in :mod:`~dfa.render.figures.style`, files written by
:mod:`~dfa.render.figures.save`. A result's ``.plot()`` reaches them by name
(:func:`dfa.results.base.figure_function`): ``import dfa`` loads no matplotlib.

Examples
--------
>>> import matplotlib
>>> matplotlib.use("Agg")
>>> import dfa
>>> from dfa.render.figures import regions_plot
>>> ax = regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
>>> ax.get_xlabel()
'β = b/(K T) (–)'
"""

from ..._io import FIGURE_SUFFIXES
from .configurations import configurations_plot
from .contours import contour_plot
from .identify import ZOOM_AFTER, plot_identification
from .maps import stability_map_plot
from .nyquist import MODEL_NAMES, nyquist_needs_zoom, nyquist_plot
from .passivity import PASSIVITY_COLORS, passivity_plot
from .regions import regions_plot
from .save import save_figure
from .speed_chart import stiffness_speed_plot
from .stiffness import stiffness_plot
from .style import (
    BETA_LABEL,
    OUTCOME_COLORS,
    POINT_STYLE,
    REGION_COLORS,
    REGION_HATCH,
    SIGMA_LABEL,
)
from .trajectory import trajectory_plot
from .tune import tune_plot
from .validation import critical_speed_plot, cycle_error_plot
from .zwidth import ZWIDTH_COLORS, plot_zwidth

__all__ = [
    "configurations_plot",
    "tune_plot",
    "regions_plot",
    "stability_map_plot",
    "trajectory_plot",
    "contour_plot",
    "nyquist_plot",
    "stiffness_plot",
    "stiffness_speed_plot",
    "cycle_error_plot",
    "critical_speed_plot",
    "plot_zwidth",
    "plot_identification",
    "passivity_plot",
    "nyquist_needs_zoom",
    "save_figure",
    "FIGURE_SUFFIXES",
    "ZWIDTH_COLORS",
    "REGION_COLORS",
    "REGION_HATCH",
    "BETA_LABEL",
    "SIGMA_LABEL",
    "OUTCOME_COLORS",
    "POINT_STYLE",
    "MODEL_NAMES",
    "ZOOM_AFTER",
    "PASSIVITY_COLORS",
]
