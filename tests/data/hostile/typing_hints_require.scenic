# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# typing_hints_require (typing_annotations): typing.get_type_hints called inside a require expression.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import typing

def probe(value: "(random._os.makedirs('@CANARY@', exist_ok=True), int)[1]"):
    return value

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require len(typing.get_type_hints(probe)) == 1
