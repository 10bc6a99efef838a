# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Legends placed off the data: shared by the analysis classes' ``plot(ax=None)`` and the
figures of :mod:`tapmc.paper`.

A legend may hide at most :data:`LEGEND_MAX_HIDDEN_FRACTION` of the plotted points of any one
series (:func:`hidden_points`). :func:`place_legend` tries the corners and edges of the axes
in a fixed order and keeps the first location that hides no point, else the one that hides
fewest within that allowance; where every location inside hides more, the legend goes beside
the axes, on the right, and :func:`replace_legends` widens the figure for it. No matplotlib
import here: the functions work on the axes they are given.
"""

import math
import weakref

import numpy as np

#: The largest fraction of one series' plotted points that its axes' legend may cover. A
#: series of fewer than 50 points (each sqrt(eps) of a bell, each frequency of a spectrum,
#: each level of a ramp) is a set of measured numbers: none of them may be hidden. A time
#: series of thousands of taps may brush a legend's corner with a few of its taps (80 of
#: 4000) without hiding its course.
LEGEND_MAX_HIDDEN_FRACTION = 0.02

#: where a legend may sit inside the axes, in the order tried (matplotlib's location names)
INSIDE_LOCATIONS = ("upper right", "upper left", "lower left", "lower right", "center right",
                    "center left", "upper center", "lower center", "center")

#: the legend beside the axes when no location inside is free: its upper left corner just
#: right of the axes' upper right corner (axes fraction)
OUTSIDE = {"loc": "upper left", "bbox_to_anchor": (1.02, 1.0), "borderaxespad": 0.0}

#: inches added to a figure's width beside a legend that went beside its axes (the gap of
#: :data:`OUTSIDE` and the figure's margin)
OUTSIDE_PAD_INCHES = 0.3

#: axes -> the keyword arguments of its legend, to place it again after a layout change
_REQUESTED = weakref.WeakKeyDictionary()
#: the axes whose legend went beside them
_OUTSIDE = weakref.WeakSet()
#: figure -> the width it was made with, before any legend beside its axes widened it
_BASE_WIDTH = weakref.WeakKeyDictionary()


def _capline_ids(ax):
    """ids of the caps of error bars: markers of the error, not points of a series."""
    ids = set()
    for container in ax.containers:
        if getattr(container, "has_xerr", None) is None:      # not an ErrorbarContainer
            continue
        _, caplines, _ = container.lines
        ids.update(id(line) for line in caplines)
    return ids


def series_points(ax):
    """The plotted points of each data series of ``ax`` in display coordinates, those inside
    the axes only: the lines and scatter collections drawn in data coordinates (a reference
    line, axhline or axvline, spans the axes and is no series; the caps of error bars are
    left out), a single marker included."""
    box = ax.get_window_extent()
    caps = _capline_ids(ax)
    candidates = [(line.get_transform(), line.get_xydata()) for line in ax.lines
                  if id(line) not in caps and line.get_visible()
                  and line.get_transform().contains_branch(ax.transData)]
    for collection in ax.collections:
        if (type(collection).__name__ == "PathCollection"
                and collection.get_offset_transform().contains_branch(ax.transData)):
            candidates.append((collection.get_offset_transform(), collection.get_offsets()))
    out = []
    for transform, xy in candidates:
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        xy = xy[np.all(np.isfinite(xy), axis=1)]
        if not len(xy):
            continue
        with np.errstate(all="ignore"):     # a log axis maps a non-positive value to NaN
            points = transform.transform(xy)
        keep = (np.all(np.isfinite(points), axis=1)
                & (points[:, 0] >= box.x0) & (points[:, 0] <= box.x1)
                & (points[:, 1] >= box.y0) & (points[:, 1] <= box.y1))
        if np.any(keep):
            out.append(points[keep])
    return out


def hidden_points(ax, bbox):
    """(hidden, plotted) per series of ``ax`` (:func:`series_points`) for a legend whose
    window extent is ``bbox``."""
    return [(int(np.sum((p[:, 0] >= bbox.x0) & (p[:, 0] <= bbox.x1)
                        & (p[:, 1] >= bbox.y0) & (p[:, 1] <= bbox.y1))), len(p))
            for p in series_points(ax)]


def allowed_hidden(plotted, fraction=LEGEND_MAX_HIDDEN_FRACTION):
    """How many of a series' ``plotted`` points a legend may cover."""
    return math.floor(fraction * plotted)


def _cost(ax, legend, renderer):
    """(series covered beyond the allowance, fraction of all points hidden): less is better."""
    counts = hidden_points(ax, legend.get_window_extent(renderer))
    over = sum(h > allowed_hidden(n) for h, n in counts)
    return over, sum(h / n for h, n in counts)


def place_legend(ax, later=False, **kw):
    """Draw the legend of ``ax`` (when it has labelled artists) where it hides no data:
    ``outside=True`` puts it beside the axes at once; otherwise the first location of
    :data:`INSIDE_LOCATIONS` that hides no point, else the one that hides fewest while
    covering no series beyond :data:`LEGEND_MAX_HIDDEN_FRACTION`, else beside the axes. The
    choice is made for the axes' present size: :func:`replace_legends` chooses again after a
    layout change; ``later=True`` leaves the choice to it (a figure laid out afterwards),
    the legend drawn meanwhile at the first location. Returns the legend."""
    if not ax.get_legend_handles_labels()[0]:
        return None
    _REQUESTED[ax] = dict(kw)
    kw = dict(kw)
    kw.pop("loc", None)
    outside = kw.pop("outside", False)
    if later:
        return ax.legend(loc=INSIDE_LOCATIONS[0], **kw)
    if outside or ax in _OUTSIDE:
        _OUTSIDE.add(ax)
        return ax.legend(**{**kw, **OUTSIDE})
    ax.get_xlim(), ax.get_ylim()      # the view limits the placement depends on, up to date
    renderer = ax.figure.canvas.get_renderer()
    best = None
    for loc in INSIDE_LOCATIONS:
        cost = _cost(ax, ax.legend(loc=loc, **kw), renderer)
        if cost == (0, 0):
            return ax.get_legend()
        if best is None or cost < best[0]:
            best = (cost, loc)
    if best[0][0] > 0:
        _OUTSIDE.add(ax)
        return ax.legend(**{**kw, **OUTSIDE})
    return ax.legend(loc=best[1], **kw)


def replace_legends(figure, layout):
    """Lay ``figure`` out with ``layout()`` (e.g. ``figure.tight_layout``) and place the legends
    of :func:`place_legend` again for the axes' new sizes, until none moves beside its axes
    any more. The figure widens by the widest legend beside its axes, so that the axes keep
    the width the figure was made with (and the legends inside them their room); a legend
    once beside its axes stays there, so this ends."""
    base = _BASE_WIDTH.setdefault(figure, figure.get_figwidth())
    for _ in range(len(figure.axes) + 2):
        layout()
        before = (sum(ax in _OUTSIDE for ax in figure.axes), figure.get_figwidth())
        for ax in figure.axes:
            if ax in _REQUESTED and ax.get_legend() is not None:
                place_legend(ax, **_REQUESTED[ax])
        renderer = figure.canvas.get_renderer()
        extra = max((ax.get_legend().get_window_extent(renderer).width / figure.dpi
                     + OUTSIDE_PAD_INCHES for ax in figure.axes
                     if ax in _OUTSIDE and ax.get_legend() is not None), default=0.0)
        figure.set_figwidth(base + extra)
        if (sum(ax in _OUTSIDE for ax in figure.axes), figure.get_figwidth()) == before:
            return      # the layout of this pass holds: no legend went beside its axes
    layout()


def laid_out(figure):
    """Whether :func:`replace_legends` has laid ``figure`` out."""
    return figure in _BASE_WIDTH
