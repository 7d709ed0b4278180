# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# typing_hints_behavior (typing_annotations): a string annotation evaluated by typing.get_type_hints at simulation time.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import typing

def probe(value: "(random._os.makedirs('@CANARY@', exist_ok=True), int)[1]"):
    return value

behavior Payload():
    typing.get_type_hints(probe)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
