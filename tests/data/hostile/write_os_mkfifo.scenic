# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# write_os_mkfifo (write_outside): os.mkfifo outside scratch from a `terminate when` expression.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def plant_fifo():
    if not random._os.path.lexists('@CANARY@'):
        random._os.mkfifo('@CANARY@')
    return False

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
terminate when plant_fifo()
