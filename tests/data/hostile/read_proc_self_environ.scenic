# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_proc_self_environ (read_secret): /proc/self/environ read from a monitor (the environment the validator was started with).
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

monitor Payload():
    data = typing.sys.modules['io'].open('/proc/self/environ', 'rb').read()
    raise RuntimeError('stolen: ' + data.decode(errors='replace'))
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
