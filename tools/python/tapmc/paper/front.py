# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The run-time-versus-error front of the redeposition (fix mc/settle) on the paper's protocol.

``bench/paper_front.py`` runs examples/paper/in.constant_eps (fresh Jullien-Meakin packing, PBC,
``TAPS`` taps at constant eps) once per setting and seed; this module holds the settings, reads
the runs and measures, for every setting, its cost (CPU s and sweeps per tap) and its bias
against the reference setting on what the paper reports: Phi_b, <Phi^c> and <Z> after 1, 10,
100 and 1000 taps and their means over the steady window. Settings are compared seed by seed:
a seed fixes the initial packing and the moves' seed, so the difference of two settings on one
seed removes most of the packing-to-packing scatter (paired differences, Student's t over the
seeds).

The reference is the tightest setting that runs in the budget (``REFERENCE``); it is shown to be
converged when the still tighter settings (``TIGHTER``) agree with it within their error.
"""

import csv
import gzip
import math
import os

from tapmc.stats import t_quantile_of_mean

#: where bench/paper_front.py writes (relative to the repository) and this module reads
DATA_DIR = os.path.join("doc", "validation", "front")
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

RUN_FIELDS = ["setting", "N", "eps", "seed", "taps", "eta", "settle_keys", "cpu_s", "wall_s",
              "cpu_per_tap", "sweeps_per_tap", "capped_taps"]
TAPS_COLUMNS = ["step", "phi_b", "phi_c", "Z", "z_top", "lateral", "central", "h_s", "sweeps",
                "accept", "capped"]


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
    return only is None or any(abs(eps - e) < 1e-12 for e in only)


def seeds(count):
    return [FIRST_SEED + SEED_STEP * k for k in range(count)]


def taps_path(out_dir, name, N, eps, seed):
    slug = name.replace(" ", "_").replace("/", "_over_").replace("(", "").replace(")", "").replace(",", "")
    return os.path.join(out_dir, "taps", "N%d_eps%g" % (N, eps), "%s_s%d.dat.gz" % (slug, seed))


def read_taps(path):
    """Rows (dict column -> number) of a taps.dat table, plain or gzipped, step 0 excluded."""
    opener = gzip.open if path.endswith(".gz") else open
    rows = []
    with opener(path, "rt") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            values = [float(w) for w in line.split()]
            row = dict(zip(TAPS_COLUMNS, values))
            row["step"] = int(row["step"])
            if row["step"] > 0:
                rows.append(row)
    return rows


def read_runs(path):
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def run_key(row):
    return (row["setting"], int(row["N"]), "%g" % float(row["eps"]), int(row["seed"]), int(row["taps"]))


# ---- analysis ----------------------------------------------------------------------------------

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


_t95 = t_quantile_of_mean  # the report's t quantile (tapmc.stats) for the mean of n seeds


def time_window(t, taps=TAPS):
    """Taps (first, last) averaged for "after t taps": t +- 10 % within the run (tap 1 alone).
    One tap's value scatters by the tap-to-tap fluctuation (sigma of a few 1e-3 at N = 1024),
    which the window averages down; the first taps differ by setting, not yet by chance."""
    return max(1, round(0.9 * t)), min(taps, round(1.1 * t))


def quantities(rows, taps=TAPS):
    """name -> value of one run's table: each observable around each of TIMES taps (mean over
    time_window) and its mean over the last STEADY_LAST taps."""
    out = {}
    for key, _ in OBSERVABLES:
        for t in TIMES:
            lo, hi = time_window(t, taps)
            if hi <= len(rows):
                out[f"{key}_t{t}"] = sum(r[key] for r in rows[lo - 1:hi]) / (hi - lo + 1)
        window = rows[-STEADY_LAST:] if len(rows) >= taps else []
        if window:
            out[f"{key}_steady"] = sum(r[key] for r in window) / len(window)
    # the window before the steady one: whether the packing still moves (not a QUANTITY_NAME)
    before = rows[-2 * STEADY_LAST:-STEADY_LAST] if len(rows) >= max(taps, 2 * STEADY_LAST) else []
    if before:
        out["phi_c_rise"] = out["phi_c_steady"] - sum(r["phi_c"] for r in before) / len(before)
    return out


QUANTITY_NAMES = tuple(f"{k}_{w}" for k, _ in OBSERVABLES
                       for w in [f"t{t}" for t in TIMES] + ["steady"])


def _mean_se(values):
    n = len(values)
    if n == 0:
        return math.nan, math.nan
    m = sum(values) / n
    if n < 2:
        return m, math.nan
    return m, math.sqrt(sum((v - m) ** 2 for v in values) / (n - 1) / n)


class Front:
    """The front measured in ``data_dir`` (runs.csv and taps/): ``compute()`` returns self;
    ``table`` (one dict per N, eps and setting), ``recommendations`` (purpose -> dict),
    ``reference_check`` (the tighter settings against the reference), ``write_csv`` and
    ``plot(N, ax=None)``; :func:`render_rst` writes its page."""

    def __init__(self, data_dir):
        self.data_dir = os.fspath(data_dir)
        runs_csv = os.path.join(self.data_dir, "runs.csv")
        if not os.path.isfile(runs_csv):
            raise FileNotFoundError(f"Front: no runs.csv in {self.data_dir} "
                                    "(run bench/paper_front.py first)")
        self.runs = [r for r in read_runs(runs_csv) if int(r["taps"]) == TAPS]
        if not self.runs:
            raise ValueError(f"Front: {runs_csv} has no run of {TAPS} taps")
        unknown = sorted({r["setting"] for r in self.runs} - set(SETTINGS))
        if unknown:
            raise ValueError(f"Front: {runs_csv} names settings this module does not know: {unknown}")
        self._table = None

    def compute(self):
        per_run = {}
        for r in self.runs:
            N, eps, seed = int(r["N"]), float(r["eps"]), int(r["seed"])
            rows = read_taps(taps_path(self.data_dir, r["setting"], N, eps, seed))
            per_run[(N, "%g" % eps, r["setting"], seed)] = (r, quantities(rows))
        table = []
        paired = {}  # (N, setting) -> (quantity, eps) -> seed -> bias on that seed
        groups = sorted({(k[0], float(k[1])) for k in per_run})
        for N, eps in groups:
            e = "%g" % eps
            ref = {k[3]: v[1] for k, v in per_run.items() if k[:3] == (N, e, REFERENCE)}
            for name in SETTINGS:
                mine = {k[3]: v for k, v in per_run.items() if k[:3] == (N, e, name)}
                if not mine:
                    continue
                seeds_ = sorted(mine)
                row = {"N": N, "eps": eps, "setting": name, "eta": SETTINGS[name]["eta"],
                       "settle_keys": mine[seeds_[0]][0]["settle_keys"], "seeds": len(seeds_)}
                row["cpu_per_tap"], row["cpu_per_tap_se"] = _mean_se(
                    [float(mine[s][0]["cpu_per_tap"]) for s in seeds_])
                row["sweeps_per_tap"], _ = _mean_se([float(mine[s][0]["sweeps_per_tap"]) for s in seeds_])
                row["capped_taps"] = sum(int(mine[s][0]["capped_taps"]) for s in seeds_)
                common = [s for s in seeds_ if s in ref]
                row["paired_seeds"] = len(common)
                row["phi_c_rise"], row["phi_c_rise_se"] = _mean_se(
                    [mine[s][1]["phi_c_rise"] for s in seeds_ if "phi_c_rise" in mine[s][1]])
                t95 = _t95(len(common))
                for q in QUANTITY_NAMES:
                    row[q], row[q + "_se"] = _mean_se([mine[s][1][q] for s in seeds_ if q in mine[s][1]])
                    by_seed = {s: mine[s][1][q] - ref[s][q] for s in common
                               if q in mine[s][1] and q in ref[s]}
                    if q in BOUNDED:
                        paired.setdefault((N, name), {})[(q, eps)] = by_seed
                    diffs = list(by_seed.values())
                    d, se = _mean_se(diffs)
                    row[q + "_bias"], row[q + "_bias_se"] = d, se
                    row[q + "_bias_bound"] = abs(d) + t95 * se if len(diffs) > 1 else math.nan
                table.append(row)
        for row in table:
            for q in BOUNDED:
                row[q + "_trend_bound"] = _trend_bound(paired.get((row["N"], row["setting"]), {}),
                                                       (q, row["eps"]))
        self._table = table
        return self

    def _need(self):
        if self._table is None:
            raise RuntimeError("Front: call compute() first")
        return self._table

    @property
    def table(self):
        return self._need()

    def rows(self, N=None, eps=None, setting=None):
        return [r for r in self._need() if (N is None or r["N"] == N)
                and (eps is None or abs(r["eps"] - eps) < 1e-12)
                and (setting is None or r["setting"] == setting)]

    @property
    def sizes(self):
        return sorted({r["N"] for r in self._need()})

    @property
    def eps_values(self):
        return sorted({r["eps"] for r in self._need()})

    def reference_check(self, N):
        """For each tighter setting at N: (name, eps, paired seeds, quantities whose 95 % interval
        of the bias excludes zero, quantities compared)."""
        out = []
        for name in TIGHTER:
            for row in self.rows(N=N, setting=name):
                if row["paired_seeds"] < 2:
                    continue
                off = [q for q in QUANTITY_NAMES if row[q + "_bias_bound"] == row[q + "_bias_bound"]
                       and abs(row[q + "_bias"]) > _t95(row["paired_seeds"]) * row[q + "_bias_se"]]
                compared = sum(1 for q in QUANTITY_NAMES if row[q + "_bias_bound"] == row[q + "_bias_bound"])
                out.append((name, row["eps"], row["paired_seeds"], off, compared))
        return out

    @property
    def compared_sizes(self):
        """The N at which the reference has run: where biases (and a figure) exist."""
        return sorted({r["N"] for r in self._need() if r["setting"] == REFERENCE})

    def recommendations(self, N):
        """purpose -> recommended setting at N (see :func:`recommend`)."""
        return recommend(self._need(), N)

    def write_csv(self, path):
        fields = list(self._need()[0].keys())
        with open(path, "w", newline="") as f:
            w = csv.DictWriter(f, fieldnames=fields)
            w.writeheader()
            for r in self._table:
                w.writerow({k: (("%.6g" % v) if isinstance(v, float) else v) for k, v in r.items()})
        return path

    def figure_table(self, N):
        """The numbers drawn by :meth:`plot` (a _plotting.FigureTable): panel a/b, bias of the
        steady <Phi^c> against CPU s per tap at each eps (series = setting, x = cost);
        panel c, bias of <Phi^c> against the tap count at the first eps (x = taps; the steady
        window is drawn at x = 2 TAPS)."""
        from ._plotting import FigureTable
        table = FigureTable()
        for panel, eps in zip("ab", self.eps_values):
            for r in self.rows(N=N, eps=eps):
                table.add(panel, r["setting"], r["cpu_per_tap"], r["phi_c_steady_bias"],
                          r["phi_c_steady_bias_se"], r["paired_seeds"])
        first = self.eps_values[0]
        for r in self.rows(N=N, eps=first):
            xs = list(TIMES) + [2 * TAPS]
            table.add("c", r["setting"], xs,
                      [r[f"phi_c_t{t}_bias"] for t in TIMES] + [r["phi_c_steady_bias"]],
                      [r[f"phi_c_t{t}_bias_se"] for t in TIMES] + [r["phi_c_steady_bias_se"]],
                      r["paired_seeds"])
        return table

    def plot(self, N, ax=None):
        """Panels a, b (bias against cost at each eps) and c (bias against taps); `ax`: three
        axes, or None for a new figure. Returns the axes."""
        from ._plotting import new_figure
        if ax is None:
            _, ax = new_figure(nrows=1, ncols=3, height=3.6, width=4.2)
        table = self.figure_table(N)
        by = {}
        for panel, series, x, mean, sem, n in table.rows:
            by.setdefault((panel, series), []).append((x, mean, sem))
        names = list(SETTINGS)
        colors = {name: "C%d" % (i % 10) for i, name in enumerate(names)}
        for (panel, series), pts in by.items():
            pts = [p for p in pts if p[1] == p[1]]  # no bias yet where the reference has not run
            if not pts:
                continue
            a = ax["abc".index(panel)]
            xs, ms, ss = zip(*pts)
            ss = [0.0 if s != s else s for s in ss]
            style = dict(color=colors[series], capsize=2, label=series)
            if panel == "c":
                a.errorbar(xs, ms, yerr=ss, marker="o", ms=3, lw=1, **style)
            else:
                a.errorbar(xs, ms, yerr=ss, marker="o", ms=4, linestyle="none", **style)
        for i, eps in enumerate(self.eps_values[:2]):
            ax[i].set_title(f"N = {N}, eps = {eps:g}: taps {TAPS - STEADY_LAST + 1}-{TAPS}", fontsize=9)
            ax[i].set_xscale("log")
            ax[i].set_xlabel("CPU s per tap (one core)")
            ax[i].set_ylabel(f"bias of <Phi^c> vs {REFERENCE}")
        ax[2].set_title(f"N = {N}, eps = {self.eps_values[0]:g}", fontsize=9)
        ax[2].set_xscale("log")
        ax[2].set_xlabel(f"taps (steady window drawn at {2 * TAPS})")
        ax[2].set_ylabel("bias of <Phi^c>")
        for a in ax:
            a.axhline(0.0, color="k", lw=0.5)
        for a in ax:  # where it covers the fewest points
            if a.get_legend_handles_labels()[0]:
                a.legend(fontsize=6, loc="best")
        return ax

    def write_figure(self, N, png, csv_path):
        from ._plotting import new_figure, write_figure
        fig, ax = new_figure(nrows=1, ncols=3, height=3.6, width=4.2)
        self.plot(N, ax=ax)
        return write_figure(fig, png, self.figure_table(N), csv_path)


def _trend_bound(biases, here):
    """The 95 % bound of how a setting's bias changes between the compared quantities (<Phi^c>
    around tap 100 and steady: BOUNDED) and tap strengths: for ``here`` = (quantity, eps),
    |mean of (bias here - bias there)| + t x its standard error for every other (quantity,
    eps) there, the difference taken seed by seed (the same seed gives the same packing at every
    eps); the largest, nan without another entry of 2 common seeds. ``biases``: (quantity, eps)
    -> seed -> bias on that seed."""
    mine = biases.get(here, {})
    bounds = []
    for there, theirs in biases.items():
        if there == here:
            continue
        seeds_ = sorted(set(mine) & set(theirs))
        if len(seeds_) < 2:
            continue
        d, se = _mean_se([mine[s] - theirs[s] for s in seeds_])
        bounds.append(abs(d) + _t95(len(seeds_)) * se)
    return max(bounds) if bounds else math.nan


def worst_trend(name, rows):
    """The largest trend bound (BOUNDED, see _trend_bound) of setting `name` over its `rows`
    (0 for the reference; nan when one is missing)."""
    if name == REFERENCE:
        return 0.0
    bounds = [float(r.get(q + "_trend_bound", math.nan)) for r in rows for q in BOUNDED]
    return max(bounds) if bounds and all(b == b for b in bounds) else math.nan


def worst_bias(name, rows):
    """The largest |bias| of <Phi^c> (BOUNDED) of setting `name` over its `rows`, signed."""
    biases = [float(r[q + "_bias"]) for r in rows for q in BOUNDED]
    return max(biases, key=abs) if biases else math.nan


def lammps_line(setting, N=4096):
    """The fix mc/settle command of a setting of SETTINGS (spheres of radius RADIUS on a floor
    at z = 0); the package default eta (1e-7) is not written."""
    keys = settle_keys(setting, N)
    words = ["fix", "settle", "all", "mc/settle", "SEED", "floor", "0.0"]
    words += [] if keys == "check 0" else keys.split()
    eta = SETTINGS[setting]["eta"]
    return " ".join(words + ([] if float(eta) == 1e-7 else ["eta", eta]))


def worst_bound(name, rows):
    """The largest 95 % bound (BOUNDED) of setting `name` over its `rows` (0 for the reference;
    nan when a bound is missing or there are no rows)."""
    if name == REFERENCE:
        return 0.0
    bounds = [r[q + "_bias_bound"] for r in rows for q in BOUNDED]
    return max(bounds) if bounds and all(b == b for b in bounds) else math.nan


def recommend(table, N):
    """purpose -> {setting, tolerance, worst_bound, cpu_per_tap} at N, from the rows of a Front's
    table (or of front_summary.csv): for each purpose the cheapest setting, run at every eps of
    the front, whose 95 % bounds (BOUNDED) meet the purpose's tolerance at every eps."""
    rows_at = [r for r in table if r["N"] == N]
    eps_all = sorted({r["eps"] for r in rows_at})
    candidates = []
    for name in SETTINGS:
        rows = [r for r in rows_at if r["setting"] == name]
        if len(rows) != len(eps_all):
            continue
        cost = sum(r["cpu_per_tap"] for r in rows) / len(rows)
        candidates.append((cost, name, worst_bound(name, rows), worst_trend(name, rows),
                           0.0 if name == REFERENCE else worst_bias(name, rows)))
    out = {}
    for purpose, tol, kind in PURPOSES:
        measure = {"bias": lambda c: c[2], "trend": lambda c: c[3]}.get(kind)
        ok = [c for c in candidates if measure is None or (measure(c) == measure(c) and measure(c) <= tol)]
        if ok:
            cost, name, worst, trend, bias = min(ok)
            out[purpose] = {"setting": name, "tolerance": tol, "criterion": kind,
                            "worst_bound": worst, "worst_trend": trend, "worst_bias": bias,
                            "cpu_per_tap": cost}
    return out


# ---- the page ------------------------------------------------------------------------------------

#: the summary the reports read (package data, written by ``tapmc-paper front``)
SUMMARY = os.path.join(os.path.dirname(os.path.abspath(__file__)), "front_summary.csv")
PAGE = os.path.join("doc", "front.rst")
FIGURE = "front"


def _pm(value, err, digits=4, sign=True):
    if value != value:
        return "n/a"
    text = f"{value:+.{digits}f}" if sign else f"{value:.{digits}f}"
    return text if err != err else f"{text} +- {err:.{digits}f}"


def _seeds(n):
    n = int(n)
    return f"{n} seed" if n == 1 else f"{n} seeds"


def _grid(header, rows):
    """An rst simple table."""
    cols = list(zip(*([header] + rows)))
    widths = [max(len(str(c)) for c in col) for col in cols]
    rule = "  ".join("=" * w for w in widths)
    out = [rule, "  ".join(str(h).ljust(w) for h, w in zip(header, widths)), rule]
    out += ["  ".join(str(c).ljust(w) for c, w in zip(r, widths)) for r in rows]
    out.append(rule)
    return out


def _dmax_lines(front, N):
    """The paper's d_max = R/5 ("an intermediate value", section II) against R/10 and R/2 at the
    default eta, from the rows at the first eps where all three ran."""
    for eps in front.eps_values:
        base = front.rows(N=N, eps=eps, setting=DEFAULT)
        alts = [front.rows(N=N, eps=eps, setting=n) for n in ("dmax R/10", "dmax R/2")]
        if not base or not all(alts):
            continue
        b = base[0]
        parts, beaten = [], []
        for (a,) in alts:
            ratio = a["cpu_per_tap"] / b["cpu_per_tap"]
            parts.append(f"{a['setting'][5:]} costs {ratio:.2f} times its CPU time per tap "
                         f"({a['sweeps_per_tap']:.0f} sweeps) and leaves <Phi^c> "
                         f"{_pm(a['phi_c_steady_bias'], a['phi_c_steady_bias_se'])} steady")
            se = math.hypot(a["phi_c_steady_bias_se"], b["phi_c_steady_bias_se"])
            closer = abs(b["phi_c_steady_bias"]) - abs(a["phi_c_steady_bias"]) > 2 * se
            if ratio <= 1.0 and closer:
                beaten.append(a["setting"][5:])
        verdict = ("so a d_max of " + " and ".join(beaten) + " redeposits better at no more cost "
                   "than the paper's R/5" if beaten else
                   "neither is both cheaper and closer to the reference (by two standard errors) "
                   "than the paper's R/5")
        return [f"**d_max** (section II: R/5 is \"an intermediate value\"), at eps = {eps:g} and "
                f"eta = {b['eta']}: against R/5 ({b['sweeps_per_tap']:.0f} sweeps per tap, "
                f"<Phi^c> {_pm(b['phi_c_steady_bias'], b['phi_c_steady_bias_se'])} steady), " + "; ".join(parts) + f": {verdict}.", ""]
    return []


def _default_lines(front, N, recs):
    """A sentence on the package default at N when no purpose recommends it: its bias, its two
    bounds against the tolerances, and its cost against the publication setting's."""
    rows = front.rows(N=N, setting=DEFAULT)
    if not rows or any(r["setting"] == DEFAULT for r in recs.values()) or "publication" not in recs:
        return []
    bound, trend = worst_bound(DEFAULT, rows), worst_trend(DEFAULT, rows)
    cpu = sum(r["cpu_per_tap"] for r in rows) / len(rows)
    return [f"The package default, *{DEFAULT}*, is recommended for no purpose at N = {N}: its "
            f"worst bias of <Phi^c> is {worst_bias(DEFAULT, rows):+.4f}, its 95 % bounds are "
            f"{bound:.4f} on the bias and {trend:.4f} on its change with eps and taps "
            f"(tolerances {PURPOSES[0][1]:g} and {PURPOSES[1][1]:g}), at "
            f"{cpu / recs['publication']['cpu_per_tap']:.2f} times the CPU time per tap of "
            f"*{recs['publication']['setting']}*.", ""]


def _preset_lines(front):
    """The presets of tapmc-paper, each made for a purpose: its setting, that setting's worst
    95 % bound and the setting this front recommends for the purpose, at the preset's own N
    when the front has it, else at the nearest N it has."""
    from .scales import SCALES
    body = []
    for preset, purpose in PRESET_PURPOSE.items():
        scale = SCALES[preset]
        N = min(front.compared_sizes or front.sizes, key=lambda n: (abs(math.log(n / scale.N)), n))
        name = setting_named(scale.eta)
        rows = front.rows(N=N, setting=name) if name else []
        worst = worst_bound(name, rows) if name else math.nan
        rec = front.recommendations(N).get(purpose, {})
        ratio = (rec["cpu_per_tap"] / (sum(r["cpu_per_tap"] for r in rows) / len(rows))
                 if rec and rows else math.nan)
        body.append([preset, f"N = {scale.N}, {scale.taps} taps", f"N = {N}", purpose,
                     name or f"eta {scale.eta:g} (not on the front)",
                     "n/a" if worst != worst else "%.4f" % worst, rec.get("setting", "none yet"),
                     "yes" if rec.get("setting") == name else "no",
                     "n/a" if ratio != ratio else "%.1f" % ratio])
    return ["**The presets of tapmc-paper** (:doc:`tapmc-paper`) against the recommendations, "
            "at the preset's N or the nearest N measured (last column: the CPU time per tap of "
            "the recommended setting over the preset's, mean over eps):", ""] + _grid(
        ["preset", "scale", "front at", "purpose", "its setting", "its worst 95 % bound",
         "recommended", "same", "CPU ratio"], body) + [""]


def figure_name(N):
    """File name (no extension) of the figure and CSV of the front at N."""
    return FIGURE if N == SIZES[0] else f"{FIGURE}_N{N}"


def render_rst(front, runs_note):
    """The page doc/front.rst of a computed Front; `runs_note` says which binary and machine."""
    lines = [".. TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.",
             ".. Generated by 'build/tapmc-paper front' from doc/validation/front: do not edit.", "",
             "Run time against error of the redeposition", "=" * 42, "",
             "Every setting of :doc:`fix mc/settle <fix_mc_settle>` that trades accuracy for time, "
             "measured on the paper's protocol (``examples/paper/in.constant_eps``: a fresh "
             f"Jullien-Meakin packing, periodic sides, {TAPS} taps at constant eps). Each run is one "
             "setting and one seed; the seed fixes the initial packing and the moves, so settings "
             "are compared seed by seed: *bias* is the mean over the seeds of (setting - reference) "
             "on the same seed, with its standard error, and the *95 % bound* is \\|bias\\| + t(0.975, "
             "seeds - 1) x its standard error, the largest bias the seeds allow at 95 % confidence. "
             f"The reference is *{REFERENCE}* (stop drift, eta = 1e-7: the drift of <Z> per sweep "
             "averaged over 32 checks, plus two standard errors, below 1e-7 <Z>). Cost is the CPU "
             "time of the lmp process per tap (deposition included, one core) and the sweeps "
             f"(N trial moves) per tap. Steady: the mean over the last {STEADY_LAST} taps; "
             "t = a-b: the mean over taps a to b (one tap's value scatters by the tap-to-tap "
             "fluctuation, which a window averages down).", "",
             runs_note, ""]
    for N in front.sizes:
        lines += [f"N = {N} (box {box_side_R(N):g}R x {box_side_R(N):g}R)",
                  "-" * len(f"N = {N} (box {box_side_R(N):g}R x {box_side_R(N):g}R)"), ""]
        for eps in front.eps_values:
            rows = front.rows(N=N, eps=eps)
            if not rows:
                continue
            seeds_ = max(r["seeds"] for r in rows)
            lines += [f"eps = {eps:g} ({_seeds(seeds_)}; bias of each quantity against "
                      f"*{REFERENCE}*, mean +- standard error):", ""]
            w100, w1000 = time_window(100), time_window(TAPS)
            header = ["setting", "sweeps/tap", "CPU s/tap", "<Phi^c> t=1",
                      "<Phi^c> t=%d-%d" % w100, "<Phi^c> t=%d-%d" % w1000, "<Phi^c> steady",
                      "Phi_b steady", "<Z> steady",
                      "95 % bound"]
            body = []
            for r in rows:
                bound = max((r[q + "_bias_bound"] for q in BOUNDED), default=math.nan)
                body.append([r["setting"] + (f" ({_seeds(r['seeds'])})" if r["seeds"] != seeds_ else ""),
                             "%.0f" % r["sweeps_per_tap"], "%.3f" % r["cpu_per_tap"],
                             _pm(r["phi_c_t1_bias"], r["phi_c_t1_bias_se"]),
                             _pm(r["phi_c_t100_bias"], r["phi_c_t100_bias_se"]),
                             _pm(r["phi_c_t1000_bias"], r["phi_c_t1000_bias_se"]),
                             _pm(r["phi_c_steady_bias"], r["phi_c_steady_bias_se"]),
                             _pm(r["phi_b_steady_bias"], r["phi_b_steady_bias_se"]),
                             _pm(r["Z_steady_bias"], r["Z_steady_bias_se"], digits=3),
                             "reference" if r["setting"] == REFERENCE else
                             ("n/a" if bound != bound else "%.4f" % bound)])
            lines += _grid(header, body) + [""]
            ref = front.rows(N=N, eps=eps, setting=REFERENCE)
            if ref:
                r = ref[0]
                lines += [f"Reference values (mean +- standard error over {_seeds(r['seeds'])}): "
                          f"<Phi^c> = {_pm(r['phi_c_t1'], r['phi_c_t1_se'], sign=False)} after one tap, "
                          f"{_pm(r['phi_c_t1000'], r['phi_c_t1000_se'], sign=False)} over taps "
                          "%d-%d, " % time_window(TAPS) +
                          f"{_pm(r['phi_c_steady'], r['phi_c_steady_se'], sign=False)} steady; "
                          f"Phi_b = {_pm(r['phi_b_steady'], r['phi_b_steady_se'], sign=False)} steady; "
                          f"<Z> = {_pm(r['Z_steady'], r['Z_steady_se'], digits=3, sign=False)} steady. "
                          f"From taps {TAPS - 2 * STEADY_LAST + 1}-{TAPS - STEADY_LAST} to the steady "
                          f"window <Phi^c> changes by {_pm(r['phi_c_rise'], r['phi_c_rise_se'])}: "
                          + ("one seed cannot say whether it still moves." if r["seeds"] < 2 else
                             f"no change resolved at 95 % confidence (t = {_t95(r['seeds']):.3g})." if
                             abs(r["phi_c_rise"]) <= _t95(r["seeds"]) * r["phi_c_rise_se"] else
                             "the packing still compacts, so the steady column is the mean of "
                             "that window, not a limit."),
                          ""]
        lines += _dmax_lines(front, N)
        checks = front.reference_check(N)
        if checks:
            lines += ["**Is the reference converged?** Each tighter setting against it (the "
                      "quantities whose 95 % interval of the bias excludes zero, out of those "
                      "compared: every observable at tap 1, around taps 10, 100 and 1000 and steady):", ""]
            for name, eps, n, off, compared in checks:
                lines.append(f"- *{name}* at eps = {eps:g}, {n} paired seeds: "
                             + (f"all {compared} agree with the reference." if not off else
                                f"{len(off)} of {compared} differ: {', '.join(off)}."))
            lines.append("")
        if N not in front.compared_sizes:
            lines += [f"The reference has not run at N = {N} yet: no bias, recommendation or "
                      "figure at this N.", ""]
            continue
        recs = front.recommendations(N)
        if recs:
            lines += ["**Recommended settings**: for each purpose the cheapest setting, run at every "
                      "eps above, whose 95 % bounds on <Phi^c> over taps "
                      f"{time_window(100)[0]}-{time_window(100)[1]} and steady are within the "
                      "purpose's tolerance at every eps. *Publication* bounds the bias itself by "
                      "0.001, the last digit the paper quotes. *Exploration* compares curves run at "
                      "one setting: a bias common to every eps and tap shifts all curves alike, so it "
                      "bounds by 0.003 (a tenth of the paper's compaction over 4000 taps at eps = "
                      "0.0225) the part of the bias that changes with eps or with the tap count "
                      "(the paired difference of the biases at two eps or two windows, seed by "
                      "seed), and states the bias. *Smoke test*: "
                      "the cheapest setting, its bias stated. The line to paste is for spheres of "
                      "radius 0.5 on a floor at z = 0; ``tapmc-paper plan`` prices a study with "
                      "each.", ""]
            body = []
            for purpose, _, _ in PURPOSES:
                if purpose not in recs:
                    body.append([purpose, "none meets it yet", "", "", "", "", ""])
                    continue
                rec = recs[purpose]
                criterion = {"bias": "bias", "trend": "its change"}.get(rec["criterion"], "-")
                bound = rec["worst_bound"] if rec["criterion"] != "trend" else rec["worst_trend"]
                body.append([purpose, rec["setting"],
                             "-" if rec["tolerance"] is None else f"{criterion} <= {rec['tolerance']:g}",
                             "0 (reference)" if rec["setting"] == REFERENCE else
                             "n/a" if bound != bound else "%.4f" % bound,
                             "%+.4f" % rec["worst_bias"], "%.3f" % rec["cpu_per_tap"],
                             "``" + lammps_line(rec["setting"], N) + "``"])
            lines += _grid(["purpose", "setting", "bound on", "its worst 95 % bound",
                            "worst bias of <Phi^c>", "CPU s/tap (mean over eps)",
                            "fix mc/settle"], body) + [""]
            lines += _default_lines(front, N, recs)
        lines += [f".. image:: validation/front/{figure_name(N)}.png", "",
                  f"Left, middle: bias of the steady <Phi^c> (taps {TAPS - STEADY_LAST + 1}-{TAPS}) against the CPU time per tap "
                  f"(error bars: standard error of the paired bias). Right: the bias against the "
                  f"tap count at eps = {front.eps_values[0]:g} (the steady window at {2 * TAPS}). "
                  f"Data: ``doc/validation/front/{figure_name(N)}.csv``.", ""]
    lines += _preset_lines(front)
    for N in SIZES:
        if N not in front.sizes:
            lines += [f"N = {N}: not measured yet (``bench/paper_front.py --N {N} --jobs 2``).", ""]
    lines += ["Reproduce: ``/usr/bin/python3 bench/paper_front.py --jobs 2`` (resumable; adds the "
              "runs missing from ``doc/validation/front/runs.csv``), then ``build/tapmc-paper "
              "front`` (this page, its figure and ``tools/python/tapmc/paper/front_summary.csv``, "
              "which the validation reports read to state the bias of their settings).", ""]
    return "\n".join(lines)


META = "meta.json"


def runs_note(data_dir):
    """What ran the front (from the meta.json bench/paper_front.py writes), as a sentence."""
    import json
    path = os.path.join(data_dir, META)
    if not os.path.isfile(path):
        return "(No meta.json: the binary and machine of these runs are not recorded.)"
    with open(path) as f:
        m = json.load(f)
    return (f"Runs: ``lmp_tapmc`` built from commit {m['commit']}, on {m['machine']} "
            f"({m['cores']} cores, {m['jobs']} runs at a time at nice {m['nice']}, other "
            f"simulations at nice 19 on the same cores), started {m['started']}.")


def write_page(root, data_dir=None):
    """Writes doc/front.rst, its figure and CSV, and the package summary under `root` (the
    repository); returns the page's path."""
    root = os.fspath(root)
    data = data_dir or os.path.join(root, DATA_DIR)
    fr = Front(data).compute()
    for N in fr.compared_sizes:
        name = figure_name(N)
        fr.write_figure(N, os.path.join(data, name + ".png"), os.path.join(data, name + ".csv"))
    package = os.path.join(root, "tools", "python", "tapmc", "paper")
    os.makedirs(package, exist_ok=True)
    fr.write_csv(os.path.join(package, os.path.basename(SUMMARY)))
    note = runs_note(data)
    page = os.path.join(root, PAGE)
    os.makedirs(os.path.dirname(page), exist_ok=True)
    with open(page, "w") as f:
        f.write(render_rst(fr, note))
    return page


def read_summary(path=SUMMARY):
    """The rows of front_summary.csv (numbers as floats), or [] when absent."""
    if not os.path.isfile(path):
        return []
    out = []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            conv = {}
            for k, v in row.items():
                try:
                    conv[k] = float(v) if k not in ("setting", "eta", "settle_keys") else v
                except ValueError:
                    conv[k] = v
            out.append(conv)
    return out


def setting_named(eta, stop="change"):
    """The front's setting with this eta and stop rule and no other keyword, or None."""
    for name, s in SETTINGS.items():
        kw = dict(s["keys"])
        rule = kw.pop("stop", "change")
        if rule == stop and not kw and float(s["eta"]) == float(eta):
            return name
    return None


def bias_sentence(eta, stop="change", path=SUMMARY):
    """What the front measured of a redeposition setting, as one sentence for the reports."""
    name = setting_named(eta, stop)
    rows = [r for r in read_summary(path) if r["setting"] == name] if name else []
    if not rows:
        return (f"The run-time-versus-error front (``doc/front.rst``) has not measured "
                f"eta = {eta:g} (stop {stop}).")
    parts = []
    for r in sorted(rows, key=lambda r: (r["N"], r["eps"])):
        if name != REFERENCE and not r.get("paired_seeds", 0) >= 1:
            continue  # the reference has not run at this N and eps yet: no bias to state
        if name == REFERENCE:
            parts.append(f"N = {r['N']:.0f}, eps = {r['eps']:g}: the reference itself")
            continue
        seeds_ = int(r["paired_seeds"])
        parts.append(f"N = {r['N']:.0f}, eps = {r['eps']:g} ({seeds_} seed{'s' if seeds_ != 1 else ''}): "
                     f"<Phi^c> {_pm(r['phi_c_t1000_bias'], r['phi_c_t1000_bias_se'])} over taps "
                     "%d-%d, " % time_window(TAPS) + f"{_pm(r['phi_c_steady_bias'], r['phi_c_steady_bias_se'])} "
                     f"steady, Phi_b {_pm(r['phi_b_steady_bias'], r['phi_b_steady_bias_se'])} "
                     f"steady, at {r['cpu_per_tap']:.3f} CPU s per tap")
    return (f"Measured bias of eta = {eta:g} (stop {stop}) against *{REFERENCE}* on the "
            f"run-time-versus-error front (``doc/front.rst``): " + "; ".join(parts) + ".")
