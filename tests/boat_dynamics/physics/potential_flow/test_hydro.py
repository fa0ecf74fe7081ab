"""Potential-flow coefficients: the file reader, and boatsim against Capytaine's solution.

The reference (tests/data/hydro/box_4x2x1_d0.5.npz) is Capytaine 3.0.0's solution for the
default 4 x 2 x 1 m box floating at 0.5 m draft with its centre of mass 0.2 m below the
reference point, made by tests/data/hydro/hydro_reference.py (see its docstring for the mesh
and the conventions).
"""

import math
from itertools import pairwise
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics.potential_flow.hydro import HydroFileError, load_coefficients

DATA = Path(__file__).resolve().parents[3] / "data" / "hydro"
BOX = DATA / "box_4x2x1_d0.5.npz"


def _write(path, **changes):
    with np.load(BOX) as data:
        arrays = {k: data[k] for k in data.files}
    arrays.update(changes)
    for k in [k for k, v in arrays.items() if v is None]:
        del arrays[k]
    np.savez(path, **arrays)
    return path


@pytest.mark.parametrize(("changes", "fragment"), [
    ({"added_mass": None}, "array 'added_mass' is missing"),
    ({"omega": np.array([1.0])}, "but 1 elsewhere"),
    ({"added_mass_inf": np.zeros((6, 5))}, "added_mass_inf has shape (6, 5), expected (6, 6)"),
    ({"center_of_mass": np.array([0.0, np.nan, 0.0])}, "center_of_mass has non-finite values"),
    # text: np.isfinite raised a TypeError (a traceback) before
    ({"center_of_mass": np.array(["0", "0", "0"])}, "center_of_mass holds <U1 values; expected "
                                                    "numbers"),
    ({"omega": np.array([b"x"] * 40)}, "omega holds |S1 values; expected numbers"),
])
def test_a_malformed_coefficient_file_is_refused_naming_the_array(tmp_path, changes, fragment):
    with pytest.raises(HydroFileError) as err:
        load_coefficients(_write(tmp_path / "bad.npz", **changes))
    assert fragment in str(err.value)


def _box(name):
    with np.load(BOX) as data:
        return data[name]


@pytest.mark.parametrize(("changes", "fragment"), [
    # each once loaded, then gave NaN odometry while the run exited 0, or allocated GiBs
    ({"directions": np.array([math.pi]), "froude_krylov": _box("froude_krylov")[:, 4:],
      "diffraction": _box("diffraction")[:, 4:]}, "at least two, increasing"),
    ({"added_mass_inf": -np.eye(6) * 1000.0}, "added_mass_inf must be symmetric positive "
                                              "semi-definite (its lowest eigenvalue is -1000)"),
    ({"omega": _box("omega") * 1e6}, "omega reaches 1.2e+07 rad/s; at most 200"),
    ({"radiation_damping": np.zeros_like(_box("radiation_damping"))},
     "radiation_damping is zero at every frequency"),
])
def test_coefficients_the_physics_cannot_use_are_refused(tmp_path, changes, fragment):
    with pytest.raises(HydroFileError) as err:
        load_coefficients(_write(tmp_path / "bad.npz", **changes))
    assert fragment in str(err.value)


_THETA = np.radians(np.arange(0.0, 360.0, 5.0))
_KOCHIN = dict(kochin_angles=_THETA, kochin_radiation=np.ones((40, 6, 72), complex),
               kochin_diffraction=np.ones((40, 5, 72), complex))


@pytest.mark.parametrize(("changes", "fragment"), [
    ({**_KOCHIN, "kochin_diffraction": None}, "Kochin arrays ['kochin_diffraction'] are missing "
                                              "(all three or none)"),
    ({**_KOCHIN, "kochin_radiation": np.ones((40, 5, 72))},
     "kochin_radiation has shape (40, 5, 72), expected ('W', 6, 'T')"),
    ({**_KOCHIN, "kochin_diffraction": np.ones((40, 4, 72))}, "D = 4, but 5 elsewhere"),
    ({**_KOCHIN, "kochin_radiation": np.full((40, 6, 72), np.nan + 0j)},
     "kochin_radiation has non-finite values"),
    ({**_KOCHIN, "kochin_angles": _THETA[::-1]}, "at least eight, real, increasing"),
])
def test_malformed_kochin_functions_are_refused_by_name(tmp_path, changes, fragment):
    with pytest.raises(HydroFileError) as err:
        load_coefficients(_write(tmp_path / "bad.npz", **changes))
    assert fragment in str(err.value)


def test_a_file_without_kochin_functions_loads_without_them(tmp_path):
    # files made before issue 31: their boats make no waves
    old = load_coefficients(BOX)
    assert not old.has_kochin and old.kochin_radiation is None
    new = load_coefficients(_write(tmp_path / "kochin.npz", **_KOCHIN))
    assert new.has_kochin and new.kochin_diffraction.dtype == complex
    assert np.array_equal(new.added_mass, old.added_mass)


def test_a_file_that_would_allocate_more_than_it_holds_is_refused_before_reading(tmp_path):
    import zipfile

    # a zip bomb: 300 MB of zeros compress to under 1 MB
    bomb = tmp_path / "bomb.npz"
    with zipfile.ZipFile(bomb, "w", zipfile.ZIP_DEFLATED) as z:
        with z.open("omega.npy", "w", force_zip64=True) as f:
            np.lib.format.write_array_header_1_0(f, {"descr": "<f8", "fortran_order": False,
                                                     "shape": (300 * 2**20 // 8,)})
            zeros = bytes(2**20)
            for _ in range(300):
                f.write(zeros)
    assert bomb.stat().st_size < 2 * 2**20
    with pytest.raises(HydroFileError, match="uncompressed; a coefficient file may hold at most"):
        load_coefficients(bomb)
    # a header declaring 1e12 elements in a few bytes
    liar = tmp_path / "liar.npz"
    with zipfile.ZipFile(liar, "w") as z, z.open("omega.npy", "w") as f:
        np.lib.format.write_array_header_1_0(f, {"descr": "<f8", "fortran_order": False,
                                                 "shape": (10**12,)})
        f.write(bytes(64))
    with pytest.raises(HydroFileError, match=r"declares \(1000000000000,\) of float64"):
        load_coefficients(liar)


def test_a_file_that_is_not_npz_is_refused(tmp_path):
    bad = tmp_path / "bad.npz"
    bad.write_bytes(b"\x00not a zip")
    with pytest.raises(HydroFileError, match=r"not a readable \.npz coefficient file"):
        load_coefficients(bad)


def _box(**extra):
    from boat_dynamics.physics.core.pipeline import init_scenario
    from boat_dynamics.physics.scenario import parse_scenario

    boat = {"center_of_mass": [0.0, 0.0, -0.2], **extra}
    return init_scenario(parse_scenario({"boats": [boat]})).boats[0]


def test_boatsim_hydrostatics_equal_capytaines():
    from boat_dynamics.physics.core.tuning import equilibrium_height, hydrostatic_stiffness

    ref = load_coefficients(BOX).hydrostatic_stiffness
    params = _box().params
    k = hydrostatic_stiffness(params, equilibrium_height(params))
    np.testing.assert_allclose(k, [ref[2, 2], ref[3, 3], ref[4, 4]], rtol=1e-6)


@pytest.mark.parametrize("direction_deg", [0, 45, 90, 135, 180])
@pytest.mark.parametrize(("index", "tolerance"), [(3, 0.03), (8, 0.03), (13, 0.03), (18, 0.05)])
def test_froude_krylov_excitation_equals_capytaines(direction_deg, index, tolerance):
    # boatsim's pressure model against Capytaine's Froude-Krylov force, amplitude and phase,
    # all six dofs about the centre of mass, at wavelengths 8.0, 1.9, 0.82 L (3 %) and 0.46 L
    # (5 %: the 4096-triangle cap leaves 6.6 panels per wavelength there).
    from boat_dynamics.physics.core.boat import BoatInputs, evaluate_forces, initial_state
    from boat_dynamics.physics.core.pipeline import init_scenario
    from boat_dynamics.physics.scenario import parse_scenario
    from ocean_sim.physics.waves import WaveComponent, WaveField

    ref = load_coefficients(BOX)
    omega = float(ref.omega[index])
    d = int(np.argmin(np.abs(ref.directions - math.radians(direction_deg))))
    a = 0.005
    sea = WaveField((WaveComponent(a, 2 * math.pi * 9.81 / omega**2, math.radians(direction_deg),
                                   0.0, 0.0),))
    sc = parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                    "buoyancy": {"pressure": "froude_krylov"}}]})
    from dataclasses import replace

    params = init_scenario(replace(sc, sea=sea)).boats[0].params
    times = np.arange(24) * (2 * math.pi / omega) / 24
    rows = [np.concatenate([(f := evaluate_forces(params, initial_state(params, [0, 0, 0], t=t),
                                                  BoatInputs(), sea).buoyancy).force,
                            f.torque]) for t in times]
    # x(t) = Re[X e^{-i omega t}]: X = (2 / n) sum x(t) e^{+i omega t}, per metre of amplitude
    measured = 2 * (np.exp(1j * omega * times) @ np.array(rows)) / len(times) / a
    expected = ref.froude_krylov[index, d]
    assert np.abs(measured - expected).max() <= tolerance * np.abs(expected).max()


def _coupled_mode(dofs: list[int], guess: float, path=BOX) -> tuple[float, float]:
    """(period s, damping ratio) of the free oscillation of ``dofs`` by potential flow.

    The complex root omega of det(-omega^2 (M + A) - i omega B + C) = 0 on the dofs (coupled:
    sway-roll, surge-pitch), with A and B at Re(omega) from the file, by fixed-point iteration:
    the frequency-domain reference of a free decay (Newman 1977, sec. 6.19).
    """
    ref = load_coefficients(path)
    ix = np.ix_(dofs, dofs)
    n, omega = len(dofs), complex(guess)
    for _ in range(100):
        mass = ref.inertia_matrix[ix] + ref.added_mass_at(omega.real)[ix]
        damping, stiffness = ref.damping_at(omega.real)[ix], ref.hydrostatic_stiffness[ix]
        companion = np.block([[np.zeros((n, n)), np.eye(n)],
                              [-np.linalg.solve(mass, stiffness), -np.linalg.solve(mass, damping)]])
        roots = 1j * np.linalg.eigvals(companion)  # s = -i omega
        roots = roots[(roots.real > 0.5) & (np.abs(roots) > 1e-6)]
        new = roots[np.argmin(np.abs(roots - omega))]
        if abs(new - omega) < 1e-12:
            break
        omega = new
    return 2 * math.pi / omega.real, -omega.imag / abs(omega)


def _free_decay(radiation: str, dof: str, pose: dict) -> tuple[float, float, int]:
    """(mean period s, damping ratio, upward crossings) of the box's free decay, flat water."""
    # potential flow alone: no viscous share (cummins); resonance replaces it by its own
    damping = {"quadratic": [0] * 6}
    if radiation == "cummins":
        damping["critical_ratio"] = [0] * 3
    boat = _box(hydrodynamics={"coefficients": str(BOX), "radiation": radiation},
                damping=damping, initial_pose=pose)
    return _decay(boat.params, boat.initial, dof)


def _decay(params, state, dof: str, duration: float = 12.0) -> tuple[float, float, int]:
    """(mean period s, damping ratio, upward crossings) of a free decay from ``state``."""
    t, x = _decay_series(params, state, dof, duration)
    dt = t[1] - t[0]
    up = np.flatnonzero((x[:-1] < 0.0) & (x[1:] >= 0.0))
    crossings = t[up] - x[up] / (x[up + 1] - x[up]) * dt
    peaks = np.array([x[i:j].max() for i, j in pairwise(up)])
    decrement = np.mean(np.log(peaks[:-1] / peaks[1:]))
    return (float(np.diff(crossings).mean()),
            decrement / math.sqrt(4 * math.pi**2 + decrement**2), len(up))


def _decay_series(params, state, dof: str, duration: float) -> tuple[np.ndarray, np.ndarray]:
    """(T,) s and (T,) m or rad: heave (from the waterline), roll or pitch of a free decay."""
    from boat_dynamics.physics.body.rigid_body import quat_to_euler
    from boat_dynamics.physics.core.boat import BoatInputs, reference_pose, step
    from ocean_sim.physics.waves import WaveField

    dt, values, times = 0.002, [], []
    for _ in range(int(duration / dt)):
        ref, q = reference_pose(params, state)
        values.append(ref[2] - params.control.height_offset if dof == "heave"
                      else quat_to_euler(q)[{"roll": 0, "pitch": 1}[dof]])
        times.append(state.t)
        state = step(params, state, BoatInputs(), WaveField(), dt)
    return np.array(times), np.array(values)


_DECAYS = [("heave", {"position": [0.0, 0.0, 0.05]}, 0, [2], 2.9),
           ("roll", {"roll_deg": 3.0}, 1, [1, 3], 3.1),
           ("pitch", {"pitch_deg": 2.0}, 2, [0, 4], 3.1)]


@pytest.mark.parametrize(("dof", "pose", "index", "dofs", "guess"), _DECAYS)
def test_free_decay_with_the_radiation_memory_is_potential_flows_coupled_mode(
        dof, pose, index, dofs, guess):
    # The Cummins model (A_inf 6 x 6 and the fitted memory; the default with a coefficient
    # file): a free decay in flat water has the period and damping ratio of the coupled
    # potential-flow mode within 3 % and 20 % (the bounds). Coupled: a box rolling
    # freely also sways, which takes its roll damping ratio from 0.040 (uncoupled) to 0.024
    # (measured 0.025); surge-pitch 0.057 -> 0.050. Without the file the box is 19-34 % short.
    period, zeta = _coupled_mode(dofs, guess)
    measured_period, measured_zeta, crossings = _free_decay("cummins", dof, pose)
    assert crossings >= 4
    assert measured_period == pytest.approx(period, rel=0.03)
    assert measured_zeta == pytest.approx(zeta, rel=0.2)


@pytest.mark.parametrize(("dof", "pose", "index", "dofs", "guess"), _DECAYS)
def test_free_decay_with_resonance_coefficients_has_the_uncoupled_period_and_damping(
        dof, pose, index, dofs, guess):
    # ``radiation: resonance``: diagonal added mass and damping at each natural frequency:
    # the free decay shows Capytaine's uncoupled natural period within 3 % and its damping
    # ratio within 20 %.
    with np.load(BOX) as data:  # computed by the reference script itself
        period, zeta = float(data["natural_period_wet"][index]), float(data["damping_ratio"][index])
    measured_period, measured_zeta, crossings = _free_decay("resonance", dof, pose)
    assert crossings >= 4
    assert measured_period == pytest.approx(period / math.sqrt(1 - zeta**2), rel=0.03)
    assert measured_zeta == pytest.approx(zeta, rel=0.2)


def test_a_coefficient_file_of_another_centre_of_mass_or_a_bad_file_is_refused(tmp_path):
    from boat_dynamics.physics.scenario import ScenarioError, parse_scenario

    with pytest.raises(ScenarioError, match=r"solved about the centre of mass \[0.0, 0.0, -0.2\]"):
        parse_scenario({"boats": [{"hydrodynamics": {"coefficients": str(BOX)}}]})
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"center_of_mass": [0, 0, -0.2],
                                   "hydrodynamics": {"coefficients": "missing.npz"}}]},
                       base_dir=tmp_path)
    assert err.value.key == "boats[0].hydrodynamics.coefficients"
    assert "not a readable .npz" in err.value.allowed


WIGLEY = DATA / "wigley_4x1x1.npz"


def _wigley(pose: dict):
    """The Wigley hull with its file and Cummins radiation, released from ``pose``."""
    from boat_dynamics.physics.core.pipeline import init_scenario
    from boat_dynamics.physics.scenario import parse_scenario

    ref = load_coefficients(WIGLEY)
    m = float(ref.inertia_matrix[0, 0])
    boat = init_scenario(parse_scenario({"boats": [{
        "hull": {"type": "mesh", "path": str(DATA / "wigley_4x1x1.stl")}, "mass": m,
        "center_of_mass": ref.center_of_mass.tolist(),
        "inertia": np.diag(ref.inertia_matrix)[3:].tolist(), "inertia_products": [0, 0, 0],
        "hydrodynamics": {"coefficients": str(WIGLEY)},
        "damping": {"quadratic": [0] * 6, "critical_ratio": [0] * 3},  # potential flow alone
        "initial_pose": pose}]})).boats[0]
    assert boat.params.control.height_offset == pytest.approx(-0.1, abs=1e-6)  # its waterline
    return boat


def _potential_flow_response(dofs: list[int], index: int, omega: np.ndarray) -> np.ndarray:
    """(W,) complex H_dd(omega), m/N or rad/(N m): dof ``dofs[index]``'s response to its own
    force, of (C - omega^2 (M + A(omega)) - i omega B(omega))^-1 on the coupled ``dofs``."""
    ref = load_coefficients(WIGLEY)
    ix = np.ix_(dofs, dofs)
    return np.array([np.linalg.inv(ref.hydrostatic_stiffness[ix]
                                   - w**2 * (ref.inertia_matrix[ix] + ref.added_mass_at(w)[ix])
                                   - 1j * w * ref.damping_at(w)[ix])[index, index]
                     for w in omega])


def _decay_response(t: np.ndarray, x: np.ndarray, stiffness: float,
                    omega: np.ndarray) -> np.ndarray:
    """(W,) complex H_dd(omega) of the linear system whose free decay from rest is x(t).

    Released from rest at x0 (held there by the force C x0 until t = 0), a linear system has
    x(t) = x0 (1 - C s(t)), s the step response, whose transform is H i / omega; so the
    transform X = int_0^inf x e^{i omega t} dt gives H = (1 + i omega X / x0) / C. Needs the
    other coupled dofs free of restoring coupling (C_jd = 0: surge-pitch, sway-roll about the
    centre of mass) and x(t) decayed to ~0 by the end.
    """
    transform = np.trapezoid(x[None, :] * np.exp(1j * omega[:, None] * t[None, :]), t, axis=1)
    return (1.0 + 1j * omega * transform / x[0]) / stiffness


def _quadrature(omega: np.ndarray, response: np.ndarray) -> float:
    """rad/s where Re H first falls through 0: the natural frequency, C = omega^2 (M + A)."""
    re = response.real
    i = np.flatnonzero((re[:-1] > 0.0) & (re[1:] <= 0.0))[0]
    return float(omega[i] - re[i] * (omega[i + 1] - omega[i]) / (re[i + 1] - re[i]))


@pytest.mark.parametrize(("dof", "pose", "dofs", "index", "duration"), [
    ("heave", {"position": [0.0, 0.0, -0.05]}, [2], 0, 12.0),
    ("pitch", {"pitch_deg": 1.0}, [0, 4], 1, 20.0),
])
def test_a_ship_like_hull_responds_as_potential_flow_at_its_natural_frequency(
        dof, pose, dofs, index, duration):
    # A Wigley-type hull (tests/data/hydro/wigley_reference.py: 4 x 1 x 1 m, draft 0.6 m,
    # boatsim's own solver) with its file and Cummins radiation, released in flat water. The
    # free decay's Fourier transform is boatsim's frequency response H_dd (_decay_response),
    # compared with potential flow's (added mass and damping at each frequency, coupled):
    # - natural period (Re H = 0, C = omega^2 (M + A(omega))): heave 1.3646 s against boatsim's
    #   1.3643 (-0.02 %), pitch 1.6401 against 1.6416 (+0.09 %); the bound is 3 %;
    # - radiation damping at the natural frequency (|H| = 1 / (omega B) there): heave +0.6 %,
    #   pitch +4.9 % (bound 20 %); H within 1.3 % (heave) and 5.5 % (pitch) of its peak from
    #   0.7 to 1.3 omega_n (bound 10 %).
    # A decay's zero crossings cannot measure this heave: with damping ratio 0.16 and
    # frequency-dependent A and B, the crossings are 1.31 s apart in boatsim and in the exact
    # linear decay alike (the Fourier integral of potential flow's own H), neither equal to
    # the natural period or to the complex root of det(-w^2 (M + A(Re w)) - i w B + C).
    stiffness = float(load_coefficients(WIGLEY).hydrostatic_stiffness[dofs[index], dofs[index]])
    boat = _wigley(pose)
    t, x = _decay_series(boat.params, boat.initial, dof, duration)
    omega = np.linspace(2.0, 8.0, 601)
    expected, measured = _potential_flow_response(dofs, index, omega), _decay_response(
        t, x, stiffness, omega)
    natural, measured_natural = _quadrature(omega, expected), _quadrature(omega, measured)
    assert 2 * math.pi / measured_natural == pytest.approx(2 * math.pi / natural, rel=0.03)
    damping = 1.0 / (natural * abs(np.interp(natural, omega, expected.imag)))
    measured_damping = 1.0 / (measured_natural * abs(np.interp(measured_natural, omega,
                                                                 measured.imag)))
    assert measured_damping == pytest.approx(damping, rel=0.2)
    near = (omega > 0.7 * natural) & (omega < 1.3 * natural)
    assert np.abs(measured - expected)[near].max() <= 0.1 * np.abs(expected[near]).max()


def test_a_ship_like_hull_rolls_with_its_potential_flow_mode():
    # Roll (coupled with sway) of the Wigley hull: its radiation damping ratio is 1e-4, so the
    # decay's period is its natural period: 3.588 s against potential flow's 3.596 (-0.2 %).
    period, _ = _coupled_mode([1, 3], 1.7, WIGLEY)
    boat = _wigley({"roll_deg": 3.0})
    measured_period, _, crossings = _decay(boat.params, boat.initial, "roll")
    assert crossings >= 3
    assert measured_period == pytest.approx(period, rel=0.03)
