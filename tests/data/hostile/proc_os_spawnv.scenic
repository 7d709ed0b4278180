# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_os_spawnv (fork_exec): os.spawnv(P_WAIT) in a `terminate when` expression, every step.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
terminate when random._os.spawnv(random._os.P_WAIT, '/usr/bin/touch', ['touch', '@CANARY@']) != 0
