"""What a scenario file is read into: frozen specs, and the error that names a bad key."""

from __future__ import annotations

import reprlib
from dataclasses import dataclass, field
from typing import Literal, get_args

import numpy as np

from boat_dynamics.physics.core.commands import CommandScript
from boat_dynamics.physics.core.model import BoatParams, BoatState
from boat_dynamics.physics.sensors import Datum, EarthField, SensorSpec
from boat_dynamics.physics.world.obstacles import World
from ocean_sim.physics.constants import GRAVITY, WATER_DENSITY
from ocean_sim.physics.environment import Environment
from ocean_sim.physics.errors import InvalidValueError
from ocean_sim.physics.waves import (
    DEFAULT_PRECISION,
    Precision,
    WaveField,
)


class ScenarioError(InvalidValueError):
    """A scenario that cannot be run.

    Attributes:
        key: path of the offending key, e.g. ``boats[0].mass``.
        value: the value found.
        allowed: what would have been accepted.
    """

    def __init__(self, key: str, value: object, allowed: str) -> None:
        super().__init__(key, value, allowed,
                         f"{key}: {shortened(value)} is not allowed: {allowed}")


_SHORT = reprlib.Repr()
_SHORT.maxlevel, _SHORT.maxlist, _SHORT.maxtuple, _SHORT.maxdict = 3, 6, 6, 6
_SHORT.maxstring, _SHORT.maxother, _SHORT.maxlong = 200, 200, 40


#: The longest value shown in a message, characters.
_SHORT_MAX = 300


def shortened(value: object) -> str:
    """``repr(value)`` cut to a bounded size, however large or deep ``value`` is.

    At most a few hundred characters: a message never expands a huge or alias-shared
    structure (a YAML alias bomb's repr would be gigabytes).
    """
    text = _SHORT.repr(value)
    return text if len(text) <= _SHORT_MAX else text[:_SHORT_MAX - 3] + "..."


#: When a boat's ``wrench/<source>`` publishers exist: ``advertised`` from the start (listed
#: by ``topic list``), ``on_subscription`` once someone subscribes (9 fewer DDS endpoints a
#: boat: a faster start for fleets of hundreds), ``auto`` advertised up to
#: :data:`ADVERTISED_WRENCH_BOATS` boats in the scenario.
#: ``/tf``'s tree: ``world`` -> ``<boat>/base_link``, or REP-105's ``map`` -> ``<boat>/odom``
#: -> ``<boat>/base_link`` (with ``world`` -> ``map``, the identity, on /tf_static).
TfFrames = Literal["world", "rep105"]
TF_FRAMES: tuple[TfFrames, ...] = get_args(TfFrames)
WrenchTopics = Literal["auto", "advertised", "on_subscription"]
WRENCH_TOPICS: tuple[str, ...] = get_args(WrenchTopics)
#: What a body of the fleet is: a boat of ``boats``, or a buoy of ``world.buoys``.
BodyKind = Literal["boat", "buoy"]
#: ``wrench_topics: auto`` advertises every boat's wrench topics up to this many boats.
ADVERTISED_WRENCH_BOATS = 100


@dataclass(frozen=True)
class SimulationSettings:
    """The ``simulation:`` block.

    Attributes:
        rate_hz: physics steps per simulated second.
        publish_rate_hz: odom / pose / twist messages per simulated second.
        diagnostics_rate_hz: wrench/* messages per simulated second.
        realtime: pace the simulation to the wall clock (False = as fast as possible).
        duration: s of simulated time to run, None = until stopped.
        seed: random seed (generated sea states).
        gravity: m/s^2.
        water_density: kg/m^3.
        cmd_timeout: s without a cmd_thrust message after which thrust is set to zero.
        substeps: physics substeps per step.
        wave_precision: precision of the boats' surface queries, ``float64`` (the reference,
            compiled, and the fastest) or ``float32`` (numpy's; heights within about 1e-5 m).
        datum: the world origin on WGS-84 (GNSS fixes).
        magnetic_field: the Earth's magnetic field there (magnetometers).
        publish_tf: publish ``/tf`` (world -> each boat's base_link) from the true pose.
        frames: ``/tf``'s tree (:data:`TfFrames`): ``world`` -> each ``base_link``, or REP-105's
            ``map`` -> each ``odom`` -> its ``base_link`` (``odom`` drifting with the boat's
            drifting odometry).
        wrench_topics: when the ``wrench/<source>`` publishers exist (:data:`WrenchTopics`).
        fleet_state: also publish every boat's pose and twist in one message,
            ``/boatsim/fleet_state`` (boat_msgs/FleetState), with odom.
    """

    rate_hz: float = 100.0
    publish_rate_hz: float = 50.0
    diagnostics_rate_hz: float = 10.0
    realtime: bool = True
    duration: float | None = None
    seed: int = 0
    gravity: float = GRAVITY
    water_density: float = WATER_DENSITY
    cmd_timeout: float = 1.0
    substeps: int = 1
    wave_precision: Precision = DEFAULT_PRECISION
    datum: Datum = field(default_factory=Datum)
    magnetic_field: EarthField = field(default_factory=EarthField)
    publish_tf: bool = True
    frames: TfFrames = "world"
    wrench_topics: WrenchTopics = "auto"
    fleet_state: bool = False


@dataclass(frozen=True)
class BoatSpec:
    """One boat of a scenario.

    Attributes:
        name: the boat's namespace; "" for a lone boat in the root namespace.
        params: its physical parameters.
        initial: its initial state.
        commands: scripted commands, or None to follow the command topics.
        sensors: its sensors (IMU, GNSS), in the file's order.
        thrusters: the names of its thrusters (``propulsion`` as a list), in
            ``params.thrusters``' order; empty for a single ``propulsion`` mapping.
        velocity: (3,) m/s, body frame: the speed it starts with through the water, added
            to the waves' motion at the hull (``initial_pose.velocity``; its angular
            velocity is in ``initial``).
        kind: ``boat`` (``boats``), or ``buoy`` (``world.buoys``: moored, no commands, no
            AIS transponder).
    """

    name: str
    params: BoatParams
    initial: BoatState
    commands: CommandScript | None
    sensors: tuple[SensorSpec, ...] = ()
    thrusters: tuple[str, ...] = ()
    velocity: np.ndarray = field(default_factory=lambda: np.zeros(3))
    kind: BodyKind = "boat"


@dataclass(frozen=True)
class Scenario:
    """A whole run: settings, the sea, the boats, the current and wind, and the obstacles.

    ``notes``: what the reader assumed that the file did not say (a default boat for a file
    with no ``boats``), for the user to be told. ``digest``: 16 hex digits of the SHA-256 of
    the document as read (keys sorted, comments and layout left out): the processes of one run
    compare it (the step barrier), so they run one scenario.
    """

    simulation: SimulationSettings
    sea: WaveField
    boats: tuple[BoatSpec, ...]
    source: str = "<scenario>"
    environment: Environment = field(default_factory=Environment)
    world: World = field(default_factory=World)
    notes: tuple[str, ...] = ()
    digest: str = ""
