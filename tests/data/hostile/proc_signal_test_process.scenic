# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_signal_test_process (fork_exec): os.kill(test process, SIGUSR2): a signal to a process outside the validator (found by pid).
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

monitor Payload():
    random._os.kill(@TEST_PID@, 12)
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
