# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc: analysis of TAPMC tapping runs (Philippe & Bideau, sections III and IV).

Submodules: ``readers`` (LAMMPS logs, fix ave/time and fix print files, dumps), ``laws``
(fits of eqs. 3, 4, 6, 7 and a sum of two exponentials), ``fluctuations`` (steady state,
power spectrum, sigma_X), ``hysteresis`` (ramp runs of Fig. 4), ``ageing`` (eqs. 5, 6),
``connected_ageing`` (the drift-free two-time function and a collapse without a law),
``profiles`` (delta Phi_lateral / central, vertical profiles), ``pores`` (tapmc-pores
outputs, the tetrahedral law, the volume tail, Percus-Yevick P0), ``packing`` (one dumped
packing checked offline: overlaps, floor, walls, the stereology scalars), ``crystallinity``
(Steinhardt q4, q6 and the ten Wolde-Frenkel crystalline spheres of a packing, per zone and
height band), ``contacts`` (coordination numbers within a gap and their distribution, as
compute contacts counts them), and for runs in a vertical tube ``cylinder`` (the container and
the volume of a sphere inside a coaxial cylinder), ``tube`` (the stereology of a dump in the
tube: Phi over the disk, the wall zone and core, the radial profile) and ``tube_runs`` (a tube
run's settings, compaction curve and radial profiles). See doc/python_analysis.rst.
"""

__version__ = "0.1.0"

from . import (ageing, connected_ageing, contacts, crystallinity, cylinder, fluctuations,
               hysteresis, laws, packing, pores, profiles, readers, tube, tube_runs)
from .ageing import Ageing
from .connected_ageing import ConnectedAgeing
from .contacts import Contacts
from .crystallinity import Crystallinity
from .cylinder import Cylinder
from .fluctuations import PowerSpectrum, SteadyState, sigma_scaling, sigma_x
from .hysteresis import Hysteresis
from .laws import (AgeingLaw, FitResult, InverseLogLaw, ProfileLaw, TwoExponentials,
                   ZLaw, profile_gradient)
from .packing import PackingCheck
from .pores import (TetrahedralLaw, VolumeTail, percus_yevick_p0, read_pores)
from .profiles import ProfileIncrease, transversal_profile, vertical_profile
from .readers import (TapmcFormatError, read_ave_time, read_dump, read_fix_print,
                      read_log)
from .tube import TubeProfile, TubeStereology
from .tube_runs import RadialProfiles, TubeCompaction, TubeSettings

__all__ = ["ageing", "connected_ageing", "contacts", "crystallinity", "cylinder", "fluctuations",
           "hysteresis", "laws", "packing", "pores", "profiles", "readers", "tube", "tube_runs",
           "Ageing", "ConnectedAgeing", "Contacts", "Crystallinity", "Cylinder",
           "TubeProfile", "TubeStereology", "RadialProfiles", "TubeCompaction", "TubeSettings",
           "PowerSpectrum", "SteadyState", "sigma_scaling", "sigma_x",
           "Hysteresis", "AgeingLaw", "FitResult", "InverseLogLaw", "ProfileLaw",
           "TwoExponentials", "ZLaw", "profile_gradient", "PackingCheck", "TetrahedralLaw",
           "VolumeTail", "percus_yevick_p0", "read_pores",
           "ProfileIncrease", "transversal_profile", "vertical_profile", "TapmcFormatError",
           "read_ave_time", "read_dump", "read_fix_print", "read_log"]
