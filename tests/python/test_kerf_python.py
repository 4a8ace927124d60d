"""The kerf Python module against the `kerf` command: the same scene gives the
same numbers to the last digit; a dict is a scene; errors name the key;
arrays view kerf's memory; a study runs. Run by ctest (python.pytest) with
PYTHONPATH at build/python, KERF_BINARY_DIR and KERF_SOURCE_DIR set."""
import json
import os
import subprocess

import numpy
import pytest

import kerf

SOURCE = os.environ["KERF_SOURCE_DIR"]
BUILD = os.environ["KERF_BINARY_DIR"]
CANTILEVER = os.path.join(SOURCE, "scenes", "cantilever.yaml")
TET4 = ["discretization.fem.element=tet4", "discretization.fem.size=0.004"]


def command_line_summary(tmp_path, overrides):
    out = tmp_path / "command_line"
    sets = [arg for o in overrides for arg in ("--set", o)]
    subprocess.run([os.path.join(BUILD, "cli", "kerf"), "run", CANTILEVER, "--quiet", "--out", str(out), *sets],
                   check=True)
    with open(out / "summary.json") as f:
        return json.load(f)


def test_tip_displacement_equals_the_command_lines_to_the_last_digit(tmp_path):
    result = kerf.run(CANTILEVER, TET4, out=str(tmp_path / "python"))
    expected = command_line_summary(tmp_path, TET4)
    assert result.summary["status"] == "ok"
    assert result.probes["tip"]["displacement"] == expected["probes"]["tip"]["displacement"]
    assert result.summary["counts"] == expected["counts"]
    assert os.path.exists(os.path.join(result.directory, "summary.json"))


def test_a_runs_folder_reads_back_typed_as_the_run_reported_it(tmp_path):
    result = kerf.run(CANTILEVER, TET4, out=str(tmp_path / "run"))
    record = kerf.read_outcome(result.directory)
    assert record.ok and record.status == "ok" and not record.diverged
    assert record.probes["tip"] == result.summary["probes"]["tip"]["displacement"]
    assert record.counts == {key: result.summary["counts"][key] for key in record.counts}
    for key in ("setup_s", "solve_s", "phases"):
        assert record.timing[key] == result.summary["timing"][key]
    assert result.record.probes == record.probes
    with pytest.raises(kerf.Error, match="summary.json"):
        kerf.read_outcome(str(tmp_path / "no_run"))


def test_arrays_are_read_only_views_of_the_final_body(tmp_path):
    result = kerf.run(CANTILEVER, TET4, out=str(tmp_path))
    points, u = result.points, result.displacement
    assert points.shape == (result.summary["counts"]["nodes"], 3) and u.shape == points.shape
    assert not points.flags.writeable and not points.flags.owndata  # kerf's memory, not a copy
    assert set(result.point_fields) >= {"displacement"}
    von_mises = result.cell_fields["von_mises"]  # FEM: per cell
    assert von_mises.shape == (result.summary["counts"]["elements"], 1) and (von_mises > 0).all()
    # The node nearest the tip probe (0.1, 0.01, 0.01) is on the end face, 0.4 mm off it: its
    # vertical displacement is the probe's to 1e-3 (measured 4e-7; the end face barely bends).
    tip = numpy.argmin(numpy.linalg.norm(points - [0.1, 0.01, 0.01], axis=1))
    assert numpy.linalg.norm(points[tip] - [0.1, 0.01, 0.01]) < 1e-3
    assert u[tip, 2] == pytest.approx(result.probes["tip"]["displacement"][2], rel=1e-3)
    assert u[:, 2].min() < 0.0  # it sags
    del result  # the arrays keep the body alive
    assert numpy.isfinite(u).all() and u[:, 2].min() < 0.0


def test_a_dict_is_a_scene_and_overrides_apply(tmp_path):
    scene = kerf.load_scene(CANTILEVER, TET4).to_dict()
    scene["output"]["vtk"] = False
    scene["name"] = "from_a_dict"
    result = kerf.run(scene, ["material.young=2e6"], out=str(tmp_path))
    assert result.summary["scene"]["name"] == "from_a_dict"
    assert result.summary["scene"]["material"]["young"] == 2e6
    stiff = result.probes["tip"]["displacement"][2]
    soft = kerf.run(kerf.load_scene(scene), out=str(tmp_path / "soft")).probes["tip"]["displacement"][2]
    assert stiff == pytest.approx(soft / 2, rel=1e-9)  # linear: twice the modulus, half the sag


def test_a_bad_scene_raises_kerf_error_naming_the_key():
    with pytest.raises(kerf.Error, match=r"key 'material\.poisson'.*0\.7") as raised:
        kerf.load_scene(CANTILEVER, ["material.poisson=0.7"])
    assert isinstance(raised.value, RuntimeError)
    with pytest.raises(kerf.Error, match=r"unknown key 'yuong' \(did you mean 'young'\?\)"):
        kerf.run({"domain": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, "material": {"yuong": 1}})
    with pytest.raises(kerf.Error, match="cantilever_missing.yaml"):
        kerf.load_scene(os.path.join(SOURCE, "scenes", "cantilever_missing.yaml"))


def test_a_failed_run_raises_and_leaves_its_summary(tmp_path):
    with pytest.raises(kerf.Error, match="Newton did not converge"):
        kerf.run(CANTILEVER, TET4 + ["material.model=neohookean", "body_force.gravity=[0,0,-5000]",
                                     "solve.newton.max_iterations=2"], out=str(tmp_path))
    with open(tmp_path / "summary.json") as f:
        assert json.load(f)["status"] == "error"


def test_studies_are_listed_and_run(tmp_path):
    names = [name for name, _ in kerf.studies()]
    assert {"hertz", "timing", "cut"} <= set(names)
    summary = kerf.study("solvers", quick=True, out=str(tmp_path))  # the quickest: 2 s
    assert summary["study"] == "solvers" and summary["quick"] and summary["headline"]
    assert os.path.exists(tmp_path / "solvers.csv")
    with pytest.raises(kerf.Error, match="no_such_study"):
        kerf.study("no_such_study")


CUTTING = os.path.join(SOURCE, "scenes", "cutting_2d.yaml")
SHORT_CUT = ["solve.duration=6e-4"]


def test_a_session_stepped_from_python_gives_the_command_lines_answer_to_the_last_digit(tmp_path):
    expected = kerf.run(CUTTING, SHORT_CUT, out=str(tmp_path / "batch")).summary
    with kerf.Session(CUTTING, SHORT_CUT, out=str(tmp_path / "session")) as session:
        u = session.displacement  # a view: the steps update it in place (the nodes stay: a meshless cut)
        assert not u.flags.writeable and not u.flags.owndata
        assert u.shape == (expected["counts"]["nodes"], 2)
        tops = []
        while not session.done:
            session.step()
            tops.append(u[:, 1].max())
            assert numpy.array_equal(u, session.displacement)
        assert session.steps_taken == session.step_count and session.time == pytest.approx(6e-4)
        assert len(set(tops)) > 1  # the view moved with the state
        probes = session.probes
    assert probes == expected["probes"]
    with open(tmp_path / "session" / "summary.json") as f:
        written = json.load(f)
    assert written["status"] == "ok" and written["probes"] == expected["probes"]


def test_a_session_refuses_a_step_past_its_end_and_a_bad_count(tmp_path):
    session = kerf.Session(os.path.join(SOURCE, "scenes", "plate_tension_2d.yaml"), ["solve.load_steps=1"],
                           out=str(tmp_path))
    with pytest.raises(kerf.Error, match="count is 0"):
        session.step(0)
    session.run()
    with pytest.raises(kerf.Error, match="solve.load_steps"):
        session.step()
    result = session.finish()
    assert result.summary["status"] == "ok" and result.displacement.shape[0] > 0


def test_a_cut_fed_from_python_as_the_run_goes_gives_the_scripted_runs_answer(tmp_path):
    # cutting_2d's polyline: two vertices at t = 0, then one every 1e-4 s; dt = 2e-5 s.
    scripted = kerf.run(CUTTING, SHORT_CUT, out=str(tmp_path / "scripted")).summary
    cut = kerf.load_scene(CUTTING, SHORT_CUT).to_dict()["cuts"][0]
    vertices, times = cut["polyline"], cut["times"]
    live = [*SHORT_CUT, f"cuts.0.polyline={vertices[:2]}", "cuts.0.times=[0, 0]", "cuts.0.live=true"]
    with kerf.Session(CUTTING, live, out=str(tmp_path / "live")) as session:
        fed = 2
        while not session.done:
            while fed < len(times) and times[fed] <= session.time + session.dt:
                session.extend_cut(0, [vertices[fed]])
                fed += 1
            session.step()
        assert session.probes == scripted["probes"]
    with pytest.raises(kerf.Error, match="cuts.0.live"):
        kerf.Session(CUTTING, SHORT_CUT, out=str(tmp_path / "not_live")).extend_cut(0, [[0.0, 0.0]])
    # A blade moved off the plate and on: the piece off it is refused, naming why, and the cut goes on.
    off = [*SHORT_CUT, "cuts.0.polyline=[[1.0, 1.0]]", "cuts.0.times=[0]", "cuts.0.live=true"]
    with kerf.Session(CUTTING, off, out=str(tmp_path / "off")) as session:
        with pytest.raises(kerf.Error, match="outside the body"):
            session.extend_cut(0, [[1.1, 1.0]])
        session.extend_cut(0, [[-0.0195, 0.0005]])
        session.run()


def test_a_session_pushes_a_sphere_and_reads_its_force(tmp_path):
    indentation = os.path.join(SOURCE, "scenes", "indentation.yaml")
    with kerf.Session(indentation, ["solve.duration=0.02", "output.vtk=false"], out=str(tmp_path)) as session:
        session.push_sphere(0, [0, 0, -0.005])
        session.run()
        assert session.contact_force(0) == session.probes["push"]["contact_force"]
        assert session.contact_force(0)[2] < 0.0
        with pytest.raises(kerf.Error, match="no larger"):
            session.push_sphere(0, [0, 0, -0.05])
        with pytest.raises(kerf.Error, match="driven by a force"):
            session.move_sphere(0, [0, 0, -0.001])


def test_ctrl_c_stops_a_sessions_steps_and_python_keeps_its_own_between_them(tmp_path):
    import signal
    import threading
    import time
    session = kerf.Session(CUTTING, ["solve.duration=0.02"], out=str(tmp_path))
    session.step()
    with pytest.raises(KeyboardInterrupt):  # between steps: Python's own handler, as without a session
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(5)
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(KeyboardInterrupt, match="interrupted"):  # within run(): kerf stops at its next check
        session.run()
    timer.join()
    assert 1 < session.steps_taken < session.step_count
    with open(tmp_path / "summary.json") as f:
        assert json.load(f)["status"] == "interrupted"
