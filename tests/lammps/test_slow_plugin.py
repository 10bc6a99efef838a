# TAPMC: geometric tapping model (Philippe & Bideau) for LAMMPS.
# The plugin route (label "slow"): a LAMMPS built with the PLUGIN package and C++ exceptions
# (tools/setup/build-lammps-plugin.sh: the same LAMMPS version as Debian's, and the current
# release, 4 Jul 2026) loads TAPMC with `plugin load`, from its own `lmp` and from its Python
# module; the paper's periodic example then follows exactly the trajectory of lmp_tapmc on
# Debian's LAMMPS (same kernels, same random streams), and in Python a bad TAPMC input raises an
# exception carrying TAPMC's message while LAMMPS stays usable. Each LAMMPS is skipped when it is
# not built, unless TAPMC_SLOW=1, which builds it (lammps_builds.py).
import json
import os
import re

import numpy as np
import pytest

from lammps_builds import LAMMPS_BUILDS, lammps_prefix, run, tapmc_against
from lmprun import LMP, MPIRUN, read_dump
from lmprun import thermo_table
from test_compaction import EXAMPLE

PYTHON = "/usr/bin/python3"
TAPS = 3

# The example, then its end state at full precision for an exact comparison of trajectories.
BODY = f"""include {os.path.abspath(EXAMPLE)}
write_dump all custom final.dump id x y z radius modify sort id format float %.17g
"""

PYTHON_DRIVER = r"""
import json, sys
import lammps
lib, body = sys.argv[1], sys.argv[2]
L = lammps.lammps(cmdargs=["-log", "log.lammps", "-screen", "none", "-nocite",
                           "-var", "taps", sys.argv[3]])
out = {"module": lammps.__file__, "has_exceptions": L.has_exceptions, "version": L.version()}
L.command("plugin load " + lib)
L.file(body)
out["step_after_example"] = L.get_thermo("step")

def attempt(commands):
    try:
        L.commands_list(commands)
    except Exception as e:
        return {"raised": type(e).__name__, "message": str(e)}
    return {"raised": None}

# an argument error (fix constructor) and an error inside a run (fix setup)
out["bad_argument"] = attempt(["fix bad all mc/settle 4928 dmax -1"])
out["bad_in_run"] = attempt(["group nobody empty", "fix lonely nobody mc/settle 7", "run 1"])
L.commands_list(["unfix lonely", "run 1", "variable phi_b equal c_phi[1]"])
out["step_after_errors"] = L.get_thermo("step")
out["phi_after_errors"] = L.extract_variable("phi_b")

# `clear`: LAMMPS 2021 unloads the plugins (TAPMC styles are unknown until the next
# `plugin load`); newer versions load them again by themselves
L.command("clear")
box = ["units lj", "atom_style sphere", "boundary p p fm", "region b block 0 4 0 4 0 4",
       "create_box 1 b"]
out["after_clear"] = attempt(box + ["fix tap all tapdilate 0.5 floor 0.0"])
L.command("plugin load " + lib)
L.commands_list(["fix tap all tapdilate 0.5 floor 0.0", "run 1"])
out["step_after_reload"] = L.get_thermo("step")
L.close()
print("RESULT " + json.dumps(out))
"""


@pytest.fixture(scope="module", params=sorted(LAMMPS_BUILDS))
def plugin(request):
    """(prefix of the plugin LAMMPS, TAPMC plugin library compiled against it, its name)."""
    prefix = lammps_prefix(request.param)
    build = tapmc_against(request.param, prefix, ["tapmc"])
    return prefix, os.path.join(build, "libtapmc.so"), request.param


def write_inputs(workdir, lib):
    with open(os.path.join(workdir, "in.body"), "w") as f:
        f.write(BODY)
    with open(os.path.join(workdir, "in.plugin"), "w") as f:
        f.write(f"plugin load {lib}\nplugin list\n" + BODY)


def final_state(workdir):
    ((_, box, _, cols),) = read_dump(os.path.join(workdir, "final.dump"))
    return box, np.column_stack([cols[c] for c in ("id", "x", "y", "z", "radius")])


def measurements(log_text):
    """Thermo rows without the timing columns (cpu, cpuremain: they differ run to run)."""
    names, table = thermo_table(log_text)
    keep = [k for k, name in enumerate(names) if name not in ("CPU", "CPULeft")]
    return [names[k] for k in keep], table[:, keep]


def lmp_tapmc_run(workdir, ranks):
    write_inputs(workdir, lib="unused")
    cmd = [LMP, "-in", "in.body", "-var", "taps", str(TAPS), "-log", "log.lammps", "-nocite"]
    rc, out = run(MPIRUN + ["-np", str(ranks)] + cmd if ranks > 1 else cmd, cwd=workdir)
    assert rc == 0, out
    return measurements(out), final_state(workdir)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The example under lmp_tapmc (Debian's LAMMPS, styles registered by the launcher)."""
    return lmp_tapmc_run(str(tmp_path_factory.mktemp("reference")), 1)


@pytest.fixture(scope="module")
def reference_two_ranks(tmp_path_factory):
    """The same on 2 ranks: fix mc/settle's decomposed redeposition (scheme auto), whose
    trajectory is fixed by the seed and the processor grid."""
    return lmp_tapmc_run(str(tmp_path_factory.mktemp("reference2")), 2)


def test_plugin_lmp_follows_the_lmp_tapmc_trajectory(plugin, reference, tmp_path):
    prefix, lib, _ = plugin
    write_inputs(str(tmp_path), lib)
    rc, out = run([os.path.join(prefix, "bin", "lmp"), "-in", "in.plugin", "-var", "taps",
                   str(TAPS), "-log", "log.lammps", "-nocite"], cwd=str(tmp_path))
    assert rc == 0, out
    for style in ("fix style plugin tapdilate", "fix style plugin mc/settle",
                  "compute style plugin stereo/profile", "command style plugin create_packing"):
        assert style in out, (style, out)
    (names, table), (box, atoms) = measurements(out), final_state(str(tmp_path))
    (ref_names, ref_table), (ref_box, ref_atoms) = reference
    assert names == ref_names
    assert table[-1, 0] == TAPS
    np.testing.assert_array_equal(table, ref_table)
    np.testing.assert_array_equal(box, ref_box)
    np.testing.assert_array_equal(atoms, ref_atoms)


def test_plugin_lmp_under_mpirun(plugin, reference_two_ranks, tmp_path):
    """`plugin load` registers the styles on every rank, and the decomposed redeposition (its
    forward communication of the moved spheres, the per-atom round that travels with migrating
    atoms) follows on the plugin LAMMPS exactly the 2-rank trajectory of lmp_tapmc (the printed
    measurements are sums over ranks, which may round differently in the last bits)."""
    prefix, lib, _ = plugin
    write_inputs(str(tmp_path), lib)
    rc, out = run(MPIRUN + ["-np", "2", os.path.join(prefix, "bin", "lmp"), "-in", "in.plugin",
                            "-var", "taps", str(TAPS), "-log", "log.lammps", "-nocite"],
                  cwd=str(tmp_path))
    assert rc == 0, out
    (names, table), (box, atoms) = measurements(out), final_state(str(tmp_path))
    (ref_names, ref_table), (ref_box, ref_atoms) = reference_two_ranks
    assert names == ref_names
    np.testing.assert_allclose(table, ref_table, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(box, ref_box)
    np.testing.assert_array_equal(atoms, ref_atoms)


def test_python_module_raises_on_bad_input_and_keeps_going(plugin, reference, tmp_path):
    prefix, lib, _ = plugin
    write_inputs(str(tmp_path), lib)
    env = dict(os.environ, PYTHONPATH=os.path.join(prefix, "python"))
    driver = tmp_path / "driver.py"
    driver.write_text(PYTHON_DRIVER)
    rc, out = run([PYTHON, str(driver), lib, "in.body", str(TAPS)], cwd=str(tmp_path), env=env)
    assert rc == 0, out
    result = json.loads(next(line for line in out.splitlines()
                             if line.startswith("RESULT "))[len("RESULT "):])
    assert result["module"].startswith(os.path.join(prefix, "python")), result["module"]
    assert result["has_exceptions"]

    # the example from Python: the same trajectory as lmp_tapmc
    assert result["step_after_example"] == TAPS
    with open(tmp_path / "log.lammps") as f:
        names, table = measurements(f.read())
    (ref_names, ref_table), (ref_box, ref_atoms) = reference
    assert names == ref_names
    np.testing.assert_array_equal(table, ref_table)
    box, atoms = final_state(str(tmp_path))
    np.testing.assert_array_equal(box, ref_box)
    np.testing.assert_array_equal(atoms, ref_atoms)

    # bad input raises a Python exception with TAPMC's message, instead of ending the process
    bad = result["bad_argument"]
    assert bad["raised"] is not None, result
    assert "fix mc/settle: dmax = -1 is outside the allowed range (0, +inf)" in bad["message"], bad
    bad = result["bad_in_run"]
    assert bad["raised"] is not None, result
    assert "fix mc/settle: group 'nobody' has no atoms" in bad["message"], bad
    # (the Python module of LAMMPS 2021 keeps the first 99 characters; in 2026 the exception has
    # the whole message, source location and input line; the log has the whole line)
    if result["version"] >= 20260704:
        assert re.search(r"\(0, \+inf\) \(\S+:\d+\)\nLast input line: fix bad all mc/settle "
                         r"4928 dmax -1$", result["bad_argument"]["message"]), result
    with open(tmp_path / "log.lammps") as f:
        log = f.read()
    assert "ERROR: fix mc/settle: dmax = -1 is outside the allowed range (0, +inf) (" in log
    # and the same LAMMPS instance runs on: one more tap
    assert result["step_after_errors"] == TAPS + 1
    assert 0.5 < result["phi_after_errors"] < 0.65

    # `clear` unloads the plugin in LAMMPS 2021 (loading it again brings the styles back); later
    # versions keep the loaded plugins through `clear`
    if result["version"] < 20220324:
        assert "Unrecognized fix style 'tapdilate'" in result["after_clear"]["message"], result
    else:
        assert result["after_clear"]["raised"] is None, result
    assert result["step_after_reload"] == 1
