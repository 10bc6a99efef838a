# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""tapmc.cylinder and tapmc.tube: the volume of a sphere inside a coaxial cylinder against exact
cases and an independent quadrature, the validation messages, the invariants of the tube's
stereology, and equality with compute stereo/profile ... container on a 300-sphere tube packing
written by lmp_tapmc (vector, wall zone and core, vertical and radial arrays, to 1e-9)."""

import math
import os
import sys
from pathlib import Path

import numpy as np
import pytest

HERE = Path(__file__).resolve().parent
SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", HERE.parent.parent))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from lammps_outputs import find_lmp  # noqa: E402
from tapmc._validate import NotComputedError  # noqa: E402
from tapmc.cylinder import (Cylinder, circle_arc_in_disk, disk_lens_area,  # noqa: E402
                            sphere_cylinder_surface_area, sphere_cylinder_volume)
from tapmc.packing import PackingCheck  # noqa: E402
from tapmc.readers import Frame, read_ave_time, read_dump, read_log  # noqa: E402
from tapmc.tube import TubeStereology  # noqa: E402
from tapmc.tube_runs import RadialProfiles  # noqa: E402

AGREEMENT = 1e-9


# ---- exact cases ------------------------------------------------------------------------------
@pytest.mark.parametrize("R", [0.5, 1.0, 3.7])
def test_sphere_on_the_axis_inside_a_thinner_cylinder(R):
    """4/3 pi (R^3 - h^3), h = sqrt(R^2 - rho^2): the sphere minus its two caps beyond the
    cylinder, for rho from almost 0 to almost R."""
    for frac in (1e-6, 0.1, 0.5, 0.9, 0.999, 1 - 1e-9):
        rho = frac * R
        h = math.sqrt(R * R - rho * rho)
        exact = 4.0 / 3.0 * math.pi * (R ** 3 - h ** 3)
        assert sphere_cylinder_volume(R, 0.0, rho) == pytest.approx(exact, rel=1e-12,
                                                                     abs=1e-14 * R ** 3)
    assert sphere_cylinder_volume(R, 0.0, 2 * R) == pytest.approx(4 / 3 * math.pi * R ** 3,
                                                                  rel=1e-15)
    # off the axis by d with d + R <= rho: the whole sphere; d >= rho + R: nothing
    assert sphere_cylinder_volume(R, 0.3 * R, 1.3 * R) == pytest.approx(4 / 3 * math.pi * R ** 3)
    assert sphere_cylinder_volume(R, 2.5 * R, 1.3 * R) == 0.0


def test_lens_area_closed_forms():
    a = np.array([1.0, 1.0, 2.0, 1.0])
    d = np.array([1.0, 0.0, 0.5, 2.5])
    lens = disk_lens_area(a, np.array([1.0, 3.0, 1.0, 1.0]), d)
    equal = 2 * math.acos(0.5) - 0.5 * math.sqrt(3.0)       # two unit disks 1 apart
    assert lens == pytest.approx([equal, math.pi, math.pi, 0.0], rel=1e-14)
    # near tangency the lens keeps its relative accuracy: h^2 from the four factors
    eps = 1e-8
    thin = float(disk_lens_area(1.0, 1.0, 2.0 - eps))
    assert thin == pytest.approx(2 * (math.acos(1 - eps / 2) - (1 - eps / 2)
                                      * math.sqrt(1 - (1 - eps / 2) ** 2)), rel=1e-6)
    assert circle_arc_in_disk(1.0, 3.0, 0.5) == pytest.approx(2 * math.pi)
    assert circle_arc_in_disk(1.0, 1.0, 1.0) == pytest.approx(2 * math.pi / 3)


def test_a_nan_input_gives_nan_not_zero():
    """A NaN fails every test that picks a case: it read as "no overlap", 0, silently."""
    nan = math.nan
    for value in (sphere_cylinder_volume(nan, 0.0, 1.0), sphere_cylinder_volume(0.5, nan, 1.0),
                  sphere_cylinder_volume(0.5, 0.0, nan), sphere_cylinder_volume(0.5, 0, 1, zlo=nan),
                  sphere_cylinder_surface_area(0.5, nan, 0.4), disk_lens_area(nan, 1.0, 0.0),
                  circle_arc_in_disk(1.0, nan, 0.5)):
        assert math.isnan(value)
    mixed = sphere_cylinder_volume(np.array([0.5, nan]), 0.0, 1.0)
    assert mixed[0] == pytest.approx(4 / 3 * math.pi * 0.125, rel=1e-14) and math.isnan(mixed[1])


def test_volume_against_an_independent_quadrature():
    """scipy.integrate.quad of the lens area over z (points at the kinks) on a grid of
    configurations crossing every case: the cylinder inside, around, tangent, off-centre."""
    from scipy.integrate import quad

    R = 1.0
    for d, rho, zlo, zhi in [(0.3, 0.5, -1, 1), (1.2, 0.5, -0.3, 0.8), (0.5, 0.5, -1, 1),
                             (2.0, 1.5, -1, 0.2), (0.7, 1.3, -0.9, 0.95), (0.0, 1.0, -1, 1),
                             (0.25, 0.75, -0.5, 0.5), (1.9, 0.1, -1, 1)]:
        def f(z):
            return float(disk_lens_area(math.sqrt(max(0.0, R * R - z * z)), rho, d))
        kinks = [s * math.sqrt(R * R - c * c) for c in (abs(rho - d), rho + d) if c < R
                 for s in (-1, 1)]
        inside = [k for k in kinks if zlo < k < zhi] or None
        ref = quad(f, zlo, zhi, points=inside, epsabs=1e-13, epsrel=1e-13, limit=400)[0]
        assert sphere_cylinder_volume(R, d, rho, zlo, zhi) == pytest.approx(ref, abs=1e-11)
        # the surface area is the volume's derivative with respect to rho (away from the
        # tangent cylinders, where the volume has a kink in rho)
        if min(abs(d + rho - R), abs(abs(rho - d) - R)) < 1e-3:
            continue
        e = 1e-5
        fd = (sphere_cylinder_volume(R, d, rho + e, zlo, zhi)
              - sphere_cylinder_volume(R, d, rho - e, zlo, zhi)) / (2 * e)
        area = sphere_cylinder_surface_area(R, d, rho, zlo, zhi)
        assert area == pytest.approx(fd, rel=1e-6, abs=1e-8)


# ---- validation -------------------------------------------------------------------------------
@pytest.mark.parametrize("args, message", [
    ((math.nan, 0.0, 1.0), "cylinder cx = nan must be finite"),
    ((0.0, math.inf, 1.0), "cylinder cy = inf must be finite"),
    ((0.0, 0.0, -2.0), "cylinder radius = -2.0 must be finite and > 0"),
    ((0.0, 0.0, "wide"), "cylinder radius = 'wide' must be a number"),
])
def test_cylinder_names_the_bad_field(args, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        Cylinder(*args)


def test_container_must_be_wider_than_its_spheres():
    pos = [[0.0, 0.0, 0.5], [0.2, 0.0, 1.5]]
    with pytest.raises(ValueError, match=r"cylinder.radius = 0.5 must exceed the largest sphere "
                                         r"radius 0.5"):
        TubeStereology(pos, [0.3, 0.5], Cylinder(0, 0, 0.5))
    with pytest.raises(ValueError, match=r"cylinder = 'tube' must be a Cylinder or \(cx, cy, "
                                         r"radius\)"):
        TubeStereology(pos, 0.3, "tube")
    with pytest.raises(ValueError, match=r"window = \(3.0, 1.0\) must be finite with za < zb"):
        TubeStereology(pos, 0.3, (0, 0, 2), window=(3.0, 1.0))
    with pytest.raises(ValueError, match="top_fraction = 0 must lie in"):
        TubeStereology(pos, 0.3, (0, 0, 2), top_fraction=0)
    tube = TubeStereology(pos, 0.3, (0, 0, 2))
    with pytest.raises(NotComputedError):
        tube.phi_b
    with pytest.raises(ValueError, match=r"planes lo = -1.0 must be >= 0"):
        tube.radial_profile((-1.0, 2.0, 4))
    with pytest.raises(ValueError, match=r"planes n = 0 must be an integer >= 1"):
        tube.vertical_profile((0.0, 2.0, 0))
    box = Frame(0, [-3, -3, 0], [3, 3, 5], [False, False, False], np.array([1, 2]),
                np.array(pos), np.array([0.3, 0.5]))
    # a (cx, cy, radius) triple is accepted wherever a cylinder is (python_analysis.rst)
    assert PackingCheck(box, cylinder=(0, 0, 2)).compute().phi_b == \
        PackingCheck(box, cylinder=Cylinder(0, 0, 2)).compute().phi_b
    with pytest.raises(ValueError, match=r"cylinder = 'tube' must be a Cylinder or \(cx, cy, "):
        PackingCheck(box, cylinder="tube")


# ---- invariants -------------------------------------------------------------------------------
def random_tube_packing(n=60, rc=2.5, seed=3):
    """Non-overlapping spheres of two radii inside a tube, drawn by rejection."""
    rng = np.random.default_rng(seed)
    pos, rad = [], []
    while len(pos) < n:
        r = rng.choice([0.4, 0.5])
        rho = (rc - r) * math.sqrt(rng.uniform())
        t = rng.uniform(0, 2 * math.pi)
        p = np.array([1.0 + rho * math.cos(t), -2.0 + rho * math.sin(t), rng.uniform(r, 6.0)])
        if all(np.linalg.norm(p - q) >= r + s for q, s in zip(pos, rad)):
            pos.append(p)
            rad.append(r)
    return np.array(pos), np.array(rad), Cylinder(1.0, -2.0, rc)


def test_profiles_add_up_to_the_zones_and_the_slabs():
    pos, rad, tube = random_tube_packing()
    t = TubeStereology(pos, rad, tube, floor=0.0, lateral=1.0).compute()
    za, zb = t.window
    radial = t.radial_profile((0.0, tube.radius, 10))
    # the annuli tile the disk: their area-weighted mean is the disk's volume fraction in the
    # window, which the wall zone and the core make up too
    w = t.wall_width
    core = (tube.radius - w) ** 2
    disk = (t.phi_wall * (tube.radius ** 2 - core) + t.phi_core * core) / tube.radius ** 2
    assert radial.mean() == pytest.approx(disk, rel=1e-12)
    # every sphere lies inside: the disk's material is the spheres' slab volumes, closed form
    from tapmc.profiles import sphere_slab_volume
    slabs = sphere_slab_volume(pos[:, 2], rad, za, zb).sum()
    assert disk == pytest.approx(slabs / (tube.area * (zb - za)), rel=1e-12)
    # Phi(z) integrated over a bin is the bin's mean; the vertical bins average to the range
    vertical = t.vertical_profile((0.0, 8.0, 16))
    z = np.linspace(0.0, 0.5, 4001)
    phi = t.cut_fraction(z)
    trapezoid = float(np.sum(0.5 * (phi[1:] + phi[:-1]) * np.diff(z)) / 0.5)
    assert vertical.phi_bin[0] == pytest.approx(trapezoid, abs=1e-6)
    assert vertical.mean() == pytest.approx(
        sphere_slab_volume(pos[:, 2], rad, 0.0, 8.0).sum() / (tube.area * 8.0), rel=1e-12)


def test_packing_check_in_a_tube():
    pos, rad, tube = random_tube_packing(n=40)
    frame = Frame(0, [-2, -5, 0], [4, 1, 9], [False, False, False], np.arange(1, 41), pos, rad)
    check = PackingCheck(frame, digits=None, cylinder=tube).compute()
    assert check.legal and check.wall_gap >= 0
    ref = TubeStereology(pos, rad, tube, floor=0.0).compute()
    assert check.scalars()["phi_wall"] == ref.phi_wall
    assert check.phi_b == ref.phi_b and check.phi_c == ref.phi_c
    pushed = pos.copy()
    k = int(np.argmax(np.hypot(pos[:, 0] - 1.0, pos[:, 1] + 2.0)))
    pushed[k, :2] += 0.2 * (pos[k, :2] - [1.0, -2.0]) / np.hypot(*(pos[k, :2] - [1.0, -2.0]))
    moved = Frame(0, [-2, -5, 0], [4, 1, 9], [False, False, False], np.arange(1, 41), pushed, rad)
    bad = PackingCheck(moved, digits=None, cylinder=tube).compute()
    assert bad.wall_gap < 0 and not bad.legal


def test_a_tube_a_whole_number_of_columns_wide_only_within_rounding_has_them_all():
    """A tube of radius 0.6 with spheres of 0.2: its bounding square is 1.2 / 0.2 = 5.999...
    columns wide, which the compute counts as 6 (floor(L / 2R + 1e-9)); h_s is then the mean
    top of the occupied one-sphere columns (the stereology had 5: h_s 0.7365 for 0.6920)."""
    radius = 0.1
    g = (np.arange(6) + 0.5) * 2 * radius
    x, y = (a.ravel() for a in np.meshgrid(g, g, indexing="ij"))
    keep = np.hypot(x - 0.6, y - 0.6) <= 0.6 - radius
    rng = np.random.default_rng(4)
    pos = np.column_stack([x[keep], y[keep], radius + rng.uniform(0, 0.8, keep.sum())])
    tube = TubeStereology(pos, radius, Cylinder(0.6, 0.6, 0.6), floor=0.0).compute()
    assert tube.surface == pytest.approx(np.mean(pos[:, 2] + radius), rel=1e-14)
    with pytest.raises(ValueError, match=r"column = 0.0001 is outside the allowed range"):
        TubeStereology(pos, radius, Cylinder(0.6, 0.6, 0.6), floor=0.0, column=1e-4).compute()


# ---- against lmp_tapmc ------------------------------------------------------------------------
INPUT = """units lj
atom_style sphere
boundary f f fm
region box block 0 6 0 6 0 30
create_box 1 box
region tube cylinder z 3 3 3 INF INF
create_packing 300 1 0.5 4928 floor 0.0 container tube
compute phi all stereo/profile floor 0.0 container tube
compute phl all stereo/profile floor 0.0 container tube lateral 1.3 window 1.5 6.0
compute rprof all stereo/profile floor 0.0 container tube axis r planes 0.0 3.0 12
compute zprof all stereo/profile floor 0.0 container tube planes 0.0 12.0 24
fix tap all tapdilate 0.01 floor 0.0 container tube
fix settle all mc/settle 4928 floor 0.0 eta 1e-4 container tube
fix rp all ave/time 1 1 1 c_rprof[*] mode vector file profile_r.dat format " %.17g"
fix zp all ave/time 1 1 1 c_zprof[*] mode vector file profile_z.dat format " %.17g"
dump d all custom 1 tube.dump id x y z radius
dump_modify d format float %.17g
thermo_style custom step c_phi[1] c_phi[2] c_phi[3] c_phi[4] c_phi[5] c_phi[6] c_phi[7] &
             c_phl[5] c_phl[6]
thermo_modify format float %.17g
thermo 1
run 2
"""


@pytest.fixture(scope="module")
def tube_run(tmp_path_factory):
    import subprocess

    lmp = find_lmp()
    folder = tmp_path_factory.mktemp("tube_run")
    (folder / "in.tube").write_text(INPUT)
    proc = subprocess.run([lmp, "-in", "in.tube", "-log", "log.lammps", "-screen", "none"],
                          cwd=folder, capture_output=True, text=True, timeout=120)
    log = (folder / "log.lammps").read_text(errors="replace")
    if proc.returncode and "unknown keyword 'container'" in log:
        pytest.skip(f"{lmp} predates the container keyword: rebuild it")
    assert proc.returncode == 0, log[-2000:] + proc.stderr
    return folder


def test_tube_stereology_equals_the_compute(tube_run):
    thermo = read_log(tube_run / "log.lammps").thermo
    frames = read_dump(tube_run / "tube.dump").frames
    radial = read_ave_time(tube_run / "profile_r.dat")
    vertical = read_ave_time(tube_run / "profile_z.dat")
    tube = Cylinder(3.0, 3.0, 3.0)
    assert len(frames) == 3 and list(radial.steps) == [0, 1, 2]
    worst = 0.0
    for k, frame in enumerate(frames):
        assert frame.n_atoms == 300
        t = TubeStereology.from_frame(frame, tube, floor=0.0).compute()
        ref = np.array([thermo[f"c_phi[{i}]"][k] for i in range(1, 8)])
        assert math.isnan(ref[5]) and math.isnan(t.phi_core)      # 7R > Rc: no core
        worst = max(worst, np.nanmax(np.abs(t.vector - ref)))
        zones = TubeStereology.from_frame(frame, tube, floor=0.0, lateral=1.3,
                                          window=(1.5, 6.0)).compute()
        worst = max(worst, abs(zones.phi_wall - thermo["c_phl[5]"][k]),
                    abs(zones.phi_core - thermo["c_phl[6]"][k]))
        worst = max(worst, np.abs(t.radial_profile((0.0, 3.0, 12)).rows
                                  - radial.blocks[k]).max())
        worst = max(worst, np.abs(t.vertical_profile((0.0, 12.0, 24)).rows
                                  - vertical.blocks[k]).max())
        check = PackingCheck(frame, floor=0.0, digits=None, cylinder=tube).compute()
        assert check.legal
        assert check.phi_c == pytest.approx(ref[1], abs=AGREEMENT)
    assert worst < AGREEMENT, worst


def test_radial_profiles_reader_on_the_compute_file(tube_run):
    profiles = RadialProfiles.from_file(tube_run / "profile_r.dat")
    assert list(profiles.steps) == [0, 1, 2] and profiles.r.size == 12
    assert profiles.settings.cylinder == Cylinder(3.0, 3.0, 3.0)
    assert profiles.settings.n == 300 and profiles.settings.eta == "1e-4"
    np.testing.assert_allclose(profiles.edges, np.linspace(0.0, 3.0, 13), atol=1e-15)
    last = profiles.profile(-1)
    assert last.step == 2 and last.cylinder.radius == 3.0
    frame = read_dump(tube_run / "tube.dump").frames[-1]
    mine = TubeStereology.from_frame(frame, (3, 3, 3), floor=0.0).radial_profile((0, 3, 12))
    assert np.abs(mine.phi_bin - last.phi_bin).max() < AGREEMENT
    assert np.abs(mine.phi_plane - last.phi_plane).max() < AGREEMENT
