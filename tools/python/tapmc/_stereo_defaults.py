# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""compute stereo/profile's defaults (doc/compute_stereo_profile.rst), shared by the box's
check (:mod:`tapmc.packing`) and the tube's (:mod:`tapmc.tube`): the Phi_b slab 4R, surface
columns 2R wide, the <Phi^c> window up to 90 % of the surface height, the wall band R with the
perturbed-zone factor 16/11 (section III.A); R is the mean radius."""

import math

BULK_OVER_R = 4.0
COLUMN_OVER_R = 2.0
TOP_FRACTION = 0.9
WALL_BAND_OVER_R = 1.0
WALL_FACTOR = 16.0 / 11.0
#: a length that is a whole number of columns in one unit system (6 diameters of 0.2) is one
#: within rounding in another (1.2 / 0.2 = 5.999...): the count is floor(length / width +
#: this), as the compute's (kColumnCountRounding)
COLUMN_COUNT_ROUNDING = 1e-9
#: the compute's most columns along x and along y (kMaxColumnsPerAxis): the default width is
#: widened to length / this beyond it; a width given narrower is refused
MAX_COLUMNS_PER_AXIS = 4096


def column_count(length, width, given=False):
    """The number of h_s columns across ``length`` for columns ``width`` wide, the compute's
    rule (tapmc_stereology.cpp, make_column_grid): floor(length / width + 1e-9), at least 1;
    beyond MAX_COLUMNS_PER_AXIS the default width is widened, a ``given`` one refused."""
    columns = math.floor(length / width + COLUMN_COUNT_ROUNDING)
    if columns > MAX_COLUMNS_PER_AXIS:
        if given:
            raise ValueError(f"column = {width:g} is outside the allowed range "
                             f"[{length / MAX_COLUMNS_PER_AXIS:g}, inf) (at most "
                             f"{MAX_COLUMNS_PER_AXIS} columns across {length:g})")
        columns = MAX_COLUMNS_PER_AXIS
    return max(1, int(columns))
