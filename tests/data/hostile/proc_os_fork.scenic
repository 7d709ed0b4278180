# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_os_fork (fork_exec): os.fork; the child creates the canary.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def spawn():
    osmodule = random._os
    pid = osmodule.fork()
    if pid == 0:
        try:
            osmodule.close(osmodule.open('@CANARY@', osmodule.O_CREAT | osmodule.O_WRONLY))
        finally:
            osmodule._exit(0)
    osmodule.waitpid(pid, 0)
    return pid

spawn()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
