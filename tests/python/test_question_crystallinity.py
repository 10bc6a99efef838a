# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""``tapmc-paper question crystallinity`` on a synthetic campaign with a known answer: an FCC
crystal on the floor (crystalline everywhere: bulk, floor layer, side-wall layer), random
packings (crystalline nowhere), and the control that must fail: a random bulk on three FCC
layers, crystalline in the floor layer only. The page's references (exact FCC and HCP) against
their closed forms; the page's sentence names the densest run; bad input (a cut dump, an
empty campaign) refused by name with the committed CSV left as it was."""

import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.crystallinity import LATTICE_Q  # noqa: E402
from tapmc.paper import cli  # noqa: E402
from tapmc.paper.questions import QUESTIONS, crystallinity  # noqa: E402

#: FCC (100) planes: cubic cell a = sqrt(2) for contact distance 1 (radius 0.5)
A = math.sqrt(2.0)
#: lattice sites per lateral side and (100) layers of the synthetic packings: 18 x a/2 = 12.7
#: (room for a floor layer 7 R from the walls, as in the paper's 32 R box), 20 layers up to
#: z = 13.9 (a bulk from 7 R = 3.5 above the floor to 3.5 below the surface)
SIDE, LAYERS = 18, 20
#: a crystalline fraction that is "none" for a random set of points (ten Wolde's criterion
#: finds a few chance crystalline spheres in dense random points at most)
RANDOM_AT_MOST = 0.02
#: the last tap of the synthetic runs
TAPS = 40


def fcc_sites(walls, layers=LAYERS):
    """FCC with (100) planes on the floor z = 0 (lowest centres at R = 0.5): sites
    (i, j, k) a/2 with i + j + k even. ``walls``: side walls at x, y = 0 and L, the outer
    columns touching them; else periodic sides of length SIDE a/2. Returns (positions, L)."""
    i, j, k = np.meshgrid(np.arange(SIDE), np.arange(SIDE), np.arange(layers), indexing="ij")
    keep = (i + j + k) % 2 == 0
    pos = np.stack([i[keep], j[keep], k[keep]], axis=1) * (A / 2) + [0, 0, 0.5]
    if walls:
        pos[:, :2] += 0.5
        return pos, 1.0 + (SIDE - 1) * A / 2
    return pos, SIDE * A / 2


def random_points(n, side, z_lo, z_hi, walls, seed):
    """``n`` uniform random centres (an ideal gas: as many bonds as a dense packing, no order;
    the criterion reads bond directions only) in the box, 0.5 from the walls."""
    rng = np.random.default_rng(seed)
    lo, hi = (0.5, side - 0.5) if walls else (0.0, side)
    return np.column_stack([rng.uniform(lo, hi, n), rng.uniform(lo, hi, n),
                            rng.uniform(z_lo, z_hi, n)])


def write_dump(path, step, pos, side, walls):
    bounds = "ff ff fm" if walls else "pp pp fm"
    lines = ["ITEM: TIMESTEP", str(step), "ITEM: NUMBER OF ATOMS", str(len(pos)),
             f"ITEM: BOX BOUNDS {bounds}", f"0 {side!r}", f"0 {side!r}", "0 40",
             "ITEM: ATOMS id x y z radius"]
    lines += [f"{k + 1} {x!r} {y!r} {z!r} 0.5" for k, (x, y, z) in enumerate(pos)]
    path.write_text("\n".join(lines) + "\n")


def write_run(campaign, name, last, phi_last, walls, seed):
    """A finished run: DONE.json, taps.dat (<Phi^c> 0.55 at t = 0, ``phi_last`` at TAPS), a
    random dump.0 and ``last`` ("fcc", "floor": random above three FCC layers) as its final
    dump."""
    folder = campaign / "runs" / name
    folder.mkdir(parents=True)
    (folder / "DONE.json").write_text("{}")
    rows = [f"{t} 0.5 {0.55 if t < TAPS else phi_last} 6" for t in range(TAPS + 1)]
    (folder / "taps.dat").write_text("# step phi_b phi_c Z\n" + "\n".join(rows) + "\n")
    crystal, side = fcc_sites(walls)
    top = float(crystal[:, 2].max())
    write_dump(folder / "dump.0.lammpstrj", 0,
               random_points(len(crystal), side, 0.5, top, walls, seed), side, walls)
    if last == "fcc":
        pos = crystal
    else:
        floor, _ = fcc_sites(walls, layers=3)
        above = random_points(len(crystal) - len(floor), side, 2.6, top, walls, seed + 1)
        pos = np.vstack([floor, above])
    write_dump(folder / f"dump.{TAPS}.lammpstrj", TAPS, pos, side, walls)
    return folder


@pytest.fixture(scope="module")
def campaign(tmp_path_factory):
    root = tmp_path_factory.mktemp("campaign")
    write_run(root, "const_pbc_eps0.01_s1", "fcc", 0.64, walls=False, seed=1)
    write_run(root, "const_pbc_eps0.1_s1", "floor", 0.60, walls=False, seed=3)
    write_run(root, "const_fbc_eps0.02_s1", "fcc", 0.62, walls=True, seed=5)
    write_run(root, "ageing_pbc_eps0.01_s1", "fcc", 0.70, walls=False, seed=7)   # not read
    return root


@pytest.fixture(scope="module")
def table(campaign, tmp_path_factory):
    out = tmp_path_factory.mktemp("out")
    assert cli.main(["question", "crystallinity", "--campaign", str(campaign),
                     "--out", str(out)]) == 0
    rows = crystallinity.load(out / crystallinity.CSV)
    return out / crystallinity.CSV, {(r["run"], int(r["tap"])): r for r in rows}


def f(row, key):
    return float(row[key])


def test_rows_per_run_and_dump(table):
    _, rows = table
    assert sorted(rows) == sorted((run, tap) for run in (
        "const_pbc_eps0.01_s1", "const_pbc_eps0.1_s1", "const_fbc_eps0.02_s1")
        for tap in (0, TAPS))
    r = rows[("const_fbc_eps0.02_s1", TAPS)]
    assert (r["bc"], r["eps"], r["seed"], r["taps"]) == ("fbc", "0.02", "1", str(TAPS))
    assert f(r, "phi_c") == 0.62 and f(rows[("const_fbc_eps0.02_s1", 0)], "phi_c") == 0.55
    assert int(r["n"]) == SIDE * SIDE * LAYERS // 2


def test_a_crystal_is_crystalline_in_every_zone(table):
    _, rows = table
    for run in ("const_pbc_eps0.01_s1", "const_fbc_eps0.02_s1"):
        r = rows[(run, TAPS)]
        # with periodic sides every sphere (the floor's and the surface's (100) layers have 8
        # bonds); between walls all but the ~100 on the box's 12 edges (fewer than 8 bonds)
        everything = f(r, "crystalline_all")
        assert everything == 1.0 if "pbc" in run else 0.95 < everything < 1.0
        # the bulk between walls is a narrow column (7 R from each wall of a 25 R box)
        assert int(r["n_bulk"]) > 10 and f(r, "crystalline_bulk") == 1.0
        assert int(r["n_floor"]) > 10 and f(r, "crystalline_floor") == 1.0
        # the bulk's spheres have FCC's own q6; surfaces and edges lower the mean a little
        assert f(r, "q6_mean") == pytest.approx(LATTICE_Q["fcc"][6], abs=0.05)
        assert f(r, "Q6") > 0.5
    walls = rows[("const_fbc_eps0.02_s1", TAPS)]
    # the side-wall layer: crystalline but for its spheres on the vertical edges where two
    # walls meet (6 bonds; the zone keeps them: it stays away from the floor and the surface)
    assert int(walls["n_walls"]) > 100 and 0.9 < f(walls, "crystalline_walls") < 1.0
    periodic = rows[("const_pbc_eps0.01_s1", TAPS)]
    assert periodic["n_walls"] == "0" and periodic["crystalline_walls"] == ""


def test_random_packings_are_not_crystalline(table):
    _, rows = table
    for run in ("const_pbc_eps0.01_s1", "const_pbc_eps0.1_s1", "const_fbc_eps0.02_s1"):
        r = rows[(run, 0)]
        assert f(r, "crystalline_all") <= RANDOM_AT_MOST
        assert f(r, "crystalline_bulk") <= RANDOM_AT_MOST
        assert f(r, "Q6") < 0.1        # ~ 1/sqrt(bonds) for bonds of random orientation


def test_control_crystalline_floor_under_a_random_bulk(table):
    """Must fail as a crystal: crystalline in the floor layer only."""
    _, rows = table
    r = rows[("const_pbc_eps0.1_s1", TAPS)]
    assert f(r, "crystalline_floor") == 1.0
    assert f(r, "crystalline_bulk") <= RANDOM_AT_MOST
    assert f(r, "crystalline_all") < 0.2


def test_references_are_the_exact_lattices():
    for name in ("fcc", "hcp"):
        ref = crystallinity.reference(name)
        assert ref.crystalline_fraction == 1.0
        assert ref.q6_mean == pytest.approx(LATTICE_Q[name][6], abs=1e-12)
        assert ref.phi == pytest.approx(math.pi / math.sqrt(18), abs=1e-12)
        assert ref.Q6 <= ref.q6_mean + 1e-12
    # a single FCC crystal: every sphere's q6m vector is the same, so Q6 = q6
    assert crystallinity.reference("fcc").Q6 == pytest.approx(LATTICE_Q["fcc"][6], abs=1e-12)
    with pytest.raises(ValueError, match="bcc"):
        crystallinity.lattice("bcc")


def test_render_names_the_densest_run(table):
    path, _ = table
    text = "\n".join(crystallinity.render(path))
    assert ".. list-table::" in text and "FCC (exact lattice, periodic)" in text
    assert "74.05 %" in text       # pi/sqrt(18)
    sentence = next(line for line in text.splitlines() if line.startswith("* The densest"))
    assert "const_pbc_eps0.01_s1 (<Phi^c> = 64.00 % after 40 taps)" in sentence
    assert "in the bulk at 100.00 % (t = 0: 0.00 %)" in sentence
    assert "The floor layer is more crystalline than the bulk in 1 of 3" in sentence
    assert "largest excess: const_pbc_eps0.1_s1" in sentence
    # the crystal's wall layer (its edges) is less crystalline than its bulk: no excess named
    assert "side-wall layer is more crystalline than the bulk in 0 of 1 tapped packings;" \
        in sentence


def test_render_of_nothing(tmp_path):
    path = tmp_path / crystallinity.CSV
    crystallinity.save(path, [["r", "pbc", "0.1", 1, 0, 40, 10, "0.55", "0.01", "0.4", "0",
                               5, "0", 1, "0", 0, ""]])
    assert crystallinity.render(path) == []          # no tapped packing


def question(capsys, *argv):
    status = cli.main(["question", *map(str, argv)])
    return status, capsys.readouterr().err


def test_a_cut_dump_is_named_and_the_committed_csv_kept(capsys, tmp_path):
    campaign = tmp_path / "campaign"
    folder = write_run(campaign, "const_pbc_eps0.01_s1", "fcc", 0.64, walls=False, seed=1)
    dump = folder / f"dump.{TAPS}.lammpstrj"
    dump.write_bytes(dump.read_bytes()[:5000])
    out = tmp_path / "out"
    out.mkdir()
    (out / crystallinity.CSV).write_text("run,eps\ncommitted,0.05\n")
    status, err = question(capsys, "crystallinity", "--campaign", campaign, "--out", out)
    assert status == 2 and "Traceback" not in err and err.count("\n") == 1
    assert f"{dump}:" in err and "cut short" in err
    assert (out / crystallinity.CSV).read_text() == "run,eps\ncommitted,0.05\n"
    assert sorted(p.name for p in out.iterdir()) == [crystallinity.CSV]


def test_a_run_without_its_final_dump_is_named(capsys, tmp_path):
    campaign = tmp_path / "campaign"
    folder = write_run(campaign, "const_fbc_eps0.02_s1", "fcc", 0.62, walls=True, seed=1)
    (folder / f"dump.{TAPS}.lammpstrj").unlink()
    status, err = question(capsys, "crystallinity", "--campaign", campaign, "--out", tmp_path)
    assert status == 2 and f"{folder}: needs dump.0.lammpstrj" in err
    assert not (tmp_path / crystallinity.CSV).exists()


def test_an_empty_campaign_writes_nothing(capsys, tmp_path):
    (tmp_path / "campaign" / "runs").mkdir(parents=True)
    status, err = question(capsys, "crystallinity", "--campaign", tmp_path / "campaign",
                           "--out", tmp_path / "out")
    assert status == 2 and "no finished run matches" in err
    assert not (tmp_path / "out").exists()
    assert "crystallinity" in QUESTIONS
