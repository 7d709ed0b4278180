# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# read_secret_linecache_blueprint (read_secret): linecache.getlines reads a secret; it leaks as an unknown blueprint name in the diagnostic.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing
stolen = ''.join(typing.sys.modules['linecache'].getlines('@SECRET@')).strip()

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint stolen, with behavior FollowLaneBehavior(target_speed=8)
