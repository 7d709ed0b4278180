# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# typing_hints_globalns (typing_annotations): the annotation string hides getattr(random, '_os'); get_type_hints gets the names as globalns.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import typing

def probe(value: "(grab(rnd, '_' + 'os').makedirs('@CANARY@', exist_ok=True), int)[1]"):
    return value

typing.get_type_hints(probe, globalns={'grab': getattr, 'rnd': random})

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
