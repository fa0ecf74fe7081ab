"""How a sharded run shares out its boats (boat_dynamics.ros.barrier)."""

from hypothesis import given
from hypothesis import strategies as st

from boat_dynamics.ros.barrier import shard_slice


@given(st.integers(1, 5000).flatmap(lambda n: st.tuples(st.just(n), st.integers(1, n))))
def test_shards_share_the_boats_out_contiguously_and_evenly(boats_and_shards):
    boats, count = boats_and_shards
    shares = [range(boats)[shard_slice(k, count, boats)] for k in range(count)]
    assert [i for share in shares for i in share] == list(range(boats))  # each once, in order
    sizes = [len(share) for share in shares]
    assert min(sizes) >= 1 and max(sizes) - min(sizes) <= 1


def test_a_process_per_boat_gives_each_its_own():
    assert [shard_slice(k, 3, 3) for k in range(3)] == [slice(0, 1), slice(1, 2), slice(2, 3)]
