# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# dunder_del_finalizer (dunder_method): a __del__ finalizer (a def, not an attribute) runs the payload when the object dies.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
failures = []

class Tripwire(object):
    def __del__(self):
        try:
            random._os.makedirs('@CANARY@', exist_ok=True)
        except OSError as error:
            failures.append(error)

wire = Tripwire()
del wire
if failures:
    raise failures[0]

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
