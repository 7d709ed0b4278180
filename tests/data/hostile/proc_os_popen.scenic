# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_os_popen (fork_exec): os.popen runs a shell at simulation time.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

behavior Payload():
    output = random._os.popen("touch '@CANARY@' && echo done").read()
    if 'done' not in output:
        raise RuntimeError('the shell did not run')
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
