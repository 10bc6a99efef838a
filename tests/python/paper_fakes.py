# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""A campaign made of written files, for figure tests that must not run LAMMPS: the run specs of
the figure modules, and per run the outputs the figures read (``taps.dat``, ``profile_x.dat``)
with values the test chooses, so that every number of the figure's CSV has a known answer."""

from pathlib import Path

TAPS_TITLE = "# step phi_b phi_c Z z_top lateral central h_s sweeps accept capped"
RAMP_TITLE = "# step level branch sqrt_eps phi_b phi_c Z"


class FakeCampaign:
    """What the figure modules read of a Campaign: ``runs``, ``directory``, ``result(name)``."""

    def __init__(self, directory, runs):
        self.directory = Path(directory)
        self.runs = list(runs)

    def result(self, name):
        folder = self.directory / "runs" / name
        folder.mkdir(parents=True, exist_ok=True)
        return folder


def write_constant_eps(campaign, spec, lateral, central):
    """taps.dat of a constant-eps run: the given lateral and central means per tap (t = 0, 1,
    ...), every other column constant."""
    rows = [TAPS_TITLE]
    for t, (lat, cen) in enumerate(zip(lateral, central)):
        rows.append(f"{t} 0.55 0.56 5.0 9.0 {lat:.10f} {cen:.10f} 10.0 100 0.1 0")
    (campaign.result(spec.name) / "taps.dat").write_text("\n".join(rows) + "\n")


def write_profile_x(campaign, spec, x, initial, final, taps):
    """profile_x.dat (fix ave/time vector mode) with the bin means ``initial`` at t = 0 and
    ``final`` at t = ``taps``; ``x`` the bin centres (distance units)."""
    lines = ["# Time-averaged data for fix xprof", "# TimeStep Number-of-rows",
             "# Row c_tprof[1] c_tprof[2] c_tprof[3]"]
    for step, phi in ((0, initial), (taps, final)):
        lines.append(f"{step} {len(x)}")
        lines += [f"{i + 1} {xi:.6f} {p:.8f} {p:.8f}" for i, (xi, p) in enumerate(zip(x, phi))]
    (campaign.result(spec.name) / "profile_x.dat").write_text("\n".join(lines) + "\n")


def write_ramp(campaign, spec, sqrt_eps_per_tap, phi_c_per_tap):
    """taps.dat of a ramp run (in.ramp's columns) from per-tap sqrt(eps) and <Phi^c> (tap 1 on;
    a row of step 0 is added)."""
    rows = [RAMP_TITLE, "0 -1 0 0.000000 0.55 0.56 5.0"]
    per_level = int(spec.variables["P"])
    for k, (sq, phi) in enumerate(zip(sqrt_eps_per_tap, phi_c_per_tap)):
        rows.append(f"{k + 1} {k // per_level} 0 {sq:.6f} 0.55 {phi:.10f} 5.0")
    (campaign.result(spec.name) / "taps.dat").write_text("\n".join(rows) + "\n")
