"""The Python package against the command line: same numbers, overrides (numpy scalars too),
errors as ValueError with the command's message, complete files, the GIL released during a
solve, and a panic that does not kill the interpreter."""

import csv
import json
import pathlib
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

import piezocontact

ROOT = pathlib.Path(__file__).resolve().parents[2]
PAPER_71 = ROOT / "cases" / "paper-7.1.toml"
PAPER_72 = ROOT / "cases" / "paper-7.2.toml"
COARSE = {"mesh.nx": 24, "mesh.ny": 4}


def strict_json(text):
    """Parses JSON, refusing the NaN and Infinity tokens that Python's json module accepts."""

    def refuse(token):
        raise AssertionError(f"{token} in a JSON output")

    return json.loads(text, parse_constant=refuse)


def cli():
    """The piezocontact command built by `cargo test` or `cargo build` (debug or release)."""
    for profile in ("release", "debug"):
        exe = ROOT / "target" / profile / "piezocontact"
        if exe.exists():
            return exe
    raise AssertionError("build the command first: cargo build -p piezocontact-cli")


def cli_run(case, out, overrides):
    """`piezocontact run CASE --out OUT --set k=v ...`; returns summary.json and the rows of
    contact.csv."""
    sets = [a for k, v in overrides.items() for a in ("--set", f"{k}={v}")]
    subprocess.run([cli(), "run", case, "--out", out, "-q", *sets], check=True)
    summary = strict_json((out / "summary.json").read_text())
    with open(out / "contact.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    return summary, rows


@pytest.mark.parametrize("case", [PAPER_71, PAPER_72])
def test_solve_gives_the_command_s_numbers(tmp_path, case):
    summary, rows = cli_run(case, tmp_path / "cli", COARSE)
    solution = piezocontact.solve(case, COARSE)
    assert solution.converged
    ours = solution.summary
    for key in ("max_abs_sigma_nu", "max_abs_sigma_tau", "contact_measure", "slip_measure"):
        assert ours["gamma3"][key] == pytest.approx(summary["gamma3"][key], rel=1e-12, abs=1e-300)
    assert ours["outer_iterations"] == summary["outer_iterations"]
    assert ours["inner_iterations"] == summary["inner_iterations"]
    contact = solution.contact
    assert list(contact) == list(rows[0])  # the contact.csv columns, in order
    for name in rows[0]:
        column = [r[name] for r in rows]
        if name == "status":
            assert list(contact[name]) == column
        else:
            # contact.csv holds each number's shortest round-trip form: equal to the last bit.
            np.testing.assert_array_equal(contact[name], np.array(column, dtype=float))


def test_points_u_and_phi_are_nodal_arrays():
    solution = piezocontact.solve(PAPER_72, COARSE)
    n = (24 + 1) * (4 + 1)
    assert solution.points.shape == (n, 2) and solution.u.shape == (n, 2)
    assert solution.phi.shape == (n,)
    # The bar [0,12]×[0,2]; its bottom moves down onto the foundation, the ends are clamped.
    assert solution.points.min(axis=0) == pytest.approx([0, 0])
    assert solution.points.max(axis=0) == pytest.approx([12, 2])
    ends = np.isclose(solution.points[:, 0], 0) | np.isclose(solution.points[:, 0], 12)
    assert np.all(solution.u[ends] == 0)
    assert solution.u[:, 1].min() < -0.5  # the gap is 0.5 m: the bar reaches the foundation
    assert np.all(np.isfinite(solution.phi))


def test_overrides_take_python_and_numpy_scalars():
    plain = piezocontact.solve(PAPER_72, {**COARSE, "friction.mu": 0.2, "conductivity.ke": 0.2})
    numpy = piezocontact.solve(
        PAPER_72,
        {
            "mesh.nx": np.int64(24),
            "mesh.ny": np.int32(4),
            "friction.mu": np.float64(0.2),
            "conductivity.ke": np.array([0.2])[0],
        },
    )
    default = piezocontact.solve(PAPER_72, COARSE)
    np.testing.assert_array_equal(plain.contact["sigma_nu"], numpy.contact["sigma_nu"])
    assert not np.array_equal(plain.contact["sigma_tau"], default.contact["sigma_tau"])
    # numpy booleans, strings and arrays too.
    with pytest.warns(piezocontact.CaseWarning) as caught:
        pv1 = piezocontact.solve(
            PAPER_72, {**COARSE, "contact.problem": "PV1", "solver.method": np.str_("newton")}
        )
    assert any("friction is not used" in str(w.message) for w in caught)
    assert pv1.summary["problem"] == "PV1" and pv1.summary["method"] == "newton"
    assert np.all(pv1.contact["sigma_tau"] == 0)


def test_a_dict_override_sets_its_keys_and_keeps_the_table_s_others():
    nested = piezocontact.solve(PAPER_71, {"mesh": {"nx": 24, "ny": 4}, "solver": {"eps": 1e-5}})
    dotted = piezocontact.solve(PAPER_71, {**COARSE, "solver.eps": 1e-5})
    # The file's method (uzawa) and its other solver keys stay; eps takes the new value.
    assert nested.summary["method"] == "uzawa"
    assert nested.summary["inner_iterations"] == dotted.summary["inner_iterations"]
    np.testing.assert_array_equal(nested.contact["sigma_nu"], dotted.contact["sigma_nu"])
    # A later key overrides an earlier one, in the dict's order, as a later --set does.
    nodes = lambda overrides: len(piezocontact.solve(PAPER_71, overrides).points)  # noqa: E731
    assert nodes({"mesh": {"nx": 24, "ny": 4}, "mesh.nx": 12}) == 13 * 5
    assert nodes({"mesh.nx": 12, "mesh": {"nx": 24, "ny": 4}}) == 25 * 5
    with pytest.raises(piezocontact.CaseError, match="case keys are strings, not 1"):
        piezocontact.solve(PAPER_71, {1: 2})


def test_the_case_s_warnings_are_python_warnings(tmp_path):
    # Under PV1 (frictionless) the file's µ and k_e are read by nothing: `run` says so on
    # stderr, and the Python package with the same words.
    overrides = {**COARSE, "contact.problem": '"PV1"'}
    sets = [a for k, v in overrides.items() for a in ("--set", f"{k}={v}")]
    command = [cli(), "run", PAPER_72, "-q", "--out", tmp_path, *sets]
    stderr = subprocess.run(command, check=True, capture_output=True, text=True).stderr
    printed = [line.removeprefix("warning: ") for line in stderr.splitlines()]
    assert len(printed) == 2 and "friction is not used" in printed[0]
    with pytest.warns(piezocontact.CaseWarning) as caught:
        piezocontact.solve(PAPER_72, {**COARSE, "contact.problem": "PV1"})
    assert issubclass(piezocontact.CaseWarning, UserWarning)
    assert [str(w.message) for w in caught] == printed


def test_bad_input_raises_a_value_error_naming_the_key():
    with pytest.raises(piezocontact.CaseError) as error:
        piezocontact.solve(PAPER_71, {"material.poisson": 0.7})
    assert isinstance(error.value, ValueError)
    message = str(error.value)
    assert "paper-7.1.toml:" in message and "material.poisson" in message
    # The command line's message, word for word.
    cli_message = subprocess.run(
        [cli(), "check", PAPER_71, "--set", "material.poisson=0.7"], capture_output=True, text=True
    ).stderr
    assert cli_message.strip() == f"error: {message}"
    # The overrides are named as such, not as the command line's --set (which they were).
    with pytest.raises(ValueError, match="unknown field `youngs`") as error:
        piezocontact.solve(PAPER_71, {"material.youngs": 1.0})
    assert "(with the overrides material.youngs=1.0)" in str(error.value)
    assert "--set" not in str(error.value)
    with pytest.raises(ValueError, match="conductivity.phi0 = 1e308 is out of range"):
        piezocontact.solve(PAPER_72, {"conductivity.phi0": 1e308})
    with pytest.raises(ValueError, match="^mesh.nx: a value of type object cannot be a case value"):
        piezocontact.solve(PAPER_71, {"mesh.nx": object()})
    # An int beyond TOML's 64 bits names its key (an OverflowError without it before).
    with pytest.raises(ValueError, match="^mesh.nx = 1180591620717411303424: an integer"):
        piezocontact.solve(PAPER_71, {"mesh.nx": 2**70})
    with pytest.raises(ValueError, match="^material.young: a value of type NoneType"):
        piezocontact.Case.from_dict({"material": {"young": None}})
    with pytest.raises(ValueError, match="cannot read"):
        piezocontact.solve(ROOT / "cases" / "no-such-case.toml")


def test_a_case_from_a_dict_solves_like_its_file(tmp_path):
    case = {
        "mesh": {"x": [0.0, 4.0], "y": [0.0, 1.0], "nx": 16, "ny": 4,
                 "segments": {"left": ["{0}x[0,1]"], "bottom": ["[0,4]x{0}"], "top": ["[0,4]x{1}"]}},
        "material": {"young": 100.0, "poisson": 0.25, "e31": -5.4, "e33": 15.8, "e15": 12.3,
                     "eps0": 8.885e-3, "beta11_rel": 916.0, "beta33_rel": 830.0},
        "boundary": {"clamped": ["left"], "grounded": ["left"], "contact": ["bottom"],
                     "traction": [{"parts": ["top"], "f2": [0.0, -2.0]}]},
        "contact": {"gap": 0.01},
    }
    from_dict = piezocontact.Case.from_dict(case, base_dir=tmp_path)
    path = tmp_path / "case.toml"
    path.write_text(from_dict.text)
    solved = from_dict.solve()
    assert solved.converged and solved.summary["kkt_residual"]["max"] <= 1e-10
    np.testing.assert_array_equal(solved.u, piezocontact.solve(path).u)
    assert np.any(solved.contact["sigma_nu"] < 0), "the beam does not touch"
    case["material"]["poisson"] = 0.6
    with pytest.raises(ValueError, match=r"case-from-dict.toml:\d+: material.poisson"):
        piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()


def test_supports_and_expressions_read_as_in_the_case_file(tmp_path):
    case = {
        "mesh": {"x": [0.0, 4.0], "y": [0.0, 1.0], "nx": 8, "ny": 2,
                 "segments": {"left": ["{0}x[0,1]"], "bottom": ["[0,4]x{0}"], "right": ["{4}x[0,1]"]}},
        "material": {"law": "linear", "young": 100.0, "poisson": 0.3, "e32": 0.0, "e33": 0.0, "e24": 0.0,
                     "eps0": 8.885e-3, "beta22_rel": 916.0, "beta33_rel": 830.0},
        "boundary": {"grounded": ["bottom"],
                     "support": [{"parts": ["left"], "fix": ["x"]},
                                 {"name": "floor", "parts": ["bottom"], "fix": ["y"]}],
                     "traction": [{"parts": ["right"], "f2": ["-2 * y", 0.0]}]},
    }
    solved = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    reactions = solved.summary["reactions"]
    assert set(reactions) == {"left", "floor"}
    # The traction -2y over y in [0, 1] pulls with -1 along x: the left roller holds it.
    assert abs(reactions["left"][0] - 1.0) < 1e-9 and abs(reactions["floor"][0]) < 1e-12
    case["boundary"]["support"][0]["fix"] = ["w"]
    with pytest.raises(ValueError, match="fix names 'w'"):
        piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()


def test_plane_models_and_normal_rollers_read_as_in_the_case_file(tmp_path):
    p = 0.5
    case = {
        "mesh": {"x": [0.0, 1.0], "y": [0.0, 2.0], "nx": 3, "ny": 5, "plane": "axisymmetric",
                 "segments": {"left": ["{0}x[0,1]"], "bottom": ["[0,1]x{0}"], "top": ["[0,1]x{2}"]}},
        "material": {"law": "linear", "young": 60.0, "poisson": 0.3, "e31": 0.0, "e33": 0.0, "e15": 0.0,
                     "eps0": 1.0, "beta11_rel": 1.0, "beta33_rel": 1.0},
        "boundary": {"grounded": ["bottom"],
                     "support": [{"name": "floor", "parts": ["bottom"], "fix": ["normal"]},
                                 {"name": "left", "parts": ["left"], "fix": ["x"]}],
                     "traction": [{"parts": ["top"], "f2": [0.0, -p]}]},
    }
    solved = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    # A cylinder of radius 1 pressed on its top: the floor holds p times the disc's area, and
    # the uniaxial state is u = (ν p r / E, −p y / E); the roller on the axis (the left
    # side, half of it) fixes what the axis fixes already.
    assert solved.summary["model"] == "axisymmetric"
    floor = solved.summary["reactions"]["floor"]
    assert abs(floor[1] - p * np.pi) < 1e-9 and floor[0] == 0.0
    expected = np.column_stack([0.3 * p / 60.0 * solved.points[:, 0], -p / 60.0 * solved.points[:, 1]])
    assert np.abs(solved.u - expected).max() < 1e-12
    case["mesh"]["plane"] = "strain"
    assert piezocontact.Case.from_dict(case, base_dir=tmp_path).solve().summary["model"] == "plane strain"
    case["mesh"]["plane"] = "axisymmetric"
    case["mesh"]["x"] = [-1.0, 1.0]
    case["mesh"]["segments"] = {"left": ["{-1}x[0,1]"], "bottom": ["[-1,1]x{0}"], "top": ["[-1,1]x{2}"]}
    with pytest.raises(ValueError, match="r < 0"):
        piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()


def test_electrodes_read_as_in_the_case_file(tmp_path):
    # A dielectric plate (e = 0) 2 wide and 1 thick: the top floats with a charge Q per unit
    # thickness, so that it rises to V = Q t / (β33 L) and the grounded bottom holds −Q.
    beta33, charge = 830.0 * 8.885e-3, 2e-3
    case = {
        "mesh": {"x": [0.0, 2.0], "y": [0.0, 1.0], "nx": 4, "ny": 2,
                 "segments": {"bottom": ["[0,2]x{0}"], "top": ["[0,2]x{1}"]}},
        "material": {"law": "linear", "young": 60.0, "poisson": 0.3, "e31": 0.0, "e33": 0.0,
                     "e15": 0.0, "eps0": 8.885e-3, "beta11_rel": 916.0, "beta33_rel": 830.0},
        "boundary": {"clamped": ["bottom"], "grounded": ["bottom"],
                     "electrode": [{"name": "sense", "parts": ["top"], "charge": charge}]},
    }
    solved = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    bottom, sense = solved.electrodes
    assert sense["name"] == "sense" and sense["kind"] == "floating" and sense["parts"] == ["top"]
    volts = charge * 1.0 / (beta33 * 2.0)
    assert abs(sense["potential"] - volts) < 1e-9 * volts
    assert abs(sense["charge"] - charge) < 1e-9 * charge
    assert bottom["kind"] == "voltage" and abs(bottom["charge"] + charge) < 1e-9 * charge
    assert np.abs(solved.phi - volts * solved.points[:, 1]).max() < 1e-9 * volts


def test_materials_by_region_and_presets_read_as_in_the_case_file(tmp_path):
    material = {"law": "linear", "young": 100.0, "poisson": 0.3, "e32": -5.4, "e33": 15.8, "e24": 12.3,
                "eps0": 8.885e-3, "beta22_rel": 916.0, "beta33_rel": 830.0}
    case = {
        "mesh": {"x": [0.0, 4.0], "y": [0.0, 1.0], "nx": 8, "ny": 2,
                 "segments": {"left": ["{0}x[0,1]"], "top": ["[0,4]x{1}"]},
                 "regions": {"lower": ["[0,4]x[0,0.5]"], "upper": ["[0,4]x[0.5,1]"]}},
        "material": material,
        "boundary": {"clamped": ["left"], "grounded": ["left"],
                     "traction": [{"parts": ["top"], "f2": [0.0, -1.0]}]},
    }
    one = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    # The same constants split into two named materials by region: the same solution.
    case["material"] = [dict(material, name="soft", regions=["lower"]),
                        dict(material, name="hard", regions=["upper"])]
    two = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    assert np.abs(two.u - one.u).max() <= 1e-12 * np.abs(one.u).max()
    # A stiffer upper material moves the tip less; an unknown region is named.
    case["material"][1]["young"] = 200.0
    stiffer = piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()
    assert np.abs(stiffer.u).max() < np.abs(one.u).max()
    case["material"][1]["regions"] = ["lid"]
    with pytest.raises(ValueError, match="no region of the mesh"):
        piezocontact.Case.from_dict(case, base_dir=tmp_path).solve()


def test_write_writes_the_files_of_run(tmp_path):
    solution = piezocontact.solve(PAPER_72, COARSE)
    out = tmp_path / "out"
    solution.write(out)
    summary = strict_json((out / "summary.json").read_text())
    # summary.json's timings count its files and the time up to its writing, after the solve.
    written, solved = dict(summary), dict(solution.summary)
    assert set(written.pop("timings_seconds")["files"]) == {"contact.csv", "solution.vtu"}
    assert solved.pop("timings_seconds")["files"] == {}
    assert written == solved
    text = (out / "contact.csv").read_text()
    assert text.splitlines()[0] == "x,y,u_nu,u_tau,sigma_nu,sigma_tau,phi,s,status"
    assert len(text.splitlines()) == 1 + len(solution.contact["x"]) and text.endswith("\n")
    binary = (out / "solution.vtu").read_bytes()
    assert b'format="appended"' in binary and binary.rstrip().endswith(b"</VTKFile>")
    solution.write(tmp_path / "text", vtu="ascii")
    text_vtu = (tmp_path / "text" / "solution.vtu").read_text()
    assert 'format="ascii"' in text_vtu and len(text_vtu) > len(binary)
    with pytest.raises(piezocontact.CaseError, match="binary"):
        solution.write(tmp_path / "other", vtu="hex")
    cli_summary, _ = cli_run(PAPER_72, tmp_path / "cli", COARSE)
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in (tmp_path / "cli").iterdir())
    # A directory with someone else's files is refused, unless forced.
    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("mine")
    with pytest.raises(ValueError, match="force=True"):
        solution.write(foreign)
    solution.write(foreign, force=True)
    assert (foreign / "notes.txt").read_text() == "mine" and (foreign / "contact.csv").exists()
    # An empty path names no directory: the caller's error (an OSError about reading '' before).
    with pytest.raises(ValueError, match="the output directory is an empty path"):
        solution.write("")
    # A directory that cannot be made is the system's error: an OSError (a CaseError before).
    (tmp_path / "a-file").write_text("")
    with pytest.raises(OSError, match="cannot create the output directory") as error:
        solution.write(tmp_path / "a-file" / "out")
    assert not isinstance(error.value, ValueError)


def test_meshio_reads_the_binary_vtu_as_the_ascii_one_bit_for_bit(tmp_path):
    """ParaView's binary encoding (appended raw data) read by another reader, meshio: the same
    points, cells and arrays as the ascii file, to the last bit, and u and ϕ those the solve
    returns; on a 3D indentation with contact, so that the contact arrays are in it."""
    meshio = pytest.importorskip("meshio")
    case = ROOT / "cases" / "indentation-3d.toml"
    solution = piezocontact.solve(case, {"mesh.file": "../meshes/indent-3d-h0.05.msh"})
    solution.write(tmp_path / "binary")
    solution.write(tmp_path / "ascii", vtu="ascii")
    binary = meshio.read(tmp_path / "binary" / "solution.vtu")
    text = meshio.read(tmp_path / "ascii" / "solution.vtu")

    def same_bits(a, b):
        a, b = np.asarray(a), np.asarray(b)
        return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()

    assert same_bits(binary.points, text.points)
    assert same_bits(binary.points, solution.points)
    assert [c.type for c in binary.cells] == [c.type for c in text.cells] == ["tetra"]
    assert all(same_bits(b.data, t.data) for b, t in zip(binary.cells, text.cells))
    assert sorted(binary.point_data) == sorted(text.point_data)
    assert {"u", "phi", "contact_pressure"} <= set(binary.point_data)
    for name, values in binary.point_data.items():
        assert same_bits(values, text.point_data[name]), name
    assert sorted(binary.cell_data) == sorted(text.cell_data)
    assert {"sigma", "D"} <= set(binary.cell_data)
    for name, blocks in binary.cell_data.items():
        assert all(same_bits(b, t) for b, t in zip(blocks, text.cell_data[name])), name
    assert same_bits(binary.point_data["u"], solution.u)
    # meshio gives a one-component array as a column.
    assert same_bits(binary.point_data["phi"].ravel(), solution.phi)


def test_3d_solutions_write_the_contact_map(tmp_path):
    solution = piezocontact.solve(
        ROOT / "cases" / "indentation-3d.toml", {"mesh.file": "../meshes/indent-3d-h0.05.msh"}
    )
    assert solution.points.shape[1] == 3 and "sigma_tau2" in solution.contact
    solution.write(tmp_path)
    assert (tmp_path / "contact_map.png").read_bytes()[-8:-4] == b"IEND"


def test_the_gil_is_released_during_a_solve():
    """A Python thread keeps running while another one solves."""
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    ticker = threading.Thread(target=tick)
    ticker.start()
    start = time.perf_counter()
    # A tight tolerance on a finer mesh: a solve of about a second.
    tight = {"mesh.nx": 192, "mesh.ny": 32, "solver.eps": 1e-7, "solver.eps_fp": 1e-7}
    piezocontact.solve(PAPER_72, tight)
    seconds = time.perf_counter() - start
    done.set()
    ticker.join()
    during = [t for t in ticks if start <= t <= start + seconds]
    assert seconds > 0.2, f"the solve took {seconds:.3f} s: too short to tell"
    assert len(during) > 10, f"{len(during)} ticks in {seconds:.2f} s: the GIL was held"


def test_a_panic_raises_instead_of_killing_the_interpreter():
    with pytest.raises(RuntimeError, match="internal error in piezocontact.*a deliberate panic"):
        piezocontact._native._panic_inside_the_guard()
    assert piezocontact.solve(PAPER_71, COARSE).converged  # the interpreter lives on


def test_an_unconverged_run_warns_and_keeps_its_result():
    with pytest.warns(RuntimeWarning, match="did not converge"):
        solution = piezocontact.solve(PAPER_72, {**COARSE, "solver.max_outer": 1})
    assert not solution.converged and solution.summary["converged"] is False
    assert np.all(np.isfinite(solution.u))


def test_the_table2_example_saves_its_figure(tmp_path):
    pytest.importorskip("matplotlib")
    example = ROOT / "python" / "examples" / "table2.py"
    subprocess.run([sys.executable, example], cwd=tmp_path, check=True, capture_output=True)
    assert (tmp_path / "table2.png").read_bytes()[:4] == b"\x89PNG"


def test_a_loading_path_gives_its_curve_and_its_steps(tmp_path):
    s = piezocontact.solve(ROOT / "cases" / "indentation-curve.toml", {"loading.depths": [0.005, 0.01]})
    assert s.converged
    curve = s.curve
    assert list(curve["step"]) == [1, 2] and list(curve["depth"]) == [0.005, 0.01]
    assert curve["converged"].dtype == bool and curve["converged"].all()
    # Deeper presses harder; the two electrodes' charges cancel (no charge enters otherwise).
    assert 0 < curve["force_z"][0] < curve["force_z"][1]
    total = curve["charge_bottom"] + curve["charge_top"]
    assert np.all(np.abs(total) <= 1e-10 * np.abs(curve["charge_top"]))
    steps = s.steps
    assert len(steps) == 2 and steps[1]["u"].shape == s.u.shape
    assert np.array_equal(steps[1]["u"], s.u) and np.array_equal(steps[1]["phi"], s.phi)
    assert not np.array_equal(steps[0]["u"], s.u)
    s.write(tmp_path / "path")
    with open(tmp_path / "path" / "curve.csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["force_z"]) for r in rows] == list(curve["force_z"])
    assert (tmp_path / "path" / "solution-0002.vtu").exists()


def test_a_path_without_contact_gives_the_command_s_curve(tmp_path):
    case = ROOT / "cases" / "cantilever-load-factors.toml"
    s = piezocontact.solve(case)
    assert s.converged and s.contact == {}
    curve = s.curve
    assert list(curve) == ["step", "load_factor", "reaction_x", "reaction_y", "charge_root", "charge_top"]
    assert list(curve["load_factor"]) == [0.5, 1.0, 1.5, 2.0]
    # The clamp holds the tip traction (f2 = -0.001 over the tip's length 2) times the factor.
    np.testing.assert_allclose(curve["reaction_y"], 0.002 * curve["load_factor"], rtol=1e-9)
    assert len(s.steps) == 4 and np.array_equal(s.steps[3]["u"], s.u)
    subprocess.run([cli(), "run", case, "--out", tmp_path / "cli", "-q"], check=True)
    with open(tmp_path / "cli" / "curve.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    for name, column in curve.items():
        assert [float(r[name]) for r in rows] == [float(v) for v in column], name


def test_ctrl_c_during_a_solve_raises_keyboard_interrupt():
    # Uzawa with a tolerance it cannot reach runs until stopped (or for about 30 s, so that
    # the test cannot hang); Ctrl-C comes from a helper thread after a second
    # (_thread.interrupt_main simulates SIGINT). Python's own handler is installed for the
    # test: a process started in the background by a shell without job control (as CI may
    # start it) inherits SIGINT ignored, and then interrupt_main does nothing.
    import _thread
    import signal

    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(1.0, _thread.interrupt_main)
    try:
        timer.start()
        start = time.monotonic()
        with pytest.raises(KeyboardInterrupt):
            piezocontact.solve(PAPER_72, {"solver.eps": 1e-25, "solver.max_inner": 150000})
        timer.join()
        assert time.monotonic() - start < 5, "the run went on after Ctrl-C"
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)


def test_threads_bound_a_solve_and_solves_in_two_threads_keep_their_own_answers():
    # Each case alone, on one thread and on two, gives the same answer to the last bit: the
    # 2D paper cases factorise on one thread; the 3D indentation on faer's parallel kernels,
    # whose work is split by the machine's cores whatever the threads that run it.
    cases = [(PAPER_71, COARSE), (PAPER_72, COARSE), (ROOT / "cases" / "indentation-3d.toml", {})]
    alone = [piezocontact.solve(path, overrides, threads=1) for path, overrides in cases]
    for (path, overrides), reference in zip(cases, alone):
        again = piezocontact.solve(path, overrides, threads=2)
        assert np.array_equal(again.u, reference.u) and np.array_equal(again.phi, reference.phi)
    # Both at once, from two Python threads (the solves release the GIL).
    results = [None, None, None]

    def work(k):
        path, overrides = cases[k]
        results[k] = piezocontact.solve(path, overrides, threads=1)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(3)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for result, reference in zip(results, alone):
        assert np.array_equal(result.u, reference.u)
        assert np.array_equal(result.phi, reference.phi)
    assert not np.array_equal(alone[0].u, alone[1].u)
    for bad in (0, -1):
        # A negative count was an OverflowError from the conversion, naming nothing.
        with pytest.raises(ValueError, match=f"threads = {bad}: give at least 1"):
            piezocontact.solve(PAPER_71, COARSE, threads=bad)
