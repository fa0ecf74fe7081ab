"""One error class for a value that is not allowed: the sea's, the scenario's and start-up's."""

import pytest

from boat_dynamics.physics.core.pipeline import InitError
from boat_dynamics.physics.scenario import ScenarioError, parse_scenario
from ocean_sim.physics.errors import InvalidValueError
from ocean_sim.physics.waves import InvalidSeaStateError, WaveComponent, WaveField


@pytest.mark.parametrize(("raise_it", "key", "value", "text"), [
    (lambda: WaveField(components=(WaveComponent(0.1, -5.0, 0.0, 0.5),)),
     "components[0].wavelength", -5.0, "components[0].wavelength = -5.0 is not allowed: "),
    (lambda: parse_scenario({"boats": [{"mass": -3.0}]}), "boats[0].mass", -3.0,
     "boats[0].mass: -3.0 is not allowed: must be in (0, inf] kg"),
    (lambda: (_ for _ in ()).throw(InitError(2, "mass", 9e9, "at most 1e4 kg: it sinks")),
     "mass", 9e9, "boat 2: mass: 9000000000.0 is not allowed: at most 1e4 kg: it sinks"),
])
def test_every_refused_value_is_one_kind_of_error_naming_key_value_and_allowed(
        raise_it, key, value, text):
    with pytest.raises(InvalidValueError) as info:
        raise_it()
    assert isinstance(info.value, InvalidSeaStateError | ScenarioError | InitError)
    assert (info.value.key, info.value.value) == (key, value)
    assert info.value.allowed and str(info.value).startswith(text)


def test_the_plain_message_names_key_value_and_allowed():
    error = InvalidValueError("rate_hz", 0.0, "in (0, 10000] Hz")
    assert str(error) == "rate_hz: 0.0 is not allowed: in (0, 10000] Hz"
    assert isinstance(error, ValueError)
