# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# attr_typing_sys_builtins_open (module_attribute): typing.sys.modules['builtins'].open writes a file outside scratch.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing

monitor Payload():
    handle = typing.sys.modules['builtins'].open('@CANARY@', 'w')
    handle.write('escaped')
    handle.close()
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
