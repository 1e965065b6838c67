"""Acceptance of the Python front: the same results as the command line (to the bit), history
arrays equal to history.csv, one-line ValueErrors naming the field, Ctrl-C stopping a run where
it is, and the GIL released during runs. No test depends on the machine's speed or load."""

import csv
import json
import os
import signal
import threading
import time

import numpy as np
import pytest

import twoball

COARSE = {"size": 0.0068, "pole_size": 0.0034}
COARSE_SETS = {"ball1.mesh": COARSE, "ball2.mesh": COARSE}
COARSE_FLAGS = [
    "--set", "ball1.mesh={size=0.0068,pole_size=0.0034}",
    "--set", "ball2.mesh={size=0.0068,pole_size=0.0034}",
]

# An oblique impact of unequal balls: copper on steel, different diameters, tangential speed.
OBLIQUE_TOML = """
[ball1]
material = "copper-fe"
diameter = 0.02
velocity = [1.0, 0.3, 0.0]
mesh = { size = 0.0068, pole_size = 0.0034 }

[ball2]
material = "steel"
diameter = 0.015
velocity = [-0.5, 0.0, 0.0]
mesh = { size = 0.0051, pole_size = 0.00255 }
"""
OBLIQUE = {
    "ball1": {"material": "copper-fe", "diameter": 0.02, "velocity": [1.0, 0.3, 0.0],
              "mesh": {"size": 0.0068, "pole_size": 0.0034}},
    "ball2": {"material": "steel", "diameter": 0.015, "velocity": [-0.5, 0.0, 0.0],
              "mesh": {"size": 0.0051, "pole_size": 0.00255}},
}


def exact(value):
    """Canonical text of a JSON value: floats by repr, so equal text means equal bits."""
    return json.dumps(value, sort_keys=True)


def without_wall_times(value):
    """`value` without the wall-clock fields (the only ones that differ between two runs)."""
    if isinstance(value, dict):
        return {
            k: without_wall_times(v)
            for k, v in value.items()
            if k not in ("wall_time_s", "cpu_time_s")
        }
    if isinstance(value, list):
        return [without_wall_times(v) for v in value]
    return value


def cli_error(cli, *args):
    code, _, err = cli(*args)
    assert code == 1, err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), err
    return lines[0][len("error: "):]


# --- analytic -----------------------------------------------------------------------------


def test_analytic_default_equals_the_cli_json_to_the_bit(cli):
    code, out, err = cli("analytic", "--json")
    assert code == 0, err
    assert exact(twoball.analytic()) == exact(json.loads(out))


def test_analytic_oblique_unequal_equals_the_cli_json_to_the_bit(cli):
    code, out, err = cli(
        "analytic", "--material", "copper-fe", "--diameter", "0.02", "--material2", "steel",
        "--diameter2", "0.015", "--v1", "1.0", "--v2", "-0.5", "--v1t", "0.3", "--json",
    )
    assert code == 0, err
    py = twoball.analytic(material="copper-fe", diameter=0.02, material2="steel",
                          diameter2=0.015, v1=1.0, v2=-0.5, v1t=0.3)
    assert py["v1t_after"] != 0.3, "the oblique case must exercise friction"
    assert exact(py) == exact(json.loads(out))


def test_materials_and_laws_equal_the_cli(cli):
    code, out, _ = cli("materials", "--json")
    assert code == 0
    assert exact(twoball.materials()) == exact(json.loads(out))
    names = [law["name"] for law in twoball.laws.list()["normal"]]
    code, listing, _ = cli("laws")
    assert code == 0 and names and all(n in listing for n in names)
    law = names[0]
    code, out, err = cli("laws", "run", "--law", law, "--v1", "2.0", "--v1t", "0.5", "--json")
    assert code == 0, err
    assert exact(twoball.laws.run(law, v1=2.0, v1t=0.5)) == exact(json.loads(out))


# --- run ----------------------------------------------------------------------------------


def read_history_csv(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], np.array([[float(x) for x in r] for r in rows[1:]])


def check_run_against_cli(py_run, py_out, cli_out):
    cli_results = json.loads((cli_out / "results.json").read_text())
    assert py_run.results["impact"] is True
    assert exact(without_wall_times(py_run.results)) == exact(without_wall_times(cli_results))
    # out= writes the usual files: the history byte for byte, results.json but wall times.
    assert (py_out / "history.csv").read_bytes() == (cli_out / "history.csv").read_bytes()
    written = json.loads((py_out / "results.json").read_text())
    assert exact(without_wall_times(written)) == exact(without_wall_times(cli_results))
    # History arrays: one per history.csv column, equal to its cells at their 10 digits.
    header, table = read_history_csv(cli_out / "history.csv")
    assert [f"{n} [{py_run.units[n]}]" for n in py_run.columns] == header
    assert len(table) > 10
    for k, name in enumerate(py_run.columns):
        column = py_run.history[name]
        assert column.dtype == np.float64 and column.shape == (len(table),)
        printed = np.array([float(f"{x:.9e}") for x in column])
        assert np.array_equal(printed, table[:, k]), name
    assert py_run.history["delta"].max() > 0 and py_run.history["normal_force"].max() > 0


def test_run_default_scene_equals_the_cli(cli, tmp_path):
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    code, _, err = cli("run", *COARSE_FLAGS, "--out", str(cli_out))
    assert code == 0, err
    r = twoball.run(out=py_out, **COARSE_SETS)
    check_run_against_cli(r, py_out, cli_out)
    assert r.results["reduction"] == "axisymmetric"


def test_run_to_a_tolerance_equals_the_cli(cli, tmp_path):
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    code, _, err = cli("run", "--tolerance", "0.5%", "--out", str(cli_out))
    assert code == 0, err
    r = twoball.run(out=py_out, tolerance=0.005)
    check_run_against_cli(r, py_out, cli_out)
    est = r.results["error_estimate"]
    assert est["method"]["kind"] == "banded_family"
    assert est["tolerance_met"] is True and est["e"]["relative_error"] <= 0.005
    for bad in (0.0, 1.5, float("nan")):
        with pytest.raises(ValueError, match="tolerance"):
            twoball.run(tolerance=bad)


def test_run_oblique_unequal_pair_equals_the_cli(cli, tmp_path):
    scene = tmp_path / "oblique.toml"
    scene.write_text(OBLIQUE_TOML)
    cli_out = tmp_path / "cli"
    code, _, err = cli("run", str(scene), "--out", str(cli_out))
    assert code == 0, err
    from_dict = twoball.run(OBLIQUE, out=tmp_path / "dict")
    check_run_against_cli(from_dict, tmp_path / "dict", cli_out)
    assert from_dict.results["reduction"] == "full" or from_dict.results["reduction"] == "half"
    assert abs(from_dict.results["v1_after"][1] - 0.3) > 1e-6, "friction acts"
    from_file = twoball.run(scene, out=tmp_path / "file")
    check_run_against_cli(from_file, tmp_path / "file", cli_out)


def test_overrides_use_the_cli_set_syntax(cli, tmp_path):
    code, _, err = cli("run", *COARSE_FLAGS, "--set", "ball1.velocity=[2.0, 0.0, 0.0]",
                       "--set", "ball2.material=steel", "--out", str(tmp_path / "cli"))
    assert code == 0, err
    r = twoball.run(overrides={"ball1.velocity": np.array([2, 0, 0])},
                    **{"ball2.material": "steel"}, **COARSE_SETS)
    cli_results = json.loads((tmp_path / "cli" / "results.json").read_text())
    assert exact(without_wall_times(r.results)) == exact(without_wall_times(cli_results))
    assert r.results["scene"]["ball1"]["velocity"] == [2.0, 0.0, 0.0]


def test_progress_callback_sees_the_run_advance():
    # The 3D quarter model on the default mesh: about a second, so many 20 ms polls on any
    # machine (the coarse mesh's 3D run can finish within one poll; the section's takes
    # milliseconds).
    seen = []
    twoball.run(progress=lambda done, total: seen.append((done, total)),
                **{"reduction.symmetry": "auto-3d"})
    assert len(seen) >= 2
    done = [d for d, _ in seen]
    assert done == sorted(done) and all(t > 0 for _, t in seen)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop()

    with pytest.raises(Stop):
        twoball.run(progress=stop, **COARSE_SETS)


# --- sweep --------------------------------------------------------------------------------

SWEEP = """
[study]
model = "analytic"
diameters = [0.005, 0.02]
left_velocity = 1.0
right_velocities = [-1.0, 0.5]
tangential = [[0.0, 0.0], [0.1, -0.1]]
history_points = 50
[base]
ball1.material = "copper-fe"
ball2.material = "copper-fe"
"""


def sweep_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    wall = rows[0].index("wall_time [s]")
    return [r[:wall] + r[wall + 1:] for r in rows]


def test_sweep_equals_the_cli_and_resumes(cli, tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(SWEEP)
    code, _, err = cli("sweep", str(spec), "--out", str(tmp_path / "cli"), "--jobs", "2")
    assert code == 0, err
    calls = []
    s = twoball.sweep(spec, tmp_path / "py", jobs=2, progress=lambda d, t: calls.append((d, t)))
    assert s["total"] == s["ran"] == 8 and s["skipped"] == 0 and s["failed"] == 0
    assert sweep_rows(tmp_path / "py" / "sweep.csv") == sweep_rows(tmp_path / "cli" / "sweep.csv")
    # Resumable: a lost case is run again, the others are kept.
    cases = sorted((tmp_path / "py" / "cases").iterdir())
    assert len(cases) == 8
    cases[3].unlink()
    again = twoball.sweep(spec, tmp_path / "py", jobs=1)
    assert again["ran"] == 1 and again["skipped"] == 7
    assert sweep_rows(tmp_path / "py" / "sweep.csv") == sweep_rows(tmp_path / "cli" / "sweep.csv")


# --- bad input ----------------------------------------------------------------------------


def test_bad_input_raises_value_error_with_the_cli_message(cli, tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(SWEEP)
    bad_scene = tmp_path / "bad.toml"
    bad_scene.write_text(OBLIQUE_TOML.replace("diameter = 0.015", "diameter = -0.015"))
    cases = [
        ("--diameter", lambda: twoball.analytic(diameter=-0.02),
         ["analytic", "--diameter", "-0.02"]),
        ("--material", lambda: twoball.analytic(material="unobtainium"),
         ["analytic", "--material", "unobtainium"]),
        ("ball1.material.yield", lambda: twoball.run(**{"ball1.material.yield": -5.0}),
         ["run", "--set", "ball1.material.yield=-5.0"]),
        ("ball2.diameter", lambda: twoball.run(bad_scene), ["run", str(bad_scene)]),
        ("--law", lambda: twoball.laws.run("no-such-law"),
         ["laws", "run", "--law", "no-such-law"]),
        ("--jobs", lambda: twoball.sweep(spec, tmp_path / "o", jobs=0),
         ["sweep", str(spec), "--out", str(tmp_path / "o2"), "--jobs", "0"]),
    ]
    for field, call, args in cases:
        with pytest.raises(ValueError) as raised:
            call()
        message = str(raised.value)
        assert "\n" not in message and field in message, message
        assert message == cli_error(cli, *args), field
    # A scene dict with the same mistake names the same field.
    bad = json.loads(json.dumps(OBLIQUE))
    bad["ball2"]["diameter"] = -0.015
    with pytest.raises(ValueError, match="ball2.diameter"):
        twoball.run(bad)


# --- Ctrl-C and the GIL -------------------------------------------------------------------


def test_keyboard_interrupt_stops_a_long_run(tmp_path):
    # Ctrl-C is sent once the run's time loop has reported progress, from a thread the
    # progress callback starts, so it lands mid-run however fast or loaded the machine is (a
    # timer at a fixed wall time can fire before the time loop starts, or after a fast run
    # has ended). Python installs its KeyboardInterrupt handler only where SIGINT was not
    # ignored when it started (a background job's is), so the test installs it.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    sent = []

    def interrupt():
        signal.pthread_kill(threading.main_thread().ident, signal.SIGINT)

    def progress(done, total):
        if not sent and done > 0:
            sent.append((done, total))
            threading.Thread(target=interrupt).start()

    try:
        with pytest.raises(KeyboardInterrupt):
            # The 3D model on a pole of D/400: seconds of time loop, so the interrupt lands
            # long before its end.
            fine = {"size": 0.002, "pole_size": 0.00005}
            twoball.run(out=tmp_path / "out", progress=progress,
                        **{"reduction.symmetry": "auto-3d",
                           "ball1.mesh": fine, "ball2.mesh": fine})
    finally:
        signal.signal(signal.SIGINT, previous)
    assert sent, "the run ended before it reported progress"
    done, total = sent[0]
    print(f"interrupt sent at t = {done:.3e} s of about {total:.3e} s")
    assert done < total
    # Ctrl-C cancels the job and waits for it to stop: a job that ran on to its end would
    # have written its results.
    assert not (tmp_path / "out" / "results.json").exists()


MEDIUM = {"size": 0.003, "pole_size": 0.0015}
THREE_D = {"reduction.symmetry": "auto-3d"}


def test_two_threads_run_two_scenes_with_the_gil_released():
    # Two runs on two Python threads give the serial runs' results to the bit, and while the
    # runs work in native code they hold no GIL: the main thread runs Python between their
    # progress reports (holding the GIL, a run would let it in only during a report).
    scenes = [
        dict(overrides={"ball1.mesh": MEDIUM, "ball2.mesh": MEDIUM, **THREE_D}),
        dict(overrides={"ball1.mesh": MEDIUM, "ball2.mesh": MEDIUM, **THREE_D,
                        "ball1.velocity": [2.0, 0.0, 0.0]}),
    ]
    serial = [twoball.run(**s).results for s in scenes]
    results = [None, None]
    reported = [False, False]
    reporting = [False, False]

    def work(k):
        def progress(done, total):
            reporting[k] = True
            reported[k] = True
            reporting[k] = False

        results[k] = twoball.run(progress=progress, **scenes[k]).results

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    ran_beside = 0
    while any(t.is_alive() for t in threads):
        if any(reported[k] and results[k] is None and not reporting[k] for k in range(2)):
            ran_beside += 1
        time.sleep(0.001)
    for t in threads:
        t.join()
    for a, b in zip(serial, results):
        assert exact(without_wall_times(a)) == exact(without_wall_times(b))
    assert ran_beside > 0
