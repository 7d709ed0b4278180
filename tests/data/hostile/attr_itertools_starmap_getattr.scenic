# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_itertools_starmap_getattr (module_attribute): itertools.starmap(getattr, [(random, '_os')]) reaches os and makes a directory.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import itertools
import random

def reach():
    osmodule = next(itertools.starmap(getattr, [(random, '_os')]))
    osmodule.mkdir('@CANARY@')
    return 1

param reached = reach()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
