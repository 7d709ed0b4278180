# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# write_rename_from_scratch (write_outside): a file written in the (allowed) working folder, then renamed to outside it.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import numpy
import random

def smuggle():
    numpy.savetxt('staged.txt', numpy.arange(3))
    random._os.rename('staged.txt', '@CANARY@')
    return 1

smuggle()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
