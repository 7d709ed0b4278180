# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# bomb_fork_bounded (bomb): a (bounded) fork bomb: 40 children that each sleep and make the canary.
# The payload runs inside a plain `def` helper.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

def bomb():
    osmodule = random._os
    children = []
    for index in range(40):
        pid = osmodule.fork()
        if pid == 0:
            try:
                osmodule.close(osmodule.open('@CANARY@', osmodule.O_CREAT | osmodule.O_WRONLY))
                random._os.sched_yield()
            finally:
                osmodule._exit(0)
        children.append(pid)
    for pid in children:
        osmodule.waitpid(pid, 0)
    return len(children)

bomb()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
