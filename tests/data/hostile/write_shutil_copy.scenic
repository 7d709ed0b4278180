# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# write_shutil_copy (write_outside): shutil.copyfile of the secret to a new file, inside a require.
# The payload runs inside a `require` / `terminate when` expression.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import typing
files = typing.sys.modules['shutil']

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
require files.copyfile('@SECRET@', '@CANARY@') == '@CANARY@'
