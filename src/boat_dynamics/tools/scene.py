"""What `boatsim view` draws, logged to a Rerun recording (https://rerun.io).

The boats' hulls at their poses, the sea around them, their paths and the forces on them,
and the world's obstacles (``/world/markers``).

Frames: Rerun's world is boatsim's ``world`` (ENU, z up: REP-103); each boat's entity
``world/<boat>`` carries the pose of its hull reference point (as its odom) and its children
are in its body frame (FLU): the hull mesh, and the force arrows at its centre of mass. Time:
the ``sim_time`` timeline, seconds of simulation time, so a bag and a live run scrub alike.

The sea is a mesh of the Gerstner surface (:func:`ocean_sim.physics.waves.sample_surface`,
heights with the horizontal displacement inverted) on a grid that follows the fleet, its
vertices on world-fixed points, coloured from trough to crest. An FFT tile's sea
(``ocean.model: fft``) is drawn from the tile's FFT grid instead: its vertices are the surface
particles of world-fixed rest points (:func:`ocean_sim.physics.fft.grid_surface`).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from boat_dynamics.physics.body.hull import box_mesh
from boat_dynamics.physics.body.rigid_body import quat_to_euler
from boat_dynamics.physics.core.model import BoatParams
from boat_dynamics.physics.core.tuning import equilibrium_height
from boat_dynamics.physics.force_models.mesh_buoyancy import MeshBuoyancy
from boat_dynamics.physics.potential_flow.hydro import HydroCoefficients
from boat_dynamics.physics.wave_making.interaction import made_waves_elevation
from boat_dynamics.physics.wave_making.kelvin_wake import ThinShip, thin_ship
from boat_dynamics.physics.wave_making.scattered_waves import outgoing_elevation
from ocean_sim.physics.constants import GRAVITY
from ocean_sim.physics.fft import grid_points, grid_surface
from ocean_sim.physics.waves import WaveField, sample_surface

__all__ = ["DEFAULT_SOURCES", "POSE_PERIOD", "HullShape", "Scene", "hull_shape", "sea_mesh"]

#: Wrench sources drawn unless asked otherwise: the ones of the size of the thrust
#: (buoyancy and the total are of the size of the boat's weight, 20x longer; the damping
#: holds the radiation force in heave, several times the thrust).
DEFAULT_SOURCES = ("thrust", "rudder", "drag", "wind")
#: The most sea-mesh vertices drawn at a time (a wide fleet gets a coarser grid).
MAX_SEA_VERTICES = 40_000
#: A boat's pose is drawn at most this often, s of simulation time (odom comes at 50 Hz; a
#: browser's viewer drawing in software fell tens of seconds behind a live run at that rate).
POSE_PERIOD = 0.05
#: The path of each boat: a point every this many s of simulation time ...
_PATH_STEP = 0.2
#: ... the most points kept, and the period of its redraw, s of simulation time: the points
#: since the last whole path (its tail, ``world/paths/<boat>/tail``) every _PATH_PERIOD, the
#: whole path (``world/paths/<boat>``) every _PATH_WHOLE_PERIOD. Redrawing the whole path every
#: second logged 60 kB/s once it was long (O(n^2) over a run), which a live viewer must ingest.
_PATH_POINTS = 5000
#: s of simulation time between the two poses a boat's velocity (its wake's) is taken from.
_VELOCITY_SPAN = 0.2
_PATH_PERIOD = 1.0
_PATH_WHOLE_PERIOD = 30.0
#: visualization_msgs/Marker types drawn (:meth:`Scene.markers`).
_TRIANGLE_LIST, _LINE_STRIP, _CYLINDER = 11, 4, 3
#: Trough and crest colours of the sea, RGB.
_TROUGH, _CREST = np.array([12, 44, 92]), np.array([96, 168, 222])
#: Colours of the hulls (boat i gets colour i modulo the count) and of the force arrows.
_HULL_COLOURS = ((232, 118, 36), (240, 200, 40), (214, 64, 64), (150, 90, 200),
                 (60, 180, 110), (230, 230, 230))
_ARROW_COLOURS = {"thrust": (255, 60, 60), "rudder": (255, 170, 0), "drag": (120, 220, 255),
                  "damping": (90, 230, 140), "wind": (245, 245, 245), "buoyancy": (70, 120, 255),
                  "diffraction": (200, 120, 255), "slamming": (255, 90, 200),
                  "total": (255, 255, 120)}


@dataclass(frozen=True)
class HullShape:
    """What is drawn of a boat.

    Attributes:
        vertices: (V, 3) m, body frame, origin at the hull reference point.
        faces: (F, 3) vertex indices.
        arrow_origin: (3,) m, body frame, where the force arrows start: above the centre of
            mass, over the deck (an arrow from the centre of mass itself would be hidden in
            the hull).
        force_scale: m of arrow per N of force.
        arrow_radius: m, the arrows' thickness (3 % of the hull's length).
        ship: the hull below its waterline, whose Kelvin wake is drawn
            (:mod:`boat_dynamics.physics.wave_making.kelvin_wake`), or None: no wake (a
            boat that makes none, ``hydrodynamics.made_waves``).
        hydro: its coefficients with Kochin functions, whose radiated and scattered waves are
            drawn (:mod:`boat_dynamics.physics.wave_making.scattered_waves`), or None.
    """

    vertices: np.ndarray
    faces: np.ndarray
    arrow_origin: np.ndarray
    force_scale: float
    arrow_radius: float
    ship: ThinShip | None = None
    hydro: HydroCoefficients | None = None


def hull_shape(params: BoatParams | None) -> HullShape:
    """A boat's hull as its buoyancy mesh (or bounding box), arrows scaled to its thrust.

    An arrow is the hull's length at the boat's full thrust (all thrusters together), or at
    a twentieth of its weight when it has none. ``params`` None: the default 4 x 2 x 1
    m box of 4100 kg, 2 kN (a boat the scenario given to the viewer does not have).
    """
    ship, hydro = None, None
    if params is None:
        from boat_dynamics.physics.body.hull import BoxHull

        mesh, com, length, thrust = box_mesh(BoxHull(4.0, 2.0, 1.0)), np.zeros(3), 4.0, 2000.0
        ship = thin_ship(mesh, 0.0)  # the default box floats at half its height
    else:
        buoyancy = params.buoyancy
        mesh = buoyancy.mesh if isinstance(buoyancy, MeshBuoyancy) else box_mesh(params.hull)
        com, length = np.asarray(params.center_of_mass, dtype=float), params.hull.length
        thrust = sum(float(np.max(t.max_thrust)) for t in params.thrusters)
        if thrust <= 0.0:
            thrust = params.mass * params.gravity / 20.0
        if params.made_waves in ("all", "wake"):
            ship = params.thin_ship or thin_ship(mesh, equilibrium_height(params))
        if params.made_waves in ("all", "scattered") and params.hydro is not None:
            hydro = params.hydro if params.hydro.has_kochin else None
    vertices = np.asarray(mesh.vertices, dtype=float)
    origin = np.array([com[0], com[1], vertices[:, 2].max() + 0.1 * length])
    return HullShape(vertices, np.asarray(mesh.faces), origin, length / thrust, 0.03 * length,
                     ship, hydro)


def sea_mesh(sea: WaveField, t: float, centre: np.ndarray, size: float, resolution: float,
             made: Callable[[np.ndarray], np.ndarray] | None = None
             ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The sea surface on a square grid around ``centre``.

    The grid's points are world-fixed multiples of ``resolution`` (the mesh does not swim
    with the fleet), at most :data:`MAX_SEA_VERTICES` of them (coarser when ``size`` asks for
    more). A sea that is an FFT tile (``sea.tile``) is drawn from its FFT grid
    (:func:`_tile_mesh`) unless that grid would be finer than
    :data:`ocean_sim.physics.fft.MAX_GRID_POINTS` a side.

    Args:
        sea: the sea state.
        t: s, simulation time.
        centre: (2,) m, world x, y.
        size: m, side of the square.
        resolution: m between grid points.
        made: (P, 2) m world points -> (P,) m, the waves the boats make, added to the sea's
            (:func:`~boat_dynamics.physics.wave_making.interaction.made_waves_elevation`),
            or None: none.

    Returns:
        vertices (V, 3) m world, triangles (T, 3) indices, colours (V, 3) uint8.
    """
    points = None if sea.tile is None else grid_points(sea.tile, resolution)
    if points is not None:
        return _tile_mesh(sea, t, centre, size, points, made)
    n = math.ceil(size / resolution) + 1
    if n * n > MAX_SEA_VERTICES:
        n = int(math.sqrt(MAX_SEA_VERTICES))
        resolution = size / (n - 1)
    start = np.round((np.asarray(centre, dtype=float) - size / 2) / resolution) * resolution
    ticks_x, ticks_y = start[0] + resolution * np.arange(n), start[1] + resolution * np.arange(n)
    gx, gy = np.meshgrid(ticks_x, ticks_y, indexing="ij")
    xy = np.column_stack([gx.ravel(), gy.ravel()])
    heights = sample_surface(sea, xy, t).heights
    if made is not None:
        heights = heights + made(xy)
    reach = max(sum(c.amplitude for c in sea.components), 1e-9)
    triangles, colours = _mesh_faces(n, heights, reach)
    return np.column_stack([xy, heights]), triangles, colours


def _tile_mesh(sea: WaveField, t: float, centre: np.ndarray, size: float, points: int,
               made: Callable[[np.ndarray], np.ndarray] | None
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`sea_mesh` of an FFT tile: the surface particles of its grid's rest points.

    The rest points are nodes of the tile's M x M grid (M = ``points``, spacing L / M at most
    the resolution asked; every ``stride``-th node when more than :data:`MAX_SEA_VERTICES`
    would be drawn), tiled periodically over the square; each vertex is the displaced
    particle, exactly the direct sum of the components there (no interpolation), raised by
    the ``made`` waves where it is.
    """
    spacing = sea.tile.size / points
    n, stride = math.ceil(size / spacing) + 1, 1
    side = int(math.sqrt(MAX_SEA_VERTICES))
    if n > side:
        stride = math.ceil((n - 1) / (side - 1))
        n = math.ceil((n - 1) / stride) + 1
    first = np.round((np.asarray(centre, dtype=float) - size / 2) / (stride * spacing))
    ticks = (first.astype(np.int64) * stride)[:, None] + stride * np.arange(n)
    gx, gy = np.meshgrid(ticks[0], ticks[1], indexing="ij")
    vertices, _ = grid_surface(sea, t, np.column_stack([gx.ravel(), gy.ravel()]), points,
                               normals=False)
    if made is not None:
        vertices[:, 2] += made(vertices[:, :2])
    # the crest colour at 2 standard deviations of the height (H_s / 2): the sum of the
    # amplitudes of thousands of waves of random phases is never reached
    reach = max(2.0 * math.sqrt(0.5 * sum(c.amplitude**2 for c in sea.components)), 1e-9)
    triangles, colours = _mesh_faces(n, vertices[:, 2], reach)
    return vertices, triangles, colours


def _mesh_faces(n: int, heights: np.ndarray, reach: float) -> tuple[np.ndarray, np.ndarray]:
    """Triangles (T, 3) of an n x n grid's vertices, and their colours (V, 3) uint8.

    Vertices row-major, x first; colours from trough (-reach, m) to crest (+reach).
    """
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:]
    triangles = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d.ravel()], 1)])
    share = np.clip(0.5 + 0.5 * heights / reach, 0.0, 1.0)[:, None]
    return triangles, (_TROUGH + share * (_CREST - _TROUGH)).astype(np.uint8)


class Scene:
    """A fleet on the sea, logged to a Rerun recording as its data comes.

    Args:
        recording: a ``rerun.RecordingStream``.
        shapes: each boat's :class:`HullShape`, by boat name ("" = the root namespace); a boat
            not among them is drawn as the default box.
        sources: the wrench sources to draw as arrows.
        sea_size: m, side of the sea drawn (widened to the fleet's extent plus 20 m).
        sea_resolution: m between its grid points.
        sea_period: s of simulation time between two drawings of the sea.
        pose_period: s of simulation time between two drawings of a boat's pose (at most).
        wrench_period: s of simulation time between two drawings of a force arrow (at most;
            0: every message).
    """

    def __init__(self, recording, shapes: dict[str, HullShape],
                 sources: Sequence[str] = DEFAULT_SOURCES, sea_size: float = 60.0,
                 sea_resolution: float = 1.0, sea_period: float = 0.5,
                 pose_period: float = POSE_PERIOD, wrench_period: float = 0.0) -> None:
        import rerun as rr

        self._rr, self._rec = rr, recording
        self._shapes, self.sources = dict(shapes), tuple(sources)
        self._sea_size, self._sea_resolution, self._sea_period = (sea_size, sea_resolution,
                                                                  sea_period)
        self._boats: dict[str, int] = {}  # name -> colour index, once drawn
        self._positions: dict[str, np.ndarray] = {}  # the latest, (3,) m
        self._moving: dict[str, tuple[float, np.ndarray, np.ndarray]] = {}  # t, p, velocity
        self._headings: dict[str, float] = {}  # the latest yaw, rad
        self._paths: dict[str, list[np.ndarray]] = {}
        self._next_path: dict[str, float] = {}
        # what is drawn at most every so often -> the next time it is due, s (simulation)
        self._next_draw: dict[object, float] = {}
        self._pose_period, self._wrench_period = pose_period, wrench_period
        self._path_count: dict[str, int] = {}  # points ever added, per boat
        self._path_whole: dict[str, int] = {}  # the count when the whole path was last drawn
        self._next_path_whole = -math.inf
        self._sea_triangles = 0  # the triangle count of the sea's indices last drawn
        self._next_path_log = -math.inf
        self._focus: str | None = None  # the boat the camera follows (blueprint)
        self.t = 0.0  # the simulation time of what is being drawn, s
        for entity in ("world", "world/focus"):
            self._log(entity, rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)

    def blueprint(self, focus: str | None = None, reach: float = 20.0):
        """One 3-D view of the world, side panels folded (the time panel stays).

        Args:
            focus: the boat the camera follows (orbiting it), or None: the world's origin.
            reach: m, the camera's distance scale (the fleet's extent).
        """
        import rerun.blueprint as rrb

        d = max(reach, 12.0)
        self._focus = focus
        eye = rrb.EyeControls3D(kind=rrb.Eye3DKind.Orbital, position=[-0.9 * d, -0.9 * d, 0.8 * d],
                                look_target=[0.0, 0.0, 0.0], eye_up=[0.0, 0.0, 1.0])
        # The view's frame is world/focus: the followed boat's position, without its rotation
        # (the camera goes along, the sea does not tilt), or the world's origin.
        return rrb.Blueprint(rrb.Spatial3DView(origin="/world/focus", contents="/world/**",
                                               name="boatsim", eye_controls=eye),
                             collapse_panels=True)

    def _part(self, name: str) -> str:
        return self._rr.escape_entity_path_part(name or "boat")

    def _entity(self, name: str) -> str:
        return f"world/{self._part(name)}"

    def _at(self, t: float) -> None:
        """Log what follows at simulation time ``t`` (s)."""
        self.t = t
        self._rr.set_time("sim_time", duration=t, recording=self._rec)

    def markers(self, markers) -> None:
        """The world's obstacles from a visualization_msgs/MarkerArray (``/world/markers``).

        Static, under ``world/obstacles/<ns>/<id>``: a TRIANGLE_LIST as a mesh, a LINE_STRIP
        as a line, a CYLINDER as a cylinder at its pose (markers in frame ``world``; other
        types are left out).
        """
        rr = self._rr
        for m in markers.markers:
            entity = f"world/obstacles/{self._part(m.ns)}/{m.id}"
            colour = [int(255 * c) for c in (m.color.r, m.color.g, m.color.b)]
            points = np.array([[p.x, p.y, p.z] for p in m.points], dtype=np.float32)
            if m.type == _TRIANGLE_LIST and len(points) >= 3:
                count = len(points) // 3 * 3
                self._log(entity, rr.Mesh3D(
                    vertex_positions=points[:count],
                    triangle_indices=np.arange(count, dtype=np.uint32).reshape(-1, 3),
                    albedo_factor=colour), static=True)
            elif m.type == _LINE_STRIP and len(points) >= 2:
                self._log(entity, rr.LineStrips3D([points], colors=[colour],
                                                  radii=[0.5 * m.scale.x]), static=True)
            elif m.type == _CYLINDER:
                p = m.pose.position
                self._log(entity, rr.Cylinders3D(
                    lengths=[m.scale.z], radii=[0.5 * m.scale.x], centers=[[p.x, p.y, p.z]],
                    colors=[colour], fill_mode=rr.components.FillMode.Solid), static=True)

    def _log(self, entity: str, archetype, static: bool = False) -> None:
        """Every drawing goes through here (tests subclass it to see what is drawn)."""
        self._rr.log(entity, archetype, static=static, recording=self._rec)

    def _boat(self, name: str) -> HullShape:
        """The boat's shape; its hull mesh is logged (static) the first time."""
        shape = self._shapes.get(name) or self._shapes.setdefault(name, hull_shape(None))
        if name not in self._boats:
            colour = _HULL_COLOURS[len(self._boats) % len(_HULL_COLOURS)]
            self._boats[name] = len(self._boats)
            entity = self._entity(name)
            self._log(f"{entity}/hull", self._rr.Mesh3D(
                vertex_positions=shape.vertices, triangle_indices=shape.faces,
                albedo_factor=[*colour, 255]), static=True)
            top = float(shape.arrow_origin[2]) + 0.5
            self._log(f"{entity}/name", self._rr.Points3D(
                [[0.0, 0.0, top]], labels=[name or "(root namespace)"], radii=[0.01],
                colors=[colour]), static=True)
        return shape

    def pose(self, t: float, name: str, position: Iterable[float],
             orientation: Iterable[float]) -> None:
        """A boat's pose: its hull reference point (m, world) and orientation (x, y, z, w).

        Drawn at most every :data:`POSE_PERIOD` s of simulation time (on a grid of it).
        """
        self._boat(name)
        p = np.asarray(list(position), dtype=float)
        self._positions[name] = p
        orientation = np.asarray(list(orientation), dtype=float)
        self._headings[name] = quat_to_euler(orientation)[2]
        self._track(name, t, p)
        if not self._due(("pose", name), t, self._pose_period):
            return
        self._at(t)
        self._log(self._entity(name), self._rr.Transform3D(
            translation=p, quaternion=self._rr.Quaternion(xyzw=list(orientation))))
        if name == self._focus:
            self._log("world/focus", self._rr.Transform3D(translation=p))
        if t >= self._next_path.get(name, -math.inf) - 1e-9:  # a point per _PATH_STEP
            self._next_path[name] = (math.floor(t / _PATH_STEP + 1e-9) + 1) * _PATH_STEP
            path = self._paths.setdefault(name, [])
            path.append(p)
            del path[:-_PATH_POINTS]
            self._path_count[name] = self._path_count.get(name, 0) + 1
        if t >= self._next_path_log:
            self._next_path_log = t + _PATH_PERIOD
            whole = t >= self._next_path_whole
            if whole:
                self._next_path_whole = t + _PATH_WHOLE_PERIOD
            self._log_paths(whole)

    def _track(self, name: str, t: float, p: np.ndarray) -> None:
        """A boat's horizontal velocity (its wake's), from its poses _VELOCITY_SPAN s apart."""
        last = self._moving.get(name)
        if last is None or t < last[0]:  # the first pose, or time went back (a new run)
            self._moving[name] = (t, p, np.zeros(2))
        elif t - last[0] >= _VELOCITY_SPAN:
            self._moving[name] = (t, p, (p[:2] - last[1][:2]) / (t - last[0]))

    def _made_waves(self, xy: np.ndarray, field: WaveField, t: float) -> np.ndarray:
        """(P,) m, the waves the boats make at world points ``xy`` (P, 2), as they move now.

        Their wakes, and the waves they radiate and scatter in ``field`` at ``t`` (each
        boat's own included: the view draws the whole sea).
        """
        out = np.zeros(xy.shape[0])
        names = [n for n in self._moving if self._boat(n).ship is not None]
        if names:
            out += made_waves_elevation([self._boat(n).ship for n in names],
                                        np.array([self._positions[n][:2] for n in names]),
                                        np.array([self._moving[n][2] for n in names]), xy,
                                        GRAVITY)
        for n in self._moving:
            hydro = self._boat(n).hydro
            if hydro is not None and field.components:
                out += outgoing_elevation(hydro, field, self._positions[n][:2],
                                          self._headings.get(n, 0.0), xy, t)
        return out

    def _log_paths(self, whole: bool = True) -> None:
        """Each boat's path: the whole of it, or its tail since the whole was last drawn."""
        for name, path in self._paths.items():
            colour = _HULL_COLOURS[self._boats[name] % len(_HULL_COLOURS)]
            entity = f"world/paths/{self._part(name)}"
            count = self._path_count[name]
            if whole or name not in self._path_whole:
                if len(path) > 1:
                    self._log(entity, self._rr.LineStrips3D([np.array(path)], colors=[colour],
                                                            radii=[0.05]))
                    self._path_whole[name] = count
                tail = path[-1:]
            else:
                tail = path[-min(count - self._path_whole[name] + 1, len(path)):]
            if name in self._path_whole:
                self._log(f"{entity}/tail", self._rr.LineStrips3D(
                    [np.array(tail)], colors=[colour], radii=[0.05]))

    def wrench(self, t: float, name: str, source: str, force: Iterable[float]) -> None:
        """A force on a boat (N, body frame), drawn from above its centre of mass."""
        if source not in self.sources:
            return
        shape = self._boat(name)
        if not self._due(("wrench", name, source), t, self._wrench_period):
            return
        f = np.asarray(list(force), dtype=float)
        self._at(t)
        self._log(f"{self._entity(name)}/forces/{source}", self._rr.Arrows3D(
            origins=[shape.arrow_origin], vectors=[f * shape.force_scale],
            colors=[_ARROW_COLOURS.get(source, (255, 255, 255))],
            radii=[shape.arrow_radius]))

    def _due(self, what: object, t: float, period: float) -> bool:
        """Whether ``what`` is drawn at ``t``: at most every ``period`` s, on a grid of it.

        When it is, the next time it is due is the next grid point (0: always due).
        """
        if period <= 0.0:
            return True
        if t < self._next_draw.get(what, -math.inf) - 1e-9:
            return False
        self._next_draw[what] = (math.floor(t / period + 1e-9) + 1) * period
        return True

    def sea(self, t: float, field: WaveField) -> None:
        """The sea at ``t`` around the fleet, once ``sea_period`` has passed since the last."""
        if not self._due("sea", t, self._sea_period):
            return
        positions = np.array(list(self._positions.values())).reshape(-1, 3)[:, :2]
        if len(positions):
            low, high = positions.min(axis=0), positions.max(axis=0)
            centre, size = (low + high) / 2, max(self._sea_size, float(np.max(high - low)) + 20)
        else:
            centre, size = np.zeros(2), self._sea_size
        vertices, triangles, colours = sea_mesh(field, t, centre, size, self._sea_resolution,
                                                lambda xy: self._made_waves(xy, field, t))
        self._at(t)
        if len(triangles) != self._sea_triangles:  # the grid's shape changed (or the first)
            self._sea_triangles = len(triangles)
            self._log("world/sea", self._rr.Mesh3D.from_fields(triangle_indices=triangles))
        self._log("world/sea", self._rr.Mesh3D.from_fields(vertex_positions=vertices,
                                                           vertex_colors=colours))

    def finish(self) -> None:
        """Draw the paths as they are now (the end of a bag or of a live view)."""
        self._log_paths()
