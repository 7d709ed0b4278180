# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_format_map (format_string): str.format_map walks random._os.environ; the token leaks as a scene parameter.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def environment_token():
    return "{r._os.environ[ARISE_HOSTILE_TOKEN]}".format_map({'r': random})

param stolen = environment_token()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
