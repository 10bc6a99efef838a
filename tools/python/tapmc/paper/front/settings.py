# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The settings of the front: the redeposition settings of fix mc/settle that trade accuracy
for time, the protocol they run (examples/paper/in.constant_eps: tap strengths, taps, sizes,
seeds), their LAMMPS keywords, and the purposes the recommendations serve."""

import math

#: taps of every run: the medium preset's run length (the paper's is 4000)
TAPS = 1000
#: tap strengths: the paper's central value (Figs. 2, 9) and the strong taps of Figs. 6-8
EPS = (0.0225, 0.1)
#: sizes the front is made for: the medium preset's and the paper's
SIZES = (1024, 4096)
#: times at which the settings are compared (taps), and the steady window (last taps)
TIMES = (1, 10, 100, 1000)
STEADY_LAST = 250
#: sphere radius of in.constant_eps (distance units): d_max values below are in these units
RADIUS = 0.5
#: two tap strengths closer than this are the same eps (they are written with %g)
EPS_MATCH = 1e-12

# name -> fix mc/settle eta, further keywords (check given in sweeps, turned into trials), and
# the eps values it runs at (None: every eps of the front). The d_max and check variations
# change one knob of the package default; the stop rule variations are the stop drift rule
# (fix_mc_settle.rst): drift eta = 4e-7 reproduces the default's sweeps at N = 4096.
SETTINGS = {
    "change 1e-5": {"eta": "1e-5", "keys": {}, "eps": None},
    "change 1e-6": {"eta": "1e-6", "keys": {}, "eps": None},
    "change 1e-7 (default)": {"eta": "1e-7", "keys": {}, "eps": None},
    "change 1e-8": {"eta": "1e-8", "keys": {}, "eps": None},
    "drift 4e-7": {"eta": "4e-7", "keys": {"stop": "drift"}, "eps": None},
    "drift 1e-7": {"eta": "1e-7", "keys": {"stop": "drift"}, "eps": None},
    "drift 3e-8": {"eta": "3e-8", "keys": {"stop": "drift"}, "eps": (0.0225,)},
    "dmax R/10": {"eta": "1e-7", "keys": {"dmax": 0.1 * RADIUS}, "eps": (0.0225,)},
    "dmax R/2": {"eta": "1e-7", "keys": {"dmax": 0.5 * RADIUS}, "eps": (0.0225,)},
    "check 10 sweeps, 1e-6": {"eta": "1e-6", "keys": {"check_sweeps": 10}, "eps": (0.0225,)},
}
DEFAULT = "change 1e-7 (default)"
REFERENCE = "drift 1e-7"
TIGHTER = ("drift 3e-8",)
FIRST_SEED = 4928
SEED_STEP = 1117
#: the package's default eta (fix_mc_settle.rst): a LAMMPS line does not repeat it
PACKAGE_ETA = 1e-7

#: observables compared (taps.dat columns) and their labels
OBSERVABLES = (("phi_b", "Phi_b"), ("phi_c", "<Phi^c>"), ("Z", "<Z>"))
#: purposes, most demanding first: (name, tolerance, what the tolerance bounds) on <Phi^c>
#: (BOUNDED). Publication: the 95 % bound of the bias itself within 0.001, the last digit the
#: paper quotes (60.6 %). Exploration: 0.003, a tenth of the rise of <Phi^c> over the paper's
#: 4000 taps at eps = 0.0225 (58 % to 60.6 %), on the part of the bias that changes with eps
#: or with the tap count (the 95 % bound of the paired difference of the biases at two eps or
#: two windows): exploration compares curves run at one setting, and a bias common to every eps
#: and tap moves all curves alike, leaving their shapes, trends and orderings as they are; the
#: bias itself is stated. Smoke test: no bound,
#: the cheapest setting (its bias is stated).
PURPOSES = (("publication", 0.001, "bias"), ("exploration", 0.003, "trend"),
            ("smoke test", None, None))
#: the quantities the purposes bound: <Phi^c> (the paper's headline measure, Figs. 4-5, 9)
#: around tap 100 and steady. Phi_b (the paper's bottom packing fraction, Fig. 2) is shown, not
#: bounded: its paired differences scatter several times more from seed to seed (see the page's
#: table), so bounding it at these tolerances would take many times the seeds.
BOUNDED = ("phi_c_t100", "phi_c_steady")
#: the preset of tapmc-paper made for each purpose
PRESET_PURPOSE = {"quick": "smoke test", "medium": "exploration", "full": "publication"}
#: every quantity measured on a run: each observable around each of TIMES taps and steady
QUANTITY_NAMES = tuple(f"{k}_{w}" for k, _ in OBSERVABLES
                       for w in [f"t{t}" for t in TIMES] + ["steady"])


def box_side_R(N):
    """Box side in units of R for N spheres: the paper's 32R at N = 4096, same bed height."""
    return 32.0 * math.sqrt(N / 4096.0)


def settle_keys(name, N):
    """The fix mc/settle keywords (besides eta) of setting `name` for N spheres."""
    keys = SETTINGS[name]["keys"]
    words = []
    for key, value in keys.items():
        if key == "check_sweeps":
            words += ["check", str(int(value) * N)]
        else:
            words += [key, value if isinstance(value, str) else "%g" % value]
    return " ".join(words) if words else "check 0"


def wanted(name, eps):
    """Whether setting `name` runs at tap strength eps."""
    only = SETTINGS[name]["eps"]
    return only is None or any(abs(eps - e) < EPS_MATCH for e in only)


def seeds(count):
    """The first `count` seeds of the front (a seed fixes the packing and the moves)."""
    return [FIRST_SEED + SEED_STEP * k for k in range(count)]


def time_window(t, taps=TAPS):
    """Taps (first, last) averaged for "after t taps": t +- 10 % within the run (tap 1 alone).
    One tap's value scatters by the tap-to-tap fluctuation (sigma of a few 1e-3 at N = 1024),
    which the window averages down; the first taps differ by setting, not yet by chance."""
    return max(1, round(0.9 * t)), min(taps, round(1.1 * t))


def lammps_line(setting, N=4096):
    """The fix mc/settle command of a setting of SETTINGS (spheres of radius RADIUS on a floor
    at z = 0); the package default eta (1e-7) is not written."""
    keys = settle_keys(setting, N)
    words = ["fix", "settle", "all", "mc/settle", "SEED", "floor", "0.0"]
    words += [] if keys == "check 0" else keys.split()
    eta = SETTINGS[setting]["eta"]
    return " ".join(words + ([] if float(eta) == PACKAGE_ETA else ["eta", eta]))


def setting_named(eta, stop="change"):
    """The front's setting with this eta and stop rule and no other keyword, or None."""
    for name, s in SETTINGS.items():
        kw = dict(s["keys"])
        rule = kw.pop("stop", "change")
        if rule == stop and not kw and float(s["eta"]) == float(eta):
            return name
    return None
