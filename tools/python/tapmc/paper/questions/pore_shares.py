# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Fig. 10's pores read as two questions (its CSV, no measurement of its own): how much the
small pores change against the large ones, and how closely (xi - xi_T)^2 follows xi^3 P(xi)
between xi_T and xi_O, the two pore claims a precise single run rejects. A section of the
page without a command."""

from __future__ import annotations

import math

import numpy as np

from tapmc.pores import XI_T

from ..claims import fmt, pore_law_deviation

#: rms departure of the (xi - xi_T)^2 law from xi^3 P(xi), relative to the curve's largest
#: value between xi_T and xi_O, below which the law is called a fair description of the shape
#: (the paper's "reasonably well", read off its figure: a tenth of the curve's height is
#: about the width of its plotted line and symbols)
LAW_FAIR_DEVIATION = 0.1
#: the small pores change "about as much" as the large ones, relative to their own size, when
#: their relative change is at least this share of the large pores'
AS_MUCH_SHARE = 0.5


def relative_change(a, ea, b, eb):
    """(b - a) / a and its error (independent errors)."""
    r = (b - a) / a
    return r, abs(b / a) * math.hypot(ea / a, eb / b)


def render(fig10):
    """The small pores against the large ones and the (xi - xi_T)^2 law, from Fig. 10's CSV."""
    if fig10 is None:
        return []
    small, large = fig10.get("params", "small"), fig10.get("params", "large")
    if small is None or large is None or len(small[0]) < 2 or not np.all(np.isfinite(small[2])):
        return []
    t0, t1 = small[0][0], small[0][-1]
    rel = {name: relative_change(c[1][0], c[2][0], c[1][-1], c[2][-1])
           for name, c in (("small", small), ("large", large))}
    absolute = abs(large[1][-1] - large[1][0]) / abs(small[1][-1] - small[1][0])
    as_much = abs(rel["small"][0]) >= AS_MUCH_SHARE * abs(rel["large"][0])
    lines = [f"Are the small pores (xi_T to xi_O) unaffected by the taps (Fig. 10)? Their share of "
             f"xi^3 P(xi) from t = {t0:g} to t = {t1:g}: {fmt(small[1][0], small[2][0])} -> "
             f"{fmt(small[1][-1], small[2][-1])} ({fmt(rel['small'][0], rel['small'][1], True)}); "
             f"the large pores' (beyond xi_O): {fmt(large[1][0], large[2][0])} -> "
             f"{fmt(large[1][-1], large[2][-1])} ({fmt(rel['large'][0], rel['large'][1], True)}). "
             f"In absolute terms, the scale of the paper's figure, the small pores' share moves "
             f"{absolute:.1f} times less than the large pores'; "
             + ("relative to their own size they change about as much: the paper's 'not notably "
                "affected' holds on the figure's scale only, and the claim's rule (no change "
                "beyond the error) rejects it." if as_much else
                "relative to their own size too they change much less: the taps act on the "
                "large pores."), ""]
    law = pore_law_deviation(fig10)
    if law is not None:
        xi_t = fig10.get("params", "xi_T")
        onset = ""
        if xi_t is not None and np.isfinite(xi_t[2][-1]):
            onset = (f" Fitted with a free onset (``tapmc.pores.TetrahedralLaw``, 0.15 to xi_O) "
                     f"the law starts at xi = {fmt(xi_t[1][-1], xi_t[2][-1], digits=4)}, "
                     f"{abs(xi_t[1][-1] - XI_T) / xi_t[2][-1]:.1f} errors "
                     f"{'below' if xi_t[1][-1] < XI_T else 'above'} the tetrahedral site "
                     f"{XI_T:.4f}, where the smallest pore lies.")
        lines += [f"How closely does (xi - xi_T)^2 follow xi^3 P(xi) between xi_T and xi_O "
                  f"(t = {law['t']:g}, {law['bins']} bins, amplitude fitted)? Relative to the "
                  f"curve's largest value there, the law departs from the histogram by "
                  f"{100 * law['rms']:.1f} % rms, at most {100 * law['max']:.1f} % (at xi = "
                  f"{law['at']:.3f}), against bin errors of {100 * law['error']:.1f} % "
                  "(median): "
                  + ("a fair description of the shape, as the paper says ('reasonably well'), "
                     "but not the law of the data at their precision, which the fit rule "
                     "tests." if law["rms"] < LAW_FAIR_DEVIATION else
                     "not a fair description of the shape.") + onset, ""]
    return lines

