# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The two errors of a campaign: a run that failed, and a folder that cannot be used."""

__all__ = ["CampaignError", "CampaignDirectoryError"]


class CampaignError(RuntimeError):
    """A run of a campaign failed, or a finished run's outputs are damaged and it cannot be
    re-run; the message names each run and its log or damaged file."""


class CampaignDirectoryError(ValueError):
    """The campaign folder cannot be used: it is not a directory, cannot be created, read or
    written, its manifest is damaged or of another format, or it holds finished runs or input
    copies that differ from the ones asked for. The message names the path and what is wrong."""
