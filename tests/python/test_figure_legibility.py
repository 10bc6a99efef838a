# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""Figures a reader can read. Every figure of the paper wing, drawn from the committed data
(each figure's typed result loaded from its committed CSV, tapmc.paper.redraw: nothing is
simulated), the front's figure from its committed runs, and every analysis class's
``plot(ax=None)`` on synthetic data obey, on every axes:

* both axes labelled;
* a legend where the axes has two labelled series or more (lines and collections whose label
  does not start with '_'), and where it has two data series or more, labelled or not;
* no legend of the figure covers more than LEGEND_MAX_HIDDEN_FRACTION of the plotted points
  of any series of any of its axes (its window extent after ``fig.canvas.draw()``);
* a paper-wing figure states its settings (N, the box, eta and the stop rule, taps,
  seeds, the campaign) on top.

The hidden-point count here is written afresh (not tapmc._legends'), so that the placement
cannot pass by sharing a mistake with its check; the fraction is the one placement uses."""

import importlib.util
import math
import os
import shutil
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.container import ErrorbarContainer  # noqa: E402

from tapmc._legends import LEGEND_MAX_HIDDEN_FRACTION  # noqa: E402
from tapmc.ageing import Ageing, scaling_collapse  # noqa: E402
from tapmc.connected_ageing import ConnectedAgeing  # noqa: E402
from tapmc.contacts import Contacts  # noqa: E402
from tapmc.crystallinity import Crystallinity  # noqa: E402
from tapmc.cylinder import Cylinder  # noqa: E402
from tapmc.fluctuations import ErrorCalibration, PowerSpectrum, SteadyState  # noqa: E402
from tapmc.hysteresis import BranchData, Hysteresis, RampBranches  # noqa: E402
from tapmc.laws import InverseLogLaw  # noqa: E402
from tapmc.paper import _plotting as P  # noqa: E402
from tapmc.paper import cli, fig8, front, redraw  # noqa: E402
from tapmc.paper.front import page as front_page  # noqa: E402
from tapmc.pores import PoreDistribution  # noqa: E402
from tapmc.profiles import ProfileIncrease  # noqa: E402
from tapmc.tube import TubeProfile  # noqa: E402
from tapmc.tube_runs import RadialProfiles, TubeCompaction, TubeSettings  # noqa: E402
from test_figure_results import fbc_campaign  # noqa: E402

#: the folders of committed figures: the medium smoke test's and the paper-scale campaign's
COMMITTED = ("doc/validation", "doc/paper_scale/validation")


# --- the checks ------------------------------------------------------------------------------

def labelled_series(ax):
    """Labels of the artists of ``ax`` that a legend lists (label not starting with '_')."""
    artists = list(ax.lines) + list(ax.collections) + list(ax.containers) + list(ax.patches)
    labels = []
    for artist in artists:
        label = artist.get_label()
        if label and not label.startswith("_") and label not in labels:
            labels.append(label)
    return labels


def plotted_points(ax):
    """(label, display points inside the axes) of each data series of ``ax``: its lines in
    data coordinates (reference lines in axes coordinates and error-bar caps excluded) and
    its scatter collections."""
    caps = {id(c) for container in ax.containers if isinstance(container, ErrorbarContainer)
            for c in container.lines[1]}
    box = ax.get_window_extent()
    found = [(line.get_label(), line.get_transform(), line.get_xydata()) for line in ax.lines
             if id(line) not in caps and line.get_transform().contains_branch(ax.transData)]
    found += [(c.get_label(), c.get_offset_transform(), c.get_offsets())
              for c in ax.collections if type(c).__name__ == "PathCollection"]
    out = []
    for label, transform, xy in found:
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        xy = xy[np.isfinite(xy).all(axis=1)]
        with np.errstate(all="ignore"):
            p = transform.transform(xy) if len(xy) else xy
        inside = (np.isfinite(p).all(axis=1) & (p[:, 0] >= box.x0) & (p[:, 0] <= box.x1)
                  & (p[:, 1] >= box.y0) & (p[:, 1] <= box.y1)) if len(p) else []
        if np.any(inside):
            out.append((label, p[inside]))
    return out


def legend_problems(fig, where):
    """What makes ``fig`` hard to read, one line per problem (empty: none)."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    legends += list(fig.legends)
    problems = []
    for i, ax in enumerate(fig.axes):
        if not ax.axison or not (ax.has_data() or ax.get_legend()):
            continue
        name = f"{where}, axes {i}"
        if not ax.get_xlabel().strip() or not ax.get_ylabel().strip():
            problems.append(f"{name}: axis label missing (x {ax.get_xlabel()!r}, "
                            f"y {ax.get_ylabel()!r})")
        labels = labelled_series(ax)
        if len(labels) >= 2 and ax.get_legend() is None:
            problems.append(f"{name}: {len(labels)} labelled series and no legend")
        series = plotted_points(ax)
        if len(series) >= 2 and ax.get_legend() is None:   # several curves, none named
            problems.append(f"{name}: {len(series)} data series and no legend")
        for legend in legends:
            box = legend.get_window_extent(renderer)
            for label, p in plotted_points(ax):
                hidden = int(np.sum((p[:, 0] >= box.x0) & (p[:, 0] <= box.x1)
                                    & (p[:, 1] >= box.y0) & (p[:, 1] <= box.y1)))
                if hidden > math.floor(LEGEND_MAX_HIDDEN_FRACTION * len(p)):
                    problems.append(f"{name}: a legend hides {hidden} of the {len(p)} points "
                                    f"of the series {label!r}")
    return problems


#: what the top line of a paper-wing figure names: N, the box, eta and the stop rule, the taps,
#: the seeds and the campaign (eps is in the figure's legends or on its axis, or for Figs. 5, 9
#: and 10, whose results do not record it, on that line too)
SETTINGS_WORDS = ("N = ", "box", "eta = ", "stop ", "taps", "seed", "campaign: ")


def states_settings(fig, words=SETTINGS_WORDS):
    """Whether the figure's top line names each of ``words``."""
    title = fig._suptitle.get_text() if fig._suptitle is not None else ""
    return all(word in title for word in words)


# --- the paper wing's figures ----------------------------------------------------------------

@pytest.mark.parametrize("folder", COMMITTED)
@pytest.mark.parametrize("name", list(redraw.FIGURE_RESULTS))
def test_committed_figure_is_readable(name, folder):
    fig = redraw.draw_committed(name, SOURCE / folder)
    try:
        assert legend_problems(fig, f"{folder}/{name}") == []
        words = SETTINGS_WORDS + (("eps = ",) if name in redraw.FIGURE_EPS else ())
        assert states_settings(fig, words), fig._suptitle
    finally:
        plt.close(fig)


@pytest.fixture(scope="module")
def computed_front():
    """The front computed from its committed runs (doc/validation/front), as its page is."""
    return front.Front(str(SOURCE / front.DATA_DIR)).compute()


def test_front_figures_are_readable(computed_front):
    assert computed_front.compared_sizes, "the committed front compares no size"
    for N in computed_front.compared_sizes:
        fig = front_page.figure(computed_front, N)
        try:
            assert legend_problems(fig, f"front N = {N}") == []
            assert states_settings(fig, ("N = ", "box", "taps", "seeds")), fig._suptitle
        finally:
            plt.close(fig)


def test_a_figure_drawn_from_a_campaign_states_its_runs_settings(tmp_path):
    """draw(campaign, out) states the settings of the campaign's runs (here the tiny scale of
    test_figure_results.py: N = 64, L = 16R, eta = 1e-4, 8 taps, two seeds) and the seeds
    behind the figure's own points."""
    campaign = fbc_campaign(tmp_path, "walls", wall_phi0=0.35)
    settings = P.figure_settings(campaign, fig8.figure_runs(campaign))
    assert settings["sizes"] == [(64, 16.0)] and settings["seeds_per_point"] == [2, 2]
    fig = fig8.plot(fig8.analyse(campaign), settings)
    try:
        assert fig._suptitle.get_text().replace("\n", " ") == (
            "N = 64, box 16R x 16R; eta = 0.0001, stop change; 8 taps per run; 2 seeds per "
            f"point; campaign: {Path(campaign.directory).name}")
        assert legend_problems(fig, "fig8 of a campaign") == []
    finally:
        plt.close(fig)
    png, csv = fig8.draw(campaign, tmp_path / "figures")
    assert png.is_file() and csv.is_file()


def test_redraw_writes_the_png_of_each_committed_csv_and_no_csv(tmp_path, capsys):
    """report --from-data --redraw (tapmc.paper.redraw.redraw): a PNG for each figure CSV of
    OUT/validation, drawn with report.json's settings; the CSV is left as it was. Without
    --from-data the option is a usage error (exit 2)."""
    folder = tmp_path / "validation"
    folder.mkdir()
    for name in ("fig4.csv", "report.json"):
        shutil.copy(SOURCE / COMMITTED[1] / name, folder / name)
    before = (folder / "fig4.csv").read_bytes()
    assert redraw.redraw(tmp_path) == [folder / "fig4.png"]
    assert (folder / "fig4.png").stat().st_size > 0
    assert (folder / "fig4.csv").read_bytes() == before
    with pytest.raises(SystemExit) as stop:
        cli.main(["report", "--redraw"])
    assert stop.value.code == 2 and "--redraw" in capsys.readouterr().err


def test_a_legend_asked_beside_its_axes_widens_the_figure():
    """legend(ax, outside=True): the legend beside the axes, placed once the figure is laid
    out, and the figure wider by it, so that the axes keep their width."""
    fig, axes = P.new_figure(1, 1)
    x = np.linspace(0, 1, 40)
    for k in range(3):
        axes[0].plot(x, x ** (k + 1), label=f"x^{k + 1}")
    axes[0].set_xlabel("x")
    axes[0].set_ylabel("y")
    P.legend(axes[0], outside=True, fontsize=7)
    width = fig.get_figwidth()
    P.finish_figure(fig)
    try:
        fig.canvas.draw()
        legend = axes[0].get_legend().get_window_extent()
        assert legend.x0 > axes[0].get_window_extent().x1
        assert fig.get_figwidth() > width
        assert legend_problems(fig, "outside") == []
    finally:
        plt.close(fig)


def test_the_check_finds_a_legend_on_the_data_and_a_missing_label():
    """The check can fail: a legend pinned over the data, an unlabelled axis, two labelled
    series without a legend."""
    fig, (a, b) = plt.subplots(1, 2)
    x = np.linspace(0, 1, 40)
    a.plot(x, x, label="rising")
    a.plot(x, 1 - x, label="falling")
    a.legend(loc="center")
    a.set_xlabel("x")
    b.plot(x, x, label="one")
    b.plot(x, x ** 2, label="two")
    b.set_xlabel("x")
    b.set_ylabel("y")
    problems = legend_problems(fig, "pinned")
    plt.close(fig)
    assert any("axes 0: axis label missing" in p for p in problems)
    assert any("axes 0: a legend hides" in p for p in problems)
    assert any("axes 1: 2 labelled series and no legend" in p for p in problems)
    fig, ax = plt.subplots()
    ax.plot(x, x)
    ax.plot(x, x ** 2)
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    problems = legend_problems(fig, "unnamed")
    plt.close(fig)
    assert problems == ["unnamed, axes 0: 2 data series and no legend"]


# --- the analysis classes' plot(ax=None) on synthetic data -----------------------------------

RNG = np.random.default_rng(7)
T = np.arange(0.0, 400.0)


def _ramp():
    levels = [0.05, 0.1, 0.15, 0.2, 0.15, 0.1, 0.05, 0.1, 0.15, 0.2]
    sqrt_eps = np.repeat(levels, 40)
    x = 0.6 + 0.05 * sqrt_eps + RNG.normal(0, 1e-3, sqrt_eps.size)
    return Hysteresis(sqrt_eps, x, taps_per_level=40, last=20).compute()


def _branches():
    up = BranchData([0.05, 0.1, 0.15, 0.2], [0.60, 0.61, 0.612, 0.605], [1e-3] * 4)
    down = BranchData([0.05, 0.1, 0.15], [0.62, 0.615, 0.61], [1e-3] * 3)
    again = BranchData([0.05, 0.1, 0.15], [0.621, 0.616, 0.611], [1e-3] * 3)
    return RampBranches(up, down, again).compute()


def _ageing_series():
    steps = np.cumsum(RNG.normal(0.0, 1.0, (6, 400)), axis=1)
    return -0.01 * np.log1p(np.arange(400.0)) + 1e-3 * steps


def _ageing_curves():
    t = np.arange(1.0, 200.0)
    return {tw: (t, 0.1 * (1 - np.exp(-t / (5 * tw ** 0.8))) * tw ** -0.3,
                 np.full(t.size, 1e-3)) for tw in (10, 30, 100)}


def _pores(timestep):
    xi = RNG.gamma(9.0, 0.05, 3000)
    edges = np.linspace(0.0, 1.5, 151)
    count, _ = np.histogram(xi, edges)
    centres = 0.5 * (edges[1:] + edges[:-1])
    p = count / (xi.size * np.diff(edges))
    vedges = np.linspace(0.0, 1.5 ** 3, 151)
    count_v, _ = np.histogram(xi ** 3, vedges)
    volume_v, _ = np.histogram(xi ** 3, vedges, weights=xi ** 3)
    norm = xi.size * np.diff(vedges)
    return PoreDistribution(dict(xi_lo=edges[:-1], xi_hi=edges[1:], xi=centres, count_xi=count,
                                 P_xi=p, xi3_P_xi=centres ** 3 * p, v_lo=vedges[:-1],
                                 v_hi=vedges[1:], v=0.5 * (vedges[1:] + vedges[:-1]),
                                 count_v=count_v, n_v=count_v / norm, rho_v=volume_v / norm),
                            0.05, xi.size, timestep)


def _cubic_packing():
    side = 6
    grid = np.array([(i, j, k) for i in range(side) for j in range(side) for k in range(side)],
                    dtype=float) + 0.5
    return grid + RNG.normal(0, 0.01, grid.shape), np.zeros(3), np.full(3, float(side))


def _tube_compaction():
    taps = np.arange(0.0, 300.0)
    phi = 0.6 - 0.03 / (1 + 0.4 * np.log1p(taps / 5.0)) + RNG.normal(0, 2e-4, taps.size)
    settings = TubeSettings(n=1200, sphere_radius=0.5, cylinder=Cylinder(4, 4, 4), eps="0.02",
                            eta="1e-5", seed="1", taps=299)
    return TubeCompaction(taps, phi - 0.01, phi, 5.0 - 0.1 * phi, phi - 0.02, phi + 0.01,
                          settings=settings).compute()


def _radial_profiles():
    r = np.linspace(0.25, 3.75, 8)
    phi = np.vstack([0.59 - 0.02 * np.arange(8), 0.6 - 0.02 * np.arange(8)])
    settings = TubeSettings(n=1200, sphere_radius=0.5, cylinder=Cylinder(4, 4, 4), eps="0.02",
                            eta="1e-5", seed="1", taps=300)
    return RadialProfiles([0, 300], r, phi, phi, settings=settings)


#: name -> a function drawing one analysis class's plot onto a new axes (returns the axes)
ANALYSIS_PLOTS = {
    "SteadyState": lambda: SteadyState(0.6 + RNG.normal(0, 1e-3, 2000)).compute().plot(),
    "ErrorCalibration": lambda: ErrorCalibration(
        {"a": ([1.0, 1.2, 0.8], [0.1] * 3), "b": ([2.0, 2.1], [0.05] * 2)},
        within_dof=19).compute().plot(),
    "PowerSpectrum": lambda: PowerSpectrum(
        np.cumsum(RNG.normal(size=2000)) * 1e-3 + RNG.normal(size=2000)).compute().plot(raw=True),
    "FitResult": lambda: InverseLogLaw().fit(
        T[1:], 0.6 - 0.02 / (1 + 0.3 * np.log(1 + T[1:] / 5))
        + RNG.normal(0, 1e-4, T.size - 1)).plot(logx=True),
    "Hysteresis": lambda: _ramp().plot(),
    "RampBranches": lambda: _branches().plot(),
    "Ageing": lambda: Ageing(_ageing_series(), [10, 50]).compute().plot(fit=False),
    "ScalingCollapse": lambda: scaling_collapse(_ageing_curves()).plot(),
    "ConnectedAgeing": lambda: ConnectedAgeing(_ageing_series(), [10, 50]).compute().plot(),
    "PoreDistribution": lambda: _pores(4000).plot(_pores(0).plot(kind="rho_v"), kind="rho_v"),
    "ProfileIncrease": lambda: ProfileIncrease(
        np.arange(0.0, 50.0), 0.55 + 1e-3 * np.sqrt(np.arange(50.0)),
        0.56 + 5e-4 * np.sqrt(np.arange(50.0))).compute().plot(),
    "Contacts": lambda: Contacts(*_cubic_packing()[:1], 0.5, *_cubic_packing()[1:],
                                 gap=0.05).compute().plot(),
    "Crystallinity": lambda: Crystallinity(_cubic_packing()[0], 0.5, np.zeros(3), np.full(3, 6.0),
                                           (True, True, True)).compute().plot(),
    "TubeCompaction": lambda: _tube_compaction().plot(),
    "TubeCompaction.height": lambda: _tube_compaction().plot_height(),
    "RadialProfiles": lambda: _radial_profiles().plot(),
    "TubeProfile": lambda: TubeProfile("z", np.linspace(0.5, 9.5, 10), np.full(10, 0.6),
                                       np.full(10, 0.6), np.linspace(0, 10, 11), step=7).plot(),
}


@pytest.mark.parametrize("name", list(ANALYSIS_PLOTS))
def test_analysis_plot_is_readable(name):
    ax = ANALYSIS_PLOTS[name]()
    fig = ax.figure
    try:
        assert legend_problems(fig, name) == []
    finally:
        plt.close(fig)


# --- the example scripts' figures ------------------------------------------------------------

def example_figures(monkeypatch, script, argv):
    """The figures ``script`` (a path under examples/) saves when run with ``argv``."""
    from matplotlib.figure import Figure
    saved, save = [], Figure.savefig

    def keep(fig, *args, **kw):
        saved.append(fig)
        return save(fig, *args, **kw)
    monkeypatch.setattr(Figure, "savefig", keep)
    spec = importlib.util.spec_from_file_location(Path(script).stem, SOURCE / script)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    module.main(argv)
    return saved


def test_the_quickstart_figure_is_readable_and_states_its_settings(tmp_path, monkeypatch):
    """plot_compaction.py on a compaction curve of the quick start's shape (300 taps, the
    reference log's settings): no legend on the data, N, the box, eps, eta, the stop rule."""
    t = np.arange(301.0)
    rng = np.random.default_rng(4928)
    phi_c = 0.5765 + 0.017 * np.log1p(t) / np.log(301) + 0.001 * rng.standard_normal(t.size)
    phi_b = 0.541 + 0.027 * np.log1p(t) / np.log(301) + 0.001 * rng.standard_normal(t.size)
    z = 7.42 - 0.27 * np.log1p(t) / np.log(301)
    with open(tmp_path / "taps.dat", "w") as f:
        f.write("# tap Phi_b Phi_c Z sweeps\n")
        for row in zip(t, phi_b, phi_c, z, 1000 + t):
            f.write(f"{int(row[0])} " + " ".join(f"{v:.6f}" for v in row[1:]) + "\n")
    log = SOURCE / "examples" / "quickstart" / "log.1Dec26.quickstart.g++.1"
    (fig,) = example_figures(monkeypatch, "examples/quickstart/plot_compaction.py",
                             [str(tmp_path / "taps.dat"), "--log", str(log),
                              "--out", str(tmp_path / "compaction")])
    try:
        assert legend_problems(fig, "quick start") == []
        assert states_settings(fig, ("N = 1024", "box 16R x 16R (P.B.C.)", "eps = 0.0225",
                                     "eta = 1e-7 (default)", "stop change (default)",
                                     "300 taps")), fig._suptitle
    finally:
        plt.close(fig)


def test_the_tube_figures_are_readable_and_state_the_stop_rule(tmp_path, monkeypatch):
    from test_tube_runs import write_run
    write_run(tmp_path)
    figures = example_figures(monkeypatch, "examples/cylinder/plot_tube.py",
                              [str(tmp_path), "--out-dir", str(tmp_path / "out")])
    assert figures
    for fig in figures:
        try:
            assert legend_problems(fig, "tube") == []
            titles = " ".join(ax.get_title() for ax in fig.axes)
            assert "stop change (default)" in titles and "eta = " in titles
        finally:
            plt.close(fig)


# --- text at the size the pages show it ------------------------------------------------------

#: the pages that show the figures below, and the thumbnail width of the summary tables (a
#: thumbnail links to the full figure: illegible by design)
PAGES = ("doc/front.rst", "doc/paper_scale/validation.rst",
         "doc/paper_scale/validation_questions.rst", "doc/validation.rst")
THUMBNAIL = "160px"


def shown_widths(png_name):
    """The ``:width:`` in pixels of every image of ``png_name`` on :data:`PAGES` (None: shown
    at its own width), thumbnails left out."""
    widths = []
    for page in PAGES:
        lines = (SOURCE / page).read_text().splitlines()
        for i, line in enumerate(lines):
            if line.strip().startswith(".. image::") and line.strip().endswith("/" + png_name):
                options = [o.strip() for o in lines[i + 1:i + 4] if o.strip().startswith(":")]
                width = next((o.split()[1] for o in options if o.startswith(":width:")), None)
                if width != THUMBNAIL:
                    widths.append(None if width is None else int(width.rstrip("px")))
    return widths


def smallest_text_px(fig, shown):
    """(points, pixels as shown) of the smallest visible text of the saved ``fig``."""
    from matplotlib.text import Text
    width = fig.get_figwidth() * P.PNG_DPI
    sizes = [t.get_fontsize() for t in fig.findobj(Text)
             if t.get_visible() and t.get_text().strip()]
    return min(sizes), P.shown_text_px(min(sizes), width, shown)


def question_figures(monkeypatch, tmp_path):
    """png name -> the figure, of every question figure drawn from its committed CSV."""
    from matplotlib.figure import Figure
    from tapmc.paper import paper_ramp, paper_ramp_figure, sigma_eta, validation
    from tapmc.paper.questions import connected_ageing, ramp_alpha, theta0
    from tapmc.paper.scales import FULL
    saved, save = {}, Figure.savefig

    def keep(fig, path, *args, **kw):
        saved[Path(path).name] = fig
        return save(fig, path, *args, **kw)
    monkeypatch.setattr(Figure, "savefig", keep)
    monkeypatch.setattr(plt, "close", lambda *a, **k: None)
    page = SOURCE / "doc" / "paper_scale"
    folder = page / "validation" / "questions"
    for module, write_figure in ((paper_ramp, paper_ramp_figure.write_figure),
                                 (sigma_eta, sigma_eta.write_figure)):
        write_figure(module.read_csv(folder / module.CSV_NAME), FULL.eta,
                     tmp_path / module.PNG_NAME, validation.report_errors(page, module))
    for module in (ramp_alpha, connected_ageing):
        module.write_figure(module.load(folder / module.CSV), tmp_path / module.PNG)
    shutil.copytree(folder, tmp_path / "questions")
    theta0.write_laws_figure(tmp_path / "questions")
    return saved


def test_question_and_front_figures_are_legible_as_the_pages_show_them(
        monkeypatch, tmp_path, computed_front):
    """Text of at least MIN_TEXT_PX pixels at the width a page shows the figure (its
    ``:width:``, at most the page body's PAGE_WIDTH_PX): connected_ageing (1100 pixels at
    500), sigma_eta (836 at 500) and the front (1557 at about 820) had legends of 5 pixels."""
    figures = question_figures(monkeypatch, tmp_path)
    for N in computed_front.compared_sizes:
        fig = front_page.figure(computed_front, N)
        P.save_figure(fig, tmp_path / f"{front_page.figure_name(N)}.png")
        figures[f"{front_page.figure_name(N)}.png"] = fig
    assert len(figures) >= 8
    small = []
    for name, fig in figures.items():
        widths = shown_widths(name)
        assert widths, f"{name}: on no page"
        for shown in widths:
            points, pixels = smallest_text_px(fig, shown)
            if pixels < P.MIN_TEXT_PX:
                small.append(f"{name} shown at {shown or 'its width'}: {points} pt text is "
                             f"{pixels:.1f} px")
        plt.close(fig)
    assert not small, "\n".join(small)
