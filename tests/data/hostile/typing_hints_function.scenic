# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# typing_hints_function (typing_annotations): typing.get_type_hints evaluates a string annotation that calls os.system.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import typing

def refused():
    raise RuntimeError('os.system was refused')

def probe(value: "(random._os.system(\"touch '@CANARY@'\") == 0 or refused(), int)[1]"):
    return value

def inspect_probe():
    return typing.get_type_hints(probe)

inspect_probe()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
