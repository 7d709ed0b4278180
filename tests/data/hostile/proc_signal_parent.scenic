# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# proc_signal_parent (fork_exec): os.kill(os.getppid(), SIGUSR2): a signal to the process that started the validator.
# The payload runs inside a `behavior`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random

behavior Payload():
    random._os.kill(random._os.getppid(), 12)
    do FollowLaneBehavior(target_speed=8)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior Payload()
