# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The run-time-versus-error front of the redeposition (fix mc/settle) on the paper's protocol.

``tapmc-paper front run`` runs examples/paper/in.constant_eps (fresh Jullien-Meakin packing,
PBC, ``TAPS`` taps at constant eps) once per setting and seed, through :mod:`tapmc.campaign`
(resumable); ``tapmc-paper front`` measures, for every setting, its cost and its paired bias
against the reference setting and writes the page doc/front.rst. Modules, one job each:

- :mod:`.settings`: the settings, their LAMMPS keywords, the protocol and the purposes;
- :mod:`.data`: the files of the front (runs.csv, the gzipped taps.dat, meta.json);
- :mod:`.runs`: running the missing runs through tapmc.campaign and recording them;
- :mod:`.analysis`: paired biases, bounds, recommendations (typed results);
- :mod:`.summary`: front_summary.csv, which the validation reports and ``tapmc-paper plan`` read;
- :mod:`.page`: the page and its figures (drawing only);
- :mod:`.command`: the ``tapmc-paper front`` command line.

This package re-exports the names the rest of tapmc.paper reads (the page and the runs are
imported from their modules: they bring matplotlib and tapmc.campaign).
"""

from .analysis import (Estimate, Front, PairedBias, Recommendation, ReferenceCheck,
                       SettingResult, quantities, recommend,
                       worst_bias, worst_bound, worst_trend)
from .data import DATA_DIR, RUN_FIELDS, FrontDataError, read_runs, read_taps, taps_path
from .settings import (BOUNDED, DEFAULT, EPS, OBSERVABLES, PRESET_PURPOSE, PURPOSES,
                       QUANTITY_NAMES, REFERENCE, SETTINGS, SIZES, STEADY_LAST, TAPS, TIGHTER,
                       TIMES, box_side_R, lammps_line, seeds, setting_named, settle_keys,
                       time_window, wanted)
from .summary import SUMMARY, bias_sentence, read_summary

__all__ = ["Estimate", "Front", "PairedBias", "Recommendation", "ReferenceCheck", "SettingResult",
           "quantities", "recommend", "worst_bias",
           "worst_bound", "worst_trend", "DATA_DIR", "RUN_FIELDS", "FrontDataError",
           "read_runs", "read_taps", "taps_path", "BOUNDED", "DEFAULT", "EPS", "OBSERVABLES",
           "PRESET_PURPOSE", "PURPOSES", "QUANTITY_NAMES", "REFERENCE", "SETTINGS", "SIZES",
           "STEADY_LAST", "TAPS", "TIGHTER", "TIMES", "box_side_R", "lammps_line", "seeds",
           "setting_named", "settle_keys", "time_window", "wanted", "SUMMARY", "bias_sentence",
           "read_summary"]
