"""boatsim's Fast DDS profile: loaded unless the user chose otherwise, and what it holds."""

import xml.etree.ElementTree as ET

from boat_dynamics.ros.participants import PROFILE, PROFILE_VARIABLES, use_profile


def test_the_profile_is_loaded_in_a_plain_environment_and_again_by_a_child():
    env = {}
    assert use_profile(env) is None
    assert env == {PROFILE_VARIABLES[0]: str(PROFILE)}
    assert use_profile(env) is None  # a child process inherits it: still boatsim's own


def test_a_users_own_profile_or_another_rmw_is_left_alone():
    for variable in PROFILE_VARIABLES:
        env = {variable: "/home/me/my_fastdds.xml"}
        note = use_profile(env)
        assert variable in note and "/home/me/my_fastdds.xml" in note
        assert env == {variable: "/home/me/my_fastdds.xml"}
    env = {"RMW_IMPLEMENTATION": "rmw_cyclonedds_cpp"}
    assert "rmw_cyclonedds_cpp" in use_profile(env)
    assert PROFILE_VARIABLES[0] not in env
    assert use_profile({"RMW_IMPLEMENTATION": "rmw_fastrtps_cpp"}) is None


def test_the_profile_makes_participants_ignore_their_own_endpoints():
    ns = {"p": "http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles"}
    participant = ET.parse(PROFILE).getroot().find("p:participant", ns)
    assert participant.get("is_default_profile") == "true"
    properties = {p.findtext("p:name", namespaces=ns): p.findtext("p:value", namespaces=ns)
                  for p in participant.iter(f"{{{ns['p']}}}property")}
    assert properties == {"fastdds.ignore_local_endpoints": "true"}

