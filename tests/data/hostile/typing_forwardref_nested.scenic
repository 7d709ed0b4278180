# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# typing_forwardref_nested (typing_annotations): a forward reference nested in typing.Optional[...] evaluated from a monitor.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
import typing

def probe(value: typing.Optional["(random._os.makedirs('@CANARY@', exist_ok=True), int)[1]"]):
    return value

monitor Payload():
    typing.get_type_hints(probe)
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
