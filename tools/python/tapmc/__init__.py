# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc: analysis of TAPMC tapping runs (Philippe & Bideau, sections III and IV).

Submodules: ``readers`` (LAMMPS logs, fix ave/time and fix print files, dumps), ``laws``
(fits of eqs. 3, 4, 6, 7 and a sum of two exponentials), ``fluctuations`` (steady state,
power spectrum, sigma_X), ``hysteresis`` (ramp runs of Fig. 4), ``ageing`` (eqs. 5, 6),
``profiles`` (delta Phi_lateral / central, vertical profiles) and ``pores`` (tapmc-pores
outputs, the tetrahedral law, the volume tail, Percus-Yevick P0). See doc/python_analysis.rst.
"""

__version__ = "0.1.0"

from . import ageing, fluctuations, hysteresis, laws, pores, profiles, readers  # noqa: F401
from .ageing import Ageing  # noqa: F401
from .fluctuations import PowerSpectrum, SteadyState, sigma_scaling, sigma_x  # noqa: F401
from .hysteresis import Hysteresis  # noqa: F401
from .laws import (AgeingLaw, FitResult, InverseLogLaw, ProfileLaw, TwoExponentials,  # noqa: F401
                   ZLaw, profile_gradient)
from .pores import (TetrahedralLaw, VolumeTail, percus_yevick_p0, read_pores)  # noqa: F401
from .profiles import ProfileIncrease, transversal_profile, vertical_profile  # noqa: F401
from .readers import (TapmcFormatError, read_ave_time, read_dump, read_fix_print,  # noqa: F401
                      read_log)
