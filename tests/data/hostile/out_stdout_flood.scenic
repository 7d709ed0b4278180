# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# out_stdout_flood (huge_output): 100 MB on stdout, then the same flood on every inherited pipe (the validator's result channel).
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
osmodule = random._os
line = 'x' * 1000000
for index in range(100):
    print(line)
for fd in range(1, 64):
    try:
        kind = osmodule.fstat(fd).st_mode & 0o170000
    except OSError:
        continue
    if kind in (0o010000, 0o140000):
        for index in range(100):
            osmodule.write(fd, line.encode())

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
