# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""compute stereo/profile's defaults (doc/compute_stereo_profile.rst), shared by the box's
check (:mod:`tapmc.packing`) and the tube's (:mod:`tapmc.tube`): the Phi_b slab 4R, surface
columns 2R wide, the <Phi^c> window up to 90 % of the surface height, the wall band R with the
perturbed-zone factor 16/11 (section III.A); R is the mean radius."""

BULK_OVER_R = 4.0
COLUMN_OVER_R = 2.0
TOP_FRACTION = 0.9
WALL_BAND_OVER_R = 1.0
WALL_FACTOR = 16.0 / 11.0
