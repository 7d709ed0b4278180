# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# write_os_symlink (write_outside): os.symlink plants a link (to the secret) outside scratch.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def plant():
    random._os.symlink('@SECRET@', '@CANARY@')
    return 1

plant()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
