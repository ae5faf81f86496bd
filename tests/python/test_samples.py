"""The Python samples run, and the Dask sweep equals a sequential run exactly."""
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

SAMPLES = SOURCE_DIR / "samples" / "python"
sys.path.insert(0, str(SAMPLES))
import sweep_dask  # noqa: E402

distributed = pytest.importorskip("dask.distributed")


def test_sweep_on_a_local_cluster_equals_the_sequential_run():
    mus, solvers, steps = [0.2, 0.3, 0.5], ["auto", "pgs!"], 60
    cluster = sweep_dask.local_cluster(2)
    try:
        with distributed.Client(cluster) as client:
            rows = sweep_dask.sweep(client, mus, solvers, steps)
    finally:
        cluster.close()
    expected = [sweep_dask.slide(mu, s, steps) for mu in mus for s in solvers]
    strip = lambda r: {k: v for k, v in r.items() if k != "ms_per_step"}  # noqa: E731
    assert [strip(r) for r in rows] == [strip(r) for r in expected]
    for row in rows:  # slides below tan 20 = 0.364 at the analytic rate, sticks above
        assert row["error"] < 1e-6, row


def test_sweep_script_prints_its_table():
    out = subprocess.run([sys.executable, str(SAMPLES / "sweep_dask.py"), "--steps", "30",
                          "--solvers", "auto"], check=True, capture_output=True, text=True,
                         timeout=240).stdout
    assert "| mu | a exact [m/s^2] | auto error |" in out
    assert out.count("\n| 0.") == 13


def run_sample(name, *args):
    return subprocess.run([sys.executable, str(SAMPLES / name), *args], check=True,
                          capture_output=True, text=True, timeout=240).stdout


def test_robot_arm_reaches_its_targets():
    out = run_sample("robot_arm.py")
    errors = [float(line.split("largest joint error ")[1].split()[0])
              for line in out.splitlines() if "largest joint error" in line]
    assert len(errors) == 2 and max(errors) < 1e-6, out


def test_compare_solvers_prints_every_solver(data_dir):
    out = run_sample("compare_solvers.py", str(data_dir / "fc3d" / "Rover1039.fc3d"))
    rows = [line for line in out.splitlines() if line.startswith("| Rover1039 |")]
    assert len(rows) == 9 and "| ac_newton | converged |" in out
