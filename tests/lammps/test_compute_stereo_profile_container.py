# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# compute stereo/profile with 'container REGION-ID' (a vertical cylinder) run as lmp_tapmc child
# processes: exact values against closed forms computed here, 1 and 2 MPI ranks, every bad input.
import math
import os

import numpy as np
import pytest

from lmprun import ave_time_rows, printed, run_lammps

VECTOR_PRINT = 'print "{tag} ' + " ".join("$(c_{id}[%d]:%%.17g)" % i for i in range(1, 8)) + '"\n'

# ---- closed forms, written apart from the kernel ---------------------------------------------


def slab(R, a, b):
    """Volume of a sphere of radius R (centre at 0) between the heights a and b."""
    a, b = max(a, -R), min(b, R)
    if a >= b:
        return 0.0
    return math.pi * ((b - a) * R * R - (b ** 3 - a ** 3) / 3.0)


def cut(R, u):
    """Area of the disk cut from a sphere of radius R by the plane u above its centre."""
    return math.pi * (R * R - u * u) if abs(u) < R else 0.0


def axial(R, rho, a, b):
    """Volume of a sphere of radius R, centred on the axis of a coaxial cylinder of radius rho,
    inside the cylinder and between the heights a and b (centre at 0): at height z the cut is
    a disk of area pi min(rho^2, R^2 - z^2), i.e. pi rho^2 for |z| < h = sqrt(R^2 - rho^2)
    and the whole disk beyond."""
    if rho >= R:
        return slab(R, a, b)
    h = math.sqrt(R * R - rho * rho)
    lo, hi = max(a, -h), min(b, h)
    middle = math.pi * rho * rho * max(0.0, hi - lo)
    return middle + slab(R, a, min(b, -h)) + slab(R, max(a, h), b)


# ---- the scene: six spheres inside a tube of radius 4 ---------------------------------------
# Spheres 1 and 5 sit on the axis (sphere 1 larger than the core radius 1 used below, so the
# core boundary cuts it); 2, 3, 4 and 6 lie wholly in the annulus 1 <= r <= 4. Every sphere is
# wholly inside the container, so each measure has a closed form.
CX, CY, RC = 5.0, 5.0, 4.0
SPHERES = [  # x, y, z, R
    (5.0, 5.0, 1.2, 1.2),
    (7.5, 5.0, 0.8, 0.8),
    (5.0, 2.0, 1.0, 0.9),
    (3.0, 6.0, 3.2, 0.7),
    (5.0, 5.0, 3.3, 0.9),
    (6.0, 7.5, 1.5, 0.6),
]

SPHERES_IN_A_BOX = """units lj
atom_style sphere
boundary f f fm
region box block 0 10 0 10 0 12
create_box 1 box
""" + "".join(
    "create_atoms 1 single {} {} {} units box\nset atom {} diameter {}\n".format(x, y, z, i + 1,
                                                                              2 * r)
    for i, (x, y, z, r) in enumerate(SPHERES))
SCENE = SPHERES_IN_A_BOX + f"region tube cylinder z {CX} {CY} {RC} 0 INF units box\n"

# explicit settings: bulk slab [0, 3], wall band [0, 0.6], wall zone 3 wide (core radius 1),
# z-window [0.5, 3], columns 2 wide over the tube's bounding square [1, 9]^2
CONTAINER = ("container tube bulk 3.0 wall_band 0.6 lateral 3.0 window 0.5 3.0 column 2.0 "
             "top_fraction 0.9")


def surface_height():
    """h_s: mean over the filled 2 x 2 columns of [1, 9]^2 of the highest sphere top."""
    tops = {}
    for x, y, z, r in SPHERES:
        col = (min(3, max(0, int(math.floor((x - 1.0) / 2.0)))),
               min(3, max(0, int(math.floor((y - 1.0) / 2.0)))))
        tops[col] = max(tops.get(col, -math.inf), z + r)
    return sum(tops.values()) / len(tops)


def expected_vector():
    area = math.pi * RC * RC
    h_s = surface_height()
    top = 0.9 * h_s
    band = min(top, 0.6)
    bulk = sum(slab(r, -z, 3.0 - z) for x, y, z, r in SPHERES) / (area * 3.0)
    corrected = sum(16.0 / 11.0 * slab(r, -z, band - z) + slab(r, band - z, top - z)
                    for x, y, z, r in SPHERES) / (area * top)
    mean_z = sum(z for x, y, z, r in SPHERES) / len(SPHERES)
    za, zb, core = 0.5, 3.0, RC - 3.0
    v_core = v_wall = 0.0
    for x, y, z, r in SPHERES:
        inside = slab(r, za - z, zb - z)
        d = math.hypot(x - CX, y - CY)
        if d == 0.0:
            in_core = axial(r, core, za - z, zb - z)
        else:
            assert d - r >= core  # wholly in the wall zone
            in_core = 0.0
        v_core += in_core
        v_wall += inside - in_core
    phi_wall = v_wall / (math.pi * (RC * RC - core * core) * (zb - za))
    phi_core = v_core / (math.pi * core * core * (zb - za))
    return [bulk, corrected, mean_z, top, phi_wall, phi_core, h_s]


def run_scene(extra, nprocs=1, grid=None):
    script = (f"processors {grid}\n" if grid else "") + SCENE + extra
    rc, out, wd = run_lammps(script, nprocs=nprocs)
    assert rc == 0, out[-2500:]
    return out, wd


TUBE_RUN = f"""compute phi all stereo/profile {CONTAINER}
compute pz all stereo/profile container tube planes 0.0 4.0 8
group axial id 1
compute rw axial stereo/profile container tube axis r planes 0.0 2.0 4 window -5.0 5.0
compute rc axial stereo/profile container tube axis r planes 0.0 2.0 4 window 0.5 1.7
compute ra all stereo/profile container tube axis r planes 0.0 4.0 16 window 0.5 3.0
thermo_style custom step c_phi[1] c_phi[2]
fix az all ave/time 1 1 1 c_pz[*] mode vector file pz.dat format " %.17g"
fix ar all ave/time 1 1 1 c_rw[*] c_rc[*] mode vector file rr.dat format " %.17g"
fix aa all ave/time 1 1 1 c_ra[*] mode vector file ra.dat format " %.17g"
run 0
""" + VECTOR_PRINT.format(tag="VEC", id="phi")


def test_vector_over_the_disk_and_the_wall_zone_against_closed_forms():
    out, _ = run_scene(TUBE_RUN)
    got = printed(out, "VEC")
    want = expected_vector()
    assert want[4] > 0.05 and want[5] > 0.05  # both zones hold material
    np.testing.assert_allclose(got, want, rtol=1e-12, atol=1e-14)


def test_phi_of_z_over_the_disk_against_closed_forms():
    _, wd = run_scene(TUBE_RUN)
    rows = ave_time_rows(os.path.join(wd, "pz.dat"))
    area, w = math.pi * RC * RC, 0.5
    planes = 0.25 + w * np.arange(8)
    np.testing.assert_allclose(rows[:, 1], planes, atol=1e-15)
    phi = [sum(cut(r, p - z) for x, y, z, r in SPHERES) / area for p in planes]
    mean = [sum(slab(r, p - w / 2 - z, p + w / 2 - z) for x, y, z, r in SPHERES) / (area * w)
            for p in planes]
    np.testing.assert_allclose(rows[:, 2], phi, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(rows[:, 3], mean, rtol=1e-13, atol=1e-15)


def test_radial_profile_of_a_sphere_on_the_axis():
    """Annulus k of the sphere on the axis (R = 1.2, centre z = 1.2) holds
    V(r_k+1) - V(r_k); with a window holding the whole sphere V(rho) = 4/3 pi (R^3 - h^3),
    h = sqrt(R^2 - rho^2); with a window cutting it, the piecewise closed form `axial`. Phi on
    the surface of radius rho is the fraction of the window's height inside |z - z_c| < h."""
    _, wd = run_scene(TUBE_RUN)
    rows = ave_time_rows(os.path.join(wd, "rr.dat"))
    R, zc = 1.2, 1.2
    edges = np.linspace(0.0, 2.0, 5)
    mids = 0.5 * (edges[1:] + edges[:-1])
    np.testing.assert_allclose(rows[:, 1], mids, atol=1e-15)
    np.testing.assert_allclose(rows[:, 4], mids, atol=1e-15)

    def whole(rho):
        h = math.sqrt(max(0.0, R * R - rho * rho))
        return 4.0 / 3.0 * math.pi * (R ** 3 - h ** 3)

    for (za, zb), cols in (((-5.0, 5.0), (2, 3)), ((0.5, 1.7), (5, 6))):
        if za < -R:
            volume = [whole(edges[k + 1]) - whole(edges[k]) for k in range(4)]
        else:
            volume = [axial(R, edges[k + 1], za - zc, zb - zc) - axial(R, edges[k], za - zc,
                                                                      zb - zc)
                      for k in range(4)]
        annulus = [math.pi * (edges[k + 1] ** 2 - edges[k] ** 2) * (zb - za) for k in range(4)]
        surface = []
        for rho in mids:
            h = math.sqrt(max(0.0, R * R - rho * rho))
            surface.append(max(0.0, min(zb - zc, h) - max(za - zc, -h)) / (zb - za))
        np.testing.assert_allclose(rows[:, cols[0]], surface, rtol=1e-12, atol=1e-14)
        np.testing.assert_allclose(rows[:, cols[1]], np.array(volume) / annulus, rtol=1e-12,
                                   atol=1e-14)
    # the annuli of the whole window hold the whole sphere
    whole_vol = sum(rows[k, 3] * math.pi * (edges[k + 1] ** 2 - edges[k] ** 2) * 10.0
                    for k in range(4))
    assert whole_vol == pytest.approx(4.0 / 3.0 * math.pi * R ** 3, rel=1e-13)


def test_radial_annuli_tile_the_window_volume():
    """Over annuli from the axis to the wall, the radial profile of every sphere (spheres cut by
    annulus boundaries: the kernel's quadrature) sums to the slab's closed-form volume."""
    _, wd = run_scene(TUBE_RUN)
    rows = ave_time_rows(os.path.join(wd, "ra.dat"))
    edges = np.linspace(0.0, RC, 17)
    volume = sum(rows[k, 3] * math.pi * (edges[k + 1] ** 2 - edges[k] ** 2) * 2.5
                 for k in range(16))
    want = sum(slab(r, 0.5 - z, 3.0 - z) for x, y, z, r in SPHERES)
    assert volume == pytest.approx(want, rel=1e-12)


# ---- a lattice in the tube: 1 and 2 ranks ---------------------------------------------------
LATTICE = """units lj
atom_style sphere
boundary f f fm
region box block 0 12 0 12 0 14
create_box 1 box
region tube cylinder z 6 6 5.5 EDGE EDGE units box
region inner cylinder z 6 6 5.0 0.5 8.5 units box
lattice sc 1.0
create_atoms 1 region inner
set group all diameter 1.0
displace_atoms all random 0.05 0.05 0.05 4711 units box
compute phi all stereo/profile container tube floor 0.0
compute pz all stereo/profile container tube planes 0.0 10.0 40
compute pr all stereo/profile container tube axis r
thermo_style custom step c_phi[1] c_phi[2] c_phi[5] c_phi[6]
fix az all ave/time 1 1 1 c_pz[*] mode vector file pz.dat format " %.17g"
fix ar all ave/time 1 1 1 c_pr[*] mode vector file pr.dat format " %.17g"
run 0
""" + VECTOR_PRINT.format(tag="VEC", id="phi")


def test_same_numbers_on_one_and_two_ranks():
    results = []
    for nprocs, grid in [(1, "* * *"), (2, "2 1 1"), (2, "1 2 1")]:
        rc, out, wd = run_lammps(f"processors {grid}\n" + LATTICE, nprocs=nprocs)
        assert rc == 0, out[-2500:]
        results.append((printed(out, "VEC"), ave_time_rows(os.path.join(wd, "pz.dat")),
                        ave_time_rows(os.path.join(wd, "pr.dat"))))
    serial = results[0]
    # every measure holds spheres; the radial profile's default rows run from the axis to the
    # wall (100 bins of the tube's radius 5.5)
    assert np.all(serial[0][[0, 1, 4, 5]] > 0.3), serial[0]
    assert serial[2].shape == (100, 4)
    assert serial[2][-1, 1] == pytest.approx(5.5 * (1.0 - 0.5 / 100), rel=1e-14)
    for parallel in results[1:]:
        for a, b in zip(serial, parallel):
            np.testing.assert_allclose(b, a, rtol=1e-12, atol=1e-14)


def test_a_wall_zone_reaching_the_axis_leaves_no_core():
    out, _ = run_scene("compute c all stereo/profile container tube lateral 4.0\n"
                       "thermo_style custom step c_c[5] c_c[6]\nrun 0\n"
                       + VECTOR_PRINT.format(tag="VEC", id="c"))
    vec = printed(out, "VEC")
    assert math.isnan(vec[5]), vec
    # the wall zone is the whole disk over the default window [floor + 2R, z_top] (R: the mean
    # radius)
    za, zb = 2.0 * sum(s[3] for s in SPHERES) / len(SPHERES), vec[3]
    volume = sum(slab(r, za - z, zb - z) for x, y, z, r in SPHERES)
    assert vec[4] == pytest.approx(volume / (math.pi * RC * RC * (zb - za)), rel=1e-12)
    assert out.count("WARNING: compute stereo/profile c: no core: the wall zone (lateral = 4 "
                     "from the wall of container tube) covers the whole container radius 4") == 1, \
        out[-2000:]


def test_doc_container_examples_run():
    """The container block of the Examples of doc/compute_stereo_profile.rst runs as written in
    a tube (the doc-snippet test skips it: its default scene is periodic)."""
    doc = os.path.join(os.environ.get("TAPMC_SOURCE_DIR", "../.."), "doc",
                       "compute_stereo_profile.rst")
    with open(doc) as f:
        text = f.read()
    block = text.split("Examples\n\"\"\"\"\"\"\"\"")[1].split("Description\n")[0]
    block = block.split(".. snippet: skip")[1]
    commands = [l.strip() for l in block.splitlines() if l.startswith("   ") and l.strip()]
    assert len(commands) >= 3 and any("container tube" in c for c in commands), commands
    rc, out, wd = run_lammps(SPHERES_IN_A_BOX + "\n".join(commands) + "\nrun 0\n")
    assert rc == 0, out[-2500:]
    assert os.path.getsize(os.path.join(wd, "profile_r.dat")) > 0


# ---- bad input: a non-zero exit and a message naming the argument ----------------------------
BOX = """units lj
atom_style sphere
boundary {boundary}
region box block 0 10 0 10 0 12
create_box 1 box
create_atoms 1 single 5 5 1 units box
set group all diameter 1.0
"""
COMPUTE = "compute s all stereo/profile container tube\n"

BAD = [
    ("f f fm", COMPUTE,
     "compute stereo/profile: container = tube: no region with this ID; allowed: the ID of a "
     "region defined as 'region tube cylinder z c1 c2 radius lo hi'"),
    ("f f fm", "region tube block 1 9 1 9 0 10 units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: region style 'block' has no exact container "
     "test here; allowed: cylinder with axis z"),
    ("f f fm", "region tube sphere 5 5 5 4 units box\n" + COMPUTE,
     "region style 'sphere' has no exact container test here"),
    ("f f fm", "region tube cylinder x 5 5 4 0 10 units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the cylinder's axis is not z (its bounding box "
     "is 10 wide in x and 8 in y); allowed: cylinder with axis z"),
    # an axis along y whose length equals the diameter: the same bounding square, told apart by
    # the probes of the wall
    ("f f fm", "region tube cylinder y 5 5 4 1 9 units box\n" + COMPUTE,
     "the cylinder's axis is not z (its bounding box is 8 wide in x and 8 in y, but its wall is "
     "not a vertical circle)"),
    ("f f fm", "region tube cylinder z 5 5 4 0 INF side out units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the region is 'side out'"),
    ("f f fm", "region tube cylinder z 5 5 4 0 INF open 3 units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the region's curved wall is open ('open 3')"),
    ("f f fm", "variable dx equal 0.0\n"
     "region tube cylinder z 5 5 4 0 INF move v_dx NULL NULL units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the region moves or rotates"),
    ("f f fm", "variable rad equal 4.0\nregion tube cylinder z 5 5 v_rad 0 INF units box\n"
     + COMPUTE,
     "compute stereo/profile: container = tube: the region's centre or radius is a variable"),
    ("f f fm", "region tube cylinder z 5 5 0.4 0 INF units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: cylinder radius = 0.4 is outside the allowed "
     "range (R_max, +inf) = (0.5, +inf) (the container must be wider than its largest sphere)"),
    ("f f fm", "region tube cylinder z 5 5 0.6 0 INF units box\n"
     "compute s all stereo/profile container tube radius 0.6\n",
     "cylinder radius = 0.6 is outside the allowed range (R_max, +inf) = (0.6, +inf)"),
    # the radii grow after the compute is defined: init() checks again
    ("f f fm", "region tube cylinder z 5 5 1 0 INF units box\n" + COMPUTE
     + "set group all diameter 2.5\nthermo_style custom step c_s[1]\nrun 0\n",
     "cylinder radius = 1 is outside the allowed range (R_max, +inf) = (1.25, +inf)"),
    ("p f fm", "region tube cylinder z 5 5 4 0 INF units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the container needs non-periodic x and y "
     "(boundary f f ...), the box is periodic in x"),
    ("p p fm", "region tube cylinder z 5 5 4 0 INF units box\n" + COMPUTE,
     "the container needs non-periodic x and y (boundary f f ...), the box is periodic in x "
     "and y"),
    ("f f fm", "region tube cylinder z 5 5 6 0 INF units box\n" + COMPUTE,
     "compute stereo/profile: container = tube: the cylinder (centre (5, 5), radius 6) reaches "
     "x from -1 to 11, outside the box (x from 0 to 10)"),
    ("f f fm", "region tube cylinder z 5 7 4 0 INF units box\n" + COMPUTE,
     "reaches y from 3 to 11, outside the box (y from 0 to 10)"),
    ("f f fm", "compute s all stereo/profile axis r\n",
     "compute stereo/profile: axis = r (the radial profile) needs a cylindrical container"),
    ("f f fm", "region tube cylinder z 5 5 4 0 INF units box\n"
     "compute s all stereo/profile container tube axis x\n",
     "compute stereo/profile: axis = x is not available with container = tube; allowed: z "
     "(Phi(z) over the disk) or r (the radial profile)"),
    ("f f fm", "region tube cylinder z 5 5 4 0 INF units box\n"
     "compute s all stereo/profile container tube axis r planes -1 4 4\n",
     "compute stereo/profile: planes lo = -1 is outside the allowed range [0, hi) = [0, 4) for "
     "axis r"),
    ("f f fm", "compute s all stereo/profile container\n", "keyword 'container' needs 1 value(s)"),
]


@pytest.mark.parametrize("boundary,body,message", BAD)
def test_bad_container(boundary, body, message):
    rc, out, _ = run_lammps(BOX.format(boundary=boundary) + body)
    assert rc != 0
    assert "ERROR" in out and message in out, out[-1500:]


def test_region_deleted_after_definition_is_caught_at_run():
    rc, out, _ = run_lammps(BOX.format(boundary="f f fm")
                            + "region tube cylinder z 5 5 4 0 INF units box\n" + COMPUTE
                            + "region tube delete\nthermo_style custom step c_s[1]\nrun 0\n")
    assert rc != 0 and "container = tube: no region with this ID" in out, out[-1500:]
