# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
"""The hard-sphere fluid of the p0-fluid question (bench/bench_hs_fluid.cpp, compiled here):
it keeps N spheres without overlap in the periodic box at the asked Phi and is an equilibrium
fluid (contact value against Carnahan-Starling); and the rendering of p0_fluid.csv into the
report's questions section (tapmc.paper.questions)."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

SOURCE = Path(os.environ.get("TAPMC_SOURCE_DIR", Path(__file__).resolve().parents[2]))
sys.path.insert(0, str(SOURCE / "tools" / "python"))

from tapmc.paper import claims, questions  # noqa: E402
from tapmc.paper.questions import p0_fluid  # noqa: E402

MC_SOURCE = SOURCE / "bench" / "bench_hs_fluid.cpp"
#: a small fluid: 4 * 6^3 = 864 spheres, enough for g(1+) to a few per cent in a second.
CELLS = 6
#: g(1+) of the small run against Carnahan-Starling: its sampling noise is about 2 %.
CONTACT_TOLERANCE = 0.06


@pytest.fixture(scope="module")
def mc(tmp_path_factory):
    cxx = os.environ.get("CXX") or shutil.which("c++") or shutil.which("g++")
    if not cxx:
        pytest.skip("no C++ compiler to build bench/bench_hs_fluid.cpp")
    exe = tmp_path_factory.mktemp("mc") / "bench_hs_fluid"
    subprocess.run([cxx, "-O2", "-std=c++17", "-o", str(exe), str(MC_SOURCE)], check=True)
    return exe


def run_mc(exe, folder, *args):
    done = subprocess.run([str(exe), *args, "--prefix", str(folder / "fluid")],
                          capture_output=True, text=True)
    return done


def parse(text):
    return p0_fluid.parse_mc(text)


def read_dump(path):
    lines = Path(path).read_text().splitlines()
    n = int(lines[3])
    box = np.array([[float(v) for v in lines[5 + k].split()] for k in range(3)])
    assert lines[4] == "ITEM: BOX BOUNDS pp pp pp"
    atoms = np.array([[float(v) for v in line.split()] for line in lines[9:9 + n]])
    return n, box, atoms


@pytest.fixture(scope="module")
def fluid(mc, tmp_path_factory):
    folder = tmp_path_factory.mktemp("fluid")
    done = run_mc(mc, folder, "--phi", "0.3", "--cells", str(CELLS), "--seed", "7",
                  "--configs", "4", "--eq-msd", "1", "--spacing-msd", "4")
    assert done.returncode == 0, done.stderr
    return folder, parse(done.stdout)


def test_mc_keeps_n_spheres_without_overlap_at_phi(fluid):
    folder, (values, configs) = fluid
    assert len(configs) == 4 and int(values["N"]) == 4 * CELLS ** 3
    for k in range(1, 5):
        n, box, atoms = read_dump(folder / f"fluid.{k}.lammpstrj")
        assert n == 4 * CELLS ** 3 and len(atoms) == n
        length = box[0, 1] - box[0, 0]
        assert np.allclose(box[:, 1] - box[:, 0], length)
        assert n * np.pi / 6 / length ** 3 == pytest.approx(0.3, rel=1e-9)
        xyz = atoms[:, 2:5]
        assert np.all((xyz >= 0) & (xyz < length)) and np.all(atoms[:, 5] == 0.5)
        d = xyz[:, None, :] - xyz[None, :, :]
        d -= length * np.round(d / length)
        r = np.sqrt((d ** 2).sum(-1)) + np.eye(n) * length
        assert r.min() >= 1.0
        assert configs[k - 1]["min_distance"] == pytest.approx(r.min(), rel=1e-9)


def test_mc_is_an_equilibrium_fluid(fluid):
    _, (values, configs) = fluid
    assert 0.25 <= values["acceptance"] <= 0.45  # tuned to 0.35, then frozen
    assert values["eq_msd"] >= 1.0 and values["min_spacing_msd"] >= 4.0
    cs = (1 - 0.15) / 0.7 ** 3
    assert values["g_contact_cs"] == pytest.approx(cs, rel=1e-5)
    assert values["g_contact"] == pytest.approx(cs, rel=CONTACT_TOLERANCE)


def test_mc_refuses_a_phi_out_of_range(mc, tmp_path):
    done = run_mc(mc, tmp_path, "--phi", "0.7")
    assert done.returncode == 1 and "--phi must be a number in [0.01, 0.58]" in done.stderr


P0_HEADER = ("phi,N,configs,phi_points,phi_points_sem,p0_points,max_abs_diff,max_abs_diff_sem,"
             "sigma_at_max,diff_at_max,py_at_max,max_abs_diff_per_config,"
             "max_abs_diff_per_config_sem,max_abs_diff_exact_phi,acceptance,delta,eq_sweeps,sample_sweeps,eq_msd,"
             "min_spacing_msd,g_contact,g_contact_sem,g_contact_cs,min_distance,mc_seconds")


def p0_csv(folder, g_high=7.55):
    rows = [(0.3, 0.0034, 1.57, 0.0034, 0.17, 2.478, 2.478),
            (0.54, 0.0065, 1.25, 0.0065, 0.13, g_high, 7.5)]
    lines = [P0_HEADER]
    for phi, diff, sigma, signed, py, g, cs in rows:
        lines.append(f"{phi},4000,4,{phi},0.0003,200000,{diff},0.0004,{sigma},{signed},{py},0.004,"
                     f"0.0003,0.005,0.35,0.1,1000,1000,2.01,0.5,{g},0.01,{cs},1.00001,10")
    (folder / "p0_fluid.csv").write_text("\n".join(lines) + "\n")


def fig9(diff):
    sigma = [1.0, 1.2, 1.4]
    return claims.FigureData({
        ("params", "phi_final"): {"x": [0.0], "mean": [0.606], "sem": [np.nan], "n": [1]},
        ("params", "max_abs_diff_final_py"): {"x": [0.0], "mean": [diff], "sem": [np.nan],
                                              "n": [1]},
        ("a", "final"): {"x": sigma, "mean": [0.39, 0.1 - diff, 0.02], "sem": [0, 0, 0],
                         "n": [1, 1, 1]},
        ("a", "percus_yevick"): {"x": sigma, "mean": [0.39, 0.1, 0.02], "sem": [0, 0, 0],
                                 "n": [0, 0, 0]}})


def test_p0_fluid_rendering_against_the_packing(tmp_path):
    p0_csv(tmp_path)
    text = "\n".join(questions.render_section(tmp_path, {"fig9": fig9(0.025)}))
    assert "``p0-fluid``" in text and "N = 4000 spheres" in text and "200000 random" in text
    assert ("   * - 0.540\n     - 0.0065 ± 0.0004\n     - 1.250\n     - +0.0065\n"
            "     - 7.550 ± 0.010") in text
    assert "within 0.7 % of Carnahan-Starling" in text
    assert ("At Phi = 0.300, where PY is most accurate, the measured P0 departs from it by at "
            "most 0.0034 ± 0.0004 (P0 above PY)") in text
    assert ("(Fig. 9's run; Phi = 60.6 %) departs from PY by 0.025 at sigma = 1.20, P0 below PY "
            "(opposite to the fluid): 3.8 times") in text and "markedly less closely" in text
    close = "\n".join(questions.render_section(tmp_path, {"fig9": fig9(0.008)}))
    assert "1.2 times the equilibrium" in close and "as close as a fluid's" in close
    assert "reaches 0.0074 at the packing's Phi; the packing's is 3.4 times that" in text
    # fig9(0.025): PY = 0.1 at the packing's max; the fluid's 0.0034 / 0.17 and 0.0065 / 0.13
    assert "the packing departs by 25 %, the fluid by 2.0 to 5.0 % (growing with Phi)" in text


def test_p0_fluid_flags_a_sample_off_carnahan_starling(tmp_path):
    p0_csv(tmp_path, g_high=6.5)
    text = "\n".join(questions.render_section(tmp_path))
    assert "more than 3 % at Phi = 0.540" in text
    # the baseline falls back to the highest Phi that passed; no Fig. 9, no comparison
    assert "the exact fluid departs" not in text and "The tapped packing" not in text


def test_section_without_p0_fluid_is_unchanged(tmp_path):
    (tmp_path / "spectral_window.csv").write_text(
        "run,eps,taps,window,slope,slope_error\na,0.01,4000,250,-1.10,0.15\n")
    before = questions.render_section(tmp_path)
    assert "p0-fluid" not in "\n".join(before)
    p0_csv(tmp_path)
    after = questions.render_section(tmp_path)
    assert after[:3] == before[:3] and "``p0-fluid``" in after[3]
    assert after[5:5 + len(before) - 5] == before[5:]


def test_p0_fluid_question_end_to_end(mc, tmp_path):
    """tapmc-paper question p0-fluid on a tiny fluid writes the CSV the page renders."""
    from tapmc.paper import _runs

    if not _runs.pores_available():
        pytest.skip("tapmc-pores is not built")
    done = subprocess.run(
        [sys.executable, "-m", "tapmc.paper", "question", "p0-fluid", "--phi", "0.3",
         "--configs", "2", "--cells", "4", "--eq-msd", "0.2", "--spacing-msd", "0.1",
         "--mc", str(mc), "--out", str(tmp_path), "--work", str(tmp_path / "work")],
        capture_output=True, text=True, timeout=120,
        env=dict(os.environ, PYTHONPATH=str(SOURCE / "tools" / "python")))
    assert done.returncode == 0, done.stderr
    rows = (tmp_path / "p0_fluid.csv").read_text().splitlines()
    assert rows[0] == P0_HEADER and len(rows) == 2 and rows[1].startswith("0.3,256,2,")
    assert (tmp_path / "work" / "p0_fluid_curves.csv").is_file()
    text = "\n".join(questions.render_section(tmp_path))
    assert "N = 256 spheres" in text and "   * - 0.300" in text


def test_p0_fluid_prefers_the_tapped_configurations(tmp_path):
    """With p0_configs.csv beside it, the packing's departure from PY is that of the mean of
    the tapped configurations (PY at their Phi), not of Fig. 9's single run."""
    from tapmc.pores import percus_yevick_p0

    p0_csv(tmp_path)
    sig = [0.0, 1.0, 1.2, 1.4]
    lines = ["sigma,initial,initial_sem,initial_n,tapped,tapped_sem,tapped_n"]
    for x in sig:
        py = float(percus_yevick_p0(x, 0.604))
        tapped = py + (0.012 if x == 1.2 else 0.0)
        lines.append(f"{x},{py},0.001,8,{tapped},0.0005,8")
    lines.append("phi,0.582,0.0005,8,0.604,0.0005,8")
    (tmp_path / "p0_configs.csv").write_text("\n".join(lines) + "\n")
    text = "\n".join(questions.render_section(tmp_path, {"fig9": fig9(0.025)}))
    assert ("(mean of 8 tapped configurations, ``p0_configs.csv``; Phi = 60.4 %) departs from "
            "PY by 0.012 at sigma = 1.20, P0 above PY") in text
