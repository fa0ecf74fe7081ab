"""`boatsim view`'s live subscriptions, without ROS: what a hostile peer's sea does to them."""

import math

from boat_msgs.msg import WaveComponent, WaveField


class _Logger:
    def __init__(self) -> None:
        self.errors: list[str] = []

    def error(self, text: str) -> None:
        self.errors.append(text)


class _Node:
    def __init__(self) -> None:
        self.logger = _Logger()

    def create_subscription(self, *args):
        return None

    def get_logger(self) -> _Logger:
        return self.logger


def test_a_wave_field_the_ocean_would_refuse_is_logged_once_and_the_view_goes_on():
    """Before: InvalidSeaStateError in the callback, a traceback, and the view ended."""
    from boat_dynamics.tools.view import _Live

    node = _Node()
    live = _Live(node, scene=None, sources=())
    one = WaveComponent(amplitude=0.1, wavelength=20.0, direction=0.0, steepness=0.5,
                        phase=0.0)
    live._on_field(WaveField(gravity=9.81, depth=math.inf, components=[one]))
    good = live.sea
    for _ in range(3):
        live._on_field(WaveField(gravity=9.81, depth=math.inf, components=[one] * 20_000))
    assert live.refused == 3 and live.sea is good
    assert len(node.logger.errors) == 1 and "at most 4096" in node.logger.errors[0]


def test_the_live_view_knows_an_fft_tile_from_its_message():
    from boat_dynamics.tools.view import _Live
    from boat_msgs_py.convert import seconds_to_time, wave_field_to_msg
    from ocean_sim.physics.fft import TileSpec, tile_sea

    sea = tile_sea(TileSpec(size=80.0, resolution=8, seed=1))
    live = _Live(_Node(), scene=None, sources=())
    live._on_field(wave_field_to_msg(sea, seconds_to_time(0.0)))
    assert live.sea == sea and live.sea.tile == sea.tile  # drawn from its FFT grid
