"""`boatsim hydro` and the shipped coefficient files: keys, lookups, panels, and the files."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.cli import main
from boat_dynamics.physics.body.rigid_body import mass_matrix
from boat_dynamics.physics.core.model import coefficients_key, hull_mesh
from boat_dynamics.physics.core.pipeline import init_scenario
from boat_dynamics.physics.core.tuning import equilibrium_height, hydrostatic_stiffness
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.potential_flow.hydro import (
    SHIPPED_COEFFICIENTS,
    coefficient_directories,
    find_coefficients,
    hydro_key,
    load_coefficients,
)
from boat_dynamics.physics.scenario import load_scenario, parse_scenario
from boat_dynamics.tools.bem_mesh import immersed_panels, mirror_symmetric

ROOT = Path(__file__).resolve().parents[3]
SCENARIOS = sorted((ROOT / "scenarios").glob("*.yaml"))
REFERENCE = ROOT / "tests" / "data" / "hydro" / "box_4x2x1_d0.5.npz"


def test_the_key_follows_the_inputs_and_nothing_else():
    v = np.array([[0.0, -0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    f = np.array([[0, 1, 2]])
    args = (v, f, 100.0, np.zeros(3), np.eye(6), 1025.0, 9.81, math.inf)
    key = hydro_key(*args)
    assert len(key) == 16 and key == hydro_key(*args)
    assert hydro_key(np.abs(v), *args[1:]) == key  # -0.0 is 0.0
    assert hydro_key(v, f, 100.0 + 1e-6, *args[3:]) != key
    assert hydro_key(*args[:-1], 25.0) != key


@pytest.mark.parametrize("path", SCENARIOS, ids=lambda p: p.stem)
def test_every_shipped_hull_has_its_file_and_the_file_is_that_hull(path, capsys, monkeypatch):
    # `boatsim hydro` finds every boat's file without solving (a solve would need Capytaine,
    # hidden here), and each file was solved for that very hull: its centre of mass, mass
    # matrix and, for a mesh boat, its hydrostatic stiffness equal boatsim's own (heave, roll,
    # pitch within 0.5 %; a sample-point boat's own stiffness only approximates its hull's).
    monkeypatch.setitem(sys.modules, "capytaine", None)
    assert main(["hydro", str(path)]) == 0
    assert "found" in capsys.readouterr().out
    scenario = load_scenario(path)
    for boat in scenario.boats:
        p = boat.params
        if p.hydro is None and (p.derive is None or p.derive.estimate is None):
            assert boat.kind == "buoy"  # coefficients: none (a buoy: small against the waves)
            continue
        found = find_coefficients(coefficients_key(p, scenario.sea.depth),
                                  coefficient_directories(path.parent))
        assert found is not None and found.parent == SHIPPED_COEFFICIENTS
        ref = load_coefficients(found)
        assert ref.center_of_mass == pytest.approx(p.center_of_mass, abs=1e-9)
        assert ref.inertia_matrix == pytest.approx(
            mass_matrix(p.mass, p.inertia, p.inertia_products), rel=1e-9)
        if isinstance(p.buoyancy, MeshBuoyancy):
            c = np.diag(ref.hydrostatic_stiffness)[[2, 3, 4]]
            assert c == pytest.approx(hydrostatic_stiffness(p), rel=5e-3)


def test_the_shipped_default_box_agrees_with_the_independent_reference():
    # Two meshes of the same box (the shipped file: 2,120 + 800 lid panels, `boatsim hydro`;
    # the reference: 2,880 + 1,152, tests/data/hydro/hydro_reference.py): added mass,
    # damping and excitation within 1.5 % of each quantity's largest value (measured <= 1 %).
    scenario = load_scenario(ROOT / "scenarios" / "default.yaml")
    key = coefficients_key(scenario.boats[0].params, scenario.sea.depth)
    shipped = load_coefficients(find_coefficients(key, (SHIPPED_COEFFICIENTS,)))
    ref = load_coefficients(REFERENCE)
    assert np.array_equal(shipped.omega, ref.omega)
    for name in ("added_mass", "radiation_damping"):
        a, b = getattr(shipped, name), getattr(ref, name)
        for i in range(6):
            assert np.abs(a[:, i, i] - b[:, i, i]).max() <= 0.015 * np.abs(b[:, i, i]).max()
    exc = shipped.froude_krylov + shipped.diffraction
    exc_ref = ref.froude_krylov + ref.diffraction
    for i in range(6):
        scale = np.abs(exc_ref[..., i]).max()
        if scale > 0:
            assert np.abs(exc[..., i] - exc_ref[..., i]).max() <= 0.015 * scale


def test_auto_finds_the_file_and_a_new_hull_gets_an_estimate_that_says_so(tmp_path):
    sc = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                    "hydrodynamics": {"coefficients": "auto"}}]}, "s", tmp_path)
    assert sc.boats[0].params.hydro is not None
    assert sc.boats[0].params.derive.estimate is None
    sc = parse_scenario({"boats": [{"hull": {"length": 5.0},
                                    "hydrodynamics": {"coefficients": "auto"}}]}, "s", tmp_path)
    p = sc.boats[0].params
    assert p.hydro is None and len(p.derive.estimate) == 16
    ready = init_scenario(sc).boats[0].params
    assert ready.hydro.source.startswith(f"estimate for hull {p.derive.estimate}: box_4x2x1")
    assert ready.radiation_memory is not None  # Cummins from the estimate
    assert ready.hydro.center_of_mass == pytest.approx(p.center_of_mass)


def test_moving_the_rotation_centre_is_exact():
    # The default box's file moved to the centre of mass of multi_boat's alpha (the same box,
    # CoM 0.2 m higher) against alpha's own file, solved separately: the same within 0.5 % of
    # each quantity's largest value (the solves' own differences).
    from boat_dynamics.physics.potential_flow.hydro import moved

    scenario = load_scenario(ROOT / "scenarios" / "multi_boat.yaml")
    alpha = scenario.boats[0].params
    own = load_coefficients(find_coefficients(coefficients_key(alpha, math.inf),
                                              (SHIPPED_COEFFICIENTS,)))
    default = load_coefficients(SHIPPED_COEFFICIENTS / "box_4x2x1_d0.500_2b2dd4941ae3d992.npz")
    shifted = moved(default, alpha.center_of_mass)
    for name in ("added_mass", "radiation_damping", "froude_krylov", "diffraction"):
        a, b = getattr(shifted, name), getattr(own, name)
        assert np.abs(a - b).max() <= 0.005 * np.abs(b).max(), name


def test_froude_scaling_scales_periods_by_the_square_root_and_undoes_itself():
    from boat_dynamics.physics.potential_flow.hydro import froude_scaled

    ref = load_coefficients(REFERENCE)
    back = froude_scaled(froude_scaled(ref, 2.5), 1 / 2.5)
    for name in ("omega", "added_mass", "radiation_damping", "froude_krylov", "added_mass_inf"):
        np.testing.assert_allclose(getattr(back, name), getattr(ref, name), rtol=1e-12,
                                   atol=1e-9)
    big = froude_scaled(ref, 4.0)
    w0 = ref.natural(2, ref.hydrostatic_stiffness[2, 2], ref.inertia_matrix[2, 2])[0]
    w1 = big.natural(2, big.hydrostatic_stiffness[2, 2], big.inertia_matrix[2, 2])[0]
    assert w0 / w1 == pytest.approx(2.0, rel=1e-9)


@pytest.mark.parametrize(("scenario", "name", "period_bound"), [
    ("multi_boat", "bravo", 0.16), ("storm", "", 0.14)])
def test_the_estimate_of_a_box_of_other_proportions(scenario, name, period_bound):
    # What the estimate is worth: the default box Froude-scaled to another box's displacement,
    # against that box's own file. Natural periods (heave, roll, pitch) within 15 % (measured:
    # 6 x 2.5 x 1.2 m: -6 / -4 / -15 %; 12 x 4 x 2.5 m: +4 / +13 / -10 %; without any
    # coefficients the default box is 19-34 % short); damping ratios within a factor 3
    # (measured 0.4-1.5x).
    from boat_dynamics.physics.potential_flow.hydro import estimate

    sc = load_scenario(ROOT / "scenarios" / f"{scenario}.yaml")
    p = next(b.params for b in sc.boats if b.name == name)
    z = equilibrium_height(p)
    own = load_coefficients(find_coefficients(coefficients_key(p, sc.sea.depth),
                                              (SHIPPED_COEFFICIENTS,)))
    guess = estimate(p.mass, p.center_of_mass, p.water_density, z, "k")
    k = hydrostatic_stiffness(p, z)
    for dof, stiffness, rigid in zip((2, 3, 4), k, (p.mass, p.inertia[0], p.inertia[1]),
                                     strict=True):
        w_own, _, zeta_own = own.natural(dof, float(stiffness), float(rigid))
        w_est, _, zeta_est = guess.natural(dof, float(stiffness), float(rigid))
        assert w_own / w_est == pytest.approx(1.0, abs=period_bound)
        assert 1 / 3 < zeta_est / zeta_own < 3


def test_a_solve_without_capytaine_is_refused_with_the_install_hint(tmp_path, capsys,
                                                                  monkeypatch):
    monkeypatch.setitem(sys.modules, "capytaine", None)  # import capytaine -> ImportError
    scenario = tmp_path / "new.yaml"
    scenario.write_text("boats:\n  - {hull: {length: 5.0}}\n")
    assert main(["hydro", str(scenario)]) == 2
    assert "pip install 'boatsim[bem]'" in capsys.readouterr().err
    assert not (tmp_path / "hydro").exists()


@pytest.mark.parametrize(("args", "message"), [
    (["--boat", "nobody"], "--boat: 'nobody' is not a boat of the scenario"),
    (["--panel-size", "0"], "--panel-size: 0.0 is not allowed: metres, > 0"),
    (["--shortest-wavelength", "0.001"],
     "--shortest-wavelength: 0.001 is not allowed: boat lengths, from 0.01 to 100"),
])
def test_a_bad_option_is_refused_naming_it(args, message, capsys):
    assert main(["hydro", *args]) == 2
    assert message in capsys.readouterr().err


def test_the_default_panels_fit_the_hull_and_the_shortest_wave():
    from boat_dynamics.tools.bem_mesh import PANELS_PER_WAVELENGTH, default_panel_size

    # the 4 x 2 x 1 m box at draft 0.5 m: L / 40, as before (its files were made so)
    assert default_panel_size((4.0, 2.0, 1.0), draft=0.5) == pytest.approx(0.1)
    # a 3 x 0.3 m slender hull at draft 0.1875 m: an eighth of the half-girth T + B / 2,
    # 0.042 m, where B / 16 alone gave 0.019 m (four times the panels)
    assert default_panel_size((3.0, 0.3, 0.3), draft=0.1875) == pytest.approx(0.3375 / 8)
    assert default_panel_size((3.0, 0.3, 0.3)) == pytest.approx(0.3 / 16)
    # a shortest wave of 0.1 L resolved: edge at most a wavelength / 5.66
    assert default_panel_size((4.0, 2.0, 1.0), draft=0.5, shortest_wavelength=0.4) == (
        pytest.approx(0.4 / PANELS_PER_WAVELENGTH))
    assert PANELS_PER_WAVELENGTH == pytest.approx(5.657, abs=1e-3)


def test_a_dry_run_prints_the_plan_and_its_cost_and_needs_no_capytaine(tmp_path, capsys,
                                                                      monkeypatch):
    # The default box (4 x 2 x 1 m, draft 0.5 m): 2,120 hull + 800 lid panels of 0.1 m, two
    # symmetries; 40 frequencies and the two limits, 6 radiation + 5 diffraction problems.
    # The estimate: 42 x (1.07e-6 x 2920 x 730 + 2.55e-10 x 4 x 730^3) = 1.9 min (measured
    # 3.04 s a frequency with the other core busy: 2.1 min).
    monkeypatch.setitem(sys.modules, "capytaine", None)
    assert main(["hydro", "--dry-run", "--force", "-o", str(tmp_path / "h")]) == 0
    out = capsys.readouterr().out
    assert ("would solve box_4x2x1_d0.500 (key 2b2dd4941ae3d992): 2120 hull + 800 lid panels "
            "of 0.1 m, two symmetries, 42 frequencies x 11 problems: about 2 min of CPU") in out
    assert "(would be made; key 2b2dd4941ae3d992)" in out
    assert not (tmp_path / "h").exists()
    # a shortest wave of 0.1 boat lengths: 0.0707 m panels, nearly three times the cost
    assert main(["hydro", "--dry-run", "--force", "--shortest-wavelength", "0.1",
                 "-o", str(tmp_path / "h")]) == 0
    assert "4380 hull + 1740 lid panels of 0.0707 m" in capsys.readouterr().out


def test_a_solve_over_the_panel_limit_is_refused_before_it_starts(tmp_path, capsys):
    assert main(["hydro", "--force", "--panel-size", "0.03", "-o", str(tmp_path / "h")]) == 2
    err = capsys.readouterr().err
    assert "panels are over the 8000-panel limit: give --panel-size more than 0.03 m" in err
    assert not (tmp_path / "h").exists()


def test_the_panels_cover_the_wetted_box_and_the_lid_its_section():
    # The default box at draft 0.5: wetted area L B + 2 (L + B) d = 14 m^2; one quarter is
    # meshed (both symmetries); the lid is the section L x B a little under the waterline.
    params = parse_scenario({"boats": [{}]}).boats[0].params
    mesh = hull_mesh(params)
    z_eq = equilibrium_height(params)
    panels = immersed_panels(mesh.vertices, mesh.faces, draft_offset=-z_eq, omega_max=12.0)
    assert panels["sym_x"] and panels["sym_y"]

    def area(p):
        a = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]) + np.cross(p[:, 2] - p[:, 0],
                                                                      p[:, 3] - p[:, 0])
        return 0.5 * np.linalg.norm(a, axis=1).sum()

    assert 4 * area(panels["hull"]) == pytest.approx(4 * 2 + 2 * 6 * 0.5, rel=1e-9)
    assert 4 * area(panels["lid"]) == pytest.approx(8.0, rel=1e-3)
    assert panels["hull"][..., 2].max() <= 1e-12
    assert -0.5 < panels["z_lid"] < 0.0
    shifted = mesh.vertices + [0.0, 0.3, 0.0]
    assert mirror_symmetric(mesh.vertices, mesh.faces, 1)
    assert not mirror_symmetric(shifted, mesh.faces, 1)


@pytest.mark.bem
def test_a_solve_reproduces_the_reference_box():
    # Only where the bem extra is installed (about a minute): `boatsim hydro`'s solver on the
    # default box against the independent reference within 1.5 %.
    pytest.importorskip("capytaine")
    from boat_dynamics.tools import bem

    params = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2]}]}).boats[0].params
    mesh = hull_mesh(params)
    out = bem.solve_hull(mesh.vertices, mesh.faces, draft_offset=0.0, mass=params.mass,
                         center_of_mass=params.center_of_mass,
                         inertia_matrix=mass_matrix(params.mass, params.inertia,
                                                    params.inertia_products))
    ref = load_coefficients(REFERENCE)
    for i in range(6):
        b = ref.radiation_damping[:, i, i]
        assert np.abs(out["radiation_damping"][:, i, i] - b).max() <= 0.015 * np.abs(b).max()
        a = ref.added_mass[:, i, i]
        assert np.abs(out["added_mass"][:, i, i] - a).max() <= 0.015 * np.abs(a).max()
    # its Kochin functions (issue 31): the radiated power equals the damping within 5 %
    k = out["omega"] ** 2 / 9.81
    power = (np.abs(out["kochin_radiation"]) ** 2).mean(axis=2) * 2 * np.pi
    energy = 4 * np.pi * 1025.0 * k[:, None] / out["omega"][:, None] * power
    damping = np.diagonal(out["radiation_damping"], axis1=1, axis2=2)
    assert np.all(np.abs(energy - damping).max(axis=0) <= 0.05 * np.abs(damping).max(axis=0))
    assert out["kochin_diffraction"].shape == (40, len(out["directions"]), 72)


def test_the_otters_gap_resonances_are_found_and_said(capsys, tmp_path):
    # The box-pontoon Otter's file (shipped before the V pontoons; two pontoons 0.54 m apart): its
    # sloshing modes n = 1, 3, 5 (omega^2 = g n pi / b: 7.55, 13.08, 16.89 rad/s; the solver's
    # 8.21, 13.22, 16.97 on its 0.42 rad/s grid, and 8.63 on n = 1's flank), in sway, roll and
    # yaw, are narrow peaks; its broad heave hump at 4.9 rad/s is not; no shipped monohull
    # file has one. Without its gap modes `boatsim hydro` says so, and that the radiation
    # memory misses the file by 80 %; the shipped Otter's file carries its modes, and
    # `boatsim hydro` has nothing to say: the memory holds them as pole pairs.
    from boat_dynamics.physics.potential_flow.hydro import SHIPPED_COEFFICIENTS, narrow_peaks

    name = "box_2x1.04x0.4_d0.078_28cbe58ae1ba94d9.npz"
    box = ROOT / "tests" / "data" / "hydro" / "otter_box_pontoons.npz"
    otter = load_coefficients(box)
    peaks = narrow_peaks(otter)
    assert sorted({round(p.omega, 2) for p in peaks}) == [8.21, 8.63, 13.22, 16.97]
    assert {p.dof for p in peaks} == {"sway", "roll", "yaw"}
    assert max(p.ratio for p in peaks if p.dof == "roll") > 100.0
    for path in SHIPPED_COEFFICIENTS.glob("*.npz"):
        shipped = load_coefficients(path)
        if not shipped.gap_modes:
            assert narrow_peaks(shipped) == (), path.name
    assert main(["hydro", str(ROOT / "scenarios" / "otter.yaml")]) == 0
    assert "warning" not in capsys.readouterr().err
    with np.load(box, allow_pickle=False) as d:
        plain = {k: d[k] for k in d.files if not k.startswith("gap_mode_")}
    (tmp_path / "hydro").mkdir()
    np.savez(tmp_path / "hydro" / name, **plain)
    text = (ROOT / "scenarios" / "otter.yaml").read_text()
    for old, new in (("path: otter.stl", f"path: {box.with_suffix('.stl')}"),
                     ("center_of_mass: [0.0, 0.0, 0.2237]", "center_of_mass: [0.0, 0.0, 0.125]"),
                     ("position: [0.0, 0.0, 0.0233]", "position: [0.0, 0.0, 0.122]")):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    (tmp_path / "otter.yaml").write_text(text)
    assert main(["hydro", str(tmp_path / "otter.yaml")]) == 0
    err = capsys.readouterr().err
    assert "narrow peaks narrower than its frequency grid at 8.21 rad/s (sway damping" in err
    assert "its radiation memory fits it only within 80 % (accepted: 10 %)" in err
    assert main(["hydro"]) == 0  # the default box: nothing to say
    assert "warning" not in capsys.readouterr().err
