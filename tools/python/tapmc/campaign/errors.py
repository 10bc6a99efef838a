# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The two errors of a campaign: a run that failed, and a folder that cannot be used."""

__all__ = ["CampaignError", "CampaignDirectoryError", "CampaignStopped", "STOPPED_STATUS"]

#: Exit status of a command whose campaign was stopped by SIGTERM or Ctrl-C (its runs'
#: attempts recorded; running it again resumes them): neither success (0) nor a failed run (1).
STOPPED_STATUS = 3


class CampaignError(RuntimeError):
    """A run of a campaign failed, or a finished run's outputs are damaged and it cannot be
    re-run; the message names each run and its log or damaged file."""


class CampaignStopped(CampaignError):
    """The campaign was stopped by a signal (SIGTERM, or SIGINT: Ctrl-C) while it ran: its
    LAMMPS children were stopped and each one's attempt recorded (wall and CPU time, the last
    tap written), and runs not yet started were left alone. ``signal``: the signal's name.
    Running the campaign again resumes every unfinished run from its latest restart file."""

    def __init__(self, message, signal):
        super().__init__(message)
        self.signal = signal


class CampaignDirectoryError(ValueError):
    """The campaign folder cannot be used: it is not a directory, cannot be created, read or
    written, its manifest is damaged or of another format, or it holds finished runs or input
    copies that differ from the ones asked for. The message names the path and what is wrong."""
