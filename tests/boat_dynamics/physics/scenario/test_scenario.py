"""Scenario parsing: the shipped files load; every refusal names key, value and what is allowed."""

import math
from pathlib import Path

import numpy as np
import pytest

from boat_dynamics.physics.core.boat import reference_pose
from boat_dynamics.physics.scenario import ScenarioError, load_scenario, parse_scenario

SCENARIOS = sorted((Path(__file__).resolve().parents[4] / "scenarios").glob("*.yaml"))


@pytest.mark.parametrize("path", SCENARIOS, ids=[p.name for p in SCENARIOS])
def test_shipped_scenarios_load(path):
    sc = load_scenario(path)
    assert sc.boats


def test_default_scenario_is_one_root_boat_on_a_moderate_sea():
    sc = load_scenario(SCENARIOS[[p.name for p in SCENARIOS].index("default.yaml")])
    assert [b.name for b in sc.boats] == [""]
    assert 0.0 < sc.sea.steepness_sum < 0.5
    assert sc.simulation.rate_hz == 100 and sc.simulation.publish_rate_hz == 50
    pos, _ = reference_pose(sc.boats[0].params, sc.boats[0].initial)
    assert pos.tolist() == [0.0, 0.0, 0.0]


def test_empty_scenario_is_one_boat_on_a_flat_sea():
    sc = parse_scenario({})
    assert len(sc.boats) == 1 and sc.sea.is_flat
    assert sc.boats[0].params.mass == pytest.approx(0.5 * 1025 * 8.0)


def test_density_derives_mass():
    sc = parse_scenario({"boats": [{"density": 300.0}]})
    assert sc.boats[0].params.mass == pytest.approx(300.0 * 8.0)


@pytest.mark.parametrize(
    ("data", "key", "fragment"),
    [
        ({"simulation": {"rate_hz": 0}}, "simulation.rate_hz", "[1, 10000]"),
        ({"simulation": {"rate_hz": 100, "publish_rate_hz": 200}},
         "simulation.publish_rate_hz", "(0, 100]"),
        ({"simulation": {"realtime": "yes"}}, "simulation.realtime", "true or false"),
        ({"simulation": {"frobnicate": 1}}, "simulation.frobnicate", "unknown key"),
        ({"ocean": {"components": [{"amplitude": 0.1, "wavelength": -3}]}},
         "ocean.components[0].wavelength", "(0, inf]"),
        ({"ocean": {"components": [{"amplitude": 3.0, "wavelength": 10, "steepness": 1}]}},
         "ocean.components", "crests loop"),
        ({"ocean": {"depth": -2}}, "ocean.depth", "(0, inf]"),
        ({"boats": [{"mass": -5}]}, "boats[0].mass", "(0, inf]"),
        ({"boats": [{"mass": "heavy"}]}, "boats[0].mass", "number"),
        ({"boats": [{"mass": 1000, "density": 500}]}, "boats[0].density", "not both"),
        ({"boats": [{"hull": {"length": math.nan}}]}, "boats[0].hull.length", "finite"),
        ({"boats": [{"hull": {"type": "mesh"}}]}, "boats[0].hull.path", "STL or OBJ"),
        ({"boats": [{"hull": {"type": "mesh", "path": "nowhere.stl"}}]}, "boats[0].hull.path",
         "cannot read"),
        ({"boats": [{"hull": {"type": "box", "subdivisions": 0}}]},
         "boats[0].hull.subdivisions", "[1, 64]"),
        ({"boats": [{"buoyancy": {"model": "mesh", "grid": [2, 2]}}]}, "boats[0].buoyancy.grid",
         "only for model sample_points"),
        ({"boats": [{"center_of_mass": [0, 0]}]}, "boats[0].center_of_mass", "3 numbers"),
        ({"boats": [{"rudder": {"model": "banana"}}]}, "boats[0].rudder.model",
         "one of: lift"),
        ({"boats": [{"name": "a"}, {"name": "a"}]}, "boats[1].name", "unique"),
        ({"boats": [{"name": "a"}, {}]}, "boats[1].name", "needs a name"),
        ({"boats": [{"name": "my boat"}]}, "boats[0].name", "ROS name"),
        # rclpy refused these with a traceback after the scenario check had passed them
        ({"boats": [{"name": "bateau_\u00e9t\u00e9"}]}, "boats[0].name", "an ASCII letter"),
        ({"boats": [{"name": "b" * 65}]}, "boats[0].name", "at most 64 characters"),
        ({"boats": [{"name": "_hidden"}]}, "boats[0].name", "ROS name"),
        ({"boats": [{"sensors": [{"type": "gnss", "name": "g\u00e9"}]}]},
         "boats[0].sensors[0].name", "ASCII"),
        ({"boats": [{"propulsion": [{"name": "l" * 300}]}]}, "boats[0].propulsion[0].name",
         "at most 64 characters"),
        ({"boats": [{"sensors": [{"type": "gnss", "position": [0, 0, 1e300]}]}]},
         "boats[0].sensors[0].position", "within +-1000"),
        ({"boats": [{"commands": [{"t": 5, "thrust": 1}, {"t": 2, "thrust": 0}]}]},
         "boats[0].commands[1].t", "later than"),
        ({"boats": [{"commands": [{"t": 0, "thrust": 2}]}]}, "boats[0].commands[0].thrust",
         "[-1, 1]"),
        ({"boats": []}, "boats", "non-empty"),
        ({"ocean": {"spectrum": {"type": "bretschneider"}}}, "ocean.spectrum.type",
         "jonswap, pierson_moskowitz"),
        ({"ocean": {"spectrum": {"significant_height": -1}}}, "ocean.spectrum.significant_height",
         "[0, 30] m"),
        ({"ocean": {"spectrum": {"beaufort": 13}}}, "ocean.spectrum.beaufort", "[0, 12]"),
        ({"ocean": {"spectrum": {"beaufort": 5, "peak_period": 7}}},
         "ocean.spectrum.peak_period", "either beaufort"),
        ({"ocean": {"spectrum": {"components": 0}}}, "ocean.spectrum.components", "[1, 1000]"),
        ({"ocean": {"spectrum": {"steepness": 1.0, "significant_height": 2.0},
                    "components": [{"amplitude": 1.0, "wavelength": 8.0, "steepness": 1.0}]}},
         "ocean", "components and spectrum together"),
        ({"boats": [{"min_wavelength": -1}]}, "boats[0].min_wavelength", "[0, 10000] m"),
        ({"boats": [{"buoyancy": {"pressure": "airy"}}]}, "boats[0].buoyancy.pressure",
         "hydrostatic, froude_krylov"),
        ({"boats": [{"buoyancy": {"pressure": "hydrostatic", "panels_per_wavelength": 8}}]},
         "boats[0].buoyancy.panels_per_wavelength", "only for pressure froude_krylov"),
        ({"boats": [{"hydrodynamics": {"coefficients": "none", "radiation": "cummins"}}]},
         "boats[0].hydrodynamics.radiation", "needs hydrodynamics.coefficients"),
        ({"boats": [{"rudder": {"model": "torque", "max_torque": 5, "skeg_area": 1}}]},
         "boats[0].rudder.skeg_area", "only for rudder model lift"),
        ({"boats": [{"buoyancy": {"pressure": "froude_krylov", "panels_per_wavelength": 0.5}}]},
         "boats[0].buoyancy.panels_per_wavelength", "[1, 100]"),
        ({"boats": [{"buoyancy": {"pressure": "froude_krylov", "max_triangles": 4.5}}]},
         "boats[0].buoyancy.max_triangles", "integer in [12, 1000000]"),
        ({"boats": [{"buoyancy": {"model": "sample_points", "pressure": "froude_krylov"}}]},
         "boats[0].buoyancy.pressure", "only for model mesh"),
        ({"simulation": {"datum": {"latitude_deg": 91}}}, "simulation.datum.latitude_deg",
         "[-89, 89] deg"),
        ({"simulation": {"datum": {"lat": 1}}}, "simulation.datum.lat", "unknown key"),
        ({"simulation": {"publish_tf": "no"}}, "simulation.publish_tf", "true or false"),
        ({"boats": [{"sensors": {"type": "imu"}}]}, "boats[0].sensors", "list of sensors"),
        ({"boats": [{"sensors": [{"type": "gnss", "heading_baseline": [0.05, 0.05, 1]}]}]},
         "boats[0].sensors[0].heading_baseline", "at least 0.1 m horizontally"),
        ({"boats": [{"sensors": [{"type": "gnss", "heading_baseline": [1, 0]}]}]},
         "boats[0].sensors[0].heading_baseline", "3 numbers"),
        ({"boats": [{"sensors": [{"type": "imu", "heading_baseline": [1, 0, 0]}]}]},
         "boats[0].sensors[0].heading_baseline", "only for a gnss"),
        ({"boats": [{"sensors": [{"type": "gnss", "noise": {"heading_sigma_deg": 100}}]}]},
         "boats[0].sensors[0].noise.heading_sigma_deg", "[0, 90] deg"),
        ({"boats": [{"sensors": [{"type": "imu", "latency": -0.01}]}]},
         "boats[0].sensors[0].latency", "[0, 60] s"),
        ({"boats": [{"sensors": [{"type": "gnss", "latency": math.inf}]}]},
         "boats[0].sensors[0].latency", "[0, 60] s"),
        ({"boats": [{"sensors": [{"type": "depth_sounder", "max_range": 0}]}]},
         "boats[0].sensors[0].max_range", "(0, 12000] m"),
        ({"boats": [{"sensors": [{"type": "depth_sounder", "min_range": 10,
                                  "max_range": 5}]}]},
         "boats[0].sensors[0].max_range", "greater than min_range (10 m)"),
        ({"boats": [{"sensors": [{"type": "depth_sounder", "field_of_view_deg": 0}]}]},
         "boats[0].sensors[0].field_of_view_deg", "(0, 180] deg"),
        ({"boats": [{"sensors": [{"type": "depth_sounder", "noise": {"range_sigma": -0.1}}]}]},
         "boats[0].sensors[0].noise.range_sigma", "[0, 100] m"),
        ({"boats": [{"sensors": [{"type": "depth_sounder", "noise": {"sigma": 0.1}}]}]},
         "boats[0].sensors[0].noise.sigma", "allowed keys here: range_sigma"),
        ({"boats": [{"sensors": [{"type": "imu", "max_range": 50}]}]},
         "boats[0].sensors[0].max_range", "only for a depth_sounder"),
        ({"simulation": {"magnetic_field": {"inclination_deg": 95}}},
         "simulation.magnetic_field.inclination_deg", "[-90, 90] deg"),
        ({"simulation": {"magnetic_field": {"intensity_nT": -1}}},
         "simulation.magnetic_field.intensity_nT", "[0, 1e+06] nT"),
        ({"simulation": {"magnetic_field": {"intensity": 5e-5}}},
         "simulation.magnetic_field.intensity", "unknown key"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {"sigma": 1.0}}]}]},
         "boats[0].sensors[0].noise.sigma", "[0, 0.001] T"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {"hard_iron": [0, 1]}}]}]},
         "boats[0].sensors[0].noise.hard_iron", "3 numbers"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {
            "hard_iron": [0, 0, 0.01]}}]}]},
         "boats[0].sensors[0].noise.hard_iron", "within +-0.001"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {
            "soft_iron": [1, 0, 0]}}]}]},
         "boats[0].sensors[0].noise.soft_iron", "3 rows of 3 numbers"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {
            "soft_iron": [[1, 0, 0], [0, 1, 0], [0, 0, 20]]}}]}]},
         "boats[0].sensors[0].noise.soft_iron", "within +-10"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {
            "soft_iron": [[1, 0, 0], [2, 0, 0], [0, 0, 1]]}}]}]},
         "boats[0].sensors[0].noise.soft_iron", "invertible"),
        ({"boats": [{"sensors": [{"type": "magnetometer", "noise": {
            "horizontal_sigma": 1}}]}]},
         "boats[0].sensors[0].noise.horizontal_sigma", "sigma, hard_iron, soft_iron"),
        ({"boats": [{"sensors": [{"type": "sonar"}]}]}, "boats[0].sensors[0].type",
         "one of: imu, gnss, odometry"),
        ({"boats": [{"sensors": [{"type": "odometry", "position": [0, 0, 1]}]}]},
         "boats[0].sensors[0].position", "reference point"),
        ({"boats": [{"sensors": [{"type": "odometry", "noise": {"position_sigma": -1}}]}]},
         "boats[0].sensors[0].noise.position_sigma", "[0, 10000] m"),
        ({"boats": [{"sensors": [{"type": "imu", "name": "my imu"}]}]},
         "boats[0].sensors[0].name", "ROS name"),
        ({"boats": [{"sensors": [{"type": "imu"}, {"type": "imu"}]}]},
         "boats[0].sensors[1].name", "unique"),
        ({"boats": [{"sensors": [{"type": "imu", "rate_hz": 500}]}]},
         "boats[0].sensors[0].rate_hz", "at most simulation.rate_hz"),
        ({"boats": [{"sensors": [{"type": "gnss", "position": [0, 0]}]}]},
         "boats[0].sensors[0].position", "3 numbers"),
        ({"boats": [{"sensors": [{"type": "imu", "noise": {"gyroscope": {
            "noise_density": math.inf}}}]}]},
         "boats[0].sensors[0].noise.gyroscope.noise_density", "rad/s/sqrt(Hz)"),
        ({"boats": [{"sensors": [{"type": "imu", "noise": {"accelerometer": {
            "bias_correlation_time": 0}}}]}]},
         "boats[0].sensors[0].noise.accelerometer.bias_correlation_time", "> 0 s"),
        ({"boats": [{"sensors": [{"type": "imu", "noise": {"gyroscope": {
            "misalignment_deg": 20}}}]}]},
         "boats[0].sensors[0].noise.gyroscope.misalignment_deg", "[0, 10] deg"),
        ({"boats": [{"sensors": [{"type": "imu", "noise": {"accelerometer": {
            "range": 0}}}]}]},
         "boats[0].sensors[0].noise.accelerometer.range", "(0, inf] m/s^2"),
        ({"boats": [{"sensors": [{"type": "imu", "noise": {"accelerometer": {
            "scale_factor": math.nan}}}]}]},
         "boats[0].sensors[0].noise.accelerometer.scale_factor", "[0, 0.5]"),
        ({"boats": [{"sensors": [{"type": "odometry", "dropout": 1.5}]}]},
         "boats[0].sensors[0].dropout", "[0, 1]"),
        ({"boats": [{"sensors": [{"type": "gnss", "outages": [[2.0, 1.0]]}]}]},
         "boats[0].sensors[0].outages[0]", "0 <= start < end"),
        ({"boats": [{"sensors": [{"type": "gnss", "outages": [1.0, 2.0]}]}]},
         "boats[0].sensors[0].outages[0]", "[start, end]"),
        ({"boats": [{"sensors": [{"type": "imu", "outages": [[1.0, 2.0]]}]}]},
         "boats[0].sensors[0].outages", "only for a gnss"),
        ({"boats": [{"sensors": [{"type": "gnss", "noise": {"horizontal_sigma": -1}}]}]},
         "boats[0].sensors[0].noise.horizontal_sigma", "[0, 10000] m"),
        ({"boats": [{"sensors": [{"type": "gnss", "noise": {"vertical_sigma": 1,
                                                             "gyroscope": {}}}]}]},
         "boats[0].sensors[0].noise.gyroscope", "unknown key"),
    ],
)
def test_refusals_name_key_value_and_allowed(data, key, fragment):
    with pytest.raises(ScenarioError) as info:
        parse_scenario(data)
    assert info.value.key == key
    assert str(info.value).startswith(f"{key}: ")
    assert fragment in info.value.allowed


def test_bad_yaml_and_missing_file(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("boats: [\n  {mass: 3\n")
    with pytest.raises(ScenarioError, match="valid YAML"):
        load_scenario(bad)
    with pytest.raises(ScenarioError, match="readable file"):
        load_scenario(tmp_path / "missing.yaml")


def test_spectrum_and_components_combine_and_the_seed_sets_the_phases():
    data = {"simulation": {"seed": 3},
            "ocean": {"depth": 30.0,
                      "components": [{"amplitude": 0.2, "wavelength": 40.0}],
                      "spectrum": {"type": "jonswap", "significant_height": 1.5,
                                   "peak_period": 7.0, "direction_deg": 90, "components": 12}}}
    a, b = parse_scenario(data), parse_scenario(data)
    assert len(a.sea.components) == 13 and a.sea.depth == 30.0
    assert a.sea == b.sea
    data["simulation"]["seed"] = 4
    c = parse_scenario(data)
    assert [x.phase for x in c.sea.components[1:]] != [x.phase for x in a.sea.components[1:]]


def test_beaufort_preset():
    sc = parse_scenario({"ocean": {"spectrum": {"beaufort": 6, "components": 32}}})
    a = sc.sea.arrays.a
    assert 4 * math.sqrt(float((a**2).sum()) / 2) == pytest.approx(3.0, rel=0.05)


def test_min_wavelength_reaches_the_boat():
    sc = parse_scenario({"boats": [{"min_wavelength": 5.0}]})
    assert sc.boats[0].params.min_wavelength == 5.0


def test_inertia_products_from_the_hull_or_the_scenario_and_refused_when_impossible():
    sc = parse_scenario({"boats": [{"name": "a"}, {"name": "b", "inertia": [1000, 4000, 4500],
                                                    "inertia_products": [0, 300, 0]}]})
    assert sc.boats[0].params.inertia_products.tolist() == [0.0, 0.0, 0.0]  # box: principal
    assert sc.boats[1].params.inertia_products.tolist() == [0.0, 300.0, 0.0]
    with pytest.raises(ScenarioError, match=r"boats\[0\]\.inertia_products.*positive definite"):
        parse_scenario({"boats": [{"inertia": [1000, 4000, 4500],
                                   "inertia_products": [0, 3000, 0]}]})


def test_wave_precision_reaches_every_boat_and_is_checked():
    assert parse_scenario({}).boats[0].params.wave_precision == "float64"
    sc = parse_scenario({"simulation": {"wave_precision": "float32"}})
    assert sc.simulation.wave_precision == sc.boats[0].params.wave_precision == "float32"
    with pytest.raises(ScenarioError, match=r"simulation\.wave_precision: 'float16'.*float32"):
        parse_scenario({"simulation": {"wave_precision": "float16"}})


def _alias_bomb(levels: int = 9) -> str:
    """A billion-laughs YAML: 9^levels values from a few hundred bytes, inside a boat."""
    rows = ["a0: &a0 [lol, lol, lol, lol, lol, lol, lol, lol, lol]"]
    rows += [f"a{i}: &a{i} [" + ", ".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, levels)]
    return "boats:\n  - name: x\n    mass:\n" + "\n".join("      " + r for r in rows) + "\n"


@pytest.mark.parametrize(("content", "fragment"), [
    (bytes(range(256)) * 16, "must be UTF-8 text (YAML); byte 128 is 0x80"),
    (("boats: " + "[" * 5000 + "]" * 5000).encode(), "nest at most 32 levels"),
    (("boats: " + "[" * 40 + "]" * 40).encode(), "nest at most 32 levels"),
    # 100,000 levels: the C composer overflowed its stack (SIGSEGV) before any check ran
    (("boats: " + "[" * 100_000 + "]" * 100_000).encode(), "nest at most 32 levels"),
    (("boats:\n" + "- " * 100_000 + "x\n").encode(), "nest at most 32 levels"),
    (("boats: " + "{a: " * 30_000 + "}" * 30_000).encode(), "nest at most 32 levels"),
    (_alias_bomb().encode(), "at most 200000 values with its YAML aliases expanded"),
    (b"# padding\n" * 110_000, "at most 1000000 bytes"),
])
def test_a_hostile_file_is_refused_with_a_short_message(tmp_path, content, fragment):
    # before: a binary file raised UnicodeDecodeError, 5000 levels RecursionError, and the
    # alias bomb's 3.2 GB error message took 63 s and 6.2 GB of memory
    path = tmp_path / "hostile.yaml"
    path.write_bytes(content)
    with pytest.raises(ScenarioError) as err:
        load_scenario(path)
    assert err.value.key == "file"
    assert fragment in err.value.allowed
    assert len(str(err.value)) < 500


def test_a_refusal_never_expands_a_large_value():
    shared = [list(range(50))] * 50  # 2,500 values through one shared list
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"mass": shared}]})
    assert err.value.key == "boats[0].mass"
    assert len(str(err.value)) < 500


def test_a_centre_of_mass_far_from_the_hull_is_refused():
    # found by the fuzzer: 4.5e15 m divided by zero in the equilibrium search
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"center_of_mass": [0.0, 0.0, 4.5e15]}]})
    assert err.value.key == "boats[0].center_of_mass"
    assert "within 10 hull sizes (40 m)" in err.value.allowed
    assert parse_scenario({"boats": [{"center_of_mass": [0.0, 0.0, -39.0]}]}).boats


def test_a_start_beyond_a_local_frame_is_refused():
    # found by the fuzzer: x = 6e307 m overflowed in the physics
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"initial_pose": {"position": [6e307, 0.0, 0.0]}}]})
    assert err.value.key == "boats[0].initial_pose.position"
    assert "within +-1e+07 m" in err.value.allowed
    assert parse_scenario({"boats": [{"initial_pose": {"position": [-9e6, 9e6, 0.0]}}]}).boats


@pytest.mark.parametrize(("key", "value", "allowed"), [
    ("velocity", [50.5, 0.0, 0.0], "within +-50"),
    ("velocity", [1.0, float("nan"), 0.0], "finite"),
    ("velocity", [1.0, 0.0], "list of 3 numbers"),
    ("angular_velocity_deg", [0.0, 0.0, -361.0], "within +-360"),
    ("angular_velocity_deg", "fast", "list of 3 numbers")])
def test_an_initial_velocity_out_of_range_is_refused_with_its_key(key, value, allowed):
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"initial_pose": {key: value}}]})
    assert err.value.key == f"boats[0].initial_pose.{key}"
    assert allowed in err.value.allowed


def test_a_hull_smaller_than_a_centimetre_is_refused():
    # found by the fuzzer: a length of 5e-324 m stopped numpy's eigenvalue solver
    with pytest.raises(ScenarioError) as err:
        parse_scenario({"boats": [{"hull": {"length": 5e-324}}]})
    assert err.value.key == "boats[0].hull.length"
    assert parse_scenario({"boats": [{"hull": {"length": 0.01, "beam": 0.01,
                                               "height": 0.01}}]}).boats


def test_wrench_topics_is_one_of_its_choices():
    assert parse_scenario({}).simulation.wrench_topics == "auto"
    for value in ("advertised", "on_subscription"):
        sim = parse_scenario({"simulation": {"wrench_topics": value}}).simulation
        assert sim.wrench_topics == value
    with pytest.raises(ScenarioError) as refused:
        parse_scenario({"simulation": {"wrench_topics": "sometimes"}})
    assert "simulation.wrench_topics" in str(refused.value)
    assert "auto, advertised, on_subscription" in str(refused.value)


def test_alike_boats_share_their_parameters_and_keep_their_own_poses():
    import numpy as np

    from boat_dynamics.physics.core.pipeline import init_scenario

    def boat(name, x, **extra):
        return {"name": name, "initial_pose": {"position": [x, 0.0, 0.0]}, **extra}

    fleet = parse_scenario({"boats": [boat("a", 0.0), boat("b", 20.0),
                                      boat("c", 40.0, mass=3000.0), boat("d", 60.0)]})
    a, b, c, d = fleet.boats
    assert a.params is b.params is d.params and c.params is not a.params
    assert [s.initial.position[0] for s in fleet.boats] == [0.0, 20.0, 40.0, 60.0]
    alone = parse_scenario({"boats": [boat("b", 20.0), boat("x", 99.0, mass=3000.0)]})
    ready, ready_alone = init_scenario(fleet), init_scenario(alone)
    assert ready.boats[0].params is ready.boats[1].params  # derived once
    for field in ("damping_linear", "damping_quadratic", "center_of_mass"):
        np.testing.assert_array_equal(getattr(ready.boats[1].params, field),
                                      getattr(ready_alone.boats[0].params, field))
    assert ready.boats[1].params.control.height_offset == (
        ready_alone.boats[0].params.control.height_offset)


def test_a_shipped_scenarios_comment_on_its_steepness_is_what_the_ocean_logs():
    import re

    root = Path(__file__).resolve().parents[4] / "scenarios"
    checked = 0
    for path in sorted(root.glob("*.yaml")):
        said = re.search(r"sum Q k a = ([0-9.]+)", path.read_text())
        if said:
            assert load_scenario(path).sea.steepness_sum == pytest.approx(
                float(said.group(1)), abs=5e-4), path.name
            checked += 1
    assert checked >= 1  # default.yaml says it


def test_a_file_without_boats_gets_a_default_boat_and_a_note_saying_so(tmp_path):
    assert parse_scenario({}).notes == (
        "the file is empty: one default boat (a 4 m x 2 m x 1 m box, 4,100 kg) in the root "
        "namespace",)
    assert parse_scenario({"simulation": {"seed": 1}}).notes[0].startswith("no `boats`: ")
    assert parse_scenario({"boats": [{}]}).notes == ()
    empty = tmp_path / "empty.yaml"
    empty.write_text("")
    assert load_scenario(empty).notes[0].startswith("the file is empty")


def test_an_imu_takes_its_scale_factor_misalignment_and_range():
    sc = parse_scenario({"boats": [{"sensors": [{"type": "imu", "noise": {
        "gyroscope": {"scale_factor": 0.001, "misalignment_deg": 0.1, "range": 5.0},
        "accelerometer": {"range": math.inf}}}]}]})
    (imu,) = sc.boats[0].sensors
    assert imu.gyroscope.scale_factor == 0.001
    assert imu.gyroscope.misalignment == pytest.approx(math.radians(0.1))
    assert (imu.gyroscope.range, imu.accelerometer.range) == (5.0, math.inf)
    assert imu.accelerometer.scale_factor == imu.accelerometer.misalignment == 0.0  # ideal


def test_a_gnss_takes_its_outages():
    sc = parse_scenario({"boats": [{"sensors": [
        {"type": "gnss", "outages": [[1, 2.5], [10.0, math.inf]]}]}]})
    assert sc.boats[0].sensors[0].outages == ((1.0, 2.5), (10.0, math.inf))
    assert sc.boats[0].sensors[0].dropout == 0.0
    sc = parse_scenario({"boats": [{"sensors": [{"type": "imu", "dropout": 0.25}]}]})
    assert sc.boats[0].sensors[0].dropout == 0.25
    assert sc.boats[0].sensors[0].latency == 0.0


def test_a_gnss_takes_a_heading_baseline_and_its_sigma():
    sc = parse_scenario({"boats": [{"sensors": [
        {"type": "gnss", "heading_baseline": [1.5, 0, 0.1],
         "noise": {"heading_sigma_deg": 0.4}}, {"type": "gnss", "name": "plain"}]}]})
    dual, plain = sc.boats[0].sensors
    assert dual.heading_baseline.tolist() == [1.5, 0.0, 0.1]
    assert dual.noise.heading_sigma == pytest.approx(math.radians(0.4))
    assert plain.heading_baseline is None
    assert plain.noise.heading_sigma == pytest.approx(math.radians(0.2))


def test_every_sensor_takes_a_latency():
    kinds = ("imu", "gnss", "odometry", "magnetometer", "depth_sounder")
    sc = parse_scenario({"boats": [{"sensors": [{"type": kind, "latency": 0.05 * (i + 1)}
                                                for i, kind in enumerate(kinds)]}]})
    assert [s.latency for s in sc.boats[0].sensors] == pytest.approx([0.05, 0.1, 0.15, 0.2,
                                                                      0.25])


def test_a_magnetometer_takes_its_iron_and_noise_and_the_field_its_datum_s_value():
    soft = [[1.1, 0.01, 0.0], [0.01, 0.9, 0.0], [0.0, 0.0, 1.0]]
    sc = parse_scenario({
        "simulation": {"magnetic_field": {"declination_deg": -2.5, "inclination_deg": 63,
                                          "intensity_nT": 48500}},
        "boats": [{"sensors": [{"type": "magnetometer", "name": "compass", "position": [1, 0, 2],
                                "noise": {"sigma": 5e-8, "hard_iron": [1e-6, 0, -2e-6],
                                          "soft_iron": soft}}]}]})
    (mag,) = sc.boats[0].sensors
    assert (mag.name, mag.rate_hz, mag.sigma) == ("compass", 20.0, 5e-8)
    assert mag.hard_iron.tolist() == [1e-6, 0.0, -2e-6] and mag.soft_iron.tolist() == soft
    field = sc.simulation.magnetic_field
    assert field.declination == pytest.approx(math.radians(-2.5))
    assert field.inclination == pytest.approx(math.radians(63.0))
    assert field.intensity == pytest.approx(48500e-9)
    (default,) = parse_scenario({"boats": [{"sensors": [{"type": "magnetometer"}]}]}
                                ).boats[0].sensors
    assert default.soft_iron.tolist() == np.eye(3).tolist() and not default.hard_iron.any()


def test_a_depth_sounder_takes_its_cone_ranges_and_noise():
    sc = parse_scenario({"boats": [{"sensors": [
        {"type": "depth_sounder", "name": "echo", "position": [0.5, 0, -0.4],
         "field_of_view_deg": 20, "min_range": 1, "max_range": 80,
         "noise": {"range_sigma": 0.1}}]}]})
    (echo,) = sc.boats[0].sensors
    assert (echo.name, echo.rate_hz, echo.min_range, echo.max_range, echo.range_sigma) == (
        "echo", 10.0, 1.0, 80.0, 0.1)
    assert echo.field_of_view == pytest.approx(math.radians(20.0))
    assert echo.position.tolist() == [0.5, 0.0, -0.4]
    (default,) = parse_scenario({"boats": [{"sensors": [{"type": "depth_sounder"}]}]}
                                ).boats[0].sensors
    assert (default.min_range, default.max_range, default.range_sigma) == (0.5, 200.0, 0.05)
