# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# tapmc.profiles: profile increases and profiles from compute stereo/profile arrays;
# tapmc.pores: Percus-Yevick P0 (limits, continuity, exact eq. 8 on a lattice by brute force),
# the tetrahedral law and the volume tail of the paper's rho_v(v) recovered from sampled pore sizes
# over seeds (with Poisson errors that match the scatter over seeds), and the tapmc-pores output
# reader (documented format, older files refused; the real program on a real packing when built).
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.laws import ProfileLaw  # noqa: E402
from tapmc.pores import (XI_O, XI_T, PoreDistribution, TetrahedralLaw, VolumeTail,  # noqa: E402
                         hist_is_current, percus_yevick_p0, read_pores)
from tapmc.profiles import ProfileIncrease, transversal_profile, vertical_profile  # noqa: E402
from tapmc.readers import AveTime, TapmcFormatError  # noqa: E402

# ------------------------------------------------------------------ Percus-Yevick P0


def test_p0_limits_and_continuity():
    for phi in (0.1, 0.3, 0.584, 0.606, 0.64):
        assert percus_yevick_p0(0.0, phi) == 1.0
        assert percus_yevick_p0(1.0, phi) == pytest.approx(1 - phi)
        h = 1e-4
        below = percus_yevick_p0(np.array([1 - 2 * h, 1 - h, 1.0]), phi)
        above = percus_yevick_p0(np.array([1.0, 1 + h, 1 + 2 * h]), phi)
        # value, slope and curvature continuous at sigma = 1 (one-sided differences)
        d1_lo, d1_hi = (below[2] - below[1]) / h, (above[1] - above[0]) / h
        assert d1_hi == pytest.approx(d1_lo, rel=2e-3)
        d2_lo = (below[2] - 2 * below[1] + below[0]) / h ** 2
        d2_hi = (above[2] - 2 * above[1] + above[0]) / h ** 2
        assert d2_hi == pytest.approx(d2_lo, rel=2e-2)
        s = np.linspace(0, 8, 801)
        p = percus_yevick_p0(s, phi)
        assert np.all(np.diff(p) <= 0) and np.all(np.diff(p[p > 1e-300]) < 0) and p[-1] < 1e-6
    # ideal-gas limit: -ln P0 -> phi sigma^3
    s = np.linspace(1, 3, 5)
    np.testing.assert_allclose(-np.log(percus_yevick_p0(s, 1e-6)), 1e-6 * s ** 3, rtol=1e-4)
    with pytest.raises(ValueError, match="phi"):
        percus_yevick_p0(1.0, 1.2)


def test_p0_eq8_exact_on_fcc_by_brute_force():
    from scipy.spatial import cKDTree
    # FCC at contact, R = 0.5 (cubic cell a = sqrt(2)), 4x4x4 cells, periodic
    a, n = np.sqrt(2.0), 4
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    cells = np.array(np.meshgrid(*[np.arange(n)] * 3, indexing="ij")).reshape(3, -1).T
    centres = ((cells[:, None, :] + basis[None]) * a).reshape(-1, 3)
    box = n * a
    phi = len(centres) * 4 / 3 * np.pi * 0.5 ** 3 / box ** 3
    assert phi == pytest.approx(np.pi / np.sqrt(18))
    rng = np.random.default_rng(3)
    points = rng.uniform(0, box, (40000, 3))
    dist, _ = cKDTree(centres, boxsize=box).query(points)
    for sigma in (0.3, 0.6, 0.9, 1.0):
        measured = np.mean(dist > sigma * 0.5)
        err = np.sqrt(measured * (1 - measured) / len(points))
        assert abs(measured - percus_yevick_p0(sigma, phi)) < 4 * err + 1e-12


# ------------------------------------------------------------------ pore-size laws


def sample_pores(rng, n, xi_t=XI_T, tail_nu=0.06):
    """Pore sizes with xi^3 P(xi) ~ (xi - xi_t)^2 on [xi_t, xi_O] (P ~ (xi - xi_t)^2 / xi^3,
    rejection sampling), plus n // 3 larger pores whose rho_v(v) = v n_v(v) (the paper's, section
    IV.B) is exp(-v / tail_nu) beyond v_O = xi_O^3: their number density is exp(-v / tail_nu) / v,
    drawn as v_O + an exponential, kept with probability v_O / v."""
    out = []
    pmax = ((XI_O - xi_t) ** 2 / xi_t ** 3)
    while len(out) < n:
        xi = rng.uniform(xi_t, XI_O, 4 * n)
        keep = rng.uniform(0, pmax, xi.size) < (xi - xi_t) ** 2 / xi ** 3
        out.extend(xi[keep])
    small = np.array(out[:n])
    v_o, tail = XI_O ** 3, []
    while len(tail) < n // 3:
        v = v_o + rng.exponential(tail_nu, n)
        tail.extend(v[rng.uniform(0, 1, n) < v_o / v])
    return small, np.concatenate([small, np.cbrt(np.array(tail[:n // 3]))])


def histogram(xi, bins=150, xi_max=1.5):
    """The columns of tapmc-pores' hist.csv from pore sizes (doc/tapmc-pores.rst): n_v counts
    the pores of each v bin, rho_v sums their v (both over N w)."""
    edges = np.linspace(0, xi_max, bins + 1)
    count, _ = np.histogram(xi, edges)
    centres = 0.5 * (edges[1:] + edges[:-1])
    p = count / (len(xi) * np.diff(edges))
    vedges = np.linspace(0, xi_max ** 3, bins + 1)
    count_v, _ = np.histogram(xi ** 3, vedges)
    volume_v, _ = np.histogram(xi ** 3, vedges, weights=xi ** 3)
    norm = len(xi) * np.diff(vedges)
    return dict(xi_lo=edges[:-1], xi_hi=edges[1:], xi=centres, count_xi=count, P_xi=p,
                xi3_P_xi=centres ** 3 * p, v_lo=vedges[:-1], v_hi=vedges[1:],
                v=0.5 * (vedges[1:] + vedges[:-1]), count_v=count_v, n_v=count_v / norm,
                rho_v=volume_v / norm)


def test_tetrahedral_law_recovers_xi_t_over_seeds():
    inside = []
    for seed in range(20):
        rng = np.random.default_rng(seed)
        _, xi = sample_pores(rng, 20000, xi_t=0.23)
        h = histogram(xi)
        res = TetrahedralLaw(xi_range=(0.15, XI_O)).fit(h["xi"], h["xi3_P_xi"],
                                                        counts=h["count_xi"])
        assert res.determined, res
        inside.append(abs(res.params["xi_T"] - 0.23) <= 2 * res.errors["xi_T"] + 0.005)
    # 0.005 = half a bin: the law is evaluated at bin centres
    assert np.mean(inside) >= 0.8
    fixed = TetrahedralLaw(fit_xi_t=False).fit(h["xi"], h["xi3_P_xi"], counts=h["count_xi"])
    assert fixed.names == ["a"]


def test_pore_law_fits_refuse_bins_of_other_lengths_by_name():
    _, xi = sample_pores(np.random.default_rng(3), 5000, tail_nu=0.06)
    h = histogram(xi, bins=100)
    law = TetrahedralLaw()
    with pytest.raises(ValueError, match="xi has 100 values but xi3_P_xi has 99"):
        law.fit(h["xi"], h["xi3_P_xi"][:-1])
    with pytest.raises(ValueError, match="xi has 100 values but counts has 99"):
        law.fit(h["xi"], h["xi3_P_xi"], counts=h["count_xi"][:-1])
    with pytest.raises(ValueError, match=r"sigma has 3 values; give one or one per bin of v "
                       r"\(100\)"):
        VolumeTail().fit(h["v"], h["rho_v"], sigma=[1.0, 1.0, 1.0])
    with pytest.raises(ValueError, match="v has 100 values but counts has 98"):
        VolumeTail().fit(h["v"], h["rho_v"], counts=h["count_v"][:-2])
    # a negative count is refused by its bin, also beside positive ones (the Poisson errors
    # used max(count, 1)) and when all are negative (once "every bin is empty")
    some = np.array(h["count_v"], dtype=float)
    some[7] = -5
    for law, x, y, counts, name in ((VolumeTail(), h["v"], h["rho_v"], some, "v"),
                                    (TetrahedralLaw(), h["xi"], h["xi3_P_xi"],
                                     -np.ones(100), "xi")):
        with pytest.raises(ValueError, match=rf"counts\[{7 if name == 'v' else 0}\] = -[15] "
                           rf"is negative: counts are the numbers of pores per bin of {name} "
                           r"\(>= 0\)"):
            law.fit(x, y, counts=counts)
    for bad in (0.5, (1.0, 0.5), (-0.1, 0.2), ("a", 1)):
        with pytest.raises(ValueError, match="must be \\(lo, hi\\) with 0 <= lo < hi"):
            VolumeTail(v_range=bad)
    # a scalar sigma or a one-element list: the same fit
    one = VolumeTail().fit(h["v"], h["rho_v"], sigma=[0.1]).params
    assert one == VolumeTail().fit(h["v"], h["rho_v"], sigma=0.1).params


def test_volume_tail_recovers_nu_over_seeds():
    z, z_number = [], []
    # Up to v = 0.3 the tail bins hold >= ~10 pores. Beyond, bins of one or two pores bias a
    # least-squares fit with errors from the counts (Neyman's chi2) low: to 0.4, nu_tail is
    # 1.4 sigma low on average over these seeds (0.6 sigma to 0.3).
    v_range = (XI_O ** 3 + 0.01, 0.3)
    for seed in range(20):
        rng = np.random.default_rng(100 + seed)
        _, xi = sample_pores(rng, 30000, tail_nu=0.06)
        h = histogram(xi, bins=300)
        res = VolumeTail(v_range=v_range).fit(h["v"], h["rho_v"], counts=h["count_v"])
        z.append((res.params["nu_tail"] - 0.06) / res.errors["nu_tail"])
        # PoreDistribution.volume_tail fits the same function, the paper's rho_v
        same = PoreDistribution(h, 0.1, len(xi)).volume_tail(v_range=v_range)
        assert same.params["nu_tail"] == pytest.approx(res.params["nu_tail"], rel=1e-9)
        # the number density n_v = rho_v / v decays faster: its fit misses 0.06 by far
        number = VolumeTail(v_range=v_range).fit(h["v"], h["n_v"])
        z_number.append((number.params["nu_tail"] - 0.06) / res.errors["nu_tail"])
    assert np.mean(np.abs(z) <= 2) >= 0.8, z
    assert np.all(np.array(z_number) < -5), z_number


def test_poisson_errors_of_rho_v_match_the_scatter_over_seeds():
    """The errors VolumeTail gives rho_v(v) from the counts of v (about v sqrt(count) / (N w))
    are the scatter of rho_v over independent samples, at small and at large v alike. Errors
    taken as constant per count (right for n_v, not for rho_v = v n_v) would be off by the
    ratio of the v's: too large below the median v, too small above."""
    from tapmc.pores import _poisson_sigma

    seeds = 60
    rho, sigma, counts = [], [], []
    for seed in range(seeds):
        _, xi = sample_pores(np.random.default_rng(500 + seed), 20000)
        h = histogram(xi, bins=400, xi_max=1.0)  # v bins 0.0025 wide
        rho.append(h["rho_v"])
        counts.append(h["count_v"])
        sigma.append(_poisson_sigma(h["v"], h["rho_v"], h["count_v"]))
    rho, sigma = np.array(rho), np.array(sigma)
    v, mean_count = h["v"], np.mean(counts, axis=0)
    full = np.all(rho > 0, axis=0) & (mean_count >= 30)  # Gaussian enough
    scatter = np.std(rho, axis=0, ddof=1)
    for lo, hi in ((XI_T ** 3, 0.04), (0.04, 0.1), (0.1, 0.3)):
        sel = full & (v >= lo) & (v < hi)
        assert sel.sum() >= 5, (lo, hi)
        # pooled over the bins of the range: 60 seeds x >= 5 bins, a few % of statistical error
        ratio = np.sqrt(np.mean((scatter[sel] / np.mean(sigma, axis=0)[sel]) ** 2))
        assert 0.85 < ratio < 1.15, (lo, hi, ratio)


# ------------------------------------------------------------------ tapmc-pores outputs

def write_pores_output(prefix, frames):
    """Files in tapmc-pores' documented format (doc/tapmc-pores.rst) for given pore sizes."""
    cols = ["xi_lo", "xi_hi", "xi", "count_xi", "P_xi", "xi3_P_xi", "v_lo", "v_hi", "v",
            "count_v", "n_v", "rho_v"]
    allxi = np.concatenate([xi for _, _, xi in frames])
    h = histogram(allxi)
    with open(f"{prefix}.hist.csv", "w") as f:
        f.write(f"# tapmc-pores: {len(frames)} frames, {allxi.size} selected pores, nu = "
                f"{np.mean(allxi ** 3):.12g}, xi below range 0, above 0\n")
        f.write("bin," + ",".join(cols) + "\n")
        for b in range(150):
            f.write(f"{b}," + ",".join(f"{h[c][b]:.12g}" for c in cols) + "\n")
    with open(f"{prefix}.frames.csv", "w") as f:
        f.write("file,frame,timestep,atoms,radius,pores,tetrahedra,unresolved,selected,"
                "degenerate_selected,nu,mean_xi,region_volume,tetrahedra_volume,seconds\n")
        for k, (file, step, xi) in enumerate(frames):
            f.write(f"{file},{k + 1},{step},100,0.5,{xi.size},{xi.size},0,{xi.size},0,"
                    f"{np.mean(xi ** 3):.12g},{np.mean(xi):.12g},10,10,0.01\n")
    with open(f"{prefix}.frame_hist.csv", "w") as f:
        f.write("file,frame,timestep,bin," + ",".join(cols) + "\n")
        for k, (file, step, xi) in enumerate(frames):
            hk = histogram(xi)
            for b in range(150):
                f.write(f"{file},{k + 1},{step},{b}," + ",".join(f"{hk[c][b]:.12g}" for c in cols)
                        + "\n")


def test_read_pores_documented_format(tmp_path):
    rng = np.random.default_rng(0)
    frames = [("a.dump", 0, sample_pores(rng, 3000)[1]), ("a.dump", 10, sample_pores(rng, 2000)[1]),
              ("b.dump", 10, sample_pores(rng, 1000)[1])]
    write_pores_output(tmp_path / "fig10", frames)
    out = read_pores(tmp_path)  # the directory holds one output
    assert out.timesteps == [0, 10]
    assert out.p0 is None and out.json is None
    agg = out.distribution()
    assert agg.selected == sum(f[2].size for f in frames)
    assert agg.nu == pytest.approx(np.mean(np.concatenate([f[2] for f in frames]) ** 3))
    d10 = out.distribution(10)
    both = np.concatenate([frames[1][2], frames[2][2]])
    np.testing.assert_allclose(d10.P_xi, histogram(both)["P_xi"], rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(d10.count_xi, histogram(both)["count_xi"])
    assert d10.nu == pytest.approx(np.mean(both ** 3))
    assert np.trapz(d10.P_xi, d10.xi) == pytest.approx(1.0, rel=1e-9)
    # the frames combined keep the paper's rho_v (integral nu) apart from n_v (integral 1)
    np.testing.assert_allclose(d10.rho_v, histogram(both)["rho_v"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(d10.n_v, histogram(both)["n_v"], rtol=1e-9, atol=1e-12)
    w = d10.v_hi - d10.v_lo
    assert np.sum(d10.rho_v * w) == pytest.approx(d10.nu, rel=1e-9)
    assert np.sum(d10.n_v * w) == pytest.approx(1.0, rel=1e-9)
    assert hist_is_current(tmp_path / "fig10.hist.csv")
    with pytest.raises(ValueError, match="timestep = 5"):
        out.distribution(5)
    # a timestep given as text: its name and value, not numpy's failed comparison
    with pytest.raises(ValueError, match="timestep = '10' must be an integer"):
        out.distribution("10")
    assert out.distribution(np.int64(10)).selected == d10.selected
    assert repr(out) == (f"<PoreOutput {str(tmp_path / 'fig10')!r}: 2 timesteps, "
                         f"{agg.selected} selected pores>")
    assert repr(d10).startswith(f"<PoreDistribution (timestep 10): {d10.selected} selected ")
    # one of the output's files stands for its prefix
    for name in ("fig10.hist.csv", "fig10.frames.csv", "fig10.frame_hist.csv"):
        assert read_pores(tmp_path / name).prefix == str(tmp_path / "fig10")
    (tmp_path / "other.hist.csv").write_text("bin\n")
    with pytest.raises(ValueError, match="give prefix"):
        read_pores(tmp_path)
    bad = tmp_path / "bad"
    write_pores_output(bad, frames[:1])
    text = (tmp_path / "bad.frames.csv").read_text().splitlines()
    (tmp_path / "bad.frames.csv").write_text("\n".join(text + ["x.dump,2,3"]) + "\n")
    with pytest.raises(TapmcFormatError, match="bad.frames.csv:3"):
        read_pores(bad)
    # An output of the tool before n_v: its rho_v column was the number density of v. Reading
    # it as the paper's rho_v would be wrong, so it is refused, and the figures remake it.
    old = tmp_path / "old"
    write_pores_output(old, frames[:1])
    for suffix in (".hist.csv", ".frame_hist.csv"):
        path = tmp_path / f"old{suffix}"
        lines = path.read_text().splitlines()
        k = next(i for i, line in enumerate(lines) if line.startswith(("bin,", "file,")))
        header = lines[k].split(",")
        drop = header.index("rho_v")
        header.remove("n_v")
        body = [line.split(",") for line in lines[k + 1:]]
        body = [r[:drop - 1] + [r[drop - 1]] for r in body]  # n_v's values under the name rho_v
        path.write_text("\n".join(lines[:k] + [",".join(header)] + [",".join(r) for r in body])
                        + "\n")
    assert not hist_is_current(tmp_path / "old.hist.csv")
    assert not hist_is_current(tmp_path / "missing.hist.csv")
    with pytest.raises(TapmcFormatError, match="old.hist.csv: written by an older tapmc-pores"):
        read_pores(old)


def _pores_binary():
    build = Path(os.environ.get("TAPMC_BUILD_DIR", SOURCE / "build"))
    exe = build / "tools" / "pores" / "tapmc-pores"
    return exe if exe.exists() else None


@pytest.mark.skipif(_pores_binary() is None, reason="tapmc-pores not built")
def test_read_pores_of_a_frame_without_pores_and_a_file_name_with_a_comma(tmp_path):
    """A selection holding no pore leaves the frame's nu and mean_xi empty: read_pores made the
    column text and nu raised numpy's UFuncTypeError; a dump named 'seed,1.dump' split its rows
    (expected 15 fields, found 16). Now nu is NaN for that frame, and the name is quoted."""
    a, n = np.sqrt(2.0), 3
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    cells = np.array(np.meshgrid(*[np.arange(n)] * 3, indexing="ij")).reshape(3, -1).T
    centres = ((cells[:, None, :] + basis[None]) * a).reshape(-1, 3) * 1.02
    box = n * a * 1.02
    lines = [f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(centres)}\n"
             f"ITEM: BOX BOUNDS pp pp pp\n0 {box}\n0 {box}\n0 {box}\nITEM: ATOMS id x y z radius"]
    lines += [f"{i + 1} {x!r} {y!r} {z!r} 0.5" for i, (x, y, z) in enumerate(centres)]
    dump = tmp_path / "seed,1.dump"
    dump.write_text("\n".join(lines) + "\n")
    proc = subprocess.run([str(_pores_binary()), "-q", "--z", "0.01:0.0100001", "-o",
                           str(tmp_path / "none"), str(dump)],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    out = read_pores(tmp_path / "none")
    assert list(out.frames["file"]) == [str(dump)]
    assert out.frames["nu"].dtype == float and np.isnan(out.frames["nu"][0])
    assert out.distribution().selected == 0 and np.isnan(out.nu)
    # a frame without pores beside one with: nu is the other's (no NaN from the empty one)
    proc = subprocess.run([str(_pores_binary()), "-q", "-o", str(tmp_path / "all"), str(dump)],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    whole = read_pores(tmp_path / "all")
    mixed = tmp_path / "mixed.frames.csv"
    rows = (tmp_path / "all.frames.csv").read_text().splitlines()
    empty = (tmp_path / "none.frames.csv").read_text().splitlines()[-1]
    mixed.write_text("\n".join(rows + [empty]) + "\n")
    (tmp_path / "mixed.hist.csv").write_text((tmp_path / "all.hist.csv").read_text())
    assert read_pores(tmp_path / "mixed").nu == pytest.approx(whole.nu, rel=1e-12)


@pytest.mark.skipif(_pores_binary() is None, reason="tapmc-pores not built")
def test_read_pores_real_program_fcc(tmp_path):
    # FCC at contact, periodic: pores are tetrahedral (2 per sphere) and octahedral (1)
    a, n = np.sqrt(2.0), 3
    basis = np.array([[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    cells = np.array(np.meshgrid(*[np.arange(n)] * 3, indexing="ij")).reshape(3, -1).T
    rng = np.random.default_rng(1)
    centres = ((cells[:, None, :] + basis[None]) * a).reshape(-1, 3) * 1.02
    centres += rng.uniform(-1e-3, 1e-3, centres.shape)
    box = n * a * 1.02
    lines = [f"ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n{len(centres)}\n"
             f"ITEM: BOX BOUNDS pp pp pp\n0 {box}\n0 {box}\n0 {box}\nITEM: ATOMS id x y z radius"]
    lines += [f"{i + 1} {x} {y} {z} 0.5" for i, (x, y, z) in enumerate(centres)]
    (tmp_path / "fcc.dump").write_text("\n".join(lines) + "\n")
    proc = subprocess.run([str(_pores_binary()), "--frame-hist", "--p0", "20000", "--json", "-o",
                           str(tmp_path / "fcc"), str(tmp_path / "fcc.dump")],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    out = read_pores(tmp_path / "fcc")
    assert out.timesteps == [0] and out.json is not None and out.p0 is not None
    d = out.distribution(0)
    # spheres expanded by 2 %: pore sizes (1.02 (xi + 1) - 1) around the two sites
    small = d.count_xi[(d.xi > 0.2) & (d.xi < 0.3)].sum()
    large = d.count_xi[(d.xi > 0.4) & (d.xi < 0.5)].sum()
    assert small == 2 * len(centres) and large >= len(centres)
    # the program's Percus-Yevick column is the same function (phi printed to 4 digits)
    np.testing.assert_allclose(out.p0["P0_percus_yevick"],
                               percus_yevick_p0(out.p0["sigma"], out.p0_phi), atol=2e-4)


@pytest.mark.skipif(_pores_binary() is None, reason="tapmc-pores not built")
def test_read_pores_real_packing_rho_v_integrates_to_nu(tmp_path):
    # The reference TAPMC dump of the pore tests (512 spheres, 20 taps) as two frames of one
    # timestep (two files), combined by PoreOutput.distribution: the paper's rho_v(v) integrates
    # to nu, the number density n_v to 1 (no pore is beyond --xi-max here: the '#' line says
    # "above 0"). Tolerance 1e-9: the tool sums the pores' v in each bin (no bin-centre
    # approximation), so only the 12 printed digits of the 150 terms are left.
    dump = SOURCE / "tests" / "pores" / "data" / "small_tapped.dump.gz"
    copy = tmp_path / "seed2.dump.gz"  # frames are told apart by their file
    copy.write_bytes(dump.read_bytes())
    proc = subprocess.run([str(_pores_binary()), "-q", "--frame-hist", "-o", str(tmp_path / "real"),
                           str(dump), str(copy)], capture_output=True, text=True, timeout=60)
    assert proc.returncode == 0, proc.stderr
    out = read_pores(tmp_path / "real")
    assert out.hist.comments[0].endswith("xi below range 0, above 0")
    for d in (out.distribution(), out.distribution(20)):
        w = d.v_hi - d.v_lo
        assert 0.08 < d.nu < 0.16 and d.selected > 3000
        assert np.sum(d.rho_v * w) == pytest.approx(d.nu, rel=1e-9)
        assert np.sum(d.n_v * w) == pytest.approx(1.0, rel=1e-9)
        # and the tail fit runs on the paper's rho_v with its Poisson errors
        res = d.volume_tail(v_range=(XI_O ** 3, 0.3))
        assert res.params["nu_tail"] > 0 and np.isfinite(res.errors["nu_tail"])


@pytest.mark.skipif(_pores_binary() is None, reason="tapmc-pores not built")
def test_run_pores_remakes_outputs_of_the_older_tool(tmp_path, monkeypatch):
    # The figures reuse a tapmc-pores output newer than its dumps; one without n_v (its rho_v
    # the number density) is made again, so Fig. 10b never plots the old quantity.
    from tapmc.paper import _runs

    monkeypatch.setenv("TAPMC_PORES", str(_pores_binary()))
    dump = SOURCE / "tests" / "pores" / "data" / "small_tapped.dump.gz"
    prefix = _runs.run_pores([dump], tmp_path / "fig10", ["-q"])
    hist = Path(f"{prefix}.hist.csv")
    made = hist.stat().st_mtime_ns
    assert _runs.run_pores([dump], prefix, ["-q"]) == prefix and hist.stat().st_mtime_ns == made
    lines = hist.read_text().splitlines()
    old = [",".join(line.split(",")[:-1]) if not line.startswith("#") else line for line in lines]
    old[1] = old[1].replace(",n_v", ",rho_v")  # the old header: n_v's values under rho_v
    hist.write_text("\n".join(old) + "\n")
    assert not hist_is_current(hist)
    _runs.run_pores([dump], prefix, ["-q"])
    assert hist_is_current(hist)
    d = read_pores(prefix).distribution()
    assert np.sum(d.rho_v * (d.v_hi - d.v_lo)) == pytest.approx(d.nu, rel=1e-9)


# ------------------------------------------------------------------ profiles

def test_profile_increase_single_and_seeds():
    t = np.arange(5.0)
    lat = np.array([0.55, 0.57, 0.575, 0.58, 0.58])
    cen = np.array([0.60, 0.601, 0.603, 0.604, 0.605])
    pi = ProfileIncrease(t, lat, cen).compute()
    np.testing.assert_allclose(pi.delta_lateral, lat - 0.55)
    np.testing.assert_allclose(pi.delta_central, cen - 0.60)
    assert np.all(np.isnan(pi.delta_lateral_sem))
    seeds = ProfileIncrease(t, np.stack([lat, lat + 0.01]), np.stack([cen, cen + 0.002 * t]))
    seeds.compute()
    np.testing.assert_allclose(seeds.delta_lateral, lat - 0.55)
    np.testing.assert_allclose(seeds.delta_central, cen - 0.60 + 0.001 * t)
    np.testing.assert_allclose(seeds.delta_central_sem, 0.001 * t)
    given = ProfileIncrease(t, lat, cen, initial=(0.5, 0.6)).compute()
    np.testing.assert_allclose(given.delta_lateral, lat - 0.5)
    table = AveTime(["TimeStep", "c_t[5]", "c_t[6]"], np.stack([t, lat, cen], axis=1))
    from_file = ProfileIncrease.from_ave_time(table, "c_t[5]", "c_t[6]").compute()
    np.testing.assert_allclose(from_file.delta_central, pi.delta_central)
    with pytest.raises(ValueError, match="must match"):
        ProfileIncrease(t, lat, np.stack([cen, cen]))
    # the initial values: one per seed or common, refused by name otherwise
    per_seed = ProfileIncrease(t, np.stack([lat, lat]), np.stack([cen, cen]),
                               initial=([0.5, 0.55], 0.6)).compute()
    np.testing.assert_allclose(per_seed.delta_lateral_all[1], lat - 0.55)
    for bad, message in ((0.6, "must be a pair"), ((0.5, 0.6, 0.7), "must be a pair"),
                         (([0.5, 0.5, 0.5], 0.6), "lateral_0 has 3 values; give 1"),
                         ((0.5, float("nan")), "central_0 has 1 values")):
        with pytest.raises(ValueError, match=message):
            ProfileIncrease(t, np.stack([lat, lat]), np.stack([cen, cen]), initial=bad)


def test_vertical_profile_from_stereo_array_and_eq7():
    R = 0.5
    z = 0.25 * R + 0.5 * R * np.arange(80)          # plane positions (bin centres), floor 0
    zb = z / R
    rng = np.random.default_rng(2)
    phi = ProfileLaw.function(zb, 0.63, 0.002, 2.0, 30.0) + rng.normal(0, 3e-3, zb.size)
    block = np.stack([z, phi + 0.01, phi], axis=1)   # columns: position, Phi(plane), bin mean
    table = AveTime(["c_p[1]", "c_p[2]", "c_p[3]"], steps=[0, 100],
                    blocks=np.stack([block * 0 + block[0], block]))
    zb_read, phi_read = vertical_profile(table, radius=R, floor=0.0)
    np.testing.assert_allclose(zb_read, zb)
    np.testing.assert_allclose(phi_read, phi)
    _, plane = vertical_profile(table, radius=R, value="plane")
    np.testing.assert_allclose(plane, phi + 0.01)
    res = ProfileLaw(boundary="pbc").fit(zb_read, phi_read, sigma=3e-3)
    assert res.determined
    assert abs(res.params["alpha"] - 0.002) < 3 * res.errors["alpha"]
    assert abs(res.params["zb_star"] - 30.0) < 3 * res.errors["zb_star"]
    xb, _ = transversal_profile(table, radius=R, wall=1.0)
    np.testing.assert_allclose(xb, (z - 1.0) / R)
    with pytest.raises(ValueError, match="vector-mode"):
        vertical_profile(AveTime(["TimeStep", "a"], np.zeros((2, 2))), radius=R)
    with pytest.raises(ValueError, match="radius"):
        vertical_profile(table, radius=-1)
    np.testing.assert_allclose(vertical_profile(table, radius=R, index=np.int64(-1))[1], phi)
    for index in (0.5, 2, -3, True):
        with pytest.raises(ValueError, match=rf"index = {index!r} must be an integer block "
                           r"index in \[-2, 1\] \(the file has 2 blocks\)"):
            vertical_profile(table, radius=R, index=index)


def test_plots():
    import matplotlib
    matplotlib.use("Agg")
    rng = np.random.default_rng(0)
    h = histogram(sample_pores(rng, 2000)[1])
    from tapmc.pores import PoreDistribution
    d = PoreDistribution(h, 0.05, 2000, 4)
    assert len(d.plot(kind="xi3P").lines) == 1 and len(d.plot(kind="rho_v").lines) == 1
    t = np.arange(1.0, 6.0)
    ax = ProfileIncrease(t, t * 0.01, t * 0.002).compute().plot()
    assert len(ax.containers) == 2


@pytest.mark.skipif(_pores_binary() is None, reason="tapmc-pores not built")
def test_spatial_jackknife_rebuilds_the_tools_histograms(tmp_path):
    # The jackknife rebuilds each replicate's histograms from the selected pores (--pores) by
    # tapmc-pores's own definitions: the columns of all blocks together equal the tool's, and
    # a replicate that drops a block has the pores of the other blocks only.
    from tapmc.pores import _histogram_columns, jackknife_error

    dump = SOURCE / "tests" / "pores" / "data" / "small_tapped.dump.gz"
    proc = subprocess.run([str(_pores_binary()), "-q", "--frame-hist", "--pores", "-o",
                           str(tmp_path / "real"), str(dump)], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, proc.stderr
    out = read_pores(tmp_path / "real")
    full = out.distribution(20)
    sel = (out.pores["timestep"] == 20) & (out.pores["selected"] == 1)
    template = {c: getattr(full, c) for c in ("xi_lo", "xi_hi", "xi", "v_lo", "v_hi", "v")}
    rebuilt = _histogram_columns(out.pores["xi"][sel], np.append(full.xi_lo, full.xi_hi[-1]),
                                 np.append(full.v_lo, full.v_hi[-1]), template)
    for name in ("count_xi", "P_xi", "xi3_P_xi", "count_v", "n_v", "rho_v"):
        np.testing.assert_allclose(rebuilt[name], getattr(full, name), rtol=1e-9, atol=1e-12,
                                   err_msg=name)
    reps = out.jackknife(20, blocks=3)
    assert len(reps) == 9
    assert sum(full.selected - r.selected for r in reps) == full.selected  # each pore once
    err = jackknife_error([r.nu for r in reps])
    assert 0 < err < 0.1 * full.nu
    with pytest.raises(ValueError, match="blocks = 1"):
        out.jackknife(20, blocks=1)
    with pytest.raises(ValueError, match="at least 2 replicates"):
        jackknife_error([1.0])


def test_jackknife_error_of_a_mean_is_its_standard_error():
    # leave-one-out replicates of a mean: the jackknife reproduces std / sqrt(n) exactly
    from tapmc.pores import jackknife_error

    x = np.random.default_rng(5).normal(size=40)
    reps = [(x.sum() - xi) / (len(x) - 1) for xi in x]
    assert jackknife_error(reps) == pytest.approx(x.std(ddof=1) / np.sqrt(len(x)), rel=1e-12)


def test_slab_fractions_of_a_lattice_and_the_profile_jackknife():
    # A simple cubic lattice of touching spheres (spacing 2R) fills pi/6 of space: every slab
    # one period thick holds exactly that fraction, whatever its offset; the jackknife of a
    # laterally uniform packing has replicates equal to the profile and zero error.
    from tapmc.fluctuations import jackknife_error
    from tapmc.profiles import slab_fractions, vertical_profile_jackknife

    R, n = 0.5, 8
    g = (np.arange(n) + 0.5) * 2 * R
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    edges = np.array([1.0, 3.0, 5.0, 7.0]) + 0.37      # period-thick slabs, any offset
    area = (n * 2 * R) ** 2
    np.testing.assert_allclose(slab_fractions(pos[:, 2], R, edges, area), np.pi / 6, rtol=1e-12)
    full, reps = vertical_profile_jackknife(pos, R, edges, [0, 0, 0], [n * 2 * R] * 3, blocks=4)
    np.testing.assert_allclose(full, np.pi / 6, rtol=1e-12)
    assert reps.shape == (16, 3)
    np.testing.assert_allclose(reps, np.pi / 6, rtol=1e-12)
    assert np.all(jackknife_error(reps) < 1e-12)
    # one block emptied: the other replicates see a looser packing, the error is no longer 0
    keep = ~((pos[:, 0] < 2.0) & (pos[:, 1] < 2.0))
    _, reps = vertical_profile_jackknife(pos[keep], R, edges, [0, 0, 0], [n * 2 * R] * 3)
    assert np.all(jackknife_error(reps) > 0.01)
    with pytest.raises(ValueError, match="blocks = 1"):
        vertical_profile_jackknife(pos, R, edges, [0, 0, 0], [8, 8, 8], blocks=1)


def test_slab_fractions_of_a_polydisperse_bed_take_a_radius_per_sphere():
    """A bidisperse simple cubic stack (layers of radius 0.5 and 0.25 alternating, spacing 1):
    one period of two layers holds (pi/6)(1 + 1/8)/2 of its volume. A radius per sphere raised
    a raw TypeError (and the mean radius, its only way in, is wrong by up to 0.09)."""
    from tapmc.profiles import slab_fractions, vertical_profile_jackknife

    n = 8
    g = np.arange(n) + 0.5
    x, y, z = np.meshgrid(g, g, g, indexing="ij")
    pos = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    radii = np.where(np.floor(pos[:, 2]) % 2 == 0, 0.5, 0.25)
    edges = np.array([1.0, 3.0, 5.0]) + 0.0     # whole periods of the two layers
    expected = np.pi / 6 * (1 + 1 / 8) / 2
    np.testing.assert_allclose(slab_fractions(pos[:, 2], radii, edges, n * n), expected,
                               rtol=1e-12)
    full, reps = vertical_profile_jackknife(pos, radii, edges, [0, 0, 0], [n, n, n], blocks=2)
    np.testing.assert_allclose(full, expected, rtol=1e-12)
    np.testing.assert_allclose(reps, expected, rtol=1e-12)
    with pytest.raises(ValueError, match="radius has 3 values for 512 spheres"):
        slab_fractions(pos[:, 2], [0.5, 0.5, 0.5], edges, n * n)
    with pytest.raises(ValueError, match=r"radius\[0\] = -0.5 must be > 0"):
        slab_fractions(pos[:, 2], -radii, edges, n * n)
