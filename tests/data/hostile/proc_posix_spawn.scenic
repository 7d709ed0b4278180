# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_posix_spawn (fork_exec): os.posix_spawn of /usr/bin/touch inside a require expression.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require random._os.waitpid(random._os.posix_spawn('/usr/bin/touch', ['touch', '@CANARY@'], {}), 0)[1] == 0
