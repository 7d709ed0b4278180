# Hostile test script for arise's sandbox: never run it outside tests/validate/test_hostile.py.
# fmt_nested_spec (format_string): a field nested in a format spec ('{0:{1.x}}') walks attributes; the token leaks in the error about the spec.
# The payload runs at the top level, while the script compiles.
# @CANARY@, @SECRET@, @SSH_KEY@, @PORT@ ... are filled in by the test (see manifest.yaml).
Town = 'arise_straight'
param map = localPath(f'maps/{Town}.xodr')
param carla_map = Town
model scenic.simulators.carla.model
import random
label = "{0:{1.__init__.__globals__[_os].environ[ARISE_HOSTILE_TOKEN]}}".format(1, random.Random())

egoLane = Uniform(*network.lanes)
ego = new Car on egoLane.centerline, with blueprint "vehicle.lincoln.mkz_2017", with behavior FollowLaneBehavior(target_speed=8)
