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

import importlib

# The submodules, and the classes and functions exported here by the one that defines them.
_EXPORTS = {
    "ageing": ("Ageing",),
    "connected_ageing": ("ConnectedAgeing",),
    "contacts": ("Contacts",),
    "crystallinity": ("Crystallinity",),
    "cylinder": ("Cylinder",),
    "fluctuations": ("PowerSpectrum", "SteadyState", "sigma_scaling", "sigma_x"),
    "hysteresis": ("Hysteresis",),
    "laws": ("AgeingLaw", "FitResult", "InverseLogLaw", "ProfileLaw", "TwoExponentials", "ZLaw",
             "profile_gradient"),
    "packing": ("PackingCheck",),
    "pores": ("TetrahedralLaw", "VolumeTail", "percus_yevick_p0", "read_pores"),
    "profiles": ("ProfileIncrease", "transversal_profile", "vertical_profile"),
    "readers": ("TapmcFormatError", "read_ave_time", "read_dump", "read_fix_print", "read_log"),
    "tube": ("TubeProfile", "TubeStereology"),
    "tube_runs": ("RadialProfiles", "TubeCompaction", "TubeSettings"),
}
_SUBMODULES = tuple(_EXPORTS)
_HOME = {name: module for module, names in _EXPORTS.items() for name in names}
# what every analysis class raises when a result is read before compute()
_HOME["NotComputedError"] = "_validate"


def __getattr__(name):
    """Submodules and their exported names load on first use (PEP 562): ``import tapmc.readers``
    or a ``tapmc-paper --help`` does not pay for scipy.stats and the fits (about 0.4 s)."""
    if name in _SUBMODULES:
        return importlib.import_module(f"{__name__}.{name}")
    if name in _HOME:
        value = getattr(importlib.import_module(f"{__name__}.{_HOME[name]}"), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))


__all__ = list(_SUBMODULES) + sorted(_HOME)
