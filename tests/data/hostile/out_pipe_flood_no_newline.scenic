# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# out_pipe_flood_no_newline (huge_output): 200 MB without a newline on every inherited pipe at simulation time (a parent that buffers lines runs out of memory).
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

behavior Payload():
    osmodule = random._os
    block = b'{' * 1000000
    for fd in range(1, 64):
        try:
            kind = osmodule.fstat(fd).st_mode & 0o170000
        except OSError:
            continue
        if kind in (0o010000, 0o140000):
            for index in range(200):
                osmodule.write(fd, block)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
