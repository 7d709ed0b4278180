# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_ssh_key_builtins (read_secret): builtins.open (through enum.sys.modules) reads a private ssh key and leaks it.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import enum
key = enum.sys.modules['builtins'].open('@SSH_KEY@').read()
raise RuntimeError('stolen key: ' + key)

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
