# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_os_execv (fork_exec): os.execv replaces the validator process with a shell.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

monitor Payload():
    random._os.execv('/bin/sh', ['sh', '-c', "touch '@CANARY@'"])
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
