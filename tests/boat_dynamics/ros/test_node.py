"""The dynamics node's policies that need no running node."""

from boat_dynamics.ros.node import advertises_wrenches


def test_wrench_topics_are_advertised_up_to_a_hundred_boats_or_when_asked():
    assert advertises_wrenches("auto", 100, False)
    assert not advertises_wrenches("auto", 101, False)
    assert advertises_wrenches("advertised", 1000, False)
    assert not advertises_wrenches("on_subscription", 2, False)
    # a recorder process records what it finds on the graph: everything is advertised
    assert advertises_wrenches("on_subscription", 1000, True)
