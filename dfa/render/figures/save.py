"""Writing a figure to a file (PNG, PDF or SVG by its suffix), atomically."""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..._io import FIGURE_SUFFIXES, atomic_open, check_output_file


def save_figure(figure: Any, path: str | os.PathLike, *, dpi: float = 120, tight: bool = True) -> Path:
    """Write a figure to ``path`` as PNG, PDF or SVG by its suffix (:data:`FIGURE_SUFFIXES`), atomically.

    Parameters
    ----------
    figure : matplotlib.figure.Figure or matplotlib.axes.Axes
        The figure, or an Axes of it (as the ``*_plot`` functions return).
    path : str or os.PathLike
        The file; its name must end in ``.png``, ``.pdf`` or ``.svg`` (anything else is refused
        before a byte is written), and its folder must exist.
    dpi : float, optional
        Resolution of a PNG (and of images inside a PDF or SVG), dots per inch (default 120).
    tight : bool, optional
        Crop the page to the drawn artists, legends beside the axes included (default True).

    Returns
    -------
    pathlib.Path
        The file written (a PDF or SVG without a creation date).

    Raises
    ------
    DFAValueError
        For another suffix, a folder, or a folder that does not exist.

    Examples
    --------
    >>> import matplotlib, os, tempfile
    >>> matplotlib.use("Agg")
    >>> import dfa
    >>> from dfa.render.figures.regions import regions_plot
    >>> ax = regions_plot(dfa.passivity_criterion(0.2, 1.0, 2.0))
    >>> d = tempfile.mkdtemp()
    >>> [save_figure(ax, os.path.join(d, "regions" + s)).name for s in FIGURE_SUFFIXES]
    ['regions.png', 'regions.pdf', 'regions.svg']
    >>> try:
    ...     save_figure(ax, os.path.join(d, "regions.jpg"))
    ... except dfa.DFAValueError as e:
    ...     print(str(e).split(": ", 1)[1])
    the file name must end in .png, .pdf or .svg, not .jpg; give path ...regions.png
    """
    fig = getattr(figure, "figure", figure)  # an Axes knows its figure; a Figure is its own
    target = check_output_file("path", os.fspath(path), FIGURE_SUFFIXES)
    fmt = next(s for s in FIGURE_SUFFIXES if target.endswith(s))[1:]
    metadata = {"pdf": {"CreationDate": None}, "svg": {"Date": None}}.get(fmt)
    with atomic_open(target, "wb") as fh:
        fig.savefig(fh, format=fmt, dpi=dpi, bbox_inches="tight" if tight else None, metadata=metadata)
    return Path(target)
